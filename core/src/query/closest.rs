//! The closest point of a mesh to a query point.

use core::ops::ControlFlow;

use glam::{Vec3, Vec3A, Vec4};

use super::closest_far::SCALE;
use super::leaf_batches::{LANES_PAY, for_each_batch};
use super::{LeafTriangleIds, LeafTriangles, Traverse, Visitor, VisitorHints};
use crate::geom::aabb_lanes::{MARGIN, enter_point};
use crate::geom::closest_point_regions;
use crate::math::{Aabb, Aabb4, ClosestPoint, Triangle, dot};

/// The closest-point visitor; `LANES` picks the leaf test (see [`LANES_PAY`]).
struct Closest<'m, S: ?Sized, const LANES: bool> {
    source: &'m S,
    point: Vec3,
    /// The query point as given (not scaled), in SIMD lanes, for box distances (see
    /// [`box_distance_squared`]).
    lanes: Vec3A,
    /// Current bound on the squared distance: the best so far, or the caller's maximum.
    limit: f32,
    /// What coordinates are multiplied by before distances are taken: 1, or
    /// [`SCALE`](super::closest_far::SCALE) for a point so far away that squared distances
    /// overflow (then `point`, `lanes` and `limit` are scaled too). A power of two, so the
    /// distances keep their order and ties.
    scale: f32,
    /// The best triangle so far (mesh index and corners), at squared distance `limit`. Its
    /// closest point is worked out once, at the end.
    best: Option<(u32, Triangle)>,
    /// Triangle references the leaves visited so far offered.
    offered: usize,
    /// Most references to be offered before the search gives up (`usize::MAX`: never).
    budget: usize,
}

impl<S: LeafTriangles + ?Sized, const LANES: bool> Visitor for Closest<'_, S, LANES> {
    #[inline(always)]
    fn enter(&mut self, aabb: &Aabb) -> Option<f32> {
        let d2 = box_distance_squared(
            Vec3A::from(aabb.min),
            Vec3A::from(aabb.max),
            self.lanes,
            self.scale,
        );
        // A product, not `d2 − d2·MARGIN`: an overflowed (infinite) distance stays comparable.
        let lo = d2 * (1.0 - MARGIN);
        (lo <= self.limit).then_some(lo)
    }

    #[inline(always)]
    fn enter_lanes(&mut self, boxes: &Aabb4) -> (u32, [f32; 4]) {
        if self.scale != 1.0 {
            let s = self.scale;
            let scaled = Aabb4 {
                min_x: boxes.min_x.map(|x| x * s),
                min_y: boxes.min_y.map(|x| x * s),
                min_z: boxes.min_z.map(|x| x * s),
                max_x: boxes.max_x.map(|x| x * s),
                max_y: boxes.max_y.map(|x| x * s),
                max_z: boxes.max_z.map(|x| x * s),
            };
            return enter_point(&scaled, self.point, self.limit, MARGIN);
        }
        enter_point(boxes, self.point, self.limit, MARGIN)
    }

    #[inline(always)]
    fn enter_lanes8(&mut self, boxes: &crate::math::Aabb8) -> (u32, [f32; 8]) {
        if self.scale != 1.0 {
            let (m0, k0) = self.enter_lanes(&boxes.half(0));
            let (m1, k1) = self.enter_lanes(&boxes.half(1));
            return (
                (m0 & 0xF) | ((m1 & 0xF) << 4),
                [k0[0], k0[1], k0[2], k0[3], k1[0], k1[1], k1[2], k1[3]],
            );
        }
        crate::geom::aabb_lanes::enter_point8(boxes, self.point, self.limit, MARGIN)
    }

    /// Repeats skipped, no cells read; empty lanes never entered (the lane tests clear unused
    /// lanes themselves).
    #[inline(always)]
    fn hints(&self) -> VisitorHints {
        VisitorHints {
            empty_lanes_never_entered: true,
            ..VisitorHints::SKIP_REPEATS
        }
    }

    #[inline(always)]
    fn revisit(&self, key: f32) -> bool {
        key <= self.limit
    }

    fn leaf(&mut self, tris: LeafTriangleIds<'_>) -> ControlFlow<()> {
        if LANES && self.scale == 1.0 {
            let source = self.source;
            for_each_batch(source, tris, |batch| {
                self.offered = self
                    .offered
                    .saturating_add(batch.used.count_ones() as usize);
                // Four triangles whose boxes all lie beyond the bound cannot win (the scalar
                // walk's cull, four at a time): their regions are not walked.
                let low = batch.lanes.box_distance_squared(self.point) * (1.0 - MARGIN);
                if low.cmple(Vec4::splat(self.limit)).bitmask() & batch.used == 0 {
                    return ControlFlow::Continue(());
                }
                let d2 = batch.lanes.closest_distance_squared(self.point);
                let mut near = d2.cmple(Vec4::splat(self.limit)).bitmask() & batch.used;
                let d2 = d2.to_array();
                while near != 0 {
                    let lane = near.trailing_zeros() as usize;
                    near &= near - 1;
                    if let (Some((tri, t)), Some(&d2)) = (batch.triangle(lane), d2.get(lane)) {
                        self.consider(d2, tri, t);
                    }
                }
                ControlFlow::Continue(())
            })?;
        } else {
            self.leaf_one_by_one(tris);
        }
        if self.offered > self.budget {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    }
}

