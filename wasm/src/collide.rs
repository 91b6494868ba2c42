//! Where meshes meet: two `MeshBvh`s (the second placed by a 4×4 matrix), or one with itself.

use std::borrow::Cow;

use js_sys::{Float32Array, Object, Uint32Array};
use meshq::Traverse;
use meshq::advanced::{BvhNode, TreeArrays};
use meshq::bvh::{BuildConfig, Bvh};
use meshq::collide::{
    Affine, CrossingSegment, DistanceLimits, Found, PairBudget, TrianglePair, intersecting_pairs,
    intersection_segments, mesh_distance, meshes_intersect, self_intersecting_pairs,
};
use meshq::error::PairBudgetSpent;
use meshq::owned::{MeshBvh as CoreBvh, MeshIndex};
use meshq::query::{PackedTriangles, With};
use wasm_bindgen::prelude::*;

use crate::MeshBvh;
use crate::args::{max_distance, number, range_error};
use crate::fields::{optional_matrix, optional_u32};
use crate::js_objects::{meshq_mesh_distance, set};

/// The BVH the checks walk: the structure itself when it is one, else one built here over the
/// same mesh (a k-d tree, octree or grid is not a tree of boxes).
fn bvh_of(index: &MeshIndex) -> Result<Cow<'_, CoreBvh>, JsError> {
    match index {
        MeshIndex::Bvh(bvh) => Ok(Cow::Borrowed(bvh)),
        other => CoreBvh::build(&other.mesh(), &BuildConfig::default())
            .map(Cow::Owned)
            .map_err(|e| JsError::new(&e.to_string())),
    }
}

/// The placement from `matrix`: 16 numbers in column-major order (three.js
/// `Matrix4.elements`), or the identity when absent.
fn placement(matrix: Option<JsValue>) -> Result<Option<Affine>, JsValue> {
    let Some(m) = optional_matrix(&matrix.unwrap_or(JsValue::UNDEFINED), "matrix")? else {
        return Ok(None);
    };
    Affine::from_cols_4x4(&m)
        .map(Some)
        .map_err(|e| range_error(&format!("matrix: {e}")))
}

/// Pairs returned when `maxPairs` is omitted: 2²⁰ (8 MiB of indices); `total` and
/// `overflowed` tell when there were more.
const DEFAULT_MAX_PAIRS: u32 = 1 << 20;

/// `maxPairs`: omitted → [`DEFAULT_MAX_PAIRS`]; otherwise a whole number.
fn pair_limit(max_pairs: Option<JsValue>) -> Result<u32, JsValue> {
    let given = optional_u32(&max_pairs.unwrap_or(JsValue::UNDEFINED), "maxPairs")?;
    Ok(given.unwrap_or(DEFAULT_MAX_PAIRS))
}

/// `maxTests`: omitted → [`PairBudget::for_triangles`] of the two meshes; otherwise a whole
/// number of triangle pairs.
fn test_budget(max_tests: Option<JsValue>, a: usize, b: usize) -> Result<PairBudget, JsValue> {
    let given = optional_u32(&max_tests.unwrap_or(JsValue::UNDEFINED), "maxTests")?;
    Ok(given.map_or_else(
        || PairBudget::for_triangles(a, b),
        |max_tests| PairBudget {
            max_tests: max_tests as usize,
        },
    ))
}

/// `stopAt`: omitted or `null` → 0 (stop only where the meshes meet); otherwise a number ≥ 0.
fn stop_distance(value: &JsValue) -> Result<f32, JsValue> {
    if value.is_undefined() || value.is_null() {
        return Ok(0.0);
    }
    let x = number(value, "stopAt")?;
    if !(x >= 0.0) {
        return Err(range_error("stopAt must be a number ≥ 0 (or omitted)"));
    }
    Ok(x as f32)
}

/// A spent budget as a `RangeError` naming the option that raises it.
fn spent(error: PairBudgetSpent) -> JsValue {
    range_error(&format!("{error} (maxTests)"))
}

/// Triangle counts of the two meshes.
fn triangle_counts(one: &MeshBvh, other: &MeshBvh) -> (usize, usize) {
    (
        one.storage.scene.mesh().triangle_count(),
        other.storage.scene.mesh().triangle_count(),
    )
}

/// The two meshes' trees with their packed triangles, as the mesh–mesh queries take them.
type Walked<'a> = With<'a, Bvh<'a>, PackedTriangles<'a>>;

