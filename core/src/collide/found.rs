//! What the mesh–mesh queries write: pairs of triangles, segments, and the counts.

use glam::Vec3;

/// Two triangles that meet: `a` is a triangle index of the first mesh, `b` of the second (of
/// one mesh, in a self-intersection, with `a < b`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct TrianglePair {
    /// The first mesh's triangle.
    pub a: u32,
    /// The second mesh's triangle.
    pub b: u32,
}

/// Where two triangles cross: the segment `start`–`end` (a single point when they touch at
/// one), in the first mesh's frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CrossingSegment {
    /// The triangles.
    pub pair: TrianglePair,
    /// One end.
    pub start: Vec3,
    /// The other end (equal to `start` for a touching point).
    pub end: Vec3,
}

/// How many results a query found, and how many of them fit in the caller's buffer (the
/// first ones in the query's walk order, which is fixed: the same inputs give the same
/// results in the same order on every target).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[must_use]
pub struct Found {
    /// Results found: all of them, whether they fit or not.
    pub total: usize,
    /// Results written to the front of the buffer: `min(total, buffer length)`.
    pub written: usize,
    /// Triangle pairs tested: those in pairs of leaves whose boxes overlap (a measure of the
    /// walk's work; all pairs but those the boxes rule out). At most the walk's
    /// [`PairBudget`](super::PairBudget).
    pub tested: usize,
}

impl Found {
    /// Whether some results did not fit (the buffer was shorter than [`total`](Self::total)).
    #[must_use]
    pub const fn overflowed(&self) -> bool {
        self.total > self.written
    }

    /// Counts one more result, writing it to `out` when there is room.
    pub(crate) fn push<T>(&mut self, out: &mut [T], item: T) {
        if let Some(slot) = out.get_mut(self.written) {
            *slot = item;
            self.written += 1;
        }
        self.total += 1;
    }
}
