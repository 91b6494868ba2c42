//! Where a k-d tree cell splits: the binned surface-area heuristic over the triangles' parts
//! inside the cell.

use super::{KdConfig, KdNode};
use crate::cells::{Decision, MAX_ARITY, ReferencePad, Splitter};
use crate::geom::clip_triangle_aabb;
use crate::math::Aabb;
use crate::mesh::ValidMesh;
use crate::query::Cell;

/// Candidate planes per axis: the bounds of 32 equal bins.
const BINS: usize = 32;

/// The k-d tree's [`Splitter`].
pub(super) struct KdSplitter<'m> {
    pub(super) mesh: &'m ValidMesh<'m>,
    pub(super) config: KdConfig,
    pub(super) depth_limit: u32,
    pub(super) pad: ReferencePad,
}

/// The best plane found: axis, coordinate, cost.
#[derive(Clone, Copy)]
struct Plane {
    axis: usize,
    at: f32,
    cost: f32,
}

impl KdSplitter<'_> {
    /// Per axis, the cheapest plane by the surface-area heuristic if it beats keeping the leaf,
    /// cheapest axis first.
    ///
    /// Each reference is binned by the bounds of the part of its triangle inside the cell
    /// (clipped, so a long triangle crossing a corner counts only where it is): at a plane, the
    /// references starting below count on the left, those ending above on the right.
    fn best_planes(&self, b: &Aabb, refs: &[u32]) -> [Option<Plane>; 3] {
        let area = b.half_area();
        if !(area > 0.0) {
            return [None; 3];
        }
        let ext = b.extent().to_array();
        let (lo, hi) = (b.min.to_array(), b.max.to_array());
        let mut starts = [[0u32; BINS]; 3];
        let mut ends = [[0u32; BINS]; 3];
        for &tri in refs {
            let Some(t) = self.mesh.triangle(tri) else {
                continue;
            };
            let tb = t.bounds();
            // A triangle inside the cell clips to itself: most do, and need no clipping.
            let pb = if b.contains_aabb(&tb) {
                tb
            } else {
                let part = clip_triangle_aabb(&t, b);
                // A reference held only through the pad clips to nothing: its bounds stand in.
                if part.is_empty() {
                    Aabb::new(tb.min.clamp(b.min, b.max), tb.max.clamp(b.min, b.max))
                } else {
                    part.bounds()
                }
            };
            let (pmin, pmax) = (pb.min.to_array(), pb.max.to_array());
            let axes = lo.iter().zip(&ext).zip(pmin.iter().zip(&pmax));
            for (((&l, &e), (&p0, &p1)), (s, en)) in
                axes.zip(starts.iter_mut().zip(ends.iter_mut()))
            {
                if e > 0.0 {
                    // `as` saturates (NaN to 0); the min keeps the top edge in the last bin.
                    let bin = |x: f32| (((x - l) / e * BINS as f32) as usize).min(BINS - 1);
                    if let Some(c) = s.get_mut(bin(p0)) {
                        *c += 1;
                    }
                    if let Some(c) = en.get_mut(bin(p1)) {
                        *c += 1;
                    }
                }
            }
        }
        let c = &self.config;
        let n = refs.len() as f32;
        let mut best: [Option<Plane>; 3] = [None; 3];
        let leaf_cost = c.triangle_cost * n;
        let axes = lo.iter().zip(&hi).zip(&ext).zip(starts.iter().zip(&ends));
        for (axis, ((((&l, &h), &e), (s, en)), best)) in axes.zip(best.iter_mut()).enumerate() {
            if !(e > 0.0) {
                continue;
            }
            let mut left = 0u32;
            let mut right: u32 = en.iter().sum();
            for k in 1..BINS {
                left += s.get(k - 1).copied().unwrap_or(0);
                right -= en.get(k - 1).copied().unwrap_or(0);
                let at = l + e * (k as f32 / BINS as f32);
                if !(at > l && at < h) {
                    continue;
                }
                let (mut below, mut above) = (*b, *b);
                below.max[axis] = at;
                above.min[axis] = at;
                let mut cost = c.traversal_cost
                    + c.triangle_cost
                        * (below.half_area() * left as f32 + above.half_area() * right as f32)
                        / area;
                if left == 0 || right == 0 {
                    cost *= 1.0 - c.empty_bonus;
                }
                if cost < leaf_cost && best.is_none_or(|p| cost < p.cost) {
                    *best = Some(Plane { axis, at, cost });
                }
            }
        }
        best.sort_unstable_by(|a, b| match (a, b) {
            (Some(a), Some(b)) => a.cost.total_cmp(&b.cost).then(a.axis.cmp(&b.axis)),
            (a, b) => b.is_some().cmp(&a.is_some()),
        });
        best
    }
}

impl KdSplitter<'_> {
    /// Writes the references of both sides of `plane` into `out` (below first); `Leaf` when
    /// both sides would hold every reference, whether or not they fit (so the decision never
    /// depends on the room), `NoRoom` when they do not fit.
    fn partition(
        &self,
        cell: &Cell,
        plane: Plane,
        refs: &[u32],
        out: &mut [u32],
    ) -> Decision<(usize, f32)> {
        let (below, above) = cell.split(plane.axis, plane.at);
        let mut written = 0usize;
        let mut lens = [0u32; MAX_ARITY];
        for ((side, len), is_above) in [below, above]
            .iter()
            .zip(lens.iter_mut())
            .zip([false, true])
        {
            for &tri in refs {
                let Some(t) = self.mesh.triangle(tri) else {
                    continue;
                };
                // Most references lie clear of the plane: they touch one side only, and the
                // other needs no overlap test.
                let reaches = self
                    .pad
                    .reaches_side(&t.bounds(), plane.axis, plane.at, is_above);
                if reaches && self.pad.touches(&t, side.aabb()) {
                    if let Some(slot) = out.get_mut(written) {
                        *slot = tri;
                    }
                    written += 1;
                    *len += 1;
                }
            }
        }
        let n = refs.len() as u32;
        if lens.iter().take(2).all(|&l| l == n) {
            return Decision::Leaf;
        }
        if written > out.len() {
            return Decision::NoRoom;
        }
        let mut cells = [*cell; MAX_ARITY];
        let [c0, c1, ..] = &mut cells;
        (*c0, *c1) = (below, above);
        Decision::Split {
            inner: (plane.axis, plane.at),
            cells,
            lens,
        }
    }
}

impl Splitter for KdSplitter<'_> {
    const ARITY: usize = 2;
    type Node = KdNode;
    type Inner = (usize, f32);

    fn split(
        &self,
        cell: &Cell,
        depth: u32,
        refs: &[u32],
        out: &mut [u32],
    ) -> Decision<(usize, f32)> {
        if refs.len() <= self.config.leaf_size as usize || depth >= self.depth_limit {
            return Decision::Leaf;
        }
        // The heuristic counts a triangle touching a plane on one side; the references count it
        // on both. If the cheapest plane then separates nothing, the next axis's may.
        for plane in self.best_planes(cell.aabb(), refs).into_iter().flatten() {
            let d = self.partition(cell, plane, refs, out);
            match d {
                Decision::Leaf => continue,
                decision => return decision,
            }
        }
        Decision::Leaf
    }

    fn inner((axis, split): (usize, f32), first_child: u32) -> KdNode {
        KdNode::inner(axis, split, first_child)
    }

    fn leaf(first: u32, count: u32) -> KdNode {
        KdNode::leaf(first, count)
    }
}
