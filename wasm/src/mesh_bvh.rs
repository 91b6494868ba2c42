//! The `MeshBvh` class: one mesh with its structure (a BVH by default), built here or loaded
//! from a blob.

use glam::Vec3;
use meshq::RayOptions;
use meshq::blob::MeshLayout;
use meshq::math::{ClosestPoint, Ray, RayHit};
use meshq::owned::MeshIndex;
use wasm_bindgen::prelude::*;

use crate::args::{
    finite_number, floats_or_numbers, max_distance, range, range_error, range_numbers, side,
    side_number, type_error, vector,
};
use crate::fields::{omitted, optional_choice, required_u32};
use crate::js_objects::{meshq_closest_point, meshq_ray_hit};
use crate::options::build_options;
use crate::storage::Storage;
use wasm_bindgen::JsCast;

/// A triangle mesh and its acceleration structure (a BVH unless `structure` picks a k-d tree,
/// octree or grid), ready for ray and closest-point queries. Every structure gives the same
/// answers, bit for bit.
///
/// Conventions: positions are `x, y, z` triples; triangles are counter-clockwise when seen from
/// their front (as in three.js). Ray directions are used as given, not normalized: a hit's `t`,
/// `near` and `far` are in units of the direction's length (world units for a unit direction,
/// as three.js rays have); `distance` is always Euclidean. On equal distance the lower triangle index wins, so answers are
/// the same on every target. Free the memory with `free()` (or let the garbage collector do it
/// through a `FinalizationRegistry`, where the engine has one).
#[wasm_bindgen]
pub struct MeshBvh {
    pub(crate) storage: Storage,
}

/// The ray `origin + t·direction`, `t` in `[near, far]`: origin and direction as `[x, y, z]` or
/// `Vector3`s, the range omitted for `[0, Infinity]` (see [`crate::args`]).
pub(crate) fn js_ray(
    origin: &JsValue,
    direction: &JsValue,
    near: Option<JsValue>,
    far: Option<JsValue>,
) -> Result<Ray, JsValue> {
    let origin = vector(origin, "origin")?;
    let dir = vector(direction, "direction")?;
    if dir == Vec3::ZERO {
        return Err(range_error("direction must not be zero"));
    }
    let (near, far) = range(&or_undefined(near), &or_undefined(far))?;
    Ok(Ray::new(origin, dir).with_range(near, far))
}

/// An omitted optional argument (`undefined` or `null` arrive as `None`) as `undefined`.
pub(crate) fn or_undefined(value: Option<JsValue>) -> JsValue {
    value.unwrap_or(JsValue::UNDEFINED)
}

/// The faces a single-ray call tests, from its optional `side` (see [`side`]).
pub(crate) fn ray_side(value: Option<JsValue>) -> Result<RayOptions, JsValue> {
    side(&or_undefined(value))
}

/// The same ray from plain numbers (converted by JavaScript on the way in), each checked
/// finite.
#[allow(clippy::too_many_arguments)]
pub(crate) fn xyz_ray(
    ox: f64,
    oy: f64,
    oz: f64,
    dx: f64,
    dy: f64,
    dz: f64,
    near: Option<f64>,
    far: Option<f64>,
) -> Result<Ray, JsValue> {
    let origin = Vec3::new(
        finite_number(ox, "ox")?,
        finite_number(oy, "oy")?,
        finite_number(oz, "oz")?,
    );
    let dir = Vec3::new(
        finite_number(dx, "dx")?,
        finite_number(dy, "dy")?,
        finite_number(dz, "dz")?,
    );
    if dir == Vec3::ZERO {
        return Err(range_error("direction must not be zero"));
    }
    let (near, far) = range_numbers(near, far)?;
    Ok(Ray::new(origin, dir).with_range(near, far))
}

/// The Euclidean distance from the ray's origin to the point at `t`: `t·|direction|`, in
/// double precision from the `f32` values the query used.
fn euclidean(ray: &Ray, t: f32) -> f64 {
    let [x, y, z] = ray.dir.to_array().map(f64::from);
    f64::from(t) * (x * x + y * y + z * z).sqrt()
}

