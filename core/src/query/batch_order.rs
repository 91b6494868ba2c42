//! The order a batch of queries is answered in: Morton order of each point, so that
//! neighbouring queries run one after another and find the nodes and triangles they read still
//! in cache; rays keep the order they are given in. Answers never depend on this order.

use glam::Vec3;

use crate::error::{BatchBuffer, BatchError};
use crate::math::{Aabb, morton_code};

/// Checks a batch of `positions.len()` queries against its `keys` scratch and its `out_len`
/// answers, then fills the first keys with the query indices in Morton order of their
/// positions (code in the high 32 bits, index in the low 32, so equal codes keep the input
/// order) and returns those keys; read the index back with [`query_index`].
///
/// # Errors
/// [`BatchError::TooLarge`] beyond `u32::MAX` queries; [`BatchError::BufferTooSmall`] for a
/// short `keys` or `out_len`. Nothing is written then.
pub(crate) fn morton_order(
    positions: impl ExactSizeIterator<Item = Vec3> + Clone,
    keys: &mut [u64],
    out_len: usize,
) -> Result<&[u64], BatchError> {
    let keys = checked_keys(positions.len(), keys, out_len)?;
    // The grid spans the batch itself, so a cluster of queries still spreads over its cells.
    let bounds = positions
        .clone()
        .filter(|p| p.is_finite())
        .fold(Aabb::EMPTY, |b, p| b.grown(p));
    if bounds.min == bounds.max || bounds.is_empty() {
        // One position for all (a camera's rays): nothing to reorder, the given order stays.
        for (key, i) in keys.iter_mut().zip(0u64..) {
            *key = i;
        }
        return Ok(keys);
    }
    for ((key, p), i) in keys.iter_mut().zip(positions).zip(0u64..) {
        *key = (u64::from(morton_code(p, &bounds)) << 32) | i;
    }
    keys.sort_unstable();
    Ok(keys)
}

/// Writes each key its own index: the given order.
pub(super) fn fill_given_order(keys: &mut [u64]) {
    for (key, i) in keys.iter_mut().zip(0u64..) {
        *key = i;
    }
}

/// The first `n` of `keys`, after checking a batch of `n` queries against them and its
/// `out_len` answers.
pub(super) fn checked_keys(
    n: usize,
    keys: &mut [u64],
    out_len: usize,
) -> Result<&mut [u64], BatchError> {
    if u32::try_from(n).is_err() {
        return Err(BatchError::TooLarge);
    }
    let too_small = |buffer, got| BatchError::BufferTooSmall {
        buffer,
        needed: n,
        got,
    };
    if out_len < n {
        return Err(too_small(BatchBuffer::Results, out_len));
    }
    let got = keys.len();
    keys.get_mut(..n)
        .ok_or(too_small(BatchBuffer::SortKeys, got))
}

/// The query index a [`morton_order`] key carries.
#[inline(always)]
pub(crate) const fn query_index(key: u64) -> usize {
    (key & 0xFFFF_FFFF) as usize
}

/// Queries gathered (and answers scattered) per chunk: the gather and scatter loops then issue
/// their scattered memory accesses back to back, where the CPU overlaps them, rather than one
/// per query between long searches. Small, so a batch costs little stack on a microcontroller.
const CHUNK: usize = 16;

/// Answers `queries` in the order of `order` (keys from [`morton_order`] or
/// [`ray_order`](super::ray_order::ray_order)) with `answer`, writing each answer to `out` at
/// its query's index.
#[inline(always)]
pub(crate) fn answer_in_order<Q: Copy, T: Copy + Default>(
    queries: &[Q],
    order: &[u64],
    out: &mut [T],
    mut answer: impl FnMut(&Q) -> T,
) {
    let Some(&first) = queries.first() else {
        return;
    };
    let mut gathered = [first; CHUNK];
    let mut answers = [T::default(); CHUNK];
    for keys in order.chunks(CHUNK) {
        for (q, &key) in gathered.iter_mut().zip(keys) {
            if let Some(&found) = queries.get(query_index(key)) {
                *q = found;
            }
        }
        for (a, q) in answers.iter_mut().zip(&gathered).take(keys.len()) {
            *a = answer(q);
        }
        for (a, &key) in answers.iter().zip(keys) {
            if let Some(slot) = out.get_mut(query_index(key)) {
                *slot = *a;
            }
        }
    }
}
