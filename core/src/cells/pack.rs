//! Packed triangles per reference, for structures whose cells share triangles.

use crate::error::{BufferKind, BuildError};
use crate::math::PackedTriangle;
use crate::mesh::ValidMesh;
use crate::query::PackedTriangles;

/// Writes the corners of triangle `items[i]` into `out[i]` for every reference `i`, so the
/// structure's leaves read contiguous runs; returns them as [`PackedTriangles`]. A cell
/// structure's references repeat triangles, so this costs 36 bytes per reference, not per
/// triangle.
///
/// # Errors
/// [`BuildError::BufferTooSmall`] (`Packed`) when `out` is shorter than `items`, and
/// [`BuildError::InvalidConfig`] (`items`) when a reference names a triangle the mesh does not
/// have; nothing is written then.
pub fn pack_references<'p>(
    mesh: &ValidMesh<'_>,
    items: &[u32],
    out: &'p mut [PackedTriangle],
) -> Result<PackedTriangles<'p>, BuildError> {
    if out.len() < items.len() {
        return Err(BuildError::BufferTooSmall {
            buffer: BufferKind::Packed,
            needed: items.len(),
            got: out.len(),
        });
    }
    if items.iter().any(|&t| t as usize >= mesh.triangle_count()) {
        return Err(BuildError::InvalidConfig { field: "items" });
    }
    let out = out.get_mut(..items.len()).unwrap_or_default();
    for (slot, &tri) in out.iter_mut().zip(items) {
        if let Some(t) = mesh.triangle(tri) {
            *slot = PackedTriangle::new(&t);
        }
    }
    let packed: &'p [PackedTriangle] = out;
    Ok(PackedTriangles::new(packed))
}
