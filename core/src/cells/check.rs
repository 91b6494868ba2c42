//! Checks every cell structure's validator shares.

use super::Words;
use crate::error::StructureError;

/// The first reference in `items` that names no triangle of a mesh of `triangle_count`
/// triangles: `(position, value)`.
pub(crate) fn first_bad_reference<W: Words>(
    items: W,
    triangle_count: usize,
) -> Option<(usize, u32)> {
    (0..items.len()).find_map(|i| {
        let tri = items.word(i).unwrap_or(u32::MAX);
        (tri as usize >= triangle_count).then_some((i, tri))
    })
}

/// Counts the nodes a validator's walk visits, refusing the walk once it visits more nodes
/// than the array holds (children named twice), so validation and every later walk stay
/// bounded by the node count.
pub(crate) struct Visits {
    seen: usize,
    total: usize,
}

impl Visits {
    /// For an array of `total` nodes.
    pub(crate) const fn new(total: usize) -> Self {
        Self { seen: 0, total }
    }

    /// One more visit; an error past the node count.
    pub(crate) fn visit(&mut self) -> Result<(), StructureError> {
        self.seen += 1;
        if self.seen > self.total {
            return Err(self.error());
        }
        Ok(())
    }

    /// At the end of the walk: an error unless every node was visited exactly once.
    pub(crate) fn finish(&self) -> Result<(), StructureError> {
        if self.seen == self.total {
            Ok(())
        } else {
            Err(self.error())
        }
    }

    fn error(&self) -> StructureError {
        StructureError::UnreachableNodes {
            reached: self.seen as u32,
            total: self.total as u32,
        }
    }
}
