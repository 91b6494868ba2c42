//! Sweep SAH split search: the classic full-sort builder (MacDonald and Booth 1990; the
//! material's first BVH builder). The node's triangles are sorted by centroid on each axis in
//! turn and the SAH cost is evaluated between neighbours every few triangles along that order.

use glam::Vec3A;

use super::binning::batches;
use super::build_box::BuildBox;
use super::centre::Side;
use super::centroid_sort::sort_by_centroid;
use super::partition::sides_of;
use super::{BvhNode, PrimRef};

/// Fewest cut positions a node is evaluated at (every position when it has fewer gaps).
pub(super) const MIN_CANDIDATES: usize = 32;

/// The cheapest cut found: the first `left_count` triangles in centroid order on `axis` go left.
#[derive(Clone, Copy, Debug)]
pub(super) struct SweepSplit {
    pub axis: usize,
    pub left_count: usize,
    /// `A_L·B(N_L) + A_R·B(N_R)` (half areas, and [`batches`] of triangles), as the binned
    /// search measures it.
    pub cost: f32,
}

impl SweepSplit {
    /// Puts the left side first (sorting on the chosen axis again if the search ended on
    /// another), returning both sides' box and centroid bounds.
    pub fn apply(&self, prims: &mut [PrimRef], tris: &mut [u32]) -> (Side, Side) {
        sort_by_centroid(prims, tris, self.axis);
        sides_of(prims, self.left_count)
    }
}

/// How many triangles apart a node of `count` triangles is cut, for a strategy `step`: `step`,
/// but at most `⌈count / MIN_CANDIDATES⌉` so that small nodes still see
/// [`MIN_CANDIDATES`] cuts (every cut when fewer), and at least 1.
pub(super) fn stride(count: usize, step: u32) -> usize {
    (step as usize).min(count.div_ceil(MIN_CANDIDATES)).max(1)
}

/// A box kept in a spare node slot.
fn stored(b: BuildBox) -> BvhNode {
    BvhNode {
        min: b.min.to_array(),
        first: 0,
        max: b.max.to_array(),
        count: 0,
    }
}

/// The box a spare node slot keeps.
fn restored(n: &BvhNode) -> BuildBox {
    BuildBox {
        min: Vec3A::from_array(n.min),
        max: Vec3A::from_array(n.max),
    }
}

/// The cheapest cut of `prims` (and `tris` alongside, same length, at least two) over the three
/// axes, cuts every [`stride`] triangles (ties: lower axis, then fewer on the left), or `None`
/// when every cost overflows or `spare` is too short. Leaves both slices sorted on the last
/// axis searched.
///
/// `spare` keeps the box of the triangles right of each cut between the two passes, one per
/// cut: `⌊(n − 1) / stride⌋` slots. The sequential builder lends the node slots it has not used
/// yet: a tree over `n` triangles has room for `2n − 1` nodes, and before a node of `c ≥ 2`
/// triangles is split at least `2(c − 1)` of them are still free.
pub(super) fn find_sweep_split(
    prims: &mut [PrimRef],
    tris: &mut [u32],
    step: u32,
    spare: &mut [BvhNode],
) -> Option<SweepSplit> {
    let n = prims.len().min(tris.len());
    if n < 2 {
        return None;
    }
    let s = stride(n, step);
    let spare = spare.get_mut(..(n - 1) / s)?;
    let mut best: Option<SweepSplit> = None;
    for axis in 0..3 {
        sort_by_centroid(prims, tris, axis);
        let sorted = prims.get(..n)?;
        // Right to left: the box of everything from cut `k·s` on, kept in slot k − 1.
        let mut right = BuildBox::EMPTY;
        for (slot, chunk) in spare.iter_mut().zip(sorted.get(s..)?.chunks(s)).rev() {
            right = chunk.iter().fold(right, |b, p| b.union(p.bounds()));
            *slot = stored(right);
        }
        // The triangles after the last cut belong to the last cut's right side: folded in
        // above as the last chunk, shorter than s or not.
        let mut left = BuildBox::EMPTY;
        for (k, (chunk, slot)) in sorted.chunks(s).zip(spare.iter()).enumerate() {
            left = chunk.iter().fold(left, |b, p| b.union(p.bounds()));
            let left_count = (k + 1) * s;
            let cost = left.half_area() * batches(left_count) as f32
                + restored(slot).half_area() * batches(n - left_count) as f32;
            if cost < best.map_or(f32::INFINITY, |b| b.cost) {
                best = Some(SweepSplit {
                    axis,
                    left_count,
                    cost,
                });
            }
        }
    }
    best
}
