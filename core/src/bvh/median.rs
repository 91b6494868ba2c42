//! The fallback split: at the median centroid, by a full sort with a total key.

use super::PrimRef;
use super::build_box::BuildBox;
use super::partition::sides_of;

/// Splits at the median centroid along the widest centroid axis (by triangle index when all
/// centroids coincide), reordering `prims` and `tris` (same length) alike. Used when SAH finds
/// nothing or would exceed the depth limit; halving keeps the subtree within it. The sort key
/// `(centroid, triangle)` is total and distinct for every triangle, so the order does not
/// depend on the sort algorithm and builds stay bit-identical everywhere.
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
    heap_sort(prims, tris, len, axis);
    let mid = len / 2;
    let (left, right) = sides_of(prims, mid);
    (mid, left, right)
}

/// Component `axis` of `v` (z for anything above 1).
fn lane(v: glam::Vec3A, axis: usize) -> f32 {
    match axis {
        0 => v.x,
        1 => v.y,
        _ => v.z,
    }
}

/// True when element `a` sorts before element `b`: centroid on `axis` by `total_cmp`, then
/// triangle index.
fn before(prims: &[PrimRef], tris: &[u32], axis: usize, a: usize, b: usize) -> bool {
    let key = |i: usize| {
        (
            prims.get(i).map_or(0.0, |p| lane(p.centroid2(), axis)),
            tris.get(i).copied().unwrap_or(0),
        )
    };
    let ((ca, ta), (cb, tb)) = (key(a), key(b));
    ca.total_cmp(&cb).then(ta.cmp(&tb)).is_lt()
}

/// In-place heapsort of the first `len` elements of both slices by [`before`]: no allocation
/// (core's stable sort needs one) and a fixed O(n log n) bound whatever the input.
fn heap_sort(prims: &mut [PrimRef], tris: &mut [u32], len: usize, axis: usize) {
    let swap = |prims: &mut [PrimRef], tris: &mut [u32], a: usize, b: usize| {
        if a < len && b < len {
            prims.swap(a, b);
            tris.swap(a, b);
        }
    };
    let sift_down = |prims: &mut [PrimRef], tris: &mut [u32], mut root: usize, end: usize| {
        loop {
            let mut child = 2 * root + 1;
            if child >= end {
                break;
            }
            if child + 1 < end && before(prims, tris, axis, child, child + 1) {
                child += 1;
            }
            if !before(prims, tris, axis, root, child) {
                break;
            }
            swap(prims, tris, root, child);
            root = child;
        }
    };
    for start in (0..len / 2).rev() {
        sift_down(prims, tris, start, len);
    }
    for end in (1..len).rev() {
        swap(prims, tris, 0, end);
        sift_down(prims, tris, 0, end);
    }
}
