//! Whether a BVH blob's triangle order is a permutation, checked without memory.
//!
//! An exact check needs a mark per triangle; a view parsed in place (from flash, with no
//! allocator) has none to spare. Instead the sums of two well-mixed 32-bit hashes of every entry
//! are compared with the same sums over `0..n`: an order that is not a permutation changes
//! them, except with a chance of about 2⁻⁶⁴ for damage not crafted against the hashes. Decoding into
//! owned buffers (`MeshBvh::from_blob`) also runs the exact check.

use crate::error::BlobError;

/// MurmurHash3's 32-bit finaliser of `x` with `seed` mixed in first: cheap on 32-bit cores
/// (the firmware's), and well mixed.
const fn mix(x: u32, seed: u32) -> u32 {
    let mut h = x ^ seed;
    h = (h ^ (h >> 16)).wrapping_mul(0x85EB_CA6B);
    h = (h ^ (h >> 13)).wrapping_mul(0xC2B2_AE35);
    h ^ (h >> 16)
}

/// Two seeds: two independent 32-bit hashes, a 64-bit fingerprint.
const SEEDS: [u32; 2] = [0x9E37_79B9, 0x7F4A_7C15];

/// The 64-bit fingerprint of a multiset of triangle indices, less another: zero exactly when
/// the two agree (but for damage crafted against the hashes, a chance of about 2⁻⁶⁴).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct MultisetFingerprint([u32; 2]);

impl MultisetFingerprint {
    /// Adds `tri` `times` times (`u32::MAX` times takes it away once: the sums wrap).
    pub(super) fn add(&mut self, tri: u32, times: u32) {
        for (sum, seed) in self.0.iter_mut().zip(SEEDS) {
            *sum = sum.wrapping_add(mix(tri, seed).wrapping_mul(times));
        }
    }

    /// Takes away each of `0..n` once.
    pub(super) fn less_each_below(&mut self, n: usize) {
        for i in (0u32..).take(n) {
            self.add(i, u32::MAX);
        }
    }

    /// Whether the multisets added and taken away agree.
    pub(super) const fn is_balanced(&self) -> bool {
        self.0[0] == 0 && self.0[1] == 0
    }
}

/// Refuses an order (entries each below `n`) that does not name every triangle of `0..n` once
/// plus, for each group of `k` split references of one triangle (`split_tris`: the triangle
/// of every entry of a split reference table, grouped), that triangle `k − 1` times more: the
/// multiset equality, checked by fingerprint. With no split references, the order must be a
/// permutation.
pub(super) fn check_order_covers(
    order: impl Iterator<Item = u32>,
    n: usize,
    split_tris: impl Iterator<Item = u32>,
) -> Result<(), BlobError> {
    let mut fingerprint = MultisetFingerprint::default();
    for tri in order {
        fingerprint.add(tri, 1);
    }
    fingerprint.less_each_below(n);
    // Every entry after the first of its group stands for one more copy of its triangle.
    let mut group: Option<u32> = None;
    for tri in split_tris {
        if group == Some(tri) {
            fingerprint.add(tri, u32::MAX);
        }
        group = Some(tri);
    }
    if fingerprint.is_balanced() {
        Ok(())
    } else {
        Err(BlobError::OrderNotPermutation)
    }
}

#[cfg(test)]
mod tests {
    use super::check_order_covers;
    use crate::error::BlobError;

    fn permutation(order: &[u32]) -> Result<(), BlobError> {
        check_order_covers(order.iter().copied(), order.len(), core::iter::empty())
    }

    #[test]
    fn permutations_pass_and_repeats_do_not() {
        let mut order: Vec<u32> = (0..1000).rev().collect();
        order.swap(3, 700);
        assert_eq!(permutation(&order), Ok(()));
        for (slot, to) in [(589, 588), (0, 999), (999, 0), (10, 11)] {
            let mut bad = order.clone();
            bad[slot] = to;
            if bad[slot] == order[slot] {
                continue;
            }
            assert_eq!(
                permutation(&bad),
                Err(BlobError::OrderNotPermutation),
                "slot {slot} → {to}"
            );
        }
        // Two entries changed so that their plain sum stays the same.
        let mut bad = order.clone();
        let (a, b) = (bad[5], bad[6]);
        (bad[5], bad[6]) = (a + 1, b - 1);
        assert!(permutation(&bad).is_err());
    }

    #[test]
    fn split_triangles_may_repeat_as_often_as_their_entries_say() {
        // Triangles 0..6; triangle 2 held three times, triangle 4 twice.
        let order = [5, 2, 0, 4, 2, 1, 3, 4, 2];
        let entries = [2, 2, 2, 4, 4];
        let covers = |order: &[u32], entries: &[u32]| {
            check_order_covers(order.iter().copied(), 6, entries.iter().copied())
        };
        assert_eq!(covers(&order, &entries), Ok(()));
        // One repeat too few or too many in the table, or a triangle repeated without entries.
        assert!(covers(&order, &[2, 2, 4, 4]).is_err());
        assert!(covers(&order, &[2, 2, 2, 2, 4, 4]).is_err());
        assert!(covers(&[5, 2, 0, 4, 2, 1, 3, 4, 1], &entries).is_err());
        assert!(covers(&[5, 2, 0, 4, 2, 1, 1, 4, 2], &entries).is_err());
        assert!(covers(&order[..8], &entries).is_err());
    }
}
