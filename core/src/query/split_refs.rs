//! The references of triangles that spatial splits cut into several leaves, and the rule that
//! lets a query report such a triangle once.

use crate::math::Aabb;

/// One leaf reference of a triangle that a spatial split cut, so that several leaves hold it
/// ([`Bvh::build_spatial`](crate::bvh::Bvh::build_spatial)): 32 bytes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SplitRef {
    /// The mesh triangle.
    pub tri: u32,
    /// The order slot of this reference.
    pub slot: u32,
    /// The box of the leaf whose range holds `slot`, exactly as its node stores it.
    pub leaf_box: Aabb,
}

impl SplitRef {
    /// A placeholder for initialising buffers.
    pub const EMPTY: Self = Self {
        tri: u32::MAX,
        slot: u32::MAX,
        leaf_box: Aabb::EMPTY,
    };
}

impl Default for SplitRef {
    fn default() -> Self {
        Self::EMPTY
    }
}

/// Bytes of a [`SplitRef`] in a blob: the triangle and the slot as little-endian `u32`, then
/// the box's six coordinates as little-endian `f32` (min then max).
pub const SPLIT_REF_BYTES: usize = 32;

impl SplitRef {
    /// The entry's blob record (see [`SPLIT_REF_BYTES`]).
    #[must_use]
    pub fn to_le_bytes(&self) -> [u8; SPLIT_REF_BYTES] {
        let mut out = [0u8; SPLIT_REF_BYTES];
        let b = self.leaf_box;
        let words = [
            self.tri,
            self.slot,
            b.min.x.to_bits(),
            b.min.y.to_bits(),
            b.min.z.to_bits(),
            b.max.x.to_bits(),
            b.max.y.to_bits(),
            b.max.z.to_bits(),
        ];
        for (chunk, w) in out.chunks_exact_mut(4).zip(words) {
            chunk.copy_from_slice(&w.to_le_bytes());
        }
        out
    }

    /// The entry a blob record holds (see [`SPLIT_REF_BYTES`]).
    #[must_use]
    pub fn from_le_bytes(bytes: &[u8; SPLIT_REF_BYTES]) -> Self {
        let mut w = [0u32; 8];
        for (word, chunk) in w.iter_mut().zip(bytes.chunks_exact(4)) {
            *word = u32::from_le_bytes([
                chunk.first().copied().unwrap_or(0),
                chunk.get(1).copied().unwrap_or(0),
                chunk.get(2).copied().unwrap_or(0),
                chunk.get(3).copied().unwrap_or(0),
            ]);
        }
        let [tri, slot, x0, y0, z0, x1, y1, z1] = w;
        let v = |x: u32, y: u32, z: u32| {
            glam::Vec3::new(f32::from_bits(x), f32::from_bits(y), f32::from_bits(z))
        };
        Self {
            tri,
            slot,
            leaf_box: Aabb::new(v(x0, y0, z0), v(x1, y1, z1)),
        }
    }
}

/// Where a table's entries live: typed, or as blob records read in place.
#[derive(Clone, Copy, Debug)]
enum Entries<'a> {
    Typed(&'a [SplitRef]),
    #[cfg_attr(not(feature = "blob-spatial"), allow(dead_code))]
    Records(&'a [[u8; SPLIT_REF_BYTES]]),
}

/// The [`SplitRef`]s of a tree, sorted by triangle then slot: one entry per reference of every
/// triangle the tree holds more than once, none for the others. Empty for a tree without
/// spatial splits. Reads typed entries or a blob's records in place.
///
/// A query that reports each triangle it meets (overlaps, triangle pairs) asks
/// [`SplitRefs::reports`] before reporting a triangle met in a leaf: of a triangle's
/// references, only the first (by slot) whose leaf box the query enters reports it. A query
/// whose test of a box is monotone (a box that holds another is entered whenever that one is)
/// enters every leaf on the way to that reference, and meets the triangle there whenever it
/// meets it anywhere, since each reference's leaf holds the part of the triangle that
/// reference stands for. So the triangle is reported exactly once.
#[derive(Clone, Copy, Debug)]
pub struct SplitRefs<'a> {
    entries: Entries<'a>,
}

/// Equal when the entries are, wherever they are stored.
impl PartialEq for SplitRefs<'_> {
    fn eq(&self, other: &Self) -> bool {
        self.len() == other.len() && self.iter().eq(other.iter())
    }
}

