//! The two halves of every query: a structure's traversal ([`Traverse`]) and the query's
//! decisions ([`Visitor`]).

use core::ops::ControlFlow;

use super::{LeafTriangleIds, LeafTriangles};
use crate::math::{Aabb, Aabb4, PackedTriangle, Ray, Triangle};

/// A query as a structure's traversal sees it: it judges boxes, says when deferred work is no
/// longer worth doing, and does the triangle work at the leaves.
///
/// Every built-in query (closest hit, any hit, closest point, box and sphere overlap) is a
/// visitor, and any [`Traverse`] structure runs it. Write your own for anything else and run
/// it with [`Traverse::traverse`].
///
/// # Keys
/// [`enter`](Self::enter) gives each box it accepts a *key*, a number the structure uses to
/// order its work: of the boxes it can visit next, it visits the one with the smaller key
/// first (the lower lane, or the left child, on equal keys), and asks
/// [`revisit`](Self::revisit) before it returns to a deferred one. The key's meaning is the
/// visitor's: the ray parameter `t` where a ray enters the box, a squared distance, or a
/// constant for a query with no order. A visitor whose [`ray`](Self::ray) is `Some` must use
/// ray parameters (in units of that ray's direction), so a structure that walks cells along
/// the ray can ask `revisit(t)` with a cell's entry `t` and stop where the answer can no
/// longer change.
pub trait Visitor {
    /// The ray this query follows, for structures that walk cells in ray order (a grid's
    /// 3D-DDA, a k-d tree's slabs): `None` (the default) for a query that is not a ray's.
    /// Structures that judge boxes through [`enter`](Self::enter) may ignore it.
    fn ray(&self) -> Option<&Ray> {
        None
    }

    /// Whether to enter the box `aabb` (a node's, or a cell's): `None` skips it and everything
    /// in it, `Some(key)` enters it (see the trait's *Keys*).
    fn enter(&mut self, aabb: &Aabb) -> Option<f32>;

    /// [`enter`](Self::enter) for four boxes at once: bit `i` of the mask is set for each lane
    /// `i` to enter, with its key in `keys[i]` (keys of lanes not entered are ignored). The
    /// structure ignores the verdict on unused (empty) lanes. The default asks `enter` lane by
    /// lane; built-in visitors test the four boxes in SIMD lanes.
    fn enter_lanes(&mut self, boxes: &Aabb4) -> (u32, [f32; 4]) {
        let mut mask = 0u32;
        let mut keys = [f32::INFINITY; 4];
        for (lane, key) in keys.iter_mut().enumerate() {
            if let Some(k) = self.enter(&boxes.lane(lane)) {
                mask |= 1 << lane;
                *key = k;
            }
        }
        (mask, keys)
    }

    /// [`enter_lanes`](Self::enter_lanes) for four boxes the structure has just computed
    /// (decoded from a compact node, or an octree cell's children) rather than read where
    /// they are stored: the same verdict and keys. The default calls `enter_lanes`; the
    /// built-in ray visitors pick each axis's planes among the values here, and by index
    /// among stored boxes.
    fn enter_computed_lanes(&mut self, boxes: &Aabb4) -> (u32, [f32; 4]) {
        self.enter_lanes(boxes)
    }

    /// [`enter_lanes`](Self::enter_lanes) for eight boxes (an eight-wide node): bit `i` of the
    /// mask for lane `i`, its key in `keys[i]`. The default asks `enter_lanes` for each half;
    /// built-in visitors test all eight at once.
    fn enter_lanes8(&mut self, boxes: &crate::math::Aabb8) -> (u32, [f32; 8]) {
        let (m0, k0) = self.enter_lanes(&boxes.half(0));
        let (m1, k1) = self.enter_lanes(&boxes.half(1));
        (
            (m0 & 0xF) | ((m1 & 0xF) << 4),
            [k0[0], k0[1], k0[2], k0[3], k1[0], k1[1], k1[2], k1[3]],
        )
    }

    /// Whether a box entered earlier with `key` and deferred is still worth visiting now (for
    /// example, not when a closer hit has been found since). Structures that walk in key order
    /// stop at the first `false`. The default visits everything.
    fn revisit(&self, key: f32) -> bool {
        let _ = key;
        true
    }

