//! The centre split: halve the centroid bounds on their longest axis, no cost model.

use glam::Vec3A;

use super::PrimRef;
use super::build_box::BuildBox;
use super::partition::{partition_by, sides_of};

/// A child's box and the bounds of its doubled centroids, as every split returns them.
pub(super) type Side = (BuildBox, BuildBox);

/// Splits at the middle of `centroids` (doubled centroid bounds) on its longest axis (lowest
/// axis on a tie): triangles whose doubled centroid lies below the middle go left. Reorders
/// `prims` and `tris` (same length) alike and returns the left count with both sides' boxes
/// and centroid bounds, or `None` when one side would be empty (all centroids on one side
/// of the middle after rounding, or no extent at all).
pub(super) fn centre_split(
    prims: &mut [PrimRef],
    tris: &mut [u32],
    centroids: &BuildBox,
) -> Option<(usize, Side, Side)> {
    let e = centroids.extent();
    let (axis, mid) = if e.x >= e.y && e.x >= e.z {
        (0, (centroids.min.x + centroids.max.x) * 0.5)
    } else if e.y >= e.z {
        (1, (centroids.min.y + centroids.max.y) * 0.5)
    } else {
        (2, (centroids.min.z + centroids.max.z) * 0.5)
    };
    let plane = Vec3A::splat(mid);
    // The comparison in all lanes at once, then the chosen axis's bit: no lane extraction.
    let k = partition_by(prims, tris, |c| (c.cmplt(plane).bitmask() >> axis) & 1 == 1);
    if k == 0 || k >= prims.len() {
        return None;
    }
    let (left, right) = sides_of(prims, k);
    Some((k, left, right))
}
