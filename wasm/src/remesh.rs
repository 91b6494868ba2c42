//! Remeshing from JavaScript: the arrays of a `BufferGeometry` in, a remeshed geometry's arrays
//! and the quality figures before and after out.

use std::collections::{BTreeMap, BTreeSet};

use js_sys::{Float32Array, Object, Uint32Array};
use meshq::collide::PairBudget;
use meshq::mesh::MeshRef;
use meshq::owned::Remeshed;
use meshq::remesh::{EdgeTarget, MeshQuality, RemeshConfig};
use wasm_bindgen::prelude::*;

use crate::args::{JsNumber, floats_or_numbers, range_error};
use crate::build::read_indices;
use crate::fields::{field, optional_number, optional_u32, optional_whole, options};
use crate::js_objects::set;

/// The keys `remesh` options accept.
const REMESH_KEYS: &[&str] = &[
    "targetLength",
    "targetRatio",
    "iterations",
    "featureAngle",
    "maxDistanceTests",
];

/// Reads `{ targetLength?, targetRatio?, iterations?, featureAngle?, maxDistanceTests? }`
/// (every field optional; `targetLength` and `targetRatio` not both), strictly (see
/// [`crate::fields`]): the run's config and the distance report's test cap, if given.
fn config(options_in: &JsValue) -> Result<(RemeshConfig, Option<u32>), JsValue> {
    let mut config = RemeshConfig::default();
    let o = options(options_in, "options", REMESH_KEYS)?;
    let o = o.as_ref();
    let positive = |name: &str| -> Result<Option<f64>, JsValue> {
        let what = format!("options.{name}");
        match optional_number(&field(o, name)?, &what)? {
            Some(x) if !(x > 0.0 && x.is_finite()) => Err(range_error(&format!(
                "{what} must be a positive finite number, got {}",
                JsNumber(x)
            ))),
            x => Ok(x),
        }
    };
    match (positive("targetLength")?, positive("targetRatio")?) {
        (Some(_), Some(_)) => {
            return Err(range_error(
                "options: give targetLength or targetRatio, not both",
            ));
        }
        (Some(l), None) => config.target = EdgeTarget::Length(l as f32),
        (None, Some(r)) => config.target = EdgeTarget::MeanEdgeTimes(r as f32),
        (None, None) => {}
    }
    if let Some(n) = optional_whole(
        &field(o, "iterations")?,
        "options.iterations",
        f64::from(RemeshConfig::MAX_ITERATIONS),
    )? {
        config.iterations = n as u32;
    }
    config.feature_angle =
        optional_number(&field(o, "featureAngle")?, "options.featureAngle")?.map(|a| a as f32);
    config.validate().map_err(|e| range_error(&e.to_string()))?;
    let max_distance_tests =
        optional_u32(&field(o, "maxDistanceTests")?, "options.maxDistanceTests")?;
    Ok((config, max_distance_tests))
}

/// Interior vertices by valence: entry `k` counts those with `k` neighbours (the last entry
/// gathers 12 and more).
fn valence_histogram(triangles: &[[u32; 3]]) -> Vec<u32> {
    let mut directed = BTreeSet::new();
    let mut neighbours: BTreeMap<u32, BTreeSet<u32>> = BTreeMap::new();
    for t in triangles {
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            directed.insert((a, b));
            neighbours.entry(a).or_default().insert(b);
            neighbours.entry(b).or_default().insert(a);
        }
    }
    let mut on_boundary = BTreeSet::new();
    for &(a, b) in &directed {
        if !directed.contains(&(b, a)) {
            on_boundary.insert(a);
            on_boundary.insert(b);
        }
    }
    let mut histogram = vec![0u32; 13];
    for (v, n) in &neighbours {
        if !on_boundary.contains(v)
            && let Some(slot) = histogram.get_mut(n.len().min(12))
        {
            *slot += 1;
        }
    }
    histogram
}

fn figures(q: &MeshQuality, triangles: &[[u32; 3]]) -> Result<Object, JsError> {
    let o = Object::new();
    set(&o, "triangles", q.triangles as f64)?;
    set(&o, "vertices", q.vertices as f64)?;
    set(&o, "valence6Percent", q.valence_6_percent)?;
    set(&o, "minAngleOffBoundary", q.min_angle_off_boundary)?;
    set(&o, "under30Percent", q.under_30_percent)?;
    set(&o, "meanEdge", q.mean_edge)?;
    set(&o, "edgeCv", q.edge_cv)?;
    let histogram = Uint32Array::from(valence_histogram(triangles).as_slice());
    set(&o, "valences", histogram)?;
    Ok(o)
}

