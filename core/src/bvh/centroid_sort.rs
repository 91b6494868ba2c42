//! Sorting a node's triangles by centroid on one axis, the boxes and the triangle indices
//! alongside, without allocation (core's stable sort needs one; its unstable sort cannot move
//! two slices together).
//!
//! The key is `(centroid, triangle)`: the centroid by `total_cmp`, then the triangle index. It
//! is total and distinct for every triangle, so the order does not depend on the algorithm and
//! builds stay bit-identical everywhere.

use super::PrimRef;

/// Component `axis` of `v` (z for anything above 1).
#[inline(always)]
pub(super) fn lane(v: glam::Vec3A, axis: usize) -> f32 {
    match axis {
        0 => v.x,
        1 => v.y,
        _ => v.z,
    }
}

/// The sort key of element `i`.
#[inline(always)]
fn key(prims: &[PrimRef], tris: &[u32], axis: usize, i: usize) -> (f32, u32) {
    (
        prims.get(i).map_or(0.0, |p| lane(p.centroid2(), axis)),
        tris.get(i).copied().unwrap_or(0),
    )
}

/// True when key `a` sorts before key `b`.
#[inline(always)]
fn before(a: (f32, u32), b: (f32, u32)) -> bool {
    a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).is_lt()
}

#[inline(always)]
fn swap(prims: &mut [PrimRef], tris: &mut [u32], a: usize, b: usize) {
    if a < prims.len() && b < prims.len() && a < tris.len() && b < tris.len() {
        prims.swap(a, b);
        tris.swap(a, b);
    }
}

/// True when `prims` (and `tris` alongside) are already in key order on `axis`: a child keeps
/// the order its parent was split in, so one of its axes usually needs no sort.
pub(super) fn is_sorted(prims: &[PrimRef], tris: &[u32], axis: usize) -> bool {
    let len = prims.len().min(tris.len());
    (1..len).all(|i| before(key(prims, tris, axis, i - 1), key(prims, tris, axis, i)))
}

/// Sorts the first `min(prims.len(), tris.len())` elements of both slices by centroid on
/// `axis`, then triangle index. Introsort: quicksort with a median-of-three pivot, heapsort
/// once the recursion passes `2·log₂ n` levels (so O(n log n) on every input); no insertion
/// sort for small runs, which would cost the firmware flash for little time. Recursion goes
/// into the smaller side only: its depth is at most `log₂ n`.
pub(super) fn sort_by_centroid(prims: &mut [PrimRef], tris: &mut [u32], axis: usize) {
    let len = prims.len().min(tris.len());
    let (Some(prims), Some(tris)) = (prims.get_mut(..len), tris.get_mut(..len)) else {
        return;
    };
    if is_sorted(prims, tris, axis) {
        return;
    }
    let limit = 2 * (usize::BITS - len.leading_zeros());
    introsort(prims, tris, axis, limit);
}

fn introsort(mut prims: &mut [PrimRef], mut tris: &mut [u32], axis: usize, mut limit: u32) {
    loop {
        let len = prims.len().min(tris.len());
        if len <= 1 {
            return;
        }
        if limit == 0 {
            heap_sort(prims, tris, axis);
            return;
        }
        limit -= 1;
        let pivot = partition(prims, tris, axis);
        let (left_prims, rest_prims) = core::mem::take(&mut prims).split_at_mut(pivot);
        let (left_tris, rest_tris) = core::mem::take(&mut tris).split_at_mut(pivot);
        // The pivot itself is in place: sort what lies after it.
        let right_prims = rest_prims.get_mut(1..).unwrap_or_default();
        let right_tris = rest_tris.get_mut(1..).unwrap_or_default();
        if left_prims.len() < right_prims.len() {
            introsort(left_prims, left_tris, axis, limit);
            (prims, tris) = (right_prims, right_tris);
        } else {
            introsort(right_prims, right_tris, axis, limit);
            (prims, tris) = (left_prims, left_tris);
        }
    }
}

