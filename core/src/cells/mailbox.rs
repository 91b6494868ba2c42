//! Remembering the triangles a traversal already offered, so a structure that references a
//! triangle from several cells offers it once.

use crate::query::LeafTriangleIds;

/// Slots of a [`Mailbox`]: enough to remember the triangles of the few cells a ray crosses
/// before a repeat, small enough to clear on every query.
const SLOTS: usize = 32;

/// A small direct-mapped memory of the triangles one traversal has offered: a triangle whose
/// slot still holds it was offered earlier and need not be tested again.
///
/// A structure that references a triangle from several cells (k-d tree, octree, grid) keeps one
/// per traversal, for visitors whose [`skips_repeats`](crate::query::VisitorHints::skips_repeats) hint is true,
/// and marks repeats with [`LeafTriangleIds::skipping`]. Triangle `t` lives in slot
/// `hash(t) mod 32`, so a repeat is caught unless another triangle of the same slot came
/// between: a triangle may be offered again, never wrongly skipped. No allocation; 128 bytes.
#[derive(Clone, Debug)]
pub struct Mailbox {
    slots: [u32; SLOTS],
}

impl Default for Mailbox {
    fn default() -> Self {
        Self::new()
    }
}

impl Mailbox {
    /// An empty mailbox.
    #[inline(always)]
    #[must_use]
    pub const fn new() -> Self {
        Self {
            slots: [u32::MAX; SLOTS],
        }
    }

    /// The leaf `ids` with every triangle this mailbox already holds marked as skipped (among
    /// its first 64 entries), after recording all of them.
    #[inline]
    #[must_use]
    pub fn filter<'a>(&mut self, ids: LeafTriangleIds<'a>) -> LeafTriangleIds<'a> {
        let mut mask = 0u64;
        let mut scan = ids.clone();
        for bit in 0..64 {
            let Some((_, tri, _)) = scan.next_entry() else {
                break;
            };
            // Fibonacci hashing: the top five bits of the product spread neighbouring indices.
            let slot = (tri.wrapping_mul(0x9E37_79B1) >> 27) as usize;
            if let Some(held) = self.slots.get_mut(slot) {
                if *held == tri {
                    mask |= 1 << bit;
                } else {
                    *held = tri;
                }
            }
        }
        ids.skipping(mask)
    }
}