    /// Visits a leaf (or a cell): its triangles as `(slot, mesh triangle index)` pairs, where
    /// the slot is what [`LeafTriangles::corners`] is asked for. `Break` ends the traversal.
    fn leaf(&mut self, tris: LeafTriangleIds<'_>) -> ControlFlow<()>;

    /// [`leaf`](Self::leaf), with the box the structure entered the leaf by: `aabb` holds the
    /// leaf's triangles, and [`enter`](Self::enter) or [`enter_lanes`](Self::enter_lanes)
    /// accepted it. Structures that can name that box call this when the
    /// [`hints`](Self::hints) ask for [`leaf_boxes`](VisitorHints::leaf_boxes); a query of
    /// several rays uses it to let only the rays that enter the box test the leaf. The default
    /// calls `leaf`.
    fn leaf_in(&mut self, aabb: &Aabb, tris: LeafTriangleIds<'_>) -> ControlFlow<()> {
        let _ = aabb;
        self.leaf(tris)
    }

    /// What this query tells every structure, so that each may skip work the query does not
    /// need (see [`VisitorHints`]); the default, [`VisitorHints::DEFAULT`], skips nothing.
    /// The answer must not change during a traversal.
    #[inline(always)]
    fn hints(&self) -> VisitorHints {
        VisitorHints::DEFAULT
    }
}

/// What a [`Visitor`] tells every structure once, in one value: each field lets a structure
/// skip work this query does not need. [`VisitorHints::DEFAULT`] holds the choice that is
/// right for every query; a visitor changes a field only when what the field says is true of
/// it (`VisitorHints { skips_repeats: true, needs_cells: false, ..VisitorHints::DEFAULT }`).
/// No answer depends on the hints, only the work done to reach it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct VisitorHints {
    /// The lane verdicts ([`Visitor::enter_lanes`], [`Visitor::enter_lanes8`]) never enter a
    /// lane whose box is [`Aabb4::EMPTY`]'s (`min = +∞`, `max = −∞` on every axis), so
    /// structures whose unused lanes hold exactly that box need not clear them from the mask.
    /// True of the built-in ray and closest-point visitors, whose box tests give such a box an
    /// empty interval or an infinite distance. Structures whose unused lanes hold other boxes
    /// (a compact node's decoded lanes) clear them whatever this says. Default `false`.
    pub empty_lanes_never_entered: bool,
    /// The order in which entered boxes are visited can change the answer or the cost enough
    /// to sort them by key. When false, structures may visit a node's entered children in lane
    /// order: an any-hit ray, whose answer is the same whichever hit ends it. Default `true`.
    pub nearest_first: bool,
    /// A triangle already offered earlier in the same traversal may be skipped (a ray or
    /// closest-point query, whose answer a repeat cannot change). Structures that reference a
    /// triangle from several cells then skip repeats they remember (a small mailbox of the
    /// last ones offered). Default `false`: a query that reports triangles needs every
    /// reference, to pick the one [`Cell`](super::Cell) that reports each.
    pub skips_repeats: bool,
    /// The query reads the [`cell`](LeafTriangleIds::cell) of the leaves it is offered. When
    /// false, structures may offer leaves without their cell (and skip working cells out).
    /// Default `true`; false only for a query that also skips repeats.
    pub needs_cells: bool,
    /// The query reads the box [`Visitor::leaf_in`] is given: structures that can name it
    /// then call `leaf_in` instead of [`Visitor::leaf`]. Default `false`.
    pub leaf_boxes: bool,
}

impl VisitorHints {
    /// Right for every query: nothing skipped.
    pub const DEFAULT: Self = Self {
        empty_lanes_never_entered: false,
        nearest_first: true,
        skips_repeats: false,
        needs_cells: true,
        leaf_boxes: false,
    };

    /// A query whose answer a repeated triangle cannot change and that reads no cells (the
    /// built-in ray, closest-point and shape-cast visitors), otherwise [`Self::DEFAULT`].
    pub const SKIP_REPEATS: Self = Self {
        skips_repeats: true,
        needs_cells: false,
        ..Self::DEFAULT
    };
}

impl Default for VisitorHints {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// An acceleration structure: it runs a [`Visitor`] over its boxes and leaves.
///
/// Implementing this one method is all a structure needs: [`Traverse::with`] then pairs it
/// with its triangles, and the pair answers every query of [`MeshQuery`](super::MeshQuery) —
/// closest hit, any hit, closest point, their batches, box and sphere overlap — with the
/// layer's visitors and leaf tests. See the [module docs](super) for a worked example.
///
/// # Contract
/// - Every triangle the structure holds is reachable through some box: a leaf holding it is
///   visited whenever the visitor enters every box on the way to it (boxes are conservative:
///   they hold their triangles, padded for rounding if need be).
/// - The walk ends: no leaf is visited twice in one traversal unless the structure says so
///   (a triangle in several cells may be offered more than once; the built-in queries give
///   the same answers either way), and it stops when [`Visitor::leaf`] returns `Break`.
/// - It never panics and allocates nothing.
///
/// Then every built-in query returns exactly what a scan of all triangles returns, whatever
/// the order of the walk: each answer is the minimum under a total order (distance, then
/// triangle index).
pub trait Traverse {
    /// Runs `visitor` over the structure.
    fn traverse<V: Visitor + ?Sized>(&self, visitor: &mut V);

