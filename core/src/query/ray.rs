//! Ray queries: the closest hit and any hit, with either triangle test.

use core::ops::ControlFlow;

use glam::{Vec3, Vec4};

use super::leaf_batches::{Batch, LANES_PAY, for_each_batch};
use super::{LeafTriangleIds, LeafTriangles, Traverse, Visitor, VisitorHints};
use crate::geom::aabb_lanes::{LaneRay, LaneRay8, MARGIN, near_far, near_far_values};
use crate::geom::{
    CullMode, LaneHits, SlabRay, TriangleHit, TriangleLanes, WatertightRay, moller_trumbore,
    two_step,
};
use crate::math::{Aabb, Aabb4, Aabb8, Ray, RayHit, Triangle};

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
    /// [`intersect_ray_triangle_two_step`](crate::geom::intersect_ray_triangle_two_step): the
    /// ray meets the triangle's plane, then the crossing point's barycentric coordinates
    /// decide; may miss (or hit twice) at shared edges.
    TwoStep,
}

impl TriangleTest {
    /// Every test, the default first.
    pub const ALL: [Self; 3] = [Self::Watertight, Self::MollerTrumbore, Self::TwoStep];

    /// The name the command line, JavaScript and Python use: `"watertight"`,
    /// `"moller-trumbore"`, `"two-step"`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Watertight => "watertight",
            Self::MollerTrumbore => "moller-trumbore",
            Self::TwoStep => "two-step",
        }
    }

    /// The test named `name` (as [`TriangleTest::name`] spells it), if any.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|t| t.name() == name)
    }
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
pub(super) trait Kernel {
    /// Whether leaves are first judged four triangles at a time with [`Self::lane_hits`].
    const LANES: bool = false;
    fn test(&self, a: Vec3, b: Vec3, c: Vec3) -> Option<TriangleHit>;
    fn shrink(&mut self, t_max: f32);
    /// What [`Self::test`] answers for four triangles, as far as lanes decide: by default
    /// nothing is sure and every lane is left to [`Self::test`].
    fn lane_hits(&self, tris: &TriangleLanes) -> LaneHits {
        let _ = tris;
        LaneHits {
            sure: 0,
            unsure: 0xF,
            t: [0.0; 4],
            u: [0.0; 4],
            v: [0.0; 4],
        }
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

struct TwoStep {
    ray: Ray,
    cull: CullMode,
}

impl Kernel for TwoStep {
    #[inline(always)]
    fn test(&self, a: Vec3, b: Vec3, c: Vec3) -> Option<TriangleHit> {
        two_step(&self.ray, a, b, c, self.cull)
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
    fn lane_hits(&self, tris: &TriangleLanes) -> LaneHits {
        self.ray.hits(tris, self.cull)
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

/// Whether a box deferred with entry `key` may still hold a hit no farther than `t_max`
/// (with the margin). Monotone in `t_max`: the largest `t_max` of several rays decides for
/// all of them.
#[inline(always)]
pub(super) fn within_reach(key: f32, t_max: f32) -> bool {
    key <= t_max + t_max.abs() * MARGIN
}

/// What a ray query keeps of the hits its kernel finds.
pub(super) trait Goal {
    /// Whether a closer hit bounds the walk (deferred boxes beyond it are skipped).
    const PRUNES: bool;

    /// Takes the hit `h` of triangle `tri` (corners `corners`); `Break` ends the walk. May
    /// shrink the ray (kernel and slabs) to the hit.
    fn take<K: Kernel>(
        &mut self,
        tri: u32,
        h: TriangleHit,
        corners: &Triangle,
        kernel: &mut K,
        slab: &mut SlabRay,
    ) -> ControlFlow<()>;
}

/// Triangle `tri`'s hit `h` as the answer a query returns.
#[inline(always)]
pub(super) fn ray_hit(tri: u32, h: TriangleHit) -> RayHit {
    RayHit {
        t: h.t,
        tri,
        u: h.u,
        v: h.v,
    }
}

/// The closest hit: the best so far, under the tie rule.
pub(super) struct Nearest(pub(super) Option<RayHit>);

impl Goal for Nearest {
    const PRUNES: bool = true;

    #[inline(always)]
    fn take<K: Kernel>(
        &mut self,
        tri: u32,
        h: TriangleHit,
        corners: &Triangle,
        kernel: &mut K,
        slab: &mut SlabRay,
    ) -> ControlFlow<()> {
        let candidate = ray_hit(tri, h);
        // The degeneracy check is only paid for a hit that would win.
        if self.0.is_none_or(|b| candidate.beats(&b)) && !corners.is_degenerate() {
            self.0 = Some(candidate);
            kernel.shrink(h.t);
            slab.t_max = h.t;
        }
        ControlFlow::Continue(())
    }
}

/// The closest hit of one ray walked alone: [`Nearest`]'s rule, with the hit kept as one
/// vector (`t`, the triangle's bits, `u`, `v` — the order of [`RayHit`]'s fields) so that the
/// walk hands it back in one 16-byte store. Its caller reads the hit in one load, which
/// separate stores of each field could not forward (a stall after every walk). Packets keep
/// [`Nearest`]: a vector per ray made their hits slower to record.
///
/// No hit yet is `t = +∞` with triangle `u32::MAX`: under the tie rule every hit beats it, so
/// no flag (and no padding to copy) is needed. Only the two together read as no hit: no mesh
/// numbers a triangle `u32::MAX`, and a structure of one's own that hands a query that id
/// still has its finite hits kept.
pub(super) struct NearestOne(Vec4);

impl NearestOne {
    /// The triangle bits of "no hit yet".
    const NO_TRIANGLE: u32 = u32::MAX;

    /// No hit yet.
    pub(super) const NONE: Self = Self(Vec4::new(
        f32::INFINITY,
        f32::from_bits(Self::NO_TRIANGLE),
        0.0,
        0.0,
    ));

    /// The lanes as a hit (the "no hit yet" one included).
    #[inline(always)]
    fn best(&self) -> RayHit {
        RayHit {
            t: self.0.x,
            tri: self.0.y.to_bits(),
            u: self.0.z,
            v: self.0.w,
        }
    }

    /// The hit kept, if any.
    #[inline(always)]
    pub(super) fn hit(&self) -> Option<RayHit> {
        let best = self.best();
        (best.tri != Self::NO_TRIANGLE || best.t != f32::INFINITY).then_some(best)
    }
}

impl Goal for NearestOne {
    const PRUNES: bool = true;

    #[inline(always)]
    fn take<K: Kernel>(
        &mut self,
        tri: u32,
        h: TriangleHit,
        corners: &Triangle,
        kernel: &mut K,
        slab: &mut SlabRay,
    ) -> ControlFlow<()> {
        let candidate = ray_hit(tri, h);
        // The degeneracy check is only paid for a hit that would win.
        if candidate.beats(&self.best()) && !corners.is_degenerate() {
            self.0 = Vec4::new(h.t, f32::from_bits(tri), h.u, h.v);
            kernel.shrink(h.t);
            slab.t_max = h.t;
        }
        ControlFlow::Continue(())
    }
}

/// Any hit: the first non-degenerate one ends the walk.
pub(super) struct Occluded(pub(super) bool);

impl Goal for Occluded {
    const PRUNES: bool = false;

    #[inline(always)]
    fn take<K: Kernel>(
        &mut self,
        _tri: u32,
        _h: TriangleHit,
        corners: &Triangle,
        _kernel: &mut K,
        _slab: &mut SlabRay,
    ) -> ControlFlow<()> {
        self.0 = !corners.is_degenerate();
        if self.0 {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    }
}

/// A ray's leaf half: its interval, its kernel and its goal — what testing triangles needs.
/// A packet keeps one per ray and judges boxes for all of them at once, so it carries none of
/// a single ray's box lanes (a packet of full visitors took longer to copy into place than a
/// small mesh's walk).
pub(super) struct RayTester<K, G> {
    pub(super) slab: SlabRay,
    kernel: K,
    pub(super) goal: G,
}

/// The ray visitor: boxes by the slab test, leaves by the kernel, hits to the goal.
///
/// The tester is borrowed, not held: a leaf's test may be a call the compiler keeps out of
/// line, and it is handed the tester's address. Were the tester a field, that address would
/// be inside the visitor, and after every leaf the walk would have to read the lanes back and
/// redo what it derives from them (each plane's offset); kept apart, the lanes are known to
/// be untouched by the call.
pub(super) struct RayVisitor<'m, 't, S: ?Sized, K, G> {
    source: &'m S,
    /// The ray as given, for structures that walk along it.
    ray: Ray,
    /// The same ray for four boxes at once, and for eight through [`LaneRay8::from_lanes`]
    /// (optimised away when no structure asks).
    lanes: LaneRay,
    tester: &'t mut RayTester<K, G>,
}

impl<S: LeafTriangles + ?Sized, K: Kernel, G: Goal> Visitor for RayVisitor<'_, '_, S, K, G> {
    #[inline(always)]
    fn ray(&self) -> Option<&Ray> {
        Some(&self.ray)
    }

    #[inline(always)]
    fn enter(&mut self, aabb: &Aabb) -> Option<f32> {
        self.tester.enter(aabb)
    }

    #[inline(always)]
    fn enter_lanes8(&mut self, boxes: &Aabb8) -> (u32, [f32; 8]) {
        LaneRay8::from_lanes(&self.lanes).enter(boxes)
    }

    #[inline(always)]
    fn enter_lanes(&mut self, boxes: &Aabb4) -> (u32, [f32; 4]) {
        self.lanes.enter(boxes, near_far)
    }

    #[inline(always)]
    fn enter_computed_lanes(&mut self, boxes: &Aabb4) -> (u32, [f32; 4]) {
        self.lanes.enter(boxes, near_far_values)
    }

    #[inline(always)]
    fn revisit(&self, key: f32) -> bool {
        !G::PRUNES || within_reach(key, self.tester.slab.t_max)
    }

    /// Repeats skipped, no cells read; empty lanes never entered (an empty box's near plane is
    /// infinitely far, its far plane infinitely near); nearest first only for a goal that
    /// prunes (any hit ends an any-hit walk, whichever comes first).
    #[inline(always)]
    fn hints(&self) -> VisitorHints {
        VisitorHints {
            empty_lanes_never_entered: true,
            nearest_first: G::PRUNES,
            ..VisitorHints::SKIP_REPEATS
        }
    }

    #[inline(always)]
    fn leaf(&mut self, tris: LeafTriangleIds<'_>) -> ControlFlow<()> {
        let flow = self.tester.leaf(self.source, tris);
        let t_max = self.tester.slab.t_max;
        self.lanes.set_t_max(t_max);
        flow
    }
}

impl<K: Kernel, G: Goal> RayTester<K, G> {
    /// The tester of `ray` with its kernel and goal.
    #[inline(always)]
    pub(super) fn new(ray: &Ray, kernel: K, goal: G) -> Self {
        Self {
            slab: SlabRay::new(ray),
            kernel,
            goal,
        }
    }

    /// The entry of `aabb` for this ray (see [`Visitor::enter`]).
    #[inline(always)]
    pub(super) fn enter(&self, aabb: &Aabb) -> Option<f32> {
        enter_box(&self.slab, aabb)
    }

    /// Tests the leaf's triangles (read from `source`), four at a time where the kernel
    /// filters lanes.
    #[inline(always)]
    pub(super) fn leaf<S: LeafTriangles + ?Sized>(
        &mut self,
        source: &S,
        tris: LeafTriangleIds<'_>,
    ) -> ControlFlow<()> {
        if K::LANES {
            return for_each_batch(source, tris, |batch| self.offer_batch(batch));
        }
        for (slot, tri) in tris {
            if let Some(corners) = source.corners(slot, tri) {
                self.offer(tri, &corners)?;
            }
        }
        ControlFlow::Continue(())
    }

    /// Hands the goal the hits of `batch` the kernel's lanes are sure of, and tests the lanes
    /// only the scalar test can decide, in lane order.
    ///
    /// A sure lane's hit was judged against the ray's interval before this batch: a hit taken
    /// from an earlier lane may since have shrunk it, so a later sure hit can lie beyond it.
    /// The goals judge every hit against what they keep (the closest by the tie rule, the
    /// nearest few), which is what the scalar test's rejection of it would have left.
    #[inline(always)]
    pub(super) fn offer_batch(&mut self, batch: &Batch<'_>) -> ControlFlow<()> {
        let hits = self.kernel.lane_hits(&batch.lanes);
        let mut maybe = (hits.sure | hits.unsure) & batch.used;
        while maybe != 0 {
            let lane = maybe.trailing_zeros() as usize;
            maybe &= maybe - 1;
            let Some((tri, corners)) = batch.triangle(lane) else {
                continue;
            };
            let sure = match (hits.t.get(lane), hits.u.get(lane), hits.v.get(lane)) {
                (Some(&t), Some(&u), Some(&v)) if hits.sure & (1 << lane) != 0 => {
                    Some(TriangleHit { t, u, v })
                }
                _ => None,
            };
            match sure {
                Some(h) => self
                    .goal
                    .take(tri, h, &corners, &mut self.kernel, &mut self.slab)?,
                None => self.offer(tri, &corners)?,
            }
        }
        ControlFlow::Continue(())
    }

    /// Tests triangle `tri` and hands a hit to the goal.
    #[inline(always)]
    fn offer(&mut self, tri: u32, corners: &Triangle) -> ControlFlow<()> {
        match self.kernel.test(corners.a, corners.b, corners.c) {
            Some(h) => self
                .goal
                .take(tri, h, corners, &mut self.kernel, &mut self.slab),
            None => ControlFlow::Continue(()),
        }
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
    walk(tree, source, ray, options, NearestOne::NONE).hit()
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
    walk(tree, source, ray, options, Occluded(false)).0
}

/// Walks `tree` with the kernel the options name — chosen once per ray, each kernel with its
/// own monomorphized traversal — and returns the goal. Kept out of line where there is an
/// operating system: inlined into the command line's loop of one ray per call, it cost random
/// rays 2–5%. On bare metal the compiler decides (inlined into its callers, the firmware's
/// code is 336 bytes smaller).
#[cfg_attr(not(target_os = "none"), inline(never))]
pub(super) fn walk<A: Traverse + ?Sized, S: LeafTriangles + ?Sized, G: Goal>(
    tree: &A,
    source: &S,
    ray: &Ray,
    options: &RayOptions,
    goal: G,
) -> G {
    match options.test {
        TriangleTest::Watertight => walk_with(
            tree,
            source,
            ray,
            Wt {
                ray: WatertightRay::new(ray),
                cull: options.cull,
            },
            goal,
        ),
        TriangleTest::MollerTrumbore => walk_with(
            tree,
            source,
            ray,
            Mt {
                ray: *ray,
                cull: options.cull,
            },
            goal,
        ),
        TriangleTest::TwoStep => walk_with(tree, source, ray, two_step_kernel(ray, options), goal),
    }
}

fn walk_with<A: Traverse + ?Sized, S: LeafTriangles + ?Sized, K: Kernel, G: Goal>(
    tree: &A,
    source: &S,
    ray: &Ray,
    kernel: K,
    goal: G,
) -> G {
    let mut tester = RayTester::new(ray, kernel, goal);
    let mut v = RayVisitor::new(source, ray, &mut tester);
    tree.traverse(&mut v);
    tester.goal
}

impl<'m, 't, S: ?Sized, K: Kernel, G: Goal> RayVisitor<'m, 't, S, K, G> {
    /// The visitor of `ray` over `source`, testing leaves with `tester`.
    #[inline(always)]
    pub(super) fn new(source: &'m S, ray: &Ray, tester: &'t mut RayTester<K, G>) -> Self {
        Self {
            source,
            ray: *ray,
            lanes: LaneRay::new(&tester.slab),
            tester,
        }
    }
}

/// The kernel `options` names for `ray`.
#[inline(always)]
pub(super) fn watertight(ray: &Ray, options: &RayOptions) -> impl Kernel + use<> {
    Wt {
        ray: WatertightRay::new(ray),
        cull: options.cull,
    }
}

/// The two-step kernel for `ray` with the options' culling.
#[inline(always)]
pub(super) fn two_step_kernel(ray: &Ray, options: &RayOptions) -> impl Kernel + use<> {
    TwoStep {
        ray: *ray,
        cull: options.cull,
    }
}

/// The Möller–Trumbore kernel for `ray` with the options' culling.
#[inline(always)]
pub(super) fn moller_trumbore_kernel(ray: &Ray, options: &RayOptions) -> impl Kernel + use<> {
    Mt {
        ray: *ray,
        cull: options.cull,
    }
}