/// The JavaScript `RayHit` object of a core hit.
pub(crate) fn hit_object(views: &Storage, ray: &Ray, hit: RayHit) -> JsValue {
    let p = ray.origin + ray.dir * hit.t;
    let n = views
        .triangle(hit.tri)
        .and_then(|t| t.unit_normal())
        .unwrap_or(Vec3::ZERO);
    let distance = euclidean(ray, hit.t);
    meshq_ray_hit(
        hit.t, distance, p.x, p.y, p.z, hit.tri, hit.u, hit.v, n.x, n.y, n.z,
    )
}

fn closest_object(views: &Storage, query: Vec3, c: ClosestPoint) -> JsValue {
    let n = views
        .triangle(c.tri)
        .and_then(|t| t.unit_normal())
        .unwrap_or(Vec3::ZERO);
    let p = c.point;
    meshq_closest_point(
        c.distance_from(query),
        p.x,
        p.y,
        p.z,
        c.tri,
        c.u,
        c.v,
        n.x,
        n.y,
        n.z,
    )
}

#[wasm_bindgen]
impl MeshBvh {
    /// Builds a structure from the arrays of a three.js `BufferGeometry`: `positions` (a
    /// `Float32Array` or an array of numbers, 3 per vertex) and `indices` (`Uint32Array`,
    /// `Uint16Array`, an array of whole numbers, or omitted / `null` for non-indexed geometry).
    /// `options` (`MeshBvhOptions`, every field optional): `structure` (`"bvh"`, the default,
    /// `"kdtree"`, `"octree"` or `"grid"`: the same answers from each), `quality` (`"balanced"`
    /// binned SAH by default, `"fast"` centre splits, `"high"`), `maxLeafSize`, `bins` and
    /// `maxDepth` (which tune the BVH; the other structures use their default configs),
    /// `spatialSplits` (`true`, or the extra room as a fraction of the triangle count, `0..=4`:
    /// a BVH with spatial splits, for scenes of long crossing triangles; the same answers,
    /// several times the build time), `sweepSah` (`true`, or the triangles between weighed
    /// cuts: nodes split by sweep SAH; the same answers, many times the build time). Throws
    /// a `TypeError` or `RangeError` naming a bad argument or an unknown option, and an `Error`
    /// with the core's message for an invalid mesh (an index out of range, a non-finite
    /// position…).
    pub fn build(
        #[wasm_bindgen(unchecked_param_type = "Float32Array | ArrayLike<number>")]
        positions: &JsValue,
        #[wasm_bindgen(
            unchecked_param_type = "Uint32Array | Uint16Array | ArrayLike<number> | null"
        )]
        indices: Option<JsValue>,
        #[wasm_bindgen(unchecked_param_type = "MeshBvhOptions | null")] options: Option<JsValue>,
    ) -> Result<MeshBvh, JsValue> {
        let positions = floats_or_numbers(positions, "positions")?;
        let choice = build_options(&options.unwrap_or(JsValue::UNDEFINED))?;
        let indices = crate::build::read_indices(&indices.unwrap_or(JsValue::NULL))?;
        let storage = crate::build::build(positions, indices, &choice)?;
        Ok(Self { storage })
    }

    /// Loads a blob baked by `meshq bake` (or `toBlob`) holding any structure, e.g. the bytes
    /// of a fetched file (a `Uint8Array`; a Node `Buffer` is one). The blob is validated once
    /// (checksum, every count, index and range), then decoded into the buffers a build makes,
    /// so queries run as fast as on a built mesh; the bytes are kept for `toBlob`. Throws a
    /// `TypeError` for anything but a `Uint8Array`, and an `Error` naming what is wrong with a
    /// damaged blob, another format version, or a blob baked without its mesh.
    #[wasm_bindgen(js_name = fromBlob)]
    pub fn from_blob(
        #[wasm_bindgen(unchecked_param_type = "Uint8Array")] bytes: &JsValue,
    ) -> Result<MeshBvh, JsValue> {
        let bytes = bytes
            .dyn_ref::<js_sys::Uint8Array>()
            .ok_or_else(|| type_error("a blob must be a Uint8Array (a Buffer is one)"))?
            .to_vec();
        let storage = crate::build::from_blob(bytes)?;
        Ok(Self { storage })
    }

    /// The blob of this mesh and structure, to save and load later with `fromBlob`, whether
    /// this mesh was built or loaded. `layout` (`BlobLayout`): `"indexed"` (positions and
    /// indices; the default), `"packed"` (larger, fastest to query in place) or `"omitted"` (no
    /// mesh; only for readers that have it). A loaded blob is returned as it was loaded when no
    /// layout is asked for, and encoded afresh in the layout asked for otherwise. `winding`
    /// true stores the winding-number expansions too (a BVH only: 112 bytes per node, format
    /// version 6), so that readers answer `windingNumber`, `contains` and `signedDistance`
    /// without working them out, in place on a device; a BVH that already prepared them for an
    /// inside query stores them anyway. Throws a `TypeError` for `winding` on another
    /// structure.
    #[wasm_bindgen(js_name = toBlob)]
    pub fn to_blob(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "BlobLayout | null")] layout: Option<JsValue>,
        #[wasm_bindgen(unchecked_param_type = "boolean | null")] winding: Option<JsValue>,
    ) -> Result<Vec<u8>, JsValue> {
        let winding = match winding {
            Some(v) if !omitted(&v) => Some(v.as_bool().ok_or_else(|| {
                type_error(&format!(
                    "winding must be a boolean, got {}",
                    crate::args::value_kind(&v)
                ))
            })?),
            _ => None,
        };
        let layout = layout.unwrap_or(JsValue::UNDEFINED);
        let mesh_layout =
            match optional_choice(&layout, "layout", &["indexed", "packed", "omitted"])? {
                None | Some("indexed") => MeshLayout::Indexed,
                Some("packed") => MeshLayout::Packed,
                Some(_) => MeshLayout::Omitted,
            };
        let mut afresh = !omitted(&layout);
        if winding == Some(true) {
            let MeshIndex::Bvh(bvh) = &mut self.storage.scene else {
                return Err(type_error("winding applies to a BVH"));
            };
            bvh.prepare_winding_numbers()
                .map_err(|e| JsValue::from(JsError::new(&e.to_string())))?;
            // Loaded bytes hold them only from format version 6 (which is written only with
            // them).
            let stored = self.storage.blob.as_deref().is_some_and(|bytes| {
                meshq::advanced::BlobHeader::read(bytes).is_ok_and(|h| h.version >= 6)
            });
            afresh |= !stored;
        }
        self.blob_bytes(afresh.then_some(mesh_layout))
            .map_err(|e| JsError::new(&e.to_string()).into())
    }

    /// Quantizes the BVH's four-wide nodes to 8-bit child boxes for queries to walk instead of
    /// the eight-wide (or four-wide) tree: half the node memory of four-wide nodes, a quarter
    /// of eight-wide (`queryNodeBytes`), the same answers from every query. Once is enough
    /// (again does nothing). Throws a `TypeError` for a k-d tree, octree or grid.
    #[wasm_bindgen(js_name = compactNodes)]
    pub fn compact_nodes(&mut self) -> Result<(), JsValue> {
        self.relay_nodes("compactNodes", meshq::MeshBvh::compact_nodes)
    }

    /// Collapses the BVH eight-wide for queries to walk (the tree a BVH walks when built or
    /// loaded) instead of four-wide or compact nodes: the same answers from every query. Once
    /// is enough (again does nothing). Throws a `TypeError` for a k-d tree, octree or grid.
    #[wasm_bindgen(js_name = eightWideNodes)]
    pub fn eight_wide_nodes(&mut self) -> Result<(), JsValue> {
        self.relay_nodes("eightWideNodes", meshq::MeshBvh::eight_wide_nodes)
    }

    /// Collapses the BVH four-wide for queries to walk instead of its eight-wide (or compact)
    /// nodes: half the bytes per node (usually a little less memory in all), more node visits
    /// per ray, the same answers from every query. Once is enough (again does nothing). Throws a `TypeError` for a k-d tree,
    /// octree or grid.
    #[wasm_bindgen(js_name = fourWideNodes)]
    pub fn four_wide_nodes(&mut self) -> Result<(), JsValue> {
        self.relay_nodes("fourWideNodes", meshq::MeshBvh::four_wide_nodes)
    }

    /// Bytes of the tree nodes queries walk (the BVH's eight-wide nodes, 256 each, as built
    /// or loaded; 128 each after `fourWideNodes`; 64 each after `compactNodes`); 0 for a k-d
    /// tree, octree or grid.
    #[wasm_bindgen(getter, js_name = queryNodeBytes)]
    pub fn query_node_bytes(&self) -> f64 {
        match &self.storage.scene {
            MeshIndex::Bvh(bvh) => bvh.query_node_bytes() as f64,
            _ => 0.0,
        }
    }

    /// Number of triangles.
    #[wasm_bindgen(getter, js_name = triangleCount)]
    pub fn triangle_count(&self) -> u32 {
        self.storage.triangle_count()
    }

    /// Which structure answers: `"bvh"`, `"kdtree"`, `"octree"` or `"grid"`.
    #[wasm_bindgen(getter, unchecked_return_type = "'bvh' | 'kdtree' | 'octree' | 'grid'")]
    pub fn structure(&self) -> String {
        self.storage.scene.kind().name().to_owned()
    }

    /// Nodes of the BVH, k-d tree or octree; cells of a grid.
    #[wasm_bindgen(getter, js_name = nodeCount)]
    pub fn node_count(&self) -> u32 {
        u32::try_from(self.storage.node_count()).unwrap_or(u32::MAX)
    }

    /// Levels `levelBoxes` shows, `0..depth` (the root is level 0): a BVH's depth, one more
    /// than a k-d tree's or octree's deepest leaf, 1 for a grid.
    #[wasm_bindgen(getter)]
    pub fn depth(&self) -> u32 {
        self.storage.depth()
    }

    /// Whether this came from a blob (`fromBlob`) rather than a build.
    #[wasm_bindgen(getter, js_name = fromBlobBytes)]
    pub fn from_blob_bytes(&self) -> bool {
        self.storage.blob.is_some()
    }

    /// The root box, padded: `[minX, minY, minZ, maxX, maxY, maxZ]`.
    pub fn bounds(&self) -> Vec<f32> {
        let b = self.storage.bounds();
        vec![b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z]
    }

    /// The closest hit of the ray `origin + t·direction` with `t` in `[near, far]`, or
    /// `null`. `origin` and `direction` (`Vec3Like`): `[x, y, z]` (an array or typed array)
    /// or `{x, y, z}` (a three.js `Vector3`), finite, the direction not zero and used as given
    /// (not normalized). `near` and `far` default to `0` and `Infinity`. `side`: `0` front
    /// faces only, `1` back faces only, `2` or omitted both (three.js `FrontSide`, `BackSide`,
    /// `DoubleSide`), or a `RayOptions` object `{ side, test }` that also picks the triangle
    /// test (`"watertight"`, the default, `"moller-trumbore"` or `"two-step"`). Returns a `RayHit`: `{ t, distance, point, triangle, u, v, normal }`,
    /// `t` the ray parameter, `distance` the Euclidean distance from the origin
    /// (`t·|direction|`), `u`, `v` the barycentric weights of the triangle's second and third
    /// corners, `normal` the unit geometric normal (front side). On equal `t` the lower
    /// triangle index wins. Throws a `TypeError` or `RangeError` naming a bad argument.
    #[wasm_bindgen(unchecked_return_type = "RayHit | null")]
    pub fn raycast(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] origin: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] direction: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "number | null")] near: Option<JsValue>,
        #[wasm_bindgen(unchecked_param_type = "number | null")] far: Option<JsValue>,
        #[wasm_bindgen(unchecked_param_type = "Side | RayOptions | null")] side: Option<JsValue>,
    ) -> Result<JsValue, JsValue> {
        self.cast(&js_ray(origin, direction, near, far)?, side)
    }

    /// [`MeshBvh::raycast`] with the ray as plain numbers (`ox, oy, oz, dx, dy, dz`): nothing
    /// is allocated per call, the fastest single-ray form in a loop. The same result; `side`
    /// is a number only (the watertight test). Unlike
    /// the other calls, its arguments are plain numbers that JavaScript converts on the way
    /// in (a string holding a number is read as that number, `null` as 0, `true` as 1); what
    /// converts to NaN is a `RangeError`. Checking each argument's type would double the cost
    /// of a call; use `raycast` for checked arguments.
    #[wasm_bindgen(js_name = raycastXyz, unchecked_return_type = "RayHit | null")]
    #[allow(clippy::too_many_arguments)]
    pub fn raycast_xyz(
        &self,
        ox: f64,
        oy: f64,
        oz: f64,
        dx: f64,
        dy: f64,
        dz: f64,
        near: Option<f64>,
        far: Option<f64>,
        #[wasm_bindgen(unchecked_param_type = "Side | null")] side: Option<f64>,
    ) -> Result<JsValue, JsValue> {
        let ray = xyz_ray(ox, oy, oz, dx, dy, dz, near, far)?;
        let views = &self.storage;
        Ok(views
            .raycast(&ray, &side_number(side)?)
            .map_or(JsValue::NULL, |hit| hit_object(views, &ray, hit)))
    }

    /// Whether the ray hits anything in `[near, far]` (occlusion, line of sight): it stops at
    /// the first hit found. Arguments as for `raycast`.
    #[wasm_bindgen(js_name = raycastAny)]
    pub fn raycast_any(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] origin: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] direction: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "number | null")] near: Option<JsValue>,
        #[wasm_bindgen(unchecked_param_type = "number | null")] far: Option<JsValue>,
        #[wasm_bindgen(unchecked_param_type = "Side | RayOptions | null")] side: Option<JsValue>,
    ) -> Result<bool, JsValue> {
        let ray = js_ray(origin, direction, near, far)?;
        Ok(self.storage.raycast_any(&ray, &ray_side(side)?))
    }

    /// The closest surface point to `point` (`Vec3Like`) within `maxDistance` (omitted or
    /// `null`: any distance; otherwise a number ≥ 0), or `null`. Returns a `ClosestPoint`:
    /// `{ distance, point, triangle, u, v, normal }`, `distance` the Euclidean distance from
    /// the query point. On equal distance the lower triangle index wins.
    #[wasm_bindgen(js_name = closestPoint, unchecked_return_type = "ClosestPoint | null")]
    pub fn closest_point(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] point: &JsValue,
        #[wasm_bindgen(js_name = maxDistance, unchecked_param_type = "number | null")]
        max_distance_in: Option<JsValue>,
    ) -> Result<JsValue, JsValue> {
        let p = vector(point, "point")?;
        let limit = max_distance(&max_distance_in.unwrap_or(JsValue::UNDEFINED))?;
        let views = &self.storage;
        Ok(views
            .closest_point(p, limit)
            .map_or(JsValue::NULL, |c| closest_object(views, p, c)))
    }

    /// Every triangle's corners, 9 numbers per triangle in triangle order (non-indexed), e.g.
    /// to display a mesh loaded from a blob.
    #[wasm_bindgen(js_name = trianglePositions)]
    pub fn triangle_positions(&self) -> Vec<f32> {
        let views = &self.storage;
        let n = views.triangle_count();
        let mut out = Vec::with_capacity(n as usize * 9);
        for t in (0..n).filter_map(|i| views.triangle(i)) {
            for p in [t.a, t.b, t.c] {
                out.extend_from_slice(&[p.x, p.y, p.z]);
            }
        }
        out
    }

    /// The mesh's vertex positions, 3 numbers per vertex, in the order `indices` refers to
    /// (as built, or as stored in a blob with its mesh): with `indices`, the indexed mesh,
    /// e.g. to remesh it.
    #[wasm_bindgen(js_name = vertexPositions)]
    pub fn vertex_positions(&self) -> Vec<f32> {
        self.storage
            .scene
            .mesh()
            .positions()
            .iter()
            .flatten()
            .copied()
            .collect()
    }

    /// The mesh's triangles, 3 vertex indices each, in triangle order.
    pub fn indices(&self) -> Vec<u32> {
        self.storage
            .scene
            .mesh()
            .triangles()
            .iter()
            .flatten()
            .copied()
            .collect()
    }

    /// Boxes to draw at depth `level` (a whole number; the root is level 0), 6 numbers per
    /// box: `minX, minY, minZ, maxX, maxY, maxZ`. A BVH: its node boxes at that depth. A k-d
    /// tree or octree: the cells its splits have cut space into by that depth (the nodes at
    /// that depth and the non-empty leaves above it). A grid: its non-empty cells.
    #[wasm_bindgen(js_name = levelBoxes)]
    pub fn level_boxes_js(
        &self,
        #[wasm_bindgen(unchecked_param_type = "number")] level: &JsValue,
    ) -> Result<Vec<f32>, JsValue> {
        Ok(self.storage.level_boxes(required_u32(level, "level")?))
    }
}

