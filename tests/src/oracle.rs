//! Brute-force answers: every triangle, the public primitive test, the crate's tie rule. They
//! share no code with the acceleration structures beyond those primitives.

use glam::Vec3;
use meshq::geom::{
    TriangleHit, TriangleTriangle, closest_point_triangle, intersect_ray_aabb,
    intersect_ray_triangle, intersect_ray_triangle_two_step, intersect_ray_triangle_watertight,
    intersect_triangle_triangle, overlap_triangle_aabb, overlap_triangle_obb,
};
use meshq::math::{Aabb, ClosestPoint, Obb, Ray, RayHit, Triangle};
use meshq::mesh::ValidMesh;
use meshq::query::{RayOptions, TriangleTest};

/// A mesh's triangles by value, gathered once so the scans below spend their time in the
/// primitive tests.
///
/// Scans skip whole chunks of `CHUNK` triangles, neighbours in Morton order of their
/// centroids, when a conservative bound rules them out: the union of the chunk's triangle boxes, each
/// grown by 10⁻⁴ of the mesh's size. A ray hit lies on its triangle up to a few ulps, far
/// inside that margin, and a chunk is skipped for a closest point only when even its box is
/// strictly farther than the best so far, so no answer or tie is ever dropped. The box tests
/// are the public division-based ones, sharing no code with the trees' traversal.
#[derive(Clone, Debug)]
pub struct BruteForce {
    /// Every triangle with its mesh index, in Morton order.
    tris: Vec<(u32, Triangle)>,
    chunks: Vec<Aabb>,
}

/// Spreads the low 10 bits of `v` to every third bit.
fn spread(v: u32) -> u64 {
    (0..10).fold(0u64, |acc, i| acc | ((u64::from(v) >> i & 1) << (3 * i)))
}

const CHUNK: usize = 32;

impl BruteForce {
    /// Gathers every triangle of `mesh`.
    #[must_use]
    pub fn new(mesh: &ValidMesh<'_>) -> Self {
        let bounds = mesh.bounds();
        let size = bounds.extent().max_element();
        let cell = |x: f32, lo: f32| (((x - lo) / size.max(f32::MIN_POSITIVE)) * 1023.0) as u32;
        let mut tris: Vec<(u32, Triangle)> = (0..mesh.triangle_count() as u32)
            .map(|i| (i, mesh.triangle(i).expect("index in range")))
            .collect();
        tris.sort_by_key(|(i, t)| {
            let c = t.bounds().center();
            let key = spread(cell(c.x, bounds.min.x))
                | spread(cell(c.y, bounds.min.y)) << 1
                | spread(cell(c.z, bounds.min.z)) << 2;
            (key, *i)
        });
        let margin = Vec3::splat(size * 1e-4);
        let chunks = tris
            .chunks(CHUNK)
            .map(|c| {
                let b = c.iter().fold(Aabb::EMPTY, |b, (_, t)| b.union(t.bounds()));
                Aabb::new(b.min - margin, b.max + margin)
            })
            .collect();
        Self { tris, chunks }
    }

    /// The number of triangles of the mesh (degenerate ones included).
    #[must_use]
    pub fn triangle_count(&self) -> usize {
        self.tris.len()
    }

    fn indexed(&self) -> impl Iterator<Item = (u32, &Triangle)> {
        self.tris.iter().map(|(i, t)| (*i, t))
    }

