//! A built grid over its arrays.

use super::GridLayout;
use crate::cells::{CellStats, Words};
#[cfg(feature = "blob-cells")]
use crate::cells::{Coverage, Held, ReferencePad};
use crate::error::StructureError;
#[cfg(feature = "blob-cells")]
use core::ops::ControlFlow;

/// A uniform grid: its [`GridLayout`] cut into cells, each listing the triangles it touches.
///
/// `offsets` has one entry per cell plus one: cell `c` holds references
/// `offsets[c]..offsets[c + 1]` of `items`, the mesh indices of the triangles it touches in
/// ascending order. The arrays are `&[u32]` from [`Grid::build`] or [`Grid::from_parts`], or a
/// blob's bytes read in place ([`LeWords`](crate::advanced::LeWords)).
///
/// It answers every query through [`Traverse`](crate::query::Traverse): rays walk the cells they
/// cross in order (3D-DDA) and stop once a hit lies before the next cell; other queries visit
/// cell ranges, halving them, nearest first.
#[derive(Clone, Copy, Debug)]
pub struct Grid<W> {
    pub(super) layout: GridLayout,
    pub(super) offsets: W,
    pub(super) items: W,
}

impl<W: Words> Grid<W> {
    /// A grid over arrays written earlier by [`Grid::build`] (kept, copied or stored), after
    /// checking they form one for a mesh of `triangle_count` triangles: resolution in range,
    /// offsets non-decreasing from 0 to the reference count, every reference a triangle of the
    /// mesh. It does not check that each cell lists exactly the triangles touching it: a grid
    /// that lists others answers wrongly, never panics.
    ///
    /// # Errors
    /// The first [`StructureError`] found.
    pub fn from_parts(
        layout: GridLayout,
        offsets: W,
        items: W,
        triangle_count: usize,
    ) -> Result<Self, StructureError> {
        super::check::check(&layout, offsets, items, triangle_count)?;
        Ok(Self {
            layout,
            offsets,
            items,
        })
    }

    /// Wraps arrays this crate built or checked itself, without checking again.
    #[cfg_attr(not(feature = "alloc"), allow(dead_code))]
    pub(crate) const fn from_validated(layout: GridLayout, offsets: W, items: W) -> Self {
        Self {
            layout,
            offsets,
            items,
        }
    }

    /// The cells' geometry.
    #[must_use]
    pub const fn layout(&self) -> &GridLayout {
        &self.layout
    }

    /// The offsets array (cells + 1 entries).
    #[must_use]
    pub const fn offsets(&self) -> W {
        self.offsets
    }

    /// The references array.
    #[must_use]
    pub const fn items(&self) -> W {
        self.items
    }

    /// The references of cell `index`: `(first, count)` in `items`.
    #[inline(always)]
    #[must_use]
    pub fn cell_range(&self, index: usize) -> Option<(usize, usize)> {
        let first = self.offsets.word(index)? as usize;
        let end = self.offsets.word(index + 1)? as usize;
        Some((first, end.checked_sub(first)?))
    }

    #[cfg(feature = "blob-cells")]
    /// The first subject of `coverage` (over `triangles` triangles, cells padded by `pad`, the
    /// build's pad) that touches a cell not holding it; `None` when every cell holds every
    /// subject that touches it.
    pub(crate) fn first_uncovered<C: Words>(
        &self,
        pad: ReferencePad,
        coverage: &mut Coverage<'_, C>,
        triangles: usize,
    ) -> Option<u32> {
        let subjects = coverage.subjects(triangles);
        (0..u32::try_from(subjects).unwrap_or(u32::MAX)).find(|&i| {
            let Some((tri, t)) = coverage.subject(i) else {
                return true;
            };
            let mut missing = false;
            let _ = self.layout.for_each_cell_touched(pad, &t, |c| {
                let held = self
                    .cell_range(c)
                    .map(|(first, n)| coverage.holds(i, tri, first, first + n));
                match held {
                    Some(Held::Yes) => ControlFlow::Continue(()),
                    Some(Held::AsEarlier) => ControlFlow::Break(()),
                    Some(Held::No) | None => {
                        missing = true;
                        ControlFlow::Break(())
                    }
                }
            });
            missing
        })
    }

    /// Cells, references and empty cells, in one pass over the offsets.
    #[must_use]
    pub fn stats(&self, triangles: usize) -> CellStats {
        let cells = self.offsets.len().saturating_sub(1);
        let mut stats = CellStats {
            references: self.items.len(),
            triangles,
            ..CellStats::default()
        };
        for c in 0..cells {
            stats.add_cell(0, self.cell_range(c).map_or(0, |(_, n)| n));
        }
        stats
    }
}
