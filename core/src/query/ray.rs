//! Ray queries: the closest hit and any hit, with either triangle test.

use core::ops::ControlFlow;

use glam::Vec3;

use super::MARGIN;
use super::box_lanes::LaneRay;
use super::leaf_batches::{LANES_PAY, for_each_batch};
use super::{LeafTriangleIds, LeafTriangles, Traverse, Visitor};
use crate::geom::{CullMode, SlabRay, TriangleHit, TriangleLanes, WatertightRay, moller_trumbore};
use crate::math::{Aabb, Aabb4, Ray, RayHit, Triangle};

/// Which ray–triangle test a query uses. Both give bit-identical answers on every target; they
/// differ only at edges shared by two triangles.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum TriangleTest {
    /// [`intersect_ray_triangle_watertight`](crate::geom::intersect_ray_triangle_watertight):
    /// no ray slips through a closed mesh (the default).
    #[default]
    Watertight,
    /// [`intersect_ray_triangle`](crate::geom::intersect_ray_triangle) (Möller–Trumbore):
    /// slightly fewer operations, may miss at shared edges.
    MollerTrumbore,
}

/// Options of a ray query.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct RayOptions {
    /// The triangle test (watertight by default).
    pub test: TriangleTest,
    /// Faces to ignore (none by default: both sides hit).
    pub cull: CullMode,
}

/// A ray–triangle test with an adjustable upper bound.
trait Kernel {
    /// Whether leaves are first filtered four triangles at a time with [`Self::may_hit`].
    const LANES: bool = false;
    fn test(&self, a: Vec3, b: Vec3, c: Vec3) -> Option<TriangleHit>;
    fn shrink(&mut self, t_max: f32);
    /// The lanes [`Self::test`] might accept (a superset of those it does).
    fn may_hit(&self, tris: &TriangleLanes) -> u32 {
        let _ = tris;
        0xF
    }
}

struct Mt {
    ray: Ray,
    cull: CullMode,
}

impl Kernel for Mt {
    #[inline(always)]
    fn test(&self, a: Vec3, b: Vec3, c: Vec3) -> Option<TriangleHit> {
        moller_trumbore(&self.ray, a, b, c, self.cull)
    }
    #[inline(always)]
    fn shrink(&mut self, t_max: f32) {
        self.ray.t_max = t_max;
    }
}

struct Wt {
    ray: WatertightRay,
    cull: CullMode,
}

impl Kernel for Wt {
    const LANES: bool = LANES_PAY;
    #[inline(always)]
    fn may_hit(&self, tris: &TriangleLanes) -> u32 {
        self.ray.may_hit(tris, self.cull)
    }
    #[inline(always)]
    fn test(&self, a: Vec3, b: Vec3, c: Vec3) -> Option<TriangleHit> {
        self.ray.intersect(a, b, c, self.cull)
    }
    #[inline(always)]
    fn shrink(&mut self, t_max: f32) {
        self.ray.set_t_max(t_max);
    }
}

/// The entry distance of `aabb` less the margin, when the ray enters it within its interval
/// (widened by the margin).
#[inline(always)]
fn enter_box(slab: &SlabRay, aabb: &Aabb) -> Option<f32> {
    let (entry, exit) = slab.clip(aabb.min.to_array(), aabb.max.to_array());
    let lo = entry - entry.abs() * MARGIN;
    let hi = exit + exit.abs() * MARGIN;
    (lo <= hi).then_some(lo)
}

struct ClosestHit<'m, S: ?Sized, K> {
    source: &'m S,
    /// The ray as given, for structures that walk along it.
    ray: Ray,
    slab: SlabRay,
    /// The same ray for wide nodes (optimised away when the tree is binary).
    lanes: LaneRay,
    kernel: K,
    best: Option<RayHit>,
}

impl<S: LeafTriangles + ?Sized, K: Kernel> Visitor for ClosestHit<'_, S, K> {
    #[inline(always)]
    fn ray(&self) -> Option<&Ray> {
        Some(&self.ray)
    }

    #[inline(always)]
    fn enter(&mut self, aabb: &Aabb) -> Option<f32> {
        enter_box(&self.slab, aabb)
    }

    #[inline(always)]
    fn enter_lanes(&mut self, boxes: &Aabb4) -> (u32, [f32; 4]) {
        self.lanes
            .enter(boxes, self.slab.t_min, self.slab.t_max, MARGIN)
    }

    #[inline(always)]
    fn revisit(&self, key: f32) -> bool {
        let t = self.slab.t_max;
        key <= t + t.abs() * MARGIN
    }

    #[inline(always)]
    fn leaf(&mut self, tris: LeafTriangleIds<'_>) -> ControlFlow<()> {
        if K::LANES {
            let source = self.source;
            return for_each_batch(source, tris, |batch| {
                let mut maybe = self.kernel.may_hit(&batch.lanes) & batch.used;
                while maybe != 0 {
                    let lane = maybe.trailing_zeros() as usize;
                    maybe &= maybe - 1;
                    if let Some((tri, corners)) = batch.triangle(lane) {
                        self.offer(tri, &corners);
                    }
                }
                ControlFlow::Continue(())
            });
        }
        for (slot, tri) in tris {
            if let Some(corners) = self.source.corners(slot, tri) {
                self.offer(tri, &corners);
            }
        }
        ControlFlow::Continue(())
    }
}