impl<S: LeafTriangles + ?Sized, const LANES: bool> Closest<'_, S, LANES> {
    /// A leaf on a target without SIMD (or of a scaled search): the scalar walk per triangle,
    /// after a cheap cull by the triangle's own box.
    #[inline(always)]
    fn leaf_one_by_one(&mut self, tris: LeafTriangleIds<'_>) {
        for (slot, tri) in tris {
            self.offered = self.offered.saturating_add(1);
            let Some(t) = self.source.corners(slot, tri) else {
                continue;
            };
            // Times 1 (exact) but in a far search.
            let s = self.scale;
            let (ta, tb, tc) = (t.a * s, t.b * s, t.c * s);
            let (a, b, c) = (Vec3A::from(ta), Vec3A::from(tb), Vec3A::from(tc));
            let box_d2 =
                box_distance_squared(a.min(b).min(c), a.max(b).max(c), self.point.into(), 1.0);
            if box_d2 * (1.0 - MARGIN) > self.limit {
                continue;
            }
            let (q, ..) = closest_point_regions(self.point, ta, tb, tc);
            let d = self.point - q;
            self.consider(dot(d, d), tri, t);
        }
    }
}

impl<S: ?Sized, const LANES: bool> Closest<'_, S, LANES> {
    /// Keeps triangle `tri` if its squared distance `d2` beats the best so far (the smaller
    /// distance, then the lower index) and it is not degenerate.
    #[inline(always)]
    fn consider(&mut self, d2: f32, tri: u32, t: Triangle) {
        let wins = match self.best {
            None => d2 <= self.limit,
            Some((best, _)) => d2 < self.limit || (d2 == self.limit && tri < best),
        };
        if wins && !t.is_degenerate() {
            self.limit = d2;
            self.best = Some((tri, t));
        }
    }
}

/// Squared distance from `p` to the box `[min, max]`, in SIMD lanes where the target has them.
///
/// Used only to decide what to visit (with [`MARGIN`] of slack), never for a reported
/// distance, so lane-wise rounding cannot change an answer: the answer is the minimum under a
/// total order (distance, then triangle index), whatever order triangles are visited in.
#[inline(always)]
fn box_distance_squared(min: Vec3A, max: Vec3A, p: Vec3A, scale: f32) -> f32 {
    // The gap itself never overflows (coordinates of a valid mesh are small); its square may,
    // so a far search scales the gap (by a power of two: exact) before squaring it.
    let d = (min - p).max(p - max).max(Vec3A::ZERO) * scale;
    d.dot(d)
}

/// The point of `source` closest to `point` through `tree` (see
/// [`MeshQuery::closest_point`](super::MeshQuery::closest_point)).
pub(crate) fn closest_point<A: Traverse + ?Sized, S: LeafTriangles + ?Sized>(
    tree: &A,
    source: &S,
    point: Vec3,
    max_distance: f32,
) -> Option<ClosestPoint> {
    closest_point_by::<A, S, LANES_PAY>(tree, source, point, max_distance)
}

/// The nearest non-degenerate triangle of `source` to `point` within `max_distance` through
/// `tree`: its mesh index and corners, the one [`closest_point`] answers on (the smaller
/// distance, then the lower index), for callers that need the triangle rather than the point
/// (the remesher judges facing by its normal; [`answer`] gives the point). `Ok`, unless the
/// leaves visited offer more than `budget` triangle references first, then `Err(Crowded)`.
/// (How many references a search is offered depends on the order it visits leaves in, so
/// whether a budget is spent can differ between structures over one mesh; the answer never
/// does.)
pub(crate) fn nearest_triangle<A: Traverse + ?Sized, S: LeafTriangles + ?Sized>(
    tree: &A,
    source: &S,
    point: Vec3,
    max_distance: f32,
    budget: usize,
) -> Result<Option<(u32, Triangle)>, Crowded> {
    search::<A, S, LANES_PAY>(tree, source, point, max_distance, None, budget)
}