/// Runs `query` on the trees of `one` and `other` (see [`bvh_of`]).
fn on_both<R>(
    one: &MeshBvh,
    other: &MeshBvh,
    query: impl FnOnce(Walked<'_>, Walked<'_>) -> R,
) -> Result<R, JsError> {
    let (a, b) = (bvh_of(&one.storage.scene)?, bvh_of(&other.storage.scene)?);
    let (ta, tb, pa, pb) = (a.bvh(), b.bvh(), a.packed(), b.packed());
    Ok(query(ta.with(&pa), tb.with(&pb)))
}

/// `{ pairs: Uint32Array (a, b per pair), total, tested, overflowed }`.
fn pairs_object(pairs: &[TrianglePair], found: Found) -> Result<Object, JsError> {
    let flat: Vec<u32> = pairs[..found.written]
        .iter()
        .flat_map(|p| [p.a, p.b])
        .collect();
    let out = Object::new();
    set(&out, "pairs", Uint32Array::from(flat.as_slice()))?;
    set(&out, "total", found.total as f64)?;
    set(&out, "tested", found.tested as f64)?;
    set(&out, "overflowed", found.overflowed())?;
    Ok(out)
}

/// Room for results: as many as were found (counted by a first pass that stores none), at
/// most `limit`, so a large `maxPairs` allocates nothing more.
fn room(
    limit: u32,
    count: impl FnOnce() -> Result<Found, PairBudgetSpent>,
) -> Result<usize, JsValue> {
    let found = count().map_err(spent)?;
    Ok(found.total.min(limit as usize))
}

#[wasm_bindgen]
impl MeshBvh {
    /// Whether this mesh meets `other`, placed in this mesh's frame by `matrix`
    /// (`Matrix4Like`: 16 numbers, column-major like three.js `Matrix4.elements`, or a
    /// `Matrix4`; omitted or `null`: as it is). Touching counts: a shared point, a corner on a
    /// face, a coplanar overlap. Stops at the first pair found. Throws a `TypeError` or
    /// `RangeError` for a matrix that is not 16 finite numbers with a bottom row `0, 0, 0, 1`.
    ///
    /// `maxTests` is the most triangle pairs the walk may consider (a whole number; omitted:
    /// 2²⁰ + 256 per triangle of the two meshes, far above what well-shaped meshes need).
    /// When it is spent before an answer — many triangles in one place, such as copies of one
    /// triangle — the call throws a `RangeError` instead of working for minutes.
    #[wasm_bindgen(js_name = intersectsMesh)]
    pub fn intersects_mesh(
        &self,
        other: &MeshBvh,
        #[wasm_bindgen(unchecked_param_type = "Matrix4Like | null")] matrix: Option<JsValue>,
        #[wasm_bindgen(js_name = maxTests, unchecked_param_type = "number | null")]
        max_tests: Option<JsValue>,
    ) -> Result<bool, JsValue> {
        let place = placement(matrix)?;
        let (na, nb) = triangle_counts(self, other);
        let budget = test_budget(max_tests, na, nb)?;
        on_both(self, other, |a, b| {
            meshes_intersect(a, b, place.as_ref(), budget)
        })?
        .map_err(spent)
    }

    /// Every pair of triangles (this mesh's, `other`'s) that meets, with `other` placed by
    /// `matrix` as in `intersectsMesh`: `{ pairs: Uint32Array, total, tested, overflowed }`,
    /// `pairs` holding triangle indices two by two. `maxPairs` caps how many are returned
    /// (a whole number; `total` still counts all, `overflowed` says some were left out);
    /// omitted: 2²⁰. `maxTests` bounds the work as in `intersectsMesh`.
    #[wasm_bindgen(js_name = intersectingPairs, unchecked_return_type = "PairsResult")]
    pub fn intersecting_pairs(
        &self,
        other: &MeshBvh,
        #[wasm_bindgen(unchecked_param_type = "Matrix4Like | null")] matrix: Option<JsValue>,
        #[wasm_bindgen(js_name = maxPairs, unchecked_param_type = "number | null")]
        max_pairs: Option<JsValue>,
        #[wasm_bindgen(js_name = maxTests, unchecked_param_type = "number | null")]
        max_tests: Option<JsValue>,
    ) -> Result<Object, JsValue> {
        let place = placement(matrix)?;
        let max_pairs = pair_limit(max_pairs)?;
        let (na, nb) = triangle_counts(self, other);
        let budget = test_budget(max_tests, na, nb)?;
        let (pairs, found) = on_both(self, other, |a, b| {
            let n = room(max_pairs, || {
                intersecting_pairs(a, b, place.as_ref(), budget, &mut [])
            })?;
            let mut pairs = vec![TrianglePair::default(); n];
            let found =
                intersecting_pairs(a, b, place.as_ref(), budget, &mut pairs).map_err(spent)?;
            Ok::<_, JsValue>((pairs, found))
        })??;
        Ok(pairs_object(&pairs, found)?)
    }