    /// The triangles of the chunks `keep` accepts, with their indices, in index order.
    fn chunked<'a>(
        &'a self,
        mut keep: impl FnMut(&Aabb) -> bool + 'a,
    ) -> impl Iterator<Item = (u32, &'a Triangle)> + 'a {
        self.chunks
            .iter()
            .enumerate()
            .filter(move |(_, b)| keep(b))
            .flat_map(move |(k, _)| {
                let first = k * CHUNK;
                self.tris[first..(first + CHUNK).min(self.tris.len())]
                    .iter()
                    .map(|(i, t)| (*i, t))
            })
    }

    /// The closest hit over all triangles (lower index on equal `t`).
    #[must_use]
    pub fn raycast(&self, ray: &Ray, options: &RayOptions) -> Option<RayHit> {
        let mut best: Option<RayHit> = None;
        for (tri, t) in self.chunked(|b| intersect_ray_aabb(ray, b).is_some()) {
            if let Some(h) = ray_triangle(ray, t, options) {
                // Smaller t wins; on equal t, the lower triangle index.
                if best.is_none_or(|b| h.t < b.t || (h.t == b.t && tri < b.tri)) {
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

    /// Every hit on a non-degenerate triangle, nearest first (lower index on equal `t`).
    #[must_use]
    pub fn raycast_all(&self, ray: &Ray, options: &RayOptions) -> Vec<RayHit> {
        let mut hits: Vec<RayHit> = self
            .chunked(|b| intersect_ray_aabb(ray, b).is_some())
            .filter(|(_, t)| !t.is_degenerate())
            .filter_map(|(tri, t)| {
                ray_triangle(ray, t, options).map(|h| RayHit {
                    t: h.t,
                    tri,
                    u: h.u,
                    v: h.v,
                })
            })
            .collect();
        hits.sort_by(|a, b| a.t.total_cmp(&b.t).then(a.tri.cmp(&b.tri)));
        hits
    }

    /// The closest point over all non-degenerate triangles within `max_distance` (lower index
    /// on equal distance).
    #[must_use]
    pub fn closest_point(&self, p: Vec3, max_distance: f32) -> Option<ClosestPoint> {
        let limit = (max_distance * max_distance).min(f32::MAX);
        let mut best: Option<ClosestPoint> = None;
        for (k, chunk) in self.chunks.iter().enumerate() {
            let bound = best.map_or(limit, |b| b.distance_squared);
            // Strictly farther than the best: nothing in the chunk can win or tie.
            if chunk.distance_squared_to_point(p) > bound * 1.001 {
                continue;
            }
            let first = k * CHUNK;
            for &(tri, ref t) in &self.tris[first..(first + CHUNK).min(self.tris.len())] {
                if t.is_degenerate() {
                    continue;
                }
                let mut c = closest_point_triangle(p, t);
                c.tri = tri;
                let wins = |b: ClosestPoint| {
                    c.distance_squared < b.distance_squared
                        || (c.distance_squared == b.distance_squared && tri < b.tri)
                };
                if c.distance_squared <= limit && best.is_none_or(wins) {
                    best = Some(c);
                }
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
            .collect::<std::collections::BTreeSet<_>>()
            .into_iter()
            .collect()
    }

    /// Indices of non-degenerate triangles meeting triangle `query`, ascending.
    #[must_use]
    pub fn overlap_triangle(&self, query: &Triangle) -> Vec<u32> {
        self.indexed()
            .filter(|(_, t)| {
                !t.is_degenerate()
                    && intersect_triangle_triangle(t, query) != TriangleTriangle::Disjoint
            })
            .map(|(i, _)| i)
            .collect::<std::collections::BTreeSet<_>>()
            .into_iter()
            .collect()
    }

    /// Indices of non-degenerate triangles sharing a point with `obb`, ascending.
    #[must_use]
    pub fn overlap_obb(&self, obb: &Obb) -> Vec<u32> {
        self.indexed()
            .filter(|(_, t)| !t.is_degenerate() && overlap_triangle_obb(t, obb))
            .map(|(i, _)| i)
            .collect::<std::collections::BTreeSet<_>>()
            .into_iter()
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
            .collect::<std::collections::BTreeSet<_>>()
            .into_iter()
            .collect()
    }
}

/// The free function of the triangle test `options` names.
fn ray_triangle(ray: &Ray, t: &Triangle, options: &RayOptions) -> Option<TriangleHit> {
    match options.test {
        TriangleTest::Watertight => intersect_ray_triangle_watertight(ray, t, options.cull),
        TriangleTest::MollerTrumbore => intersect_ray_triangle(ray, t, options.cull),
        TriangleTest::TwoStep => intersect_ray_triangle_two_step(ray, t, options.cull),
    }
}
