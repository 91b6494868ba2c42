//! Leaf access: which triangles a leaf holds, and where their corners are read.

use core::slice;

use super::Cell;
use crate::math::{PackedTriangle, Triangle};
use crate::mesh::ValidMesh;

/// The triangles of one leaf (or cell): `(slot, mesh triangle index)` pairs, slots ascending by
/// one from the first.
///
/// The *slot* is the position of the entry in the structure's reference array (a BVH's order
/// array): [`LeafTriangles`] sources stored in that order ([`PackedTriangles`]) read corners
/// by slot; the mesh reads them by triangle index.
///
/// A structure that references a triangle from several cells passes the leaf's
/// [`cell`](Self::cell), and may mark entries it already offered earlier in the same traversal
/// as skipped: iteration leaves them out.
#[derive(Clone, Debug)]
pub struct LeafTriangleIds<'a> {
    next_slot: usize,
    /// Bit `i` set: the entry `i` places after the current one is skipped.
    skip: u64,
    cell: Option<Cell>,
    ids: Ids<'a>,
}

#[derive(Clone, Debug)]
enum Ids<'a> {
    /// Native `u32`s in a slice.
    Words(slice::Iter<'a, u32>),
    /// Little-endian `u32`s in bytes (a blob).
    Bytes(slice::Iter<'a, [u8; 4]>),
}

impl<'a> LeafTriangleIds<'a> {
    /// The triangles `ids`, in slots `first_slot, first_slot + 1, …`.
    #[inline(always)]
    #[must_use]
    pub fn new(first_slot: usize, ids: &'a [u32]) -> Self {
        Self {
            next_slot: first_slot,
            skip: 0,
            cell: None,
            ids: Ids::Words(ids.iter()),
        }
    }

    /// The triangles in slots `first..first + count` of `order`, or `None` unless all exist.
    #[inline(always)]
    #[must_use]
    pub(crate) fn in_order(order: &'a [u32], first: usize, count: usize) -> Option<Self> {
        let ids = order.get(first..first.checked_add(count)?)?;
        Some(Self::new(first, ids))
    }

    /// [`LeafTriangleIds::new`] over little-endian `u32`s stored as bytes (as a blob holds
    /// them), read in place.
    #[inline(always)]
    #[must_use]
    pub fn from_le_bytes(first_slot: usize, ids: &'a [[u8; 4]]) -> Self {
        Self {
            next_slot: first_slot,
            skip: 0,
            cell: None,
            ids: Ids::Bytes(ids.iter()),
        }
    }

    /// The same entries, with entry `i` (counted from the next one) left out of iteration when
    /// bit `i` of `mask` is set: entries a structure already offered in this traversal. Only
    /// the first 64 entries can be skipped.
    #[inline(always)]
    #[must_use]
    pub(crate) const fn skipping(mut self, mask: u64) -> Self {
        self.skip = mask;
        self
    }

    /// The same entries, as the leaf of `cell` (see [`LeafTriangleIds::cell`]).
    #[inline(always)]
    #[must_use]
    pub(crate) const fn with_cell(mut self, cell: Cell) -> Self {
        self.cell = Some(cell);
        self
    }

    /// The cell this leaf owns, when the structure may reference a triangle from several
    /// leaves (k-d tree, octree, grid); `None` for a structure that references each triangle
    /// once (a BVH), and possibly for a visitor whose
    /// [`needs_cells`](super::VisitorHints::needs_cells) hint is false. A query that reports triangles
    /// must report each from one cell only: see [`Cell`].
    #[inline(always)]
    #[must_use]
    pub const fn cell(&self) -> Option<&Cell> {
        self.cell.as_ref()
    }

    /// The slot of the next entry (the first one, before iterating), skipped or not.
    #[inline(always)]
    #[must_use]
    pub(crate) const fn first_slot(&self) -> usize {
        self.next_slot
    }

    /// Entries left, skipped ones included (the length of the slot run they occupy).
    #[inline(always)]
    #[must_use]
    pub fn entries(&self) -> usize {
        match &self.ids {
            Ids::Words(it) => it.len(),
            Ids::Bytes(it) => it.len(),
        }
    }

    /// The skip mask of the next (up to) 64 entries, as [`skipping`](Self::skipping) set it
    /// (for the tests of the lane reads).
    #[cfg(test)]
    #[must_use]
    pub(crate) const fn skip_mask(&self) -> u64 {
        self.skip
    }

    /// The next `n` entries (at most four, fewer if fewer are left) at once: their triangles
    /// in lanes (lanes past them hold 0) and the mask of the lanes not skipped. Every lane is
    /// read through a select of addresses, not a branch on how many entries the leaf has.
    #[inline(always)]
    pub(crate) fn next_four(&mut self, n: usize) -> ([u32; 4], u32) {
        const NONE: u32 = 0;
        const NONE_BYTES: [u8; 4] = [0; 4];
        let (ids, left) = match &mut self.ids {
            Ids::Words(it) => {
                let rest = it.as_slice();
                let ids = core::array::from_fn(|i| *rest.get(i).unwrap_or(&NONE));
                *it = rest.get(n.min(rest.len())..).unwrap_or(&[]).iter();
                (ids, rest.len())
            }
            Ids::Bytes(it) => {
                let rest = it.as_slice();
                let ids = core::array::from_fn(|i| {
                    u32::from_le_bytes(*rest.get(i).unwrap_or(&NONE_BYTES))
                });
                *it = rest.get(n.min(rest.len())..).unwrap_or(&[]).iter();
                (ids, rest.len())
            }
        };
        let taken = n.min(left).min(4);
        let present = (1u32 << taken) - 1;
        let used = present & !(self.skip as u32);
        self.skip = self.skip.checked_shr(taken as u32).unwrap_or(0);
        self.next_slot = self.next_slot.wrapping_add(taken);
        (ids, used)
    }

    /// The next entry, skipped or not: `(slot, triangle, skipped)`.
    #[inline(always)]
    pub(crate) fn next_entry(&mut self) -> Option<(usize, u32, bool)> {
        let tri = match &mut self.ids {
            Ids::Words(it) => *it.next()?,
            Ids::Bytes(it) => u32::from_le_bytes(*it.next()?),
        };
        let slot = self.next_slot;
        self.next_slot = slot.wrapping_add(1);
        let skipped = self.skip & 1 != 0;
        self.skip >>= 1;
        Some((slot, tri, skipped))
    }
}

impl Iterator for LeafTriangleIds<'_> {
    type Item = (usize, u32);

    #[inline(always)]
    fn next(&mut self) -> Option<(usize, u32)> {
        loop {
            let (slot, tri, skipped) = self.next_entry()?;
            if !skipped {
                return Some((slot, tri));
            }
        }
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = self.entries();
        let live_mask = if n >= 64 { u64::MAX } else { (1u64 << n) - 1 };
        let left = n - (self.skip & live_mask).count_ones() as usize;
        (left, Some(left))
    }
}