    /// Where this mesh and `other` (placed by `matrix`) cross, for drawing: a `Float32Array`
    /// with 6 numbers per segment (start x, y, z, end x, y, z) in this mesh's frame, one
    /// segment per pair of crossing triangles. Coplanar overlaps have no segment and are
    /// left out. At most 2²⁰ segments (the first in walk order); `maxTests` bounds the work
    /// as in `intersectsMesh`.
    #[wasm_bindgen(js_name = intersectionSegments)]
    pub fn intersection_segments(
        &self,
        other: &MeshBvh,
        #[wasm_bindgen(unchecked_param_type = "Matrix4Like | null")] matrix: Option<JsValue>,
        #[wasm_bindgen(js_name = maxTests, unchecked_param_type = "number | null")]
        max_tests: Option<JsValue>,
    ) -> Result<Float32Array, JsValue> {
        let place = placement(matrix)?;
        let (na, nb) = triangle_counts(self, other);
        let budget = test_budget(max_tests, na, nb)?;
        let segments = on_both(self, other, |a, b| {
            let n = room(DEFAULT_MAX_PAIRS, || {
                intersection_segments(a, b, place.as_ref(), budget, &mut [])
            })?;
            let empty = CrossingSegment {
                pair: TrianglePair::default(),
                start: glam::Vec3::ZERO,
                end: glam::Vec3::ZERO,
            };
            let mut segments = vec![empty; n];
            let found = intersection_segments(a, b, place.as_ref(), budget, &mut segments)
                .map_err(spent)?;
            segments.truncate(found.written);
            Ok::<_, JsValue>(segments)
        })??;
        let flat: Vec<f32> = segments
            .iter()
            .flat_map(|s| [s.start.to_array(), s.end.to_array()])
            .flatten()
            .collect();
        Ok(Float32Array::from(flat.as_slice()))
    }

    /// The closest pair of points of this mesh and `other`, placed in this mesh's frame by
    /// `matrix` as in `intersectsMesh`: `{ distance, pointA, pointB, triangleA, triangleB }`
    /// (`MeshDistance`, both points in this mesh's frame), or `null` when no pair is within
    /// `maxDistance` (omitted or `null`: any distance; a small bound answers "within d?"
    /// fast). Meshes that meet (touching counts) are at distance exactly 0. `stopAt` (omitted:
    /// 0) ends the search at the first pair found that close, though a closer one may exist
    /// (three-mesh-bvh's `minThreshold`). Apart, the distance is the smallest to within a
    /// factor 1 + 2⁻¹⁷; ties go to the first pair found, the same on every target.
    /// `maxTests` bounds the work as in `intersectsMesh`.
    #[wasm_bindgen(js_name = distanceToMesh, unchecked_return_type = "MeshDistance | null")]
    pub fn distance_to_mesh(
        &self,
        other: &MeshBvh,
        #[wasm_bindgen(unchecked_param_type = "Matrix4Like | null")] matrix: Option<JsValue>,
        #[wasm_bindgen(js_name = maxDistance, unchecked_param_type = "number | null")]
        max_distance_in: Option<JsValue>,
        #[wasm_bindgen(js_name = stopAt, unchecked_param_type = "number | null")]
        stop_at_in: Option<JsValue>,
        #[wasm_bindgen(js_name = maxTests, unchecked_param_type = "number | null")]
        max_tests: Option<JsValue>,
    ) -> Result<JsValue, JsValue> {
        let place = placement(matrix)?;
        let limit = max_distance(&max_distance_in.unwrap_or(JsValue::UNDEFINED))?;
        let stop_at = stop_distance(&stop_at_in.unwrap_or(JsValue::UNDEFINED))?;
        let (na, nb) = triangle_counts(self, other);
        let budget = test_budget(max_tests, na, nb)?;
        let limits = DistanceLimits {
            max_distance: limit,
            stop_at,
        };
        let found = on_both(self, other, |a, b| {
            mesh_distance(a, b, place.as_ref(), limits, budget)
        })?
        .map_err(spent)?;
        Ok(found.map_or(JsValue::NULL, |f| {
            meshq_mesh_distance(
                f.distance,
                f.on_a.x,
                f.on_a.y,
                f.on_a.z,
                f.on_b.x,
                f.on_b.y,
                f.on_b.z,
                f.triangle_a,
                f.triangle_b,
            )
        }))
    }

