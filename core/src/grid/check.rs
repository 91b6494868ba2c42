//! Checking that arrays form a grid.

use super::{GridConfig, GridLayout};
use crate::cells::{Words, first_bad_reference};
use crate::error::StructureError;

/// Checks `offsets` and `items` against `layout` (see [`Grid::from_parts`](super::Grid::from_parts)).
pub(super) fn check<W: Words>(
    layout: &GridLayout,
    offsets: W,
    items: W,
    triangle_count: usize,
) -> Result<(), StructureError> {
    if layout
        .resolution
        .iter()
        .any(|&r| r == 0 || r > GridConfig::MAX_RESOLUTION)
    {
        return Err(StructureError::BadResolution);
    }
    let b = layout.bounds;
    // A grid over no triangles has the empty box (infinite corners), as every structure does.
    let empty_mesh = triangle_count == 0 && b.is_empty();
    if !empty_mesh && (!b.is_finite() || b.is_empty()) {
        return Err(StructureError::BadBounds { node: 0 });
    }
    let cells = layout.cell_count().ok_or(StructureError::BadResolution)?;
    if offsets.len() != cells + 1 {
        return Err(StructureError::BadResolution);
    }
    let mut prev = 0u32;
    for c in 0..=cells {
        let o = offsets.word(c).ok_or(StructureError::BadResolution)?;
        let out_of_order = if c == 0 { o != 0 } else { o < prev };
        if out_of_order || (c == cells && o as usize != items.len()) {
            return Err(StructureError::BadCellOffsets { cell: c as u32 });
        }
        prev = o;
    }
    let Some((i, tri)) = first_bad_reference(items, triangle_count) else {
        return Ok(());
    };
    let cell = (0..cells)
        .find(|&c| offsets.word(c + 1).is_some_and(|e| e as usize > i))
        .unwrap_or(0);
    Err(StructureError::TriangleOutOfRange {
        node: cell as u32,
        tri,
    })
}
