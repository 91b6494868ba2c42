//! Whether a BVH blob's triangle order is a permutation, checked without memory.
//!
//! An exact check needs a mark per triangle; a view parsed in place (from flash, with no
//! allocator) has none to spare. Instead the sums of two well-mixed 32-bit hashes of every entry
//! are compared with the same sums over `0..n`: an order that is not a permutation changes
//! them, except with a chance of about 2⁻⁶⁴ for damage not crafted against the hashes. Decoding into
//! owned buffers (`MeshBvh::from_blob`) also runs the exact check.

use super::format::ORDER_BYTES;
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

/// Refuses an `order` (little-endian `u32` entries, each already checked to be below its
/// length) that is not a permutation of `0..order.len()`.
pub(super) fn check_order_is_permutation(order: &[[u8; ORDER_BYTES]]) -> Result<(), BlobError> {
    // The sums wrap; for a permutation the entries' and the indices' sums are equal.
    let [mut a, mut b] = [0u32; 2];
    let [sa, sb] = SEEDS;
    for (i, entry) in (0u32..).zip(order) {
        let tri = u32::from_le_bytes(*entry);
        a = a.wrapping_add(mix(tri, sa)).wrapping_sub(mix(i, sa));
        b = b.wrapping_add(mix(tri, sb)).wrapping_sub(mix(i, sb));
    }
    if a == 0 && b == 0 {
        Ok(())
    } else {
        Err(BlobError::OrderNotPermutation)
    }
}

#[cfg(test)]
mod tests {
    use super::check_order_is_permutation;
    use crate::error::BlobError;

    fn entries(order: &[u32]) -> Vec<[u8; 4]> {
        order.iter().map(|t| t.to_le_bytes()).collect()
    }

    #[test]
    fn permutations_pass_and_repeats_do_not() {
        let mut order: Vec<u32> = (0..1000).rev().collect();
        order.swap(3, 700);
        assert_eq!(check_order_is_permutation(&entries(&order)), Ok(()));
        for (slot, to) in [(589, 588), (0, 999), (999, 0), (10, 11)] {
            let mut bad = order.clone();
            bad[slot] = to;
            if bad[slot] == order[slot] {
                continue;
            }
            assert_eq!(
                check_order_is_permutation(&entries(&bad)),
                Err(BlobError::OrderNotPermutation),
                "slot {slot} → {to}"
            );
        }
        // Two entries changed so that their plain sum stays the same.
        let mut bad = order.clone();
        let (a, b) = (bad[5], bad[6]);
        (bad[5], bad[6]) = (a + 1, b - 1);
        assert!(check_order_is_permutation(&entries(&bad)).is_err());
    }
}