    /// Where this mesh meets itself: pairs of its triangles (lower index first) that meet
    /// beyond the corners or edge they share (crossing beyond a shared corner, or folded over
    /// a neighbour); triangles sharing nothing count when they touch at all. Corners are shared
    /// by index or by position (within about 2⁻²⁰ of the coordinates' magnitude), so an
    /// unwelded mesh's seams do not count. Returns
    /// `{ pairs, total, tested, overflowed }` as `intersectingPairs` does, `maxPairs` (omitted:
    /// 2²⁰) and `maxTests` (omitted: 2²⁰ + 512 per triangle) as there.
    #[wasm_bindgen(js_name = selfIntersections, unchecked_return_type = "PairsResult")]
    pub fn self_intersections(
        &self,
        #[wasm_bindgen(js_name = maxPairs, unchecked_param_type = "number | null")]
        max_pairs: Option<JsValue>,
        #[wasm_bindgen(js_name = maxTests, unchecked_param_type = "number | null")]
        max_tests: Option<JsValue>,
    ) -> Result<Object, JsValue> {
        let max_pairs = pair_limit(max_pairs)?;
        let bvh = bvh_of(&self.storage.scene)?;
        let (tree, mesh) = (bvh.bvh(), bvh.mesh());
        let n = mesh.triangle_count();
        let budget = test_budget(max_tests, n, n)?;
        let room = room(max_pairs, || {
            self_intersecting_pairs(&tree, &mesh, budget, &mut [])
        })?;
        let mut pairs = vec![TrianglePair::default(); room];
        let found = self_intersecting_pairs(&tree, &mesh, budget, &mut pairs).map_err(spent)?;
        Ok(pairs_object(&pairs, found)?)
    }
}

#[wasm_bindgen]
impl MeshBvh {
    /// The BVH as flat arrays, for walks written in JavaScript (the three.js drop-in's
    /// `shapecast`): `{ boxes: Float32Array (minX, minY, minZ, maxX, maxY, maxZ per node),
    /// first: Uint32Array, count: Uint32Array, order: Uint32Array }`. Node 0 is the root; an
    /// inner node (`count` 0) has children `first` and `first + 1`; a leaf holds the
    /// triangles `order[first .. first + count]`. Boxes are padded slightly, so they hold
    /// their triangles despite rounding. For a k-d tree, octree or grid, the BVH is built
    /// over the same mesh for the call.
    #[wasm_bindgen(js_name = treeArrays, unchecked_return_type = "TreeArrays")]
    pub fn tree_arrays(&self) -> Result<Object, JsError> {
        let bvh = bvh_of(&self.storage.scene)?;
        let tree = bvh.bvh();
        let nodes: Vec<BvhNode> = (0..tree.node_count())
            .filter_map(|i| tree.node(i))
            .collect();
        let mut order = vec![0u32; tree.slot_count()];
        for n in nodes.iter().filter(|n| n.is_leaf()) {
            let ids = tree.leaf_triangles(n.first as usize, n.count as usize);
            for (slot, tri) in ids.into_iter().flatten() {
                if let Some(s) = order.get_mut(slot) {
                    *s = tri;
                }
            }
        }
        let boxes: Vec<f32> = nodes
            .iter()
            .flat_map(|n| [n.min, n.max])
            .flatten()
            .collect();
        let first: Vec<u32> = nodes.iter().map(|n| n.first).collect();
        let count: Vec<u32> = nodes.iter().map(|n| n.count).collect();
        let out = Object::new();
        set(&out, "boxes", Float32Array::from(boxes.as_slice()))?;
        set(&out, "first", Uint32Array::from(first.as_slice()))?;
        set(&out, "count", Uint32Array::from(count.as_slice()))?;
        set(&out, "order", Uint32Array::from(order.as_slice()))?;
        Ok(out)
    }
}
