//! Brute-force answers: every triangle, the public primitive test, the crate's tie rule. They
//! share no code with the acceleration structures beyond those primitives.

use glam::Vec3;
use meshq::bvh::{RayOptions, TriangleTest};
use meshq::geom::{
    closest_point_triangle, intersect_ray_triangle, intersect_ray_triangle_watertight,
    overlap_triangle_aabb,
};
use meshq::math::{Aabb, ClosestPoint, Ray, RayHit, Triangle};
use meshq::mesh::ValidMesh;

/// A mesh's triangles by value, gathered once so the scans below spend their time in the
/// primitive tests.
#[derive(Clone, Debug)]
pub struct BruteForce {
    tris: Vec<Triangle>,
}

impl BruteForce {
    /// Gathers every triangle of `mesh`.
    #[must_use]
    pub fn new(mesh: &ValidMesh<'_>) -> Self {
        let tris = (0..mesh.triangle_count() as u32)
            .map(|i| mesh.triangle(i).expect("index in range"))
            .collect();
        Self { tris }
    }

    fn indexed(&self) -> impl Iterator<Item = (u32, &Triangle)> {
        (0u32..).zip(&self.tris)
    }

    /// The closest hit over all triangles (lower index on equal `t`).
    #[must_use]
    pub fn raycast(&self, ray: &Ray, options: &RayOptions) -> Option<RayHit> {
        let mut best: Option<RayHit> = None;
        for (tri, t) in self.indexed() {
            let hit = match options.test {
                TriangleTest::Watertight => intersect_ray_triangle_watertight(ray, t, options.cull),
                TriangleTest::MollerTrumbore => intersect_ray_triangle(ray, t, options.cull),
            };
            if let Some(h) = hit {
                // Strictly smaller t wins; scanning in index order keeps the lower index on ties.
                if best.is_none_or(|b| h.t < b.t) {
                    best = Some(RayHit {
                        t: h.t,
                        tri,
                        u: h.u,
                        v: h.v,
                    });
                }
            }
        }
        best
    }

    /// The closest point over all non-degenerate triangles within `max_distance` (lower index
    /// on equal distance).
    #[must_use]
    pub fn closest_point(&self, p: Vec3, max_distance: f32) -> Option<ClosestPoint> {
        let limit = max_distance * max_distance;
        let mut best: Option<ClosestPoint> = None;
        for (tri, t) in self.indexed() {
            if t.is_degenerate() {
                continue;
            }
            let mut c = closest_point_triangle(p, t);
            c.tri = tri;
            if c.distance_squared <= limit
                && best.is_none_or(|b| c.distance_squared < b.distance_squared)
            {
                best = Some(c);
            }
        }
        best
    }

    /// Indices of non-degenerate triangles overlapping `aabb`, ascending.
    #[must_use]
    pub fn overlap_aabb(&self, aabb: &Aabb) -> Vec<u32> {
        self.indexed()
            .filter(|(_, t)| !t.is_degenerate() && overlap_triangle_aabb(t, aabb))
            .map(|(i, _)| i)
            .collect()
    }

    /// Indices of non-degenerate triangles within `radius` of `center`, ascending.
    #[must_use]
    pub fn overlap_sphere(&self, center: Vec3, radius: f32) -> Vec<u32> {
        self.indexed()
            .filter(|(_, t)| {
                !t.is_degenerate()
                    && closest_point_triangle(center, t).distance_squared <= radius * radius
            })
            .map(|(i, _)| i)
            .collect()
    }
}
