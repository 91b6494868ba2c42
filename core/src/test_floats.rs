//! Deterministic random floats for the unit tests, so that every run tests the same cases.

use std::vec::Vec;

/// `n` xorshift floats in `[-1, 1)` from `state` (not zero).
pub(crate) fn floats(mut state: u64, n: usize) -> Vec<f32> {
    (0..n)
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            ((state >> 40) as f32 / (1u64 << 24) as f32) * 2.0 - 1.0
        })
        .collect()
}