impl<S: ?Sized, K: Kernel> ClosestHit<'_, S, K> {
    /// Tests triangle `tri` and keeps its hit if it beats the best so far.
    #[inline(always)]
    fn offer(&mut self, tri: u32, corners: &Triangle) {
        let Some(h) = self.kernel.test(corners.a, corners.b, corners.c) else {
            return;
        };
        let candidate = RayHit {
            t: h.t,
            tri,
            u: h.u,
            v: h.v,
        };
        // The degeneracy check is only paid for a hit that would win.
        if self.best.is_none_or(|b| candidate.beats(&b)) && !corners.is_degenerate() {
            self.best = Some(candidate);
            self.kernel.shrink(h.t);
            self.slab.t_max = h.t;
        }
    }
}

struct AnyHit<'m, S: ?Sized, K> {
    source: &'m S,
    /// The ray as given, for structures that walk along it.
    ray: Ray,
    slab: SlabRay,
    /// The same ray for wide nodes (optimised away when the tree is binary).
    lanes: LaneRay,
    kernel: K,
    found: bool,
}

impl<S: LeafTriangles + ?Sized, K: Kernel> Visitor for AnyHit<'_, S, K> {
    #[inline(always)]
    fn ray(&self) -> Option<&Ray> {
        Some(&self.ray)
    }

    #[inline(always)]
    fn enter(&mut self, aabb: &Aabb) -> Option<f32> {
        enter_box(&self.slab, aabb)
    }

    #[inline(always)]
    fn enter_lanes(&mut self, boxes: &Aabb4) -> (u32, [f32; 4]) {
        self.lanes
            .enter(boxes, self.slab.t_min, self.slab.t_max, MARGIN)
    }

    #[inline(always)]
    fn leaf(&mut self, tris: LeafTriangleIds<'_>) -> ControlFlow<()> {
        if K::LANES {
            let source = self.source;
            return for_each_batch(source, tris, |batch| {
                let mut maybe = self.kernel.may_hit(&batch.lanes) & batch.used;
                while maybe != 0 {
                    let lane = maybe.trailing_zeros() as usize;
                    maybe &= maybe - 1;
                    if let Some((_, corners)) = batch.triangle(lane)
                        && self.hits(&corners)
                    {
                        return ControlFlow::Break(());
                    }
                }
                ControlFlow::Continue(())
            });
        }
        for (slot, tri) in tris {
            if let Some(corners) = self.source.corners(slot, tri)
                && self.hits(&corners)
            {
                return ControlFlow::Break(());
            }
        }
        ControlFlow::Continue(())
    }
}

impl<S: ?Sized, K: Kernel> AnyHit<'_, S, K> {
    /// Whether the ray hits the (non-degenerate) triangle; records it.
    #[inline(always)]
    fn hits(&mut self, corners: &Triangle) -> bool {
        self.found =
            self.kernel.test(corners.a, corners.b, corners.c).is_some() && !corners.is_degenerate();
        self.found
    }
}

/// The closest hit of `ray` on `source` through `tree` (see
/// [`MeshQuery::raycast_with`](super::MeshQuery::raycast_with)).
#[inline]
pub(crate) fn raycast_with<A: Traverse + ?Sized, S: LeafTriangles + ?Sized>(
    tree: &A,
    source: &S,
    ray: &Ray,
    options: &RayOptions,
) -> Option<RayHit> {
    if !ray.is_valid() {
        return None;
    }
    with_kernel(ray, options, ClosestQuery { tree, source })
}

/// Whether `ray` hits `source` through `tree` (see
/// [`MeshQuery::raycast_any_with`](super::MeshQuery::raycast_any_with)).
#[inline]
pub(crate) fn raycast_any_with<A: Traverse + ?Sized, S: LeafTriangles + ?Sized>(
    tree: &A,
    source: &S,
    ray: &Ray,
    options: &RayOptions,
) -> bool {
    if !ray.is_valid() {
        return false;
    }
    with_kernel(ray, options, AnyQuery { tree, source })
}

/// A ray query, run with whichever kernel the options name: the choice is made once per ray
/// and each kernel gets its own monomorphized traversal.
trait WithKernel {
    type Output;
    fn run<K: Kernel>(self, ray: &Ray, slab: SlabRay, kernel: K) -> Self::Output;
}

fn with_kernel<W: WithKernel>(ray: &Ray, options: &RayOptions, query: W) -> W::Output {
    let slab = SlabRay::new(ray);
    match options.test {
        TriangleTest::Watertight => query.run(
            ray,
            slab,
            Wt {
                ray: WatertightRay::new(ray),
                cull: options.cull,
            },
        ),
        TriangleTest::MollerTrumbore => query.run(
            ray,
            slab,
            Mt {
                ray: *ray,
                cull: options.cull,
            },
        ),
    }
}

struct ClosestQuery<'q, A: ?Sized, S: ?Sized> {
    tree: &'q A,
    source: &'q S,
}

impl<A: Traverse + ?Sized, S: LeafTriangles + ?Sized> WithKernel for ClosestQuery<'_, A, S> {
    type Output = Option<RayHit>;

    fn run<K: Kernel>(self, ray: &Ray, slab: SlabRay, kernel: K) -> Option<RayHit> {
        let mut v = ClosestHit {
            source: self.source,
            ray: *ray,
            slab,
            lanes: LaneRay::new(&slab),
            kernel,
            best: None,
        };
        self.tree.traverse(&mut v);
        v.best
    }
}

struct AnyQuery<'q, A: ?Sized, S: ?Sized> {
    tree: &'q A,
    source: &'q S,
}

impl<A: Traverse + ?Sized, S: LeafTriangles + ?Sized> WithKernel for AnyQuery<'_, A, S> {
    type Output = bool;

    fn run<K: Kernel>(self, ray: &Ray, slab: SlabRay, kernel: K) -> bool {
        let mut v = AnyHit {
            source: self.source,
            ray: *ray,
            slab,
            lanes: LaneRay::new(&slab),
            kernel,
            found: false,
        };
        self.tree.traverse(&mut v);
        v.found
    }
}
