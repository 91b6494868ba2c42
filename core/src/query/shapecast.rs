//! A query of the caller's own shape, as three-mesh-bvh's `shapecast` runs one: the caller
//! judges boxes and triangles, the layer walks the structure.

use core::ops::ControlFlow;

use super::{LeafTriangleIds, LeafTriangles, Traverse, Visitor, VisitorHints};
use crate::math::{Aabb, Triangle};

/// How a shape meets a box.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BoundsOverlap {
    /// The shape and the box share no point: nothing inside the box is offered.
    Outside,
    /// The shape may meet what is inside the box: the box is entered.
    Crosses,
    /// The box lies wholly inside the shape: the box is entered, and triangles whose own box is
    /// judged `Inside` are offered as contained.
    Inside,
}

/// A shape of the caller's own, cast against a mesh by
/// [`MeshQuery::shapecast`](super::MeshQuery::shapecast): the walk asks it about boxes and
/// offers it the triangles inside the boxes it enters.
///
/// Judging a box `Crosses` when unsure is always safe (it costs only time); judging a box
/// `Outside` that the shape meets loses the triangles inside it.
pub trait ShapeCast {
    /// How the shape meets `aabb`, a node's or a cell's box (closed, corners included).
    fn bounds(&mut self, aabb: &Aabb) -> BoundsOverlap;

    /// The order in which boxes are entered: of the boxes the walk can go into next, the one
    /// with the smaller score first (for example the distance to the shape, to find near
    /// triangles first). The default, 0 for every box, keeps the structure's own order.
    fn score(&mut self, aabb: &Aabb) -> f32 {
        let _ = aabb;
        0.0
    }

    /// Offers triangle `tri` (its index in the mesh) with its corners. `contained` is true when
    /// [`bounds`](Self::bounds) judged the triangle's own box `Inside` the shape. `Break` ends
    /// the cast. Degenerate (zero-area) triangles are never offered.
    fn triangle(&mut self, tri: u32, corners: &Triangle, contained: bool) -> ControlFlow<()>;
}

/// The set of triangles already offered, one bit per triangle index.
struct Seen<'s>(&'s mut [u64]);

impl Seen<'_> {
    /// Marks `tri`; true when it was marked already. Indices beyond the set are never marked.
    fn check_and_mark(&mut self, tri: u32) -> bool {
        let bit = 1u64 << (tri % 64);
        match self.0.get_mut((tri / 64) as usize) {
            Some(word) => {
                let seen = *word & bit != 0;
                *word |= bit;
                seen
            }
            None => false,
        }
    }
}

/// The visitor that runs a [`ShapeCast`].
struct Cast<'a, S: ?Sized, C: ?Sized> {
    source: &'a S,
    cast: &'a mut C,
    seen: Option<Seen<'a>>,
}

impl<S: LeafTriangles + ?Sized, C: ShapeCast + ?Sized> Visitor for Cast<'_, S, C> {
    fn enter(&mut self, aabb: &Aabb) -> Option<f32> {
        match self.cast.bounds(aabb) {
            BoundsOverlap::Outside => None,
            BoundsOverlap::Crosses | BoundsOverlap::Inside => Some(self.cast.score(aabb)),
        }
    }

    fn hints(&self) -> VisitorHints {
        VisitorHints::SKIP_REPEATS
    }

    fn leaf(&mut self, tris: LeafTriangleIds<'_>) -> ControlFlow<()> {
        for (slot, tri) in tris {
            let Some(corners) = self.source.corners(slot, tri) else {
                continue;
            };
            if corners.is_degenerate() {
                continue;
            }
            if let Some(seen) = &mut self.seen
                && seen.check_and_mark(tri)
            {
                continue;
            }
            let contained = self.cast.bounds(&corners.bounds()) == BoundsOverlap::Inside;
            self.cast.triangle(tri, &corners, contained)?;
        }
        ControlFlow::Continue(())
    }
}

/// Runs `cast` over `source` through `tree` (see
/// [`MeshQuery::shapecast`](super::MeshQuery::shapecast)).
pub(crate) fn shapecast<A, S, C>(tree: &A, source: &S, cast: &mut C, seen: Option<&mut [u64]>)
where
    A: Traverse + ?Sized,
    S: LeafTriangles + ?Sized,
    C: ShapeCast + ?Sized,
{
    let seen = seen.map(|words| {
        words.fill(0);
        Seen(words)
    });
    tree.traverse(&mut Cast { source, cast, seen });
}
