//! The fallback split: at the median centroid, by a full sort with a total key
//! ([`sort_by_centroid`]).

use super::PrimRef;
use super::build_box::BuildBox;
use super::centroid_sort::sort_by_centroid;
use super::partition::sides_of;

/// Splits at the median centroid along the widest centroid axis (by triangle index when all
/// centroids coincide), reordering `prims` and `tris` (same length) alike. Used when SAH finds
/// nothing or would exceed the depth limit; halving keeps the subtree within it.
pub(super) fn median_split(
    prims: &mut [PrimRef],
    tris: &mut [u32],
    centroids: &BuildBox,
) -> (usize, (BuildBox, BuildBox), (BuildBox, BuildBox)) {
    let e = centroids.extent();
    let axis = if e.x >= e.y && e.x >= e.z {
        0
    } else if e.y >= e.z {
        1
    } else {
        2
    };
    let len = prims.len().min(tris.len());
    sort_by_centroid(prims, tris, axis);
    let mid = len / 2;
    let (left, right) = sides_of(prims, mid);
    (mid, left, right)
}