/// A search that gave up: its leaves offered more triangle references than its budget.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Crowded;

/// [`closest_point`] with the leaf test chosen by `LANES`, so tests can run the one the
/// target would not.
fn closest_point_by<A: Traverse + ?Sized, S: LeafTriangles + ?Sized, const LANES: bool>(
    tree: &A,
    source: &S,
    point: Vec3,
    max_distance: f32,
) -> Option<ClosestPoint> {
    search::<A, S, LANES>(tree, source, point, max_distance, None, usize::MAX)
        .ok()
        .flatten()
        .map(|best| answer(point, best))
}

/// The nearest non-degenerate triangle (index and corners) within `max_distance` of `point`,
/// with `seed` offered first as a candidate: a triangle near the point (the previous answer of
/// a batch, say) bounds the search from the start. The answer does not depend on the seed —
/// it is the minimum under the same total order, and the seed is just one more triangle
/// considered — only the work done does. `Err(Crowded)` when the leaves visited offered more
/// than `budget` references (`usize::MAX`: never).
pub(super) fn search<A: Traverse + ?Sized, S: LeafTriangles + ?Sized, const LANES: bool>(
    tree: &A,
    source: &S,
    point: Vec3,
    max_distance: f32,
    seed: Option<(u32, Triangle)>,
    budget: usize,
) -> Result<Option<(u32, Triangle)>, Crowded> {
    if !point.is_finite() || !(max_distance >= 0.0) {
        return Ok(None);
    }
    let scale = scale_for(point);
    let scaled = point * scale;
    let scaled_max = max_distance * scale;
    let mut v = Closest::<S, LANES> {
        source,
        point: scaled,
        lanes: point.into(),
        // Capped: a bound that overflowed would let every triangle tie at infinity.
        limit: (scaled_max * scaled_max).min(f32::MAX),
        scale,
        best: None,
        offered: 0,
        budget,
    };
    if let Some((tri, t)) = seed {
        // The scalar walk gives the lanes' bits, so the seed ties with itself when its leaf
        // comes up, and the tie rule sees one distance per triangle.
        let (q, ..) = closest_point_regions(scaled, t.a * scale, t.b * scale, t.c * scale);
        let d = scaled - q;
        v.consider(dot(d, d), tri, t);
    }
    tree.traverse(&mut v);
    if v.offered > budget {
        return Err(Crowded);
    }
    Ok(v.best)
}

/// What a search from `point` multiplies coordinates by: 1, or [`SCALE`] (2⁻⁶⁴) for a point
/// beyond 2⁶² (4.6e18) on some axis, whose squared distances to a valid mesh (coordinates
/// within [`MAX_COORDINATE`](crate::math::MAX_COORDINATE)) could overflow `f32`. A power of two:
/// the scaled distances keep the order and ties of the exact ones.
fn scale_for(point: Vec3) -> f32 {
    if point.abs().max_element() > 4_611_686_018_427_387_904.0 {
        SCALE
    } else {
        1.0
    }
}

/// The answer for the nearest triangle `tri` with corners `t`.
pub(crate) fn answer(point: Vec3, (tri, t): (u32, Triangle)) -> ClosestPoint {
    // The lanes computed this triangle's distance with the walk's own arithmetic, so the walk
    // agrees with the distance it was chosen by; a far point is worked out scaled, as it was
    // found, and scaled back (exact, or +inf for a squared distance past f32).
    let scale = scale_for(point);
    let p = point * scale;
    let (q, u, v, feature) = closest_point_regions(p, t.a * scale, t.b * scale, t.c * scale);
    let d = p - q;
    let up = 1.0 / scale;
    ClosestPoint {
        point: q * up,
        tri,
        u,
        v,
        distance_squared: dot(d, d) * up * up,
        feature,
    }
}

#[cfg(test)]
mod tests {
    use std::vec;
    use std::vec::Vec;

    use super::*;
    use crate::bvh::{BuildConfig, Bvh, BvhNode, PrimRef, node_capacity};
    use crate::geom::closest_point_triangle;
    use crate::math::PackedTriangle;
    use crate::mesh::MeshRef;
    use crate::query::closest_batch::closest_points_by;
    use crate::test_floats::floats;
    use crate::wide::{WideBvh, WideNode};