/// Remeshes the triangle mesh `positions` (x, y, z per vertex) / `indices` (three per
/// triangle; `null` for non-indexed geometry) toward uniform, near-equilateral triangles on
/// its surface, exactly as the native `meshq remesh` does (the same output, bit for bit).
///
/// `options`: `{ targetLength?, targetRatio?, iterations?, featureAngle?, maxDistanceTests? }`
/// — the target edge length in the mesh's units, or as a multiple of the mean edge length
/// (default 1), the iteration count (default 10), the crease angle in degrees to keep (default
/// none) and the most point–triangle tests the distance report may make (a whole number;
/// default 2²⁰ + 256 per triangle of the input and the result).
///
/// Returns `{ positions: Float32Array, indices: Uint32Array, iterations, splits, collapses,
/// flips, relaxed, creases, peakVertices, peakTriangles, distance, distanceSamples,
/// distanceSamplesMeasured, before, after }` (the peaks: the
/// most vertices and triangles held at once), where `before` and `after` hold `triangles`,
/// `vertices`, `valence6Percent`, `minAngleOffBoundary` (degrees), `under30Percent`,
/// `meanEdge`, `edgeCv` and `valences` (interior vertices by valence, the last entry 12 and
/// more), and `distance` is the two-sided distance to the input (sampled at vertices and
/// centroids) over the input's bounding-box diagonal: the largest over the
/// `distanceSamplesMeasured` of the `distanceSamples` samples the test cap let it measure
/// (fewer only where no box separates triangles). Throws on a mesh that is not manifold or
/// consistently oriented, naming the edge or vertex.
#[wasm_bindgen(unchecked_return_type = "RemeshResult")]
pub fn remesh(
    #[wasm_bindgen(unchecked_param_type = "Float32Array | ArrayLike<number>")] positions: &JsValue,
    #[wasm_bindgen(unchecked_param_type = "Uint32Array | Uint16Array | ArrayLike<number> | null")]
    indices: Option<JsValue>,
    #[wasm_bindgen(unchecked_param_type = "RemeshOptions | null")] options: Option<JsValue>,
) -> Result<Object, JsValue> {
    let positions = floats_or_numbers(positions, "positions")?;
    if !positions.len().is_multiple_of(3) {
        return Err(range_error("positions must hold x, y, z per vertex"));
    }
    let indices = indices.unwrap_or(JsValue::NULL);
    let options = options.unwrap_or(JsValue::UNDEFINED);
    let indices = match read_indices(&indices)? {
        Some(flat) => flat,
        None => (0..(positions.len() / 3) as u32).collect(),
    };
    let mesh = MeshRef::from_flat(&positions, &indices)
        .and_then(MeshRef::validate)
        .map_err(|e| JsError::new(&e.to_string()))?;
    let (config, max_distance_tests) = config(&options)?;
    let out = Remeshed::of(&mesh, &config).map_err(|e| JsError::new(&e.to_string()))?;
    let budget = max_distance_tests.map_or_else(
        || PairBudget::for_triangles(mesh.triangle_count(), out.triangles.len()),
        |max_tests| PairBudget {
            max_tests: max_tests as usize,
        },
    );
    let distance = out
        .distance_to(&mesh, budget)
        .map_err(|e| JsError::new(&e.to_string()))?;
    let result = Object::new();
    let flat_positions: Vec<f32> = out.positions.iter().flatten().copied().collect();
    let flat_indices: Vec<u32> = out.triangles.iter().flatten().copied().collect();
    set(
        &result,
        "positions",
        Float32Array::from(flat_positions.as_slice()),
    )?;
    set(
        &result,
        "indices",
        Uint32Array::from(flat_indices.as_slice()),
    )?;
    let r = out.report;
    set(&result, "iterations", r.iterations)?;
    set(&result, "splits", r.splits as f64)?;
    set(&result, "collapses", r.collapses as f64)?;
    set(&result, "flips", r.flips as f64)?;
    set(&result, "relaxed", r.relaxed as f64)?;
    set(&result, "creases", r.creases as f64)?;
    set(&result, "peakVertices", r.peak_vertices as f64)?;
    set(&result, "peakTriangles", r.peak_triangles as f64)?;
    set(&result, "distance", distance.relative)?;
    set(&result, "distanceSamples", distance.samples as f64)?;
    set(&result, "distanceSamplesMeasured", distance.measured as f64)?;
    set(&result, "before", figures(&out.before, mesh.triangles())?)?;
    set(&result, "after", figures(&out.after, &out.triangles)?)?;
    Ok(result)
}
