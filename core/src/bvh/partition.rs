//! Reordering a node's triangles into left-then-right, shared by every split strategy.

use glam::Vec3A;

use super::PrimRef;
use super::build_box::BuildBox;

/// Reorders `prims`, and `tris` alongside (same length), so that those whose doubled centroid
/// ([`PrimRef::centroid2`]) satisfies `goes_left` come first; returns how many. The relative
/// order within each side is fixed by the input order, so the result is deterministic.
///
/// Branch-free Lomuto partition: every element is swapped with the first right-side slot
/// whichever side it goes to (swapping two right-side elements changes nothing that matters),
/// so the unpredictable side test never becomes a mispredicted branch.
#[inline(always)]
pub(super) fn partition_by(
    prims: &mut [PrimRef],
    tris: &mut [u32],
    goes_left: impl Fn(Vec3A) -> bool,
) -> usize {
    let len = prims.len().min(tris.len());
    let mut k = 0;
    for i in 0..len {
        let Some(p) = prims.get(i) else {
            break;
        };
        let left = goes_left(p.centroid2());
        // k <= i < len.
        if k < len {
            prims.swap(k, i);
            tris.swap(k, i);
        }
        k += usize::from(left);
    }
    k
}

/// Bounds of the boxes and of the doubled centroids of `prims`: one pass of independent
/// min/max, cheaper than growing two sides by select inside the partition loop.
pub(super) fn bounds_of(prims: &[PrimRef]) -> (BuildBox, BuildBox) {
    prims
        .iter()
        .fold((BuildBox::EMPTY, BuildBox::EMPTY), |(b, c), p| {
            (b.union(p.bounds()), c.grown(p.centroid2()))
        })
}

/// Bounds of the doubled centroids of `prims`.
pub(super) fn centroid_bounds(prims: &[PrimRef]) -> BuildBox {
    prims
        .iter()
        .fold(BuildBox::EMPTY, |c, p| c.grown(p.centroid2()))
}

/// Both sides' box and centroid bounds after a partition at `left_count`.
pub(super) fn sides_of(
    prims: &[PrimRef],
    left_count: usize,
) -> ((BuildBox, BuildBox), (BuildBox, BuildBox)) {
    let (left, right) = prims.split_at(left_count.min(prims.len()));
    (bounds_of(left), bounds_of(right))
}
