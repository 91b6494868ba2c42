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
        let out = self.packed_slots(out)?;
        pack_run(mesh, self.order, out);
        let tris: &'p [PackedTriangle] = out;
        Ok(PackedTriangles::new(tris))
    }

    /// [`Bvh::pack_triangles`] on rayon's thread pool (feature `parallel`): the same triangles
    /// in the same slots, copied by several threads at once.
    ///
    /// # Errors
    /// As [`Bvh::pack_triangles`].
    #[cfg(feature = "parallel")]
    pub fn pack_triangles_parallel<'p>(
        &self,
        mesh: &ValidMesh<'_>,
        out: &'p mut [PackedTriangle],
    ) -> Result<PackedTriangles<'p>, BuildError> {
        use rayon::prelude::*;
        /// Slots per task: enough copying for a task's start-up to vanish.
        const RUN: usize = 16 * 1024;
        let out = self.packed_slots(out)?;
        out.par_chunks_mut(RUN)
            .zip(self.order.par_chunks(RUN))
            .for_each(|(out, order)| pack_run(mesh, order, out));
        let tris: &'p [PackedTriangle] = out;
        Ok(PackedTriangles::new(tris))
    }

    /// The first slots of `out`, one per triangle of this tree, or the error of a short `out`.
    fn packed_slots<'p>(
        &self,
        out: &'p mut [PackedTriangle],
    ) -> Result<&'p mut [PackedTriangle], BuildError> {
        let (n, got) = (self.order.len(), out.len());
        out.get_mut(..n).ok_or(BuildError::BufferTooSmall {
            buffer: BufferKind::Packed,
            needed: n,
            got,
        })
    }
}

/// Writes the corners of triangle `order[i]` into `out[i]` (triangles the mesh lacks, which a
/// tree built from it never names, leave their slot alone).
fn pack_run(mesh: &ValidMesh<'_>, order: &[u32], out: &mut [PackedTriangle]) {
    for (slot, &tri) in out.iter_mut().zip(order) {
        if let Some(t) = mesh.triangle(tri) {
            *slot = PackedTriangle::new(&t);
        }
    }
}