impl ExactSizeIterator for LeafTriangleIds<'_> {}

/// Where a query reads a leaf's triangle corners: from the mesh by triangle index, or from
/// [`PackedTriangles`] by slot. Implement it to supply leaf geometry your own way.
pub trait LeafTriangles {
    /// The corners of the triangle in slot `slot`, whose mesh index is `tri`; `None` when the
    /// source does not have it (the query then skips it).
    fn corners(&self, slot: usize, tri: u32) -> Option<Triangle>;

    /// The triangles of slots `first..first + count` as one contiguous run, when the source
    /// stores them that way (as [`PackedTriangles`] do), so a query can load a leaf with wide
    /// loads; `None` (the default) makes queries call [`corners`](Self::corners) per triangle.
    /// A run must hold exactly what `corners` returns for the same slots.
    fn run(&self, first: usize, count: usize) -> Option<&[PackedTriangle]> {
        let _ = (first, count);
        None
    }
}

impl LeafTriangles for ValidMesh<'_> {
    #[inline(always)]
    fn corners(&self, _slot: usize, tri: u32) -> Option<Triangle> {
        self.triangle(tri)
    }
}

/// Triangles copied in a structure's slot order (slot `i` holds mesh triangle `order[i]`), so a
/// leaf reads one contiguous run instead of gathering indices and vertices. Queries given
/// packed triangles return exactly what they return given the mesh, bit for bit, usually
/// faster; the cost is 36 bytes per triangle.
///
/// Made by [`Bvh::pack_triangles`](crate::bvh::Bvh::pack_triangles), or by
/// [`PackedTriangles::new`] over a buffer it filled earlier. Refit does not update it: pack
/// again after vertices move.
#[derive(Clone, Copy, Debug)]
pub struct PackedTriangles<'a> {
    tris: &'a [PackedTriangle],
}

