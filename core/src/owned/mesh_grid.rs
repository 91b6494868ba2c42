//! The owned grid's build: the cell offsets and references in one pass over the triangles.

use alloc::vec;
use alloc::vec::Vec;

use crate::cells::ReferencePad;
use crate::error::{BufferKind, BuildError};
use crate::grid::{GridLayout, for_each_cell};
use crate::mesh::ValidMesh;

/// The cell offsets and references of `layout` over `mesh`: what [`Grid::build`] writes given
/// buffers of exactly the measured lengths, found with one pass of triangle–cell tests instead
/// of three (measure, count, fill) by keeping each reference's cell.
pub(super) fn fill_in_one_pass(
    layout: &GridLayout,
    mesh: &ValidMesh<'_>,
) -> Result<(Vec<u32>, Vec<u32>), BuildError> {
    // Offsets and references are `u32`s: past that, say which array cannot hold them (a
    // resolution within `MAX_RESOLUTION` never needs that many cells).
    let too_many = |buffer, needed| BuildError::BufferTooSmall {
        buffer,
        needed,
        got: u32::MAX as usize,
    };
    let cells = layout
        .cell_count()
        .filter(|&c| c < u32::MAX as usize)
        .ok_or(too_many(BufferKind::CellOffsets, usize::MAX))?;
    let pad = ReferencePad::of(&layout.bounds);
    // Each reference's cell, triangle by triangle; `ends[t]` is where triangle t's stop.
    let mut cell_of = Vec::with_capacity(mesh.triangle_count() * 2);
    let mut ends = Vec::with_capacity(mesh.triangle_count());
    let mut offsets = vec![0u32; cells + 1];
    for tri in 0..mesh.triangle_count() as u32 {
        for_each_cell(layout, pad, mesh, tri, |c| {
            cell_of.push(c as u32);
            if let Some(o) = offsets.get_mut(c + 1) {
                *o += 1;
            }
        });
        ends.push(cell_of.len());
    }
    if cell_of.len() > u32::MAX as usize {
        return Err(too_many(BufferKind::References, cell_of.len()));
    }
    let mut sum = 0u32;
    for o in &mut offsets {
        sum += *o;
        *o = sum;
    }
    // A counting sort, triangles ascending within each cell: `next[c]` is where cell c's next
    // reference goes.
    let mut next = offsets.clone();
    let mut items = vec![0u32; cell_of.len()];
    let mut start = 0usize;
    for (tri, &end) in (0u32..).zip(&ends) {
        for &c in cell_of.get(start..end).unwrap_or_default() {
            if let Some(at) = next.get_mut(c as usize) {
                if let Some(slot) = items.get_mut(*at as usize) {
                    *slot = tri;
                }
                *at += 1;
            }
        }
        start = end;
    }
    Ok((offsets, items))
}
