//! Building a grid: count the references of a resolution, shrink it until they fit, fill.

use core::ops::ControlFlow;

use super::{Grid, GridConfig, GridLayout};
use crate::cells::{REFERENCES_PER_TRIANGLE, ReferencePad};
use crate::error::{BufferKind, BuildError};
use crate::mesh::ValidMesh;

/// What a grid build needs: its layout and the exact length of each buffer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridSizes {
    /// The cells' geometry.
    pub layout: GridLayout,
    /// Length of the offsets buffer: cells + 1.
    pub offsets: usize,
    /// Length of the references buffer: one per triangle and cell it touches.
    pub items: usize,
}

/// Calls `each(cell index)` for every cell triangle `tri` of `mesh` touches, in ascending
/// index order.
pub(crate) fn for_each_cell(
    layout: &GridLayout,
    pad: ReferencePad,
    mesh: &ValidMesh<'_>,
    tri: u32,
    mut each: impl FnMut(usize),
) {
    if let Some(t) = mesh.triangle(tri) {
        let _ = layout.for_each_cell_touched(pad, &t, |c| {
            each(c);
            ControlFlow::Continue(())
        });
    }
}

/// The references `layout` needs for `mesh`, counting no further than `limit`.
fn count_references(layout: &GridLayout, mesh: &ValidMesh<'_>, limit: usize) -> usize {
    let pad = ReferencePad::of(&layout.bounds);
    let mut total = 0usize;
    for tri in 0..mesh.triangle_count() as u32 {
        for_each_cell(layout, pad, mesh, tri, |_| total += 1);
        if total > limit {
            break;
        }
    }
    total
}

/// The finest layout for `mesh` from `config`'s λ, halved (coarser cells) until the cells its
/// triangles' padded boxes span number at most `budget` in all (down to a single cell), with
/// its exact reference count, which that sum bounds. Each try costs one pass over the
/// triangles' boxes; only the layout chosen is counted triangle by cell.
pub(crate) fn layout_within(
    mesh: &ValidMesh<'_>,
    config: &GridConfig,
    budget: usize,
) -> (GridLayout, usize) {
    let mut lambda = config.cells_per_triangle;
    loop {
        let layout = GridLayout::for_triangles(
            mesh.bounds(),
            mesh.triangle_count(),
            lambda,
            config.max_resolution,
        );
        if box_references(&layout, mesh) <= budget || layout.resolution == [1, 1, 1] {
            return (layout, count_references(&layout, mesh, usize::MAX));
        }
        lambda *= 0.5;
    }
}

/// The cells the padded bounds of each triangle of `mesh` span in `layout`, summed
/// (saturating): at least the references, which only touched cells make.
fn box_references(layout: &GridLayout, mesh: &ValidMesh<'_>) -> usize {
    let pad = ReferencePad::of(&layout.bounds);
    let mut total = 0usize;
    for tri in 0..mesh.triangle_count() as u32 {
        let Some(t) = mesh.triangle(tri) else {
            continue;
        };
        let (lo, hi) = layout.cells_touching(&pad.grow(&t.bounds()));
        let span = hi.iter().zip(lo).fold(1usize, |n, (&h, l)| {
            n.saturating_mul(h.saturating_sub(l) as usize + 1)
        });
        total = total.saturating_add(span);
    }
    total
}

/// The reference budget of the owned and measured grids: [`REFERENCES_PER_TRIANGLE`] per
/// triangle.
pub(crate) fn reference_budget(mesh: &ValidMesh<'_>) -> usize {
    mesh.triangle_count()
        .saturating_mul(REFERENCES_PER_TRIANGLE)
}

impl<'a> Grid<&'a [u32]> {
    /// The exact buffer lengths [`Grid::build`] needs to build `mesh` with `config`: the
    /// finest layout from λ, halved until the references number at most
    /// [`REFERENCES_PER_TRIANGLE`] per triangle (on ordinary meshes, λ itself). Counting passes
    /// only; nothing written.
    ///
    /// # Errors
    /// [`BuildError::InvalidConfig`] for a config out of range.
    pub fn measure(mesh: &ValidMesh<'_>, config: &GridConfig) -> Result<GridSizes, BuildError> {
        config.validate()?;
        let (layout, items) = layout_within(mesh, config, reference_budget(mesh));
        let cells = layout.cell_count().unwrap_or(usize::MAX);
        Ok(GridSizes {
            layout,
            offsets: cells.saturating_add(1),
            items,
        })
    }

