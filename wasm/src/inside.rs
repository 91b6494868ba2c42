//! Inside, outside and how far: winding numbers, containment and signed distance on a
//! `MeshBvh`, one point at a time or a batch per call. The winding-number expansions are made
//! by the first such call (a BVH's own tree; for a k-d tree, octree or grid, a BVH of the same
//! mesh beside it) and kept.

use glam::Vec3;
use meshq::MeshQuery;
use meshq::bvh::BuildConfig;
use meshq::inside::{SampleGrid, WindingAccuracy, WindingTree};
use meshq::owned::{MeshBvh as OwnedBvh, MeshIndex};
use wasm_bindgen::prelude::*;

use crate::MeshBvh;
use crate::args::{
    JsNumber, floats, max_distance, number, output_f32, output_u32, range_error, vector,
};
use crate::batch::{MISS_DISTANCE, MISS_TRIANGLE};
use crate::js_objects::{meshq_signed_distance, set};
use crate::storage::Storage;

/// The `accuracy` argument: omitted or `null` for the default far ratio (2), a number ≥ 1, or
/// `Infinity` for the exact sum.
fn accuracy(value: &JsValue) -> Result<WindingAccuracy, JsValue> {
    if value.is_undefined() || value.is_null() {
        return Ok(WindingAccuracy::DEFAULT);
    }
    let x = number(value, "accuracy")?;
    WindingAccuracy::new(x as f32).ok_or_else(|| {
        range_error(&format!(
            "accuracy must be a number ≥ 1 (Infinity: exact), got {}",
            JsNumber(x)
        ))
    })
}

/// What a signed distance takes its sign from: `accuracy` a winding-number accuracy, or the
/// string `'pseudo-normal'`.
enum SignBy {
    Winding(WindingAccuracy),
    PseudoNormal,
}

/// `accuracy` of the signed-distance calls: as [`accuracy`], or `'pseudo-normal'`.
fn sign_by(value: &JsValue) -> Result<SignBy, JsValue> {
    match value.as_string().as_deref() {
        Some("pseudo-normal") => Ok(SignBy::PseudoNormal),
        Some(other) => Err(range_error(&format!(
            "accuracy must be a number ≥ 1 or 'pseudo-normal', got '{other}'"
        ))),
        None => accuracy(value).map(SignBy::Winding),
    }
}

impl Storage {
    /// The mesh's pseudo-normals, made once; an `Error` naming the edge for a mesh that is
    /// not closed, manifold and consistently oriented.
    fn pseudo_normals(&mut self) -> Result<&meshq::owned::MeshPseudoNormals, JsValue> {
        if self.pseudo.is_none() {
            let made = meshq::owned::MeshPseudoNormals::of(&self.scene.mesh())
                .map_err(|e| JsValue::from(JsError::new(&e.to_string())))?;
            self.pseudo = Some(made);
        }
        self.pseudo
            .as_ref()
            .ok_or_else(|| JsValue::from(JsError::new("pseudo-normals missing")))
    }

    /// Makes the winding-number expansions, once.
    fn prepare_winding(&mut self) -> Result<(), JsValue> {
        let failed = |e: meshq::error::BuildError| JsValue::from(JsError::new(&e.to_string()));
        match &mut self.scene {
            MeshIndex::Bvh(bvh) => bvh.prepare_winding_numbers().map_err(failed)?,
            other => {
                if self.winding.is_none() {
                    let bvh = OwnedBvh::build(&other.mesh(), &BuildConfig::default())
                        .and_then(OwnedBvh::with_winding_numbers)
                        .map_err(failed)?;
                    self.winding = Some(bvh);
                }
            }
        }
        Ok(())
    }

    /// The winding-number tree [`Storage::prepare_winding`] made.
    fn winding(&self) -> Result<WindingTree<'_>, JsValue> {
        let bvh = match (&self.scene, &self.winding) {
            (MeshIndex::Bvh(bvh), _) | (_, Some(bvh)) => bvh,
            _ => return Err(JsError::new("no winding-number tree").into()),
        };
        bvh.winding()
            .ok_or_else(|| JsError::new("the winding-number tree was not prepared").into())
    }
}

