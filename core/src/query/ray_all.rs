//! Every hit along a ray, nearest first, into a caller's buffer.

use core::ops::ControlFlow;

use super::ray::{Goal, Kernel, ray_hit, walk};
use super::{LeafTriangles, RayOptions, Traverse};
use crate::geom::{SlabRay, TriangleHit};
use crate::math::{Ray, RayHit, Triangle};

/// What [`MeshQuery::raycast_all`](super::MeshQuery::raycast_all) wrote: the nearest hits, and
/// whether the ray has more beyond them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct RayHits {
    /// Hits written to the front of the buffer, nearest first.
    pub written: usize,
    /// True when the ray hits further triangles than fit in the buffer (all of them ranking
    /// after the hits written).
    pub more: bool,
}

impl RayHits {
    /// True when every hit was written.
    #[must_use]
    pub const fn is_complete(&self) -> bool {
        !self.more
    }
}

/// Keeps the nearest `out.len()` distinct hits in order, and whether any others exist.
///
/// A structure that references a triangle from several cells may offer it again; the test is
/// the same, so a repeat has the same `(t, tri)` and is dropped where it would be inserted.
struct Nearest<'o> {
    out: &'o mut [RayHit],
    len: usize,
    more: bool,
}

impl Nearest<'_> {
    /// Where `hit` belongs among the kept hits, or `None` when it is already kept.
    fn position(&self, hit: &RayHit) -> Option<usize> {
        let kept = self.out.get(..self.len).unwrap_or_default();
        let at = kept.partition_point(|k| k.beats(hit));
        match kept.get(at) {
            Some(k) if k.t == hit.t && k.tri == hit.tri => None,
            _ => Some(at),
        }
    }

    /// Once the buffer is full and a hit beyond it has been seen, nothing after the last kept
    /// hit can change the answer: the walk narrows to it (inclusive, for ties on `t`).
    fn narrow<K: Kernel>(&self, kernel: &mut K, slab: &mut SlabRay) {
        if self.more
            && let Some(last) = self.len.checked_sub(1).and_then(|i| self.out.get(i))
        {
            kernel.shrink(last.t);
            slab.t_max = last.t;
        }
    }
}

impl Goal for Nearest<'_> {
    const PRUNES: bool = true;

    fn take<K: Kernel>(
        &mut self,
        tri: u32,
        h: TriangleHit,
        corners: &Triangle,
        kernel: &mut K,
        slab: &mut SlabRay,
    ) -> ControlFlow<()> {
        if corners.is_degenerate() {
            return ControlFlow::Continue(());
        }
        let hit = ray_hit(tri, h);
        let Some(at) = self.position(&hit) else {
            return ControlFlow::Continue(());
        };
        if self.len < self.out.len() {
            insert(self.out.get_mut(at..=self.len), hit);
            self.len += 1;
            return ControlFlow::Continue(());
        }
        // Full: the hit either ranks after every kept one, or displaces the last.
        self.more = true;
        if self.out.is_empty() {
            return ControlFlow::Break(());
        }
        insert(self.out.get_mut(at..), hit);
        self.narrow(kernel, slab);
        ControlFlow::Continue(())
    }
}

/// Puts `hit` first in `tail`, shifting the rest one place on (the last falls off).
fn insert(tail: Option<&mut [RayHit]>, hit: RayHit) {
    if let Some(tail) = tail
        && !tail.is_empty()
    {
        tail.rotate_right(1);
        if let Some(first) = tail.first_mut() {
            *first = hit;
        }
    }
}

/// Every hit of `ray` on `source` through `tree`, nearest first (see
/// [`MeshQuery::raycast_all`](super::MeshQuery::raycast_all)).
pub(crate) fn raycast_all<A: Traverse + ?Sized, S: LeafTriangles + ?Sized>(
    tree: &A,
    source: &S,
    ray: &Ray,
    options: &RayOptions,
    out: &mut [RayHit],
) -> RayHits {
    if !ray.is_valid() {
        return RayHits {
            written: 0,
            more: false,
        };
    }
    let goal = walk(
        tree,
        source,
        ray,
        options,
        Nearest {
            out,
            len: 0,
            more: false,
        },
    );
    RayHits {
        written: goal.len,
        more: goal.more,
    }
}