impl Default for SplitRefs<'_> {
    fn default() -> Self {
        Self::NONE
    }
}

impl<'a> SplitRefs<'a> {
    /// No split references (a tree without spatial splits).
    pub const NONE: SplitRefs<'static> = SplitRefs {
        entries: Entries::Typed(&[]),
    };

    /// A view over `refs`, which must be sorted by `(tri, slot)` (unchecked here: an unsorted
    /// table gives wrong counts of reports, never a panic).
    #[must_use]
    pub const fn new(refs: &'a [SplitRef]) -> Self {
        Self {
            entries: Entries::Typed(refs),
        }
    }

    /// A view over blob records (see [`SPLIT_REF_BYTES`]), sorted as [`SplitRefs::new`] asks.
    #[must_use]
    #[cfg(feature = "blob-spatial")]
    pub(crate) const fn from_records(records: &'a [[u8; SPLIT_REF_BYTES]]) -> Self {
        Self {
            entries: Entries::Records(records),
        }
    }

    /// Number of entries.
    #[must_use]
    pub const fn len(&self) -> usize {
        match self.entries {
            Entries::Typed(t) => t.len(),
            Entries::Records(r) => r.len(),
        }
    }

    /// True when no triangle is held more than once.
    #[must_use]
    pub const fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Entry `i` (by triangle, then slot), or `None` past the end.
    #[inline]
    #[must_use]
    pub fn get(&self, i: usize) -> Option<SplitRef> {
        match self.entries {
            Entries::Typed(t) => t.get(i).copied(),
            Entries::Records(r) => r.get(i).map(SplitRef::from_le_bytes),
        }
    }

    /// The entries in order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = SplitRef> + Clone + '_ {
        // Every index below the length has its entry.
        (0..self.len()).map(|i| self.get(i).unwrap_or(SplitRef::EMPTY))
    }

    /// The triangle of entry `i` (`u32::MAX` past the end), decoded alone.
    #[inline]
    fn tri_at(&self, i: usize) -> u32 {
        match self.entries {
            Entries::Typed(t) => t.get(i).map_or(u32::MAX, |r| r.tri),
            Entries::Records(r) => r
                .get(i)
                .and_then(|b| b.first_chunk::<4>())
                .map_or(u32::MAX, |w| u32::from_le_bytes(*w)),
        }
    }

    /// Where the entries of triangle `tri` lie: `first..end` (empty when it is held once).
    #[must_use]
    pub fn range_of(&self, tri: u32) -> core::ops::Range<usize> {
        // Binary searches over the entry index, as `partition_point` does over a slice.
        let point = |pred: &dyn Fn(u32) -> bool| {
            let (mut lo, mut hi) = (0, self.len());
            while lo < hi {
                let mid = lo + (hi - lo) / 2;
                if pred(self.tri_at(mid)) {
                    lo = mid + 1;
                } else {
                    hi = mid;
                }
            }
            lo
        };
        point(&|t| t < tri)..point(&|t| t <= tri)
    }

    /// Every reference of triangle `tri`, by slot (none when it is held once).
    pub fn of(&self, tri: u32) -> impl Iterator<Item = SplitRef> + Clone + '_ {
        self.range_of(tri).filter_map(|i| self.get(i))
    }

    /// Whether the reference of `tri` in `slot` is the one that reports it to a query that
    /// enters boxes by `enters`: always for a triangle held once; otherwise when `enters`
    /// accepts this reference's leaf box and none of the triangle's earlier references'.
    #[inline]
    pub fn reports(&self, slot: usize, tri: u32, mut enters: impl FnMut(&Aabb) -> bool) -> bool {
        if self.is_empty() {
            return true;
        }
        for r in self.of(tri) {
            let entered = enters(&r.leaf_box);
            if r.slot as usize == slot {
                return entered;
            }
            if entered {
                return false;
            }
        }
        // A slot missing from the table (a table that does not match its tree) reports.
        true
    }

    /// Whether the pair of references (`a`: slot, triangle and leaf box of a reference in this
    /// table's tree; `b`: the same in `other`'s) is the one that reports the triangle pair to
    /// a walk that pairs leaves whose boxes `meet`: the first pair, in order of `a`'s
    /// reference then `b`'s, whose leaf boxes meet. A triangle held once stands for its one
    /// reference. Always true when neither triangle is split.
    pub(crate) fn reports_pair(
        &self,
        a: (usize, u32, Aabb),
        other: &SplitRefs<'_>,
        b: (usize, u32, Aabb),
        mut meet: impl FnMut(&Aabb, &Aabb) -> bool,
    ) -> bool {
        let (range_a, range_b) = (self.range_of(a.1), other.range_of(b.1));
        if range_a.is_empty() && range_b.is_empty() {
            return true;
        }
        for ra in refs_or_one(self, range_a, a) {
            for rb in refs_or_one(other, range_b.clone(), b) {
                let met = meet(&ra.leaf_box, &rb.leaf_box);
                if ra.slot as usize == a.0 && rb.slot as usize == b.0 {
                    return met;
                }
                if met {
                    return false;
                }
            }
        }
        true
    }
}