impl<'a> PackedTriangles<'a> {
    /// Wraps triangles in a structure's slot order: what
    /// [`Bvh::pack_triangles`](crate::bvh::Bvh::pack_triangles) wrote for the same tree and
    /// mesh (kept, or moved since). Nothing is checked: triangles in another order give wrong
    /// answers, never a panic; slots past the end are skipped.
    #[inline]
    #[must_use]
    pub const fn new(tris: &'a [PackedTriangle]) -> Self {
        Self { tris }
    }

    /// The packed triangles, in slot order.
    #[must_use]
    pub const fn as_slice(&self) -> &'a [PackedTriangle] {
        self.tris
    }
}

impl LeafTriangles for PackedTriangles<'_> {
    #[inline(always)]
    fn corners(&self, slot: usize, tri: u32) -> Option<Triangle> {
        self.tris.corners(slot, tri)
    }

    #[inline(always)]
    fn run(&self, first: usize, count: usize) -> Option<&[PackedTriangle]> {
        self.tris.run(first, count)
    }
}

/// A slice of triangles in a structure's slot order reads as [`PackedTriangles`] do.
impl LeafTriangles for [PackedTriangle] {
    #[inline(always)]
    fn corners(&self, slot: usize, _tri: u32) -> Option<Triangle> {
        self.get(slot).map(PackedTriangle::triangle)
    }

    #[inline(always)]
    fn run(&self, first: usize, count: usize) -> Option<&[PackedTriangle]> {
        self.get(first..first.checked_add(count)?)
    }
}

#[cfg(test)]
mod tests {
    use super::LeafTriangleIds;

    /// `next_four` takes the same entries, in the same lanes, with the same skips, as `n` calls
    /// of `next_entry`, for words and bytes, every length and skip mask, and leaves the rest
    /// where `next_entry` would.
    #[test]
    fn next_four_is_next_entry_four_times() {
        let words: [u32; 6] = [7, 3, 9, 1, 4, 8];
        let bytes = words.map(u32::to_le_bytes);
        for len in 0..=words.len() {
            for take in 0..=4 {
                for skip in 0..64u64 {
                    let fresh = |as_bytes: bool| {
                        let ids = if as_bytes {
                            LeafTriangleIds::from_le_bytes(10, &bytes[..len])
                        } else {
                            LeafTriangleIds::new(10, &words[..len])
                        };
                        ids.skipping(skip)
                    };
                    for as_bytes in [false, true] {
                        let (mut fast, mut slow) = (fresh(as_bytes), fresh(as_bytes));
                        let (ids, used) = fast.next_four(take);
                        let mut want_used = 0;
                        for (lane, &id) in ids.iter().enumerate().take(take) {
                            if let Some((slot, tri, skipped)) = slow.next_entry() {
                                assert_eq!(slot, 10 + lane);
                                assert_eq!(id, tri, "lane {lane}");
                                want_used |= u32::from(!skipped) << lane;
                            }
                        }
                        assert_eq!(used, want_used, "len {len} take {take} skip {skip:b}");
                        assert_eq!(fast.first_slot(), slow.first_slot());
                        assert_eq!(fast.skip_mask(), slow.skip_mask());
                        assert!(fast.eq(slow), "the rest differs");
                    }
                }
            }
        }
    }
}
