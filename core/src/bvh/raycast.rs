use core::ops::ControlFlow;

use glam::{Vec3, Vec4};

use super::leaf_batches::{LANES_PAY, for_each_batch};
use super::traverse::Walk;
use super::wide::WideNode;
use super::wide::lanes::LaneRay;
use super::wide::traverse::LaneVisitor;
use super::{Bvh, BvhNode, BvhVisitor, LeafTriangleIds, LeafTriangles};
use crate::geom::{CullMode, SlabRay, TriangleHit, TriangleLanes, WatertightRay, moller_trumbore};
use crate::math::{Ray, RayHit, Triangle};

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

/// Relative slack on box entry/exit distances: a box is entered when it might hold a hit within
/// a few thousand ulps of the current best, so rounding in the slab test can never cull a
/// triangle whose own rounded `t` would win (ties included).
const MARGIN: f32 = 1.0 / 65_536.0;

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

#[inline(always)]
fn enter_box(slab: &SlabRay, node: &BvhNode) -> Option<f32> {
    let (entry, exit) = slab.clip(node.min, node.max);
    let lo = entry - entry.abs() * MARGIN;
    let hi = exit + exit.abs() * MARGIN;
    (lo <= hi).then_some(lo)
}

struct ClosestHit<'m, S: ?Sized, K> {
    source: &'m S,
    slab: SlabRay,
    /// The same ray for wide nodes (optimised away when the tree is binary).
    lanes: LaneRay,
    kernel: K,
    best: Option<RayHit>,
}

impl<S: LeafTriangles + ?Sized, K: Kernel> BvhVisitor for ClosestHit<'_, S, K> {
    #[inline(always)]
    fn enter(&mut self, node: &BvhNode) -> Option<f32> {
        enter_box(&self.slab, node)
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

impl<S: LeafTriangles + ?Sized, K: Kernel> LaneVisitor for ClosestHit<'_, S, K> {
    #[inline(always)]
    fn enter_lanes(&mut self, node: &WideNode) -> (u32, Vec4) {
        self.lanes
            .enter(node, self.slab.t_min, self.slab.t_max, MARGIN)
    }
}

struct AnyHit<'m, S: ?Sized, K> {
    source: &'m S,
    slab: SlabRay,
    /// The same ray for wide nodes (optimised away when the tree is binary).
    lanes: LaneRay,
    kernel: K,
    found: bool,
}

impl<S: LeafTriangles + ?Sized, K: Kernel> BvhVisitor for AnyHit<'_, S, K> {
    #[inline(always)]
    fn enter(&mut self, node: &BvhNode) -> Option<f32> {
        enter_box(&self.slab, node)
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

impl<S: LeafTriangles + ?Sized, K: Kernel> LaneVisitor for AnyHit<'_, S, K> {
    #[inline(always)]
    fn enter_lanes(&mut self, node: &WideNode) -> (u32, Vec4) {
        self.lanes
            .enter(node, self.slab.t_min, self.slab.t_max, MARGIN)
    }
}

impl Bvh<'_> {
    /// The closest hit of `ray` on the triangles of `source` — the [`ValidMesh`] this BVH was
    /// built from, or its [`PackedTriangles`](super::PackedTriangles) (same answer, bit for
    /// bit) — with the watertight test and both faces: [`RayOptions::default`].
    ///
    /// [`ValidMesh`]: crate::mesh::ValidMesh
    ///
    /// Conventions: `t` in units of the ray direction's length, within `[t_min, t_max]`
    /// (inclusive); on equal `t` the lower triangle index wins, so every structure and target
    /// returns the same hit; degenerate triangles are never hit; an invalid ray
    /// ([`Ray::is_valid`]) hits nothing.
    #[must_use]
    pub fn raycast<S: LeafTriangles + ?Sized>(&self, source: &S, ray: &Ray) -> Option<RayHit> {
        self.raycast_with(source, ray, &RayOptions::default())
    }

    /// [`Bvh::raycast`] with explicit options.
    #[must_use]
    pub fn raycast_with<S: LeafTriangles + ?Sized>(
        &self,
        source: &S,
        ray: &Ray,
        options: &RayOptions,
    ) -> Option<RayHit> {
        raycast_with(self, source, ray, options)
    }

    /// True when `ray` hits any triangle within `[t_min, t_max]` (occlusion / line of sight),
    /// stopping at the first hit found. Agrees with [`Bvh::raycast`]: `raycast_any` is true
    /// exactly when `raycast` returns a hit.
    #[must_use]
    pub fn raycast_any<S: LeafTriangles + ?Sized>(&self, source: &S, ray: &Ray) -> bool {
        self.raycast_any_with(source, ray, &RayOptions::default())
    }

    /// [`Bvh::raycast_any`] with explicit options.
    #[must_use]
    pub fn raycast_any_with<S: LeafTriangles + ?Sized>(
        &self,
        source: &S,
        ray: &Ray,
        options: &RayOptions,
    ) -> bool {
        raycast_any_with(self, source, ray, options)
    }
}

/// [`Bvh::raycast_with`] over any storage.
#[inline]
pub(crate) fn raycast_with<A: Walk + ?Sized, S: LeafTriangles + ?Sized>(
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

/// [`Bvh::raycast_any_with`] over any storage.
#[inline]
pub(crate) fn raycast_any_with<A: Walk + ?Sized, S: LeafTriangles + ?Sized>(
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
    fn run<K: Kernel>(self, slab: SlabRay, kernel: K) -> Self::Output;
}

fn with_kernel<W: WithKernel>(ray: &Ray, options: &RayOptions, query: W) -> W::Output {
    let slab = SlabRay::new(ray);
    match options.test {
        TriangleTest::Watertight => query.run(
            slab,
            Wt {
                ray: WatertightRay::new(ray),
                cull: options.cull,
            },
        ),
        TriangleTest::MollerTrumbore => query.run(
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

impl<A: Walk + ?Sized, S: LeafTriangles + ?Sized> WithKernel for ClosestQuery<'_, A, S> {
    type Output = Option<RayHit>;

    fn run<K: Kernel>(self, slab: SlabRay, kernel: K) -> Option<RayHit> {
        let mut v = ClosestHit {
            source: self.source,
            slab,
            lanes: LaneRay::new(&slab),
            kernel,
            best: None,
        };
        self.tree.walk(&mut v);
        v.best
    }
}

struct AnyQuery<'q, A: ?Sized, S: ?Sized> {
    tree: &'q A,
    source: &'q S,
}

impl<A: Walk + ?Sized, S: LeafTriangles + ?Sized> WithKernel for AnyQuery<'_, A, S> {
    type Output = bool;

    fn run<K: Kernel>(self, slab: SlabRay, kernel: K) -> bool {
        let mut v = AnyHit {
            source: self.source,
            slab,
            lanes: LaneRay::new(&slab),
            kernel,
            found: false,
        };
        self.tree.walk(&mut v);
        v.found
    }
}