/// The entries `range` of `table`, or, when it is empty (a triangle held once), the one
/// reference `at` (slot, triangle, leaf box) the walk is at.
fn refs_or_one<'t>(
    table: &'t SplitRefs<'_>,
    range: core::ops::Range<usize>,
    at: (usize, u32, Aabb),
) -> impl Iterator<Item = SplitRef> + 't {
    let one = range.is_empty().then(|| SplitRef {
        tri: at.1,
        slot: u32::try_from(at.0).unwrap_or(u32::MAX),
        leaf_box: at.2,
    });
    one.into_iter()
        .chain(range.filter_map(move |i| table.get(i)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn entry(tri: u32, slot: u32, x: f32) -> SplitRef {
        SplitRef {
            tri,
            slot,
            leaf_box: Aabb::new(Vec3::splat(x), Vec3::splat(x + 1.0)),
        }
    }

    fn table() -> [SplitRef; 5] {
        [
            entry(2, 4, 0.0),
            entry(2, 9, 2.0),
            entry(7, 1, 0.0),
            entry(7, 5, 4.0),
            entry(7, 8, 8.0),
        ]
    }

    #[cfg(feature = "blob-spatial")]
    #[test]
    fn records_read_back_as_the_entries_they_were_made_from() {
        let typed = table();
        let records: Vec<_> = typed.iter().map(SplitRef::to_le_bytes).collect();
        let from_bytes = SplitRefs::from_records(&records);
        let from_typed = SplitRefs::new(&typed);
        assert_eq!(from_bytes.iter().collect::<Vec<_>>(), typed.to_vec());
        for tri in 0..10 {
            assert_eq!(from_bytes.range_of(tri), from_typed.range_of(tri), "{tri}");
        }
    }

    #[test]
    fn each_triangle_has_the_range_of_its_entries() {
        let typed = table();
        let t = SplitRefs::new(&typed);
        assert_eq!(t.range_of(7), 2..5);
        assert_eq!(t.range_of(3), 2..2);
        assert_eq!(t.range_of(0), 0..0);
    }

    #[test]
    fn the_first_entered_reference_reports() {
        let typed = table();
        let t = SplitRefs::new(&typed);
        // A query entering boxes that reach x ≥ 3.5: of triangle 7's references (boxes at 0,
        // 4 and 8), the one in slot 5 reports, the one in slot 8 does not.
        let enters = |b: &Aabb| b.max.x >= 3.5;
        assert!(!t.reports(1, 7, enters));
        assert!(t.reports(5, 7, enters));
        assert!(!t.reports(8, 7, enters));
        // Triangles held once always report.
        assert!(t.reports(3, 3, |_| false));
        assert!(SplitRefs::NONE.reports(0, 7, |_| false));
        // Pairs: triangle 2 (boxes at 0 and 2) against triangle 7 of the same table, boxes
        // meeting when they overlap: (slot 4, slot 1) is the first pair that meets.
        let meet = |a: &Aabb, b: &Aabb| a.overlaps(b);
        let r = |sa: usize, sb: usize, ta: u32, tb: u32| {
            t.reports_pair((sa, ta, Aabb::EMPTY), &t, (sb, tb, Aabb::EMPTY), meet)
        };
        assert!(r(4, 1, 2, 7));
        assert!(!r(9, 5, 2, 7));
        assert!(!r(4, 5, 2, 7));
        // A triangle held once (0) against triangle 7: its own leaf box stands for it.
        let once = Aabb::new(Vec3::splat(4.5), Vec3::splat(5.0));
        assert!(t.reports_pair((0, 0, once), &t, (5, 7, Aabb::EMPTY), meet));
        assert!(!t.reports_pair((0, 0, once), &t, (8, 7, Aabb::EMPTY), meet));
    }
}
