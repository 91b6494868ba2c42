//! Where a blob's queries read triangles: the mesh stored in the blob, or the caller's.

use glam::Vec3;

use super::format::{
    PACKED_BYTES, POSITION_BYTES, TRIANGLE_BYTES, f32x3_from_bytes, u32x3_from_bytes,
};
use crate::error::BlobError;
use crate::math::Triangle;
use crate::mesh::{ValidMesh, check_triangle, check_vertex};
use crate::query::LeafTriangles;

/// The triangles a [`BlobView`](super::BlobView) queries: read in place from the blob, or the
/// caller's mesh for a blob baked without one. Validated at load like a
/// [`ValidMesh`]: coordinates finite and bounded, indices in range.
#[derive(Clone, Copy, Debug)]
pub enum BlobMesh<'a> {
    /// Positions and vertex-index triples in the blob, input order.
    Indexed {
        /// 12 bytes per vertex: x, y, z as little-endian `f32`.
        positions: &'a [[u8; POSITION_BYTES]],
        /// 12 bytes per triangle: three little-endian `u32` vertex indices.
        triangles: &'a [[u8; TRIANGLE_BYTES]],
    },
    /// Triangle corners in the blob, leaf order (slot `i` is input triangle `order[i]`).
    Packed {
        /// 36 bytes per triangle: corners a, b, c.
        corners: &'a [[u8; PACKED_BYTES]],
    },
    /// The caller's mesh (the blob stores none).
    External(ValidMesh<'a>),
}

impl BlobMesh<'_> {
    /// Number of triangles.
    #[must_use]
    pub const fn triangle_count(&self) -> usize {
        match self {
            Self::Indexed { triangles, .. } => triangles.len(),
            Self::Packed { corners } => corners.len(),
            Self::External(m) => m.triangle_count(),
        }
    }

    /// Input triangle `tri`'s vertex indices, when the mesh is indexed (stored or external).
    #[must_use]
    pub fn triangle_indices(&self, tri: u32) -> Option<[u32; 3]> {
        match self {
            Self::Indexed { triangles, .. } => triangles.get(tri as usize).map(u32x3_from_bytes),
            Self::Packed { .. } => None,
            Self::External(m) => m.triangles().get(tri as usize).copied(),
        }
    }

    /// Vertex `vertex`'s position, when the mesh is indexed (stored or external).
    #[must_use]
    pub fn position(&self, vertex: u32) -> Option<[f32; 3]> {
        match self {
            Self::Indexed { positions, .. } => positions.get(vertex as usize).map(f32x3_from_bytes),
            Self::Packed { .. } => None,
            Self::External(m) => m.positions().get(vertex as usize).copied(),
        }
    }

    /// Input triangle `tri`'s corners, when the mesh is indexed (a packed blob stores corners by
    /// leaf slot, not by input index).
    #[must_use]
    pub fn triangle(&self, tri: u32) -> Option<Triangle> {
        match self {
            Self::Indexed { .. } => {
                let [i, j, k] = self.triangle_indices(tri)?;
                Some(Triangle::new(
                    Vec3::from_array(self.position(i)?),
                    Vec3::from_array(self.position(j)?),
                    Vec3::from_array(self.position(k)?),
                ))
            }
            Self::Packed { .. } => None,
            Self::External(m) => m.triangle(tri),
        }
    }
}

impl LeafTriangles for BlobMesh<'_> {
    #[inline(always)]
    fn corners(&self, slot: usize, tri: u32) -> Option<Triangle> {
        match self {
            Self::Indexed {
                positions,
                triangles,
            } => {
                let [i, j, k] = u32x3_from_bytes(triangles.get(tri as usize)?);
                let p = |v: u32| {
                    positions
                        .get(v as usize)
                        .map(|b| Vec3::from_array(f32x3_from_bytes(b)))
                };
                Some(Triangle::new(p(i)?, p(j)?, p(k)?))
            }
            Self::Packed { corners } => {
                // The corners carry no index of their own: refusing an out-of-range `tri` here
                // is what lets validation reject an order entry that names no triangle.
                if tri as usize >= corners.len() {
                    return None;
                }
                let ([a, b, c], []) = corners.get(slot)?.as_chunks::<12>() else {
                    return None;
                };
                Some(Triangle::new(
                    Vec3::from_array(f32x3_from_bytes(a)),
                    Vec3::from_array(f32x3_from_bytes(b)),
                    Vec3::from_array(f32x3_from_bytes(c)),
                ))
            }
            Self::External(m) => m.triangle(tri),
        }
    }
}

/// Checks stored positions and triangles with the rules of [`MeshRef::validate`](crate::mesh::MeshRef::validate).
pub(super) fn check_indexed(
    positions: &[[u8; POSITION_BYTES]],
    triangles: &[[u8; TRIANGLE_BYTES]],
) -> Result<(), BlobError> {
    let vertex_count = u32::try_from(positions.len()).map_err(|_| BlobError::TooLarge)?;
    for (vertex, p) in (0u32..).zip(positions) {
        check_vertex(vertex, f32x3_from_bytes(p))?;
    }
    for (triangle, t) in (0u32..).zip(triangles) {
        check_triangle(triangle, u32x3_from_bytes(t), vertex_count)?;
    }
    Ok(())
}

/// Checks stored packed corners (each corner counts as a vertex, numbered `3·slot + corner`).
pub(super) fn check_packed(corners: &[[u8; PACKED_BYTES]]) -> Result<(), BlobError> {
    for (slot, t) in (0u32..).zip(corners) {
        let (points, _) = t.as_chunks::<12>();
        for (corner, p) in (0u32..).zip(points) {
            let vertex = slot.saturating_mul(3).saturating_add(corner);
            check_vertex(vertex, f32x3_from_bytes(p)).map_err(BlobError::from)?;
        }
    }
    Ok(())
}