    /// Builds the grid of `mesh` into `offsets` (cell starts) and `items` (references), which
    /// it borrows. Each cell lists the triangles it touches in ascending index order.
    ///
    /// Stays inside the buffers: when the configured λ needs more cells or references than
    /// they hold, λ is halved (coarser cells) until both fit, down to a single cell. The result
    /// depends only on the mesh, the config and the two lengths. Buffers are used from the
    /// front; the grid borrows exactly the prefix it uses.
    ///
    /// # Errors
    /// - [`BuildError::InvalidConfig`] for a config out of range;
    /// - [`BuildError::BufferTooSmall`] when even one cell does not fit (`offsets` shorter
    ///   than 2 with triangles, `items` shorter than the triangle count). Nothing usable is
    ///   returned then; the buffers' contents are unspecified.
    pub fn build(
        mesh: &ValidMesh<'_>,
        config: &GridConfig,
        offsets: &'a mut [u32],
        items: &'a mut [u32],
    ) -> Result<Self, BuildError> {
        config.validate()?;
        let n = mesh.triangle_count();
        let budget = items.len().min(u32::MAX as usize);
        let mut lambda = config.cells_per_triangle;
        loop {
            let layout = GridLayout::for_triangles(mesh.bounds(), n, lambda, config.max_resolution);
            let cells = layout.cell_count().unwrap_or(usize::MAX);
            let single = layout.resolution == [1, 1, 1];
            if cells < offsets.len() {
                let refs = count_into(
                    &layout,
                    mesh,
                    offsets.get_mut(..=cells).unwrap_or_default(),
                    budget,
                );
                if refs <= budget {
                    return Ok(fill(layout, mesh, offsets, items, cells, refs));
                }
                if single {
                    return Err(BuildError::BufferTooSmall {
                        buffer: BufferKind::References,
                        needed: refs,
                        got: items.len(),
                    });
                }
            } else if single {
                return Err(BuildError::BufferTooSmall {
                    buffer: BufferKind::CellOffsets,
                    needed: 2,
                    got: offsets.len(),
                });
            }
            lambda *= 0.5;
        }
    }
}

/// Counts each cell's references into `offsets[cell + 1]` (`offsets[0] = 0`), stopping once the
/// total passes `limit`; returns the total.
fn count_into(
    layout: &GridLayout,
    mesh: &ValidMesh<'_>,
    offsets: &mut [u32],
    limit: usize,
) -> usize {
    let pad = ReferencePad::of(&layout.bounds);
    offsets.fill(0);
    let mut total = 0usize;
    for tri in 0..mesh.triangle_count() as u32 {
        for_each_cell(layout, pad, mesh, tri, |c| {
            if let Some(o) = offsets.get_mut(c + 1) {
                *o += 1;
            }
            total += 1;
        });
        if total > limit {
            break;
        }
    }
    total
}

/// Writes the cell lists of `layout` (which needs `cells` cells and `refs` references, both
/// fitting, with the counts already in `offsets` by [`count_into`]) by a counting sort, and
/// returns the grid over the used prefixes.
fn fill<'a>(
    layout: GridLayout,
    mesh: &ValidMesh<'_>,
    offsets: &'a mut [u32],
    items: &'a mut [u32],
    cells: usize,
    refs: usize,
) -> Grid<&'a [u32]> {
    let pad = ReferencePad::of(&layout.bounds);
    let offsets = offsets.get_mut(..=cells).unwrap_or_default();
    let items = items.get_mut(..refs).unwrap_or_default();
    // Counts sit one cell up, so the running sum below leaves each cell's start in place.
    let mut sum = 0u32;
    for o in offsets.iter_mut() {
        sum += *o;
        *o = sum;
    }
    // offsets[c] is now the start of cell c; each write advances it to the cell's end…
    for tri in 0..mesh.triangle_count() as u32 {
        for_each_cell(&layout, pad, mesh, tri, |c| {
            if let Some(o) = offsets.get_mut(c) {
                if let Some(slot) = items.get_mut(*o as usize) {
                    *slot = tri;
                }
                *o += 1;
            }
        });
    }
    // …which is the next cell's start: shift back by one.
    for c in (1..=cells).rev() {
        let prev = offsets.get(c - 1).copied().unwrap_or(0);
        if let Some(o) = offsets.get_mut(c) {
            *o = prev;
        }
    }
    if let Some(first) = offsets.first_mut() {
        *first = 0;
    }
    let (offsets, items): (&'a [u32], &'a [u32]) = (offsets, items);
    Grid {
        layout,
        offsets,
        items,
    }
}
