use serde::{Deserialize, Serialize};

use super::Bvh;
use crate::error::{BufferKind, BuildError};
use crate::math::{Triangle, Vec3};
use crate::mesh::ValidMesh;

/// A triangle's corners by value: 36 bytes, a plain `#[repr(C)]` record.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PackedTriangle {
    /// First corner.
    pub a: [f32; 3],
    /// Second corner.
    pub b: [f32; 3],
    /// Third corner.
    pub c: [f32; 3],
}

impl PackedTriangle {
    /// The corners as a [`Triangle`].
    #[inline(always)]
    #[must_use]
    pub fn triangle(&self) -> Triangle {
        Triangle::new(
            Vec3::from_array(self.a),
            Vec3::from_array(self.b),
            Vec3::from_array(self.c),
        )
    }

    /// A placeholder for initializing buffers.
    pub const EMPTY: Self = Self {
        a: [0.0; 3],
        b: [0.0; 3],
        c: [0.0; 3],
    };
}

/// Triangles copied in a BVH's leaf order (slot `i` holds mesh triangle `order[i]`), so a leaf
/// reads one contiguous run instead of gathering indices and vertices. Queries given packed
/// triangles return exactly what they return given the mesh, bit for bit, usually faster; the
/// cost is 36 bytes per triangle.
///
/// Made by [`Bvh::pack_triangles`]. Refit does not update it: pack again after vertices move.
#[derive(Clone, Copy, Debug)]
pub struct PackedTriangles<'a> {
    tris: &'a [PackedTriangle],
}

impl<'a> PackedTriangles<'a> {
    /// Wraps triangles known to be in a tree's leaf order.
    #[cfg_attr(not(feature = "blob"), allow(dead_code))]
    pub(crate) const fn from_leaf_order(tris: &'a [PackedTriangle]) -> Self {
        Self { tris }
    }

    /// The packed triangles, in leaf order.
    #[must_use]
    pub const fn as_slice(&self) -> &'a [PackedTriangle] {
        self.tris
    }
}

/// Where a query reads a leaf's triangle corners: from the mesh by triangle index, or from
/// [`PackedTriangles`] by order slot. Implement it to supply leaf geometry your own way.
pub trait LeafTriangles {
    /// The corners of the triangle in order slot `slot`, whose mesh index is `tri`; `None`
    /// when the source does not have it (the query then skips it).
    fn corners(&self, slot: usize, tri: u32) -> Option<Triangle>;

    /// The triangles of order slots `first..first + count` as one contiguous run, when the
    /// source stores them that way (as [`PackedTriangles`] do), so a query can load a leaf
    /// with wide loads; `None` (the default) makes queries call [`corners`](Self::corners) per
    /// triangle. A run must hold exactly what `corners` returns for the same slots.
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

impl LeafTriangles for PackedTriangles<'_> {
    #[inline(always)]
    fn corners(&self, slot: usize, _tri: u32) -> Option<Triangle> {
        self.tris.get(slot).map(PackedTriangle::triangle)
    }

    #[inline(always)]
    fn run(&self, first: usize, count: usize) -> Option<&[PackedTriangle]> {
        self.tris.get(first..first.checked_add(count)?)
    }
}

impl Bvh<'_> {
    /// Copies `mesh`'s triangles into `out` in this tree's leaf order (one per triangle) and
    /// returns the view that queries accept in place of the mesh.
    ///
    /// # Errors
    /// [`BuildError::BufferTooSmall`] (nothing written) when `out` has fewer slots than the
    /// tree has triangles.
    pub fn pack_triangles<'p>(
        &self,
        mesh: &ValidMesh<'_>,
        out: &'p mut [PackedTriangle],
    ) -> Result<PackedTriangles<'p>, BuildError> {
        let n = self.order.len();
        if out.len() < n {
            return Err(BuildError::BufferTooSmall {
                buffer: BufferKind::Packed,
                needed: n,
                got: out.len(),
            });
        }
        let out = out.get_mut(..n).unwrap_or_default();
        for (slot, &tri) in out.iter_mut().zip(self.order) {
            if let Some(t) = mesh.triangle(tri) {
                *slot = PackedTriangle {
                    a: t.a.to_array(),
                    b: t.b.to_array(),
                    c: t.c.to_array(),
                };
            }
        }
        let tris: &'p [PackedTriangle] = out;
        Ok(PackedTriangles { tris })
    }
}