impl MeshBvh {
    /// Lays out the BVH's query nodes with `relay` (one of the owned type's node choices), or
    /// a `TypeError` naming `call` for a k-d tree, octree or grid.
    fn relay_nodes(
        &mut self,
        call: &str,
        relay: fn(&mut meshq::MeshBvh) -> Result<(), meshq::error::BuildError>,
    ) -> Result<(), JsValue> {
        match &mut self.storage.scene {
            MeshIndex::Bvh(bvh) => relay(bvh).map_err(|e| JsError::new(&e.to_string()).into()),
            _ => Err(type_error(&format!("{call} applies to a BVH"))),
        }
    }

    /// The blob bytes: the loaded ones when `layout` is `None` and this came from a blob,
    /// else encoded afresh (a packed blob's mesh has three vertices of its own per triangle:
    /// the same triangles, the same answers).
    pub fn blob_bytes(
        &self,
        layout: Option<MeshLayout>,
    ) -> Result<Vec<u8>, meshq::error::BlobError> {
        match (&self.storage.blob, layout) {
            (Some(bytes), None) => Ok(bytes.clone()),
            _ => self
                .storage
                .scene
                .to_blob(layout.unwrap_or(MeshLayout::Indexed)),
        }
    }

    /// Boxes at `level`, for Rust callers and tests (see `levelBoxes`).
    #[must_use]
    pub fn level_boxes(&self, level: u32) -> Vec<f32> {
        self.storage.level_boxes(level)
    }

    fn cast(&self, ray: &Ray, side_in: Option<JsValue>) -> Result<JsValue, JsValue> {
        let views = &self.storage;
        Ok(views
            .raycast(ray, &ray_side(side_in)?)
            .map_or(JsValue::NULL, |hit| hit_object(views, ray, hit)))
    }

    /// The closest hit as core types, for Rust callers and tests.
    #[must_use]
    pub fn raycast_ray(&self, ray: &Ray) -> Option<RayHit> {
        self.storage
            .raycast(ray, &meshq::query::RayOptions::default())
    }

    /// Any hit, for Rust callers and tests.
    #[must_use]
    pub fn raycast_any_ray(&self, ray: &Ray) -> bool {
        self.storage
            .raycast_any(ray, &meshq::query::RayOptions::default())
    }

    /// The closest point as core types, for Rust callers and tests.
    #[must_use]
    pub fn closest_point_at(&self, point: Vec3, max_distance: f32) -> Option<ClosestPoint> {
        self.storage.closest_point(point, max_distance)
    }

    /// The root box as a core type.
    #[must_use]
    pub fn root_bounds(&self) -> meshq::math::Aabb {
        self.storage.bounds()
    }
}
