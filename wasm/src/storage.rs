//! What a [`crate::MeshBvh`] holds: the core's owned [`MeshIndex`] (mesh, structure of any kind,
//! packed triangles) and, for a loaded blob, its bytes.

use meshq::MeshQuery;
use meshq::math::{ClosestPoint, Ray, RayHit, Triangle};
use meshq::owned::MeshIndex;
use meshq::query::RayOptions;
use wasm_bindgen::JsError;

/// A mesh with its structure, and the blob it was loaded from (handed back as is by `toBlob`).
pub struct Storage {
    /// The mesh and every buffer its queries read.
    pub scene: MeshIndex,
    /// The blob this was loaded from.
    pub blob: Option<Vec<u8>>,
    /// For a k-d tree, octree or grid: a BVH of the same mesh with its winding-number
    /// expansions, made by the first inside query (a BVH prepares its own).
    pub winding: Option<meshq::owned::MeshBvh>,
    /// The mesh's angle-weighted pseudo-normals, made by the first query signed by them.
    pub pseudo: Option<meshq::owned::MeshPseudoNormals>,
}

/// The queries go through [`MeshQuery`]'s generic implementation for `MeshIndex` (one walk
/// for every kind of structure), not `MeshIndex`'s own methods that pick the structure first:
/// those compile a walk per kind, about 42 KB more of `.wasm`, for batches and single calls
/// that measured within 2% of these in Node.
impl Storage {
    pub fn raycast(&self, ray: &Ray, options: &RayOptions) -> Option<RayHit> {
        MeshQuery::raycast_with(&self.scene, ray, options)
    }

    pub fn raycast_any(&self, ray: &Ray, options: &RayOptions) -> bool {
        MeshQuery::raycast_any_with(&self.scene, ray, options)
    }

    /// Every hit along `ray`, nearest first: the core writes into a buffer that grows until
    /// every hit fits (it can never need more than one place per triangle).
    pub fn raycast_all(&self, ray: &Ray, options: &RayOptions) -> Vec<RayHit> {
        let most = self.scene.mesh().triangle_count().max(1);
        let empty = RayHit {
            t: 0.0,
            tri: 0,
            u: 0.0,
            v: 0.0,
        };
        let mut hits = vec![empty; most.min(16)];
        loop {
            let found = MeshQuery::raycast_all(&self.scene, ray, options, &mut hits);
            if found.is_complete() || hits.len() >= most {
                hits.truncate(found.written);
                return hits;
            }
            hits.resize(most.min(hits.len() * 4), empty);
        }
    }

    pub fn closest_point(&self, point: glam::Vec3, max_distance: f32) -> Option<ClosestPoint> {
        MeshQuery::closest_point(&self.scene, point, max_distance)
    }

    /// Batches answer in Morton order (see `MeshQuery::closest_points`); the sort keys are
    /// allocated here.
    pub fn closest_points(
        &self,
        points: &[glam::Vec3],
        max_distance: f32,
        out: &mut [Option<ClosestPoint>],
    ) -> Result<(), JsError> {
        let mut keys = vec![0u64; points.len()];
        MeshQuery::closest_points(&self.scene, points, max_distance, &mut keys, out)
            .map_err(batch_error)
    }

    pub fn raycast_batch(
        &self,
        rays: &[Ray],
        options: &RayOptions,
        out: &mut [Option<RayHit>],
    ) -> Result<(), JsError> {
        let mut keys = vec![0u64; rays.len()];
        MeshQuery::raycast_batch(&self.scene, rays, options, &mut keys, out).map_err(batch_error)
    }

    pub fn raycast_any_batch(
        &self,
        rays: &[Ray],
        options: &RayOptions,
        out: &mut [bool],
    ) -> Result<(), JsError> {
        let mut keys = vec![0u64; rays.len()];
        MeshQuery::raycast_any_batch(&self.scene, rays, options, &mut keys, out)
            .map_err(batch_error)
    }

    pub fn triangle(&self, index: u32) -> Option<Triangle> {
        self.scene.mesh().triangle(index)
    }

    pub fn triangle_count(&self) -> u32 {
        u32::try_from(self.scene.mesh().triangle_count()).unwrap_or(u32::MAX)
    }

    pub fn bounds(&self) -> meshq::math::Aabb {
        match &self.scene {
            MeshIndex::Bvh(s) => s.bounds(),
            MeshIndex::KdTree(s) => s.bounds(),
            MeshIndex::Octree(s) => s.bounds(),
            MeshIndex::Grid(s) => s.bounds(),
        }
    }
}

fn batch_error(e: meshq::error::BatchError) -> JsError {
    JsError::new(&e.to_string())
}