/// Lomuto partition around the median of the first, middle and last keys: returns the
/// pivot's final position, every element before it sorting before it and every one after it
/// after (keys are distinct).
fn partition(prims: &mut [PrimRef], tris: &mut [u32], axis: usize) -> usize {
    let last = prims.len().min(tris.len()) - 1;
    let mid = last / 2;
    let k = |p: &[PrimRef], t: &[u32], i| key(p, t, axis, i);
    // Order first, middle and last, then park the median at the end.
    if before(k(prims, tris, mid), k(prims, tris, 0)) {
        swap(prims, tris, mid, 0);
    }
    if before(k(prims, tris, last), k(prims, tris, 0)) {
        swap(prims, tris, last, 0);
    }
    if before(k(prims, tris, last), k(prims, tris, mid)) {
        swap(prims, tris, last, mid);
    }
    swap(prims, tris, mid, last);
    let pivot = k(prims, tris, last);
    let mut store = 0;
    for i in 0..last {
        if before(k(prims, tris, i), pivot) {
            swap(prims, tris, i, store);
            store += 1;
        }
    }
    swap(prims, tris, store, last);
    store
}

/// In-place heapsort by the same key: a fixed O(n log n) bound whatever the input.
fn heap_sort(prims: &mut [PrimRef], tris: &mut [u32], axis: usize) {
    let len = prims.len().min(tris.len());
    let sift_down = |prims: &mut [PrimRef], tris: &mut [u32], mut root: usize, end: usize| {
        loop {
            let mut child = 2 * root + 1;
            if child >= end {
                break;
            }
            if child + 1 < end
                && before(
                    key(prims, tris, axis, child),
                    key(prims, tris, axis, child + 1),
                )
            {
                child += 1;
            }
            if !before(key(prims, tris, axis, root), key(prims, tris, axis, child)) {
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

#[cfg(test)]
mod tests {
    use glam::Vec3A;

    use super::*;

    /// Boxes whose centroids repeat (many ties broken by the triangle index), in an order
    /// from a small generator, with their triangle indices shuffled alike.
    fn boxes(n: usize, seed: u32) -> (std::vec::Vec<PrimRef>, std::vec::Vec<u32>) {
        let mut s = seed;
        let mut next = move || {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            s
        };
        (0..n)
            .map(|i| {
                let c = Vec3A::new((next() % 37) as f32, (next() % 5) as f32, next() as f32);
                // 7 shares no factor with the sizes tested: the indices are distinct.
                (PrimRef { min: c, max: c }, i as u32 * 7 % n as u32)
            })
            .unzip()
    }

    #[test]
    fn sorts_like_a_sort_of_the_keys_on_every_axis_and_size() {
        for n in [0, 1, 2, 3, 16, 17, 100, 1000, 5000] {
            for axis in 0..3 {
                let (mut prims, mut tris) = boxes(n, 12345 + n as u32);
                let mut expected: std::vec::Vec<_> = prims
                    .iter()
                    .zip(&tris)
                    .map(|(p, &t)| (lane(p.centroid2(), axis), t, *p))
                    .collect();
                expected.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                sort_by_centroid(&mut prims, &mut tris, axis);
                let got: std::vec::Vec<_> =
                    prims.iter().zip(&tris).map(|(p, &t)| (t, *p)).collect();
                let want: std::vec::Vec<_> = expected.iter().map(|e| (e.1, e.2)).collect();
                assert_eq!(got, want, "n {n} axis {axis}");
                assert!(is_sorted(&prims, &tris, axis));
            }
        }
    }

    #[test]
    fn heapsort_alone_sorts_too() {
        let (mut prims, mut tris) = boxes(779, 99);
        heap_sort(&mut prims, &mut tris, 1);
        assert!(is_sorted(&prims, &tris, 1));
        let (mut prims, mut tris) = boxes(779, 99);
        introsort(&mut prims, &mut tris, 0, 0);
        assert!(is_sorted(&prims, &tris, 0));
    }
}