/// The points of a batch: a `Float32Array` of 3 numbers per point.
fn batch_points(points: &JsValue) -> Result<Vec<Vec3>, JsValue> {
    let values = floats(points, "points")?;
    if !values.len().is_multiple_of(3) {
        return Err(range_error(&format!(
            "points hold {} numbers, not a multiple of 3",
            values.len()
        )));
    }
    Ok(values
        .chunks_exact(3)
        .map(|p| Vec3::new(p[0], p[1], p[2]))
        .collect())
}

#[wasm_bindgen]
impl MeshBvh {
    /// The generalized winding number of the mesh at `point` (`Vec3Like`): 1 inside a closed
    /// mesh whose triangles face outwards, 0 outside, fractions near holes, so that open,
    /// non-manifold and self-intersecting meshes have an inside too. `accuracy` (omitted: 2) is
    /// the far ratio of the fast winding number: a group of triangles counts by its expansion
    /// when the point is farther than `accuracy` times its radius (larger is more exact and
    /// slower; `Infinity` sums every triangle). The first call prepares the expansions.
    #[wasm_bindgen(js_name = windingNumber)]
    pub fn winding_number(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] point: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "number | null")] accuracy_in: Option<JsValue>,
    ) -> Result<f32, JsValue> {
        let p = vector(point, "point")?;
        let accuracy = accuracy(&accuracy_in.unwrap_or(JsValue::UNDEFINED))?;
        Ok({
            self.storage.prepare_winding()?;
            self.storage.winding()?
        }
        .winding_number(p, accuracy))
    }

    /// Whether `point` (`Vec3Like`) is inside the mesh: `|windingNumber| ≥ 0.5`. `accuracy` as
    /// for `windingNumber`.
    pub fn contains(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] point: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "number | null")] accuracy_in: Option<JsValue>,
    ) -> Result<bool, JsValue> {
        let p = vector(point, "point")?;
        let accuracy = accuracy(&accuracy_in.unwrap_or(JsValue::UNDEFINED))?;
        Ok({
            self.storage.prepare_winding()?;
            self.storage.winding()?
        }
        .contains(p, accuracy))
    }

    /// The signed distance from `point` (`Vec3Like`) to the mesh, negative inside: the closest
    /// surface point within `maxDistance` (omitted or `null`: any distance), exactly as
    /// `closestPoint` finds it, signed by the winding number (`accuracy` as for
    /// `windingNumber`), or, with `accuracy` `'pseudo-normal'`, by the angle-weighted
    /// pseudo-normal at the closest point (no winding number computed; for closed, manifold,
    /// consistently oriented meshes: others throw an `Error` naming an open or non-manifold
    /// edge; `windingNumber` is then 1 inside, 0 outside). Returns `{ distance, point,
    /// triangle, u, v, normal, windingNumber }` (`SignedDistance`) or `null` when nothing lies
    /// within `maxDistance`.
    #[wasm_bindgen(js_name = signedDistance, unchecked_return_type = "SignedDistance | null")]
    pub fn signed_distance(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] point: &JsValue,
        #[wasm_bindgen(js_name = maxDistance, unchecked_param_type = "number | null")]
        max_distance_in: Option<JsValue>,
        #[wasm_bindgen(unchecked_param_type = "number | 'pseudo-normal' | null")]
        accuracy_in: Option<JsValue>,
    ) -> Result<JsValue, JsValue> {
        let p = vector(point, "point")?;
        let limit = max_distance(&max_distance_in.unwrap_or(JsValue::UNDEFINED))?;
        let found = match sign_by(&accuracy_in.unwrap_or(JsValue::UNDEFINED))? {
            SignBy::Winding(accuracy) => {
                self.storage.prepare_winding()?;
                self.storage.winding()?.signed_distance(p, limit, accuracy)
            }
            SignBy::PseudoNormal => {
                self.storage.pseudo_normals()?;
                let (scene, normals) = (&self.storage.scene, &self.storage.pseudo);
                normals
                    .as_ref()
                    .and_then(|n| n.view().signed_distance(scene, &scene.mesh(), p, limit))
            }
        };
        let Some(s) = found else {
            return Ok(JsValue::NULL);
        };
        let n = self
            .storage
            .scene
            .mesh()
            .triangle(s.closest.tri)
            .and_then(|t| t.unit_normal())
            .unwrap_or(Vec3::ZERO);
        let c = s.closest;
        Ok(meshq_signed_distance(
            s.distance,
            c.point.x,
            c.point.y,
            c.point.z,
            c.tri,
            c.u,
            c.v,
            n.x,
            n.y,
            n.z,
            s.winding_number,
        ))
    }

    /// The winding number of every point of `points` (a `Float32Array`, 3 numbers per point)
    /// into `numbers[i]` (a `Float32Array`, one per point), each exactly `windingNumber`'s;
    /// `accuracy` as there. Returns the number of points inside (`|w| ≥ 0.5`).
    #[wasm_bindgen(js_name = windingNumberBatch)]
    pub fn winding_number_batch(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "Float32Array")] points: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Float32Array")] numbers: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "number | null")] accuracy_in: Option<JsValue>,
    ) -> Result<u32, JsValue> {
        let queries = batch_points(points)?;
        let out = output_f32(numbers, "numbers", queries.len(), " (one per point)")?;
        let accuracy = accuracy(&accuracy_in.unwrap_or(JsValue::UNDEFINED))?;
        let tree = {
            self.storage.prepare_winding()?;
            self.storage.winding()?
        };
        let mut answers = vec![0.0f32; queries.len()];
        let mut keys = vec![0u64; queries.len()];
        tree.winding_numbers(&queries, accuracy, &mut keys, &mut answers)
            .map_err(|e| JsValue::from(JsError::new(&e.to_string())))?;
        out.copy_from(&answers);
        Ok(answers.iter().filter(|w| w.abs() >= 0.5).count() as u32)
    }

    /// The signed distance of every point of `points` (a `Float32Array`, 3 numbers per point)
    /// within `maxDistance` (omitted: any distance) into `distances[i]` (a `Float32Array`,
    /// negative inside) and the closest point's triangle into `triangles[i]` (a
    /// `Uint32Array`), each exactly `signedDistance`'s; a point that finds nothing writes
    /// `MISS_DISTANCE` and `MISS_TRIANGLE`. `accuracy` as for `signedDistance` (a ratio, or
    /// `'pseudo-normal'`). Returns the number of points found.
    #[wasm_bindgen(js_name = signedDistanceBatch)]
    pub fn signed_distance_batch(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "Float32Array")] points: &JsValue,
        #[wasm_bindgen(js_name = maxDistance, unchecked_param_type = "number | null | undefined")]
        max_distance_in: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Float32Array")] distances: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Uint32Array")] triangles: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "number | 'pseudo-normal' | null")]
        accuracy_in: Option<JsValue>,
    ) -> Result<u32, JsValue> {
        let queries = batch_points(points)?;
        let n = queries.len();
        let limit = max_distance(max_distance_in)?;
        let distances = output_f32(distances, "distances", n, " (one per point)")?;
        let triangles = output_u32(triangles, "triangles", n, " (one per point)")?;
        crate::batch::outputs_apart(&[(&distances, "distances"), (&triangles, "triangles")])?;
        // Each answer: the signed distance and the closest point's triangle.
        let mut answers: Vec<Option<(f32, u32)>> = vec![None; n];
        let mut keys = vec![0u64; n];
        let failed = |e: meshq::error::BatchError| JsValue::from(JsError::new(&e.to_string()));
        match sign_by(&accuracy_in.unwrap_or(JsValue::UNDEFINED))? {
            SignBy::Winding(accuracy) => {
                let tree = {
                    self.storage.prepare_winding()?;
                    self.storage.winding()?
                };
                let mut signed = vec![None; n];
                tree.signed_distances(
                    &self.storage.scene,
                    &queries,
                    limit,
                    accuracy,
                    &mut keys,
                    &mut signed,
                )
                .map_err(failed)?;
                for (answer, s) in answers.iter_mut().zip(&signed) {
                    *answer = s.map(|s| (s.distance, s.closest.tri));
                }
            }
            SignBy::PseudoNormal => {
                self.storage.pseudo_normals()?;
                let scene = &self.storage.scene;
                let mut closest = vec![None; n];
                MeshQuery::closest_points(scene, &queries, limit, &mut keys, &mut closest)
                    .map_err(failed)?;
                let mesh = scene.mesh();
                if let Some(normals) = &self.storage.pseudo {
                    for ((answer, found), &p) in answers.iter_mut().zip(&closest).zip(&queries) {
                        *answer = found.and_then(|c| {
                            let inside = normals.view().inside_at(&mesh, p, &c)?;
                            let d = c.distance_from(p);
                            Some((if inside { -d } else { d }, c.tri))
                        });
                    }
                }
            }
        }
        let (mut d, mut t) = (Vec::with_capacity(n), Vec::with_capacity(n));
        for a in &answers {
            d.push(a.map_or(MISS_DISTANCE, |(distance, _)| distance));
            t.push(a.map_or(MISS_TRIANGLE, |(_, tri)| tri));
        }
        distances.copy_from(&d);
        triangles.copy_from(&t);
        Ok(answers.iter().filter(|a| a.is_some()).count() as u32)
    }

    /// A signed-distance volume: `resolution` samples (2–1024) along the longest axis of the
    /// mesh's box grown by `padding` (omitted: 0.1) times that axis on every side, cubic cells,
    /// values negative inside; samples farther than `band` (omitted: no band) hold `±band`.
    /// `accuracy` as for `windingNumber`. Returns `{ values, counts, origin, spacing }`:
    /// `values` a `Float32Array` with x fastest (ready for a `Data3DTexture` of size
    /// `counts`), `origin` the first sample `[x, y, z]`, `spacing` the cell size.
    #[wasm_bindgen(js_name = signedDistanceGrid, unchecked_return_type = "SignedDistanceGrid")]
    pub fn signed_distance_grid(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "number")] resolution: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "number | null")] padding: Option<JsValue>,
        #[wasm_bindgen(unchecked_param_type = "number | null")] band: Option<JsValue>,
        #[wasm_bindgen(unchecked_param_type = "number | null")] accuracy_in: Option<JsValue>,
    ) -> Result<JsValue, JsValue> {
        let samples = number(resolution, "resolution")?;
        if !(2.0..=1024.0).contains(&samples) || samples.fract() != 0.0 {
            return Err(range_error(&format!(
                "resolution must be a whole number from 2 to 1024, got {}",
                JsNumber(samples)
            )));
        }
        let padding = match padding {
            None => 0.1,
            Some(v) if v.is_undefined() || v.is_null() => 0.1,
            Some(v) => {
                let p = number(&v, "padding")?;
                if !(p >= 0.0 && p.is_finite()) {
                    return Err(range_error(&format!(
                        "padding must be a number ≥ 0, got {}",
                        JsNumber(p)
                    )));
                }
                p as f32
            }
        };
        let band = max_distance(&band.unwrap_or(JsValue::UNDEFINED))
            .map_err(|_| range_error("band must be a number ≥ 0 (or omitted for none)"))?;
        let accuracy = accuracy(&accuracy_in.unwrap_or(JsValue::UNDEFINED))?;
        self.storage.prepare_winding()?;
        let tree = self.storage.winding()?;
        let grid = SampleGrid::cubic(tree.mesh().bounds(), samples as u32, padding)
            .ok_or_else(|| range_error("the mesh has no extent to sample"))?;
        let mut values = vec![0.0f32; grid.len()];
        tree.signed_distance_grid(&self.storage.scene, &grid, band, accuracy, 0, &mut values)
            .map_err(|e| JsValue::from(JsError::new(&e.to_string())))?;
        let out = js_sys::Object::new();
        let counts = grid.counts();
        set(&out, "values", js_sys::Float32Array::from(&values[..]))?;
        set(&out, "counts", js_sys::Uint32Array::from(&counts[..]))?;
        set(
            &out,
            "origin",
            js_sys::Float32Array::from(&grid.min().to_array()[..]),
        )?;
        set(&out, "spacing", grid.spacing().x)?;
        Ok(out.into())
    }
}
