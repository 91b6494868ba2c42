use super::Bvh;
use crate::error::{BufferKind, BuildError};
use crate::math::PackedTriangle;
use crate::mesh::ValidMesh;
use crate::query::PackedTriangles;

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
                *slot = PackedTriangle::new(&t);
            }
        }
        let tris: &'p [PackedTriangle] = out;
        Ok(PackedTriangles::new(tris))
    }
}