    /// Both leaf tests, on the binary and the wide tree and on packed and indexed triangles,
    /// return the brute-force minimum over a soup of small triangles (every fifth one
    /// degenerate, every seventh a copy of its predecessor, and leaves of up to 7 triangles, so
    /// lanes run short and full batches).
    #[test]
    fn both_leaf_tests_equal_brute_force() {
        let tris = 600;
        let mut positions = floats(7, tris * 9);
        for t in 0..tris {
            // Shrink each triangle around its first corner; every fifth collapses to a segment.
            let (head, rest) = positions.split_at_mut(t * 9 + 3);
            let a = [head[t * 9], head[t * 9 + 1], head[t * 9 + 2]];
            for (k, x) in rest.iter_mut().take(6).enumerate() {
                *x = a[k % 3] + (*x - a[k % 3]) * 0.05;
            }
            if t % 5 == 0 {
                for k in 0..3 {
                    rest[3 + k] = (a[k] + rest[k]) * 0.5;
                }
            }
        }
        // Every seventh triangle repeats the one before: exact ties, which the lower index wins.
        for t in (7..tris).step_by(7) {
            positions.copy_within((t - 1) * 9..t * 9, t * 9);
        }
        let indices: Vec<u32> = (0..(tris * 3) as u32).collect();
        let mesh = MeshRef::from_flat(&positions, &indices)
            .and_then(MeshRef::validate)
            .unwrap_or_else(|e| panic!("{e}"));
        let config = BuildConfig {
            max_leaf_size: 7,
            ..BuildConfig::default()
        };
        let mut nodes = vec![BvhNode::EMPTY; node_capacity(tris)];
        let mut order = vec![0u32; tris];
        let mut scratch = vec![PrimRef::EMPTY; tris];
        let bvh = Bvh::build(&mesh, &config, &mut nodes, &mut order, &mut scratch)
            .unwrap_or_else(|e| panic!("{e}"));
        let mut packed = vec![PackedTriangle::EMPTY; tris];
        let packed = bvh
            .pack_triangles(&mesh, &mut packed)
            .unwrap_or_else(|e| panic!("{e}"));
        let sizes = WideBvh::<WideNode>::measure(&bvh);
        let mut entries = vec![crate::wide::plan::PlanEntry::EMPTY; sizes.plan];
        let mut wide = vec![WideNode::EMPTY; sizes.nodes];
        let wide = WideBvh::build(&bvh, &mut entries, &mut wide).unwrap_or_else(|e| panic!("{e}"));

        let probes = floats(11, 3 * 2_000);
        let points: Vec<Vec3> = probes
            .chunks_exact(3)
            .map(|p| Vec3::new(p[0], p[1], p[2]) * 1.5)
            .collect();
        let brute = |p: Vec3, max: f32| {
            (0..tris as u32)
                .filter_map(|t| {
                    let tri = mesh.triangle(t)?;
                    let mut c = closest_point_triangle(p, &tri);
                    c.tri = t;
                    (!tri.is_degenerate() && c.distance_squared <= max * max).then_some(c)
                })
                .reduce(|best, c| if c.beats(&best) { c } else { best })
        };
        for (i, &p) in points.iter().enumerate() {
            let max = if i % 3 == 0 { 0.05 } else { f32::INFINITY };
            let want = brute(p, max);
            let got = [
                closest_point_by::<_, _, true>(&bvh, &packed, p, max),
                closest_point_by::<_, _, true>(&bvh, &mesh, p, max),
                closest_point_by::<_, _, false>(&bvh, &packed, p, max),
                closest_point_by::<_, _, true>(&wide, &packed, p, max),
                closest_point_by::<_, _, false>(&wide, &mesh, p, max),
            ];
            for (k, got) in got.into_iter().enumerate() {
                assert_eq!(got, want, "variant {k}, probe {p}");
            }
        }

        // Batches (seeded searches in Morton order) answer each point as alone, with both leaf
        // tests, on both trees, within a limit and without.
        let mut keys = vec![0u64; points.len()];
        for max in [0.05, f32::INFINITY] {
            let want: Vec<_> = points.iter().map(|&p| brute(p, max)).collect();
            for k in 0..3 {
                let mut out = vec![None; points.len()];
                let done = match k {
                    0 => closest_points_by::<_, _, true>(
                        &bvh, &packed, &points, max, &mut keys, &mut out,
                    ),
                    1 => closest_points_by::<_, _, false>(
                        &wide, &mesh, &points, max, &mut keys, &mut out,
                    ),
                    _ => closest_points_by::<_, _, true>(
                        &wide, &packed, &points, max, &mut keys, &mut out,
                    ),
                };
                assert_eq!(done, Ok(()));
                assert_eq!(out, want, "batch variant {k}, max {max}");
            }
        }
    }
}