    /// The references of triangles the structure holds in more than one leaf by spatial
    /// splits ([`Bvh::build_spatial`](crate::bvh::Bvh::build_spatial)), which the built-in
    /// reporting queries read to report each triangle once; empty (the default) for
    /// structures that hold each triangle once or own cells ([`Cell`](super::Cell)).
    fn split_refs(&self) -> crate::query::SplitRefs<'_> {
        crate::query::SplitRefs::NONE
    }

    /// Whether this structure walks packets well: visitors for several rays at once, which
    /// judge a node's boxes together ([`Visitor::enter_lanes`], [`Visitor::enter_lanes8`]) and
    /// have no single [`ray`](Visitor::ray). Ray batches
    /// ([`MeshQuery::raycast_batch`](super::MeshQuery::raycast_batch)) then walk runs of rays
    /// from one origin together, else one ray at a time; the answers are the same either way.
    /// The default is `false`; the wide BVHs (four-wide, eight-wide and compact nodes) walk
    /// packets.
    #[inline(always)]
    fn walks_packets(&self) -> bool {
        false
    }

    /// What the structure can tell a batch about itself without a walk (see [`BatchHint`]);
    /// `None` (the default) when it knows nothing. Only ever used to order a batch's work: no
    /// answer depends on it.
    #[inline(always)]
    fn batch_hint(&self) -> Option<BatchHint> {
        None
    }

    /// This structure with the triangles it was built over — the
    /// [`ValidMesh`](crate::mesh::ValidMesh), or a packed copy in its leaf order — ready for
    /// every query of [`MeshQuery`](super::MeshQuery).
    #[inline(always)]
    fn with<'a, S: LeafTriangles + ?Sized>(&'a self, triangles: &'a S) -> With<'a, Self, S> {
        With::new(self, triangles)
    }
}

/// What a structure tells batch queries about itself ([`Traverse::batch_hint`]): a large
/// structure's nodes and triangles do not fit in the caches, so a large batch of rays from
/// many origins is answered in an order that keeps rays crossing the same region together
/// ([`MeshQuery::raycast_batch`](super::MeshQuery::raycast_batch)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BatchHint {
    /// A box holding every triangle (finite; any box that does works, a tight one best).
    pub bounds: Aabb,
    /// How many triangles the structure indexes.
    pub triangles: usize,
}

/// A structure paired with the triangles it indexes, made by [`Traverse::with`]: it answers
/// every [`MeshQuery`](super::MeshQuery). Two references, free to make and copy.
///
/// The triangles must be those the structure was built over (the mesh, or a packed copy in its
/// slot order): other triangles give meaningless answers, never a panic.
#[derive(Debug)]
pub struct With<'a, T: ?Sized, S: ?Sized> {
    structure: &'a T,
    triangles: &'a S,
}

impl<T: ?Sized, S: ?Sized> Clone for With<'_, T, S> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<T: ?Sized, S: ?Sized> Copy for With<'_, T, S> {}

impl<'a, T: ?Sized, S: ?Sized> With<'a, T, S> {
    /// Pairs `structure` with `triangles` (what [`Traverse::with`] does).
    #[inline(always)]
    #[must_use]
    pub const fn new(structure: &'a T, triangles: &'a S) -> Self {
        Self {
            structure,
            triangles,
        }
    }

    /// The structure.
    #[must_use]
    pub const fn structure(&self) -> &'a T {
        self.structure
    }

    /// The triangles.
    #[must_use]
    pub const fn triangles(&self) -> &'a S {
        self.triangles
    }
}

impl<T: Traverse + ?Sized, S: ?Sized> Traverse for With<'_, T, S> {
    #[inline(always)]
    fn traverse<V: Visitor + ?Sized>(&self, visitor: &mut V) {
        self.structure.traverse(visitor);
    }

    #[inline(always)]
    fn split_refs(&self) -> crate::query::SplitRefs<'_> {
        self.structure.split_refs()
    }

    #[inline(always)]
    fn walks_packets(&self) -> bool {
        self.structure.walks_packets()
    }

    #[inline(always)]
    fn batch_hint(&self) -> Option<BatchHint> {
        self.structure.batch_hint()
    }
}

impl<T: ?Sized, S: LeafTriangles + ?Sized> LeafTriangles for With<'_, T, S> {
    #[inline(always)]
    fn corners(&self, slot: usize, tri: u32) -> Option<Triangle> {
        self.triangles.corners(slot, tri)
    }

    #[inline(always)]
    fn run(&self, first: usize, count: usize) -> Option<&[PackedTriangle]> {
        self.triangles.run(first, count)
    }
}
