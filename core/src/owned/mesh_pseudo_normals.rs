//! Pseudo-normals in buffers this value owns.

use alloc::vec;
use alloc::vec::Vec;

use glam::Vec3;

use crate::inside::{PseudoNormalError, PseudoNormals};
use crate::mesh::ValidMesh;

/// The angle-weighted pseudo-normals of a closed, manifold, consistently oriented mesh
/// ([`PseudoNormals`]), owning their buffers: 12 bytes per vertex and 36 per triangle.
#[derive(Clone, Debug)]
pub struct MeshPseudoNormals {
    vertices: Vec<Vec3>,
    edges: Vec<[Vec3; 3]>,
}

impl MeshPseudoNormals {
    /// Computes the pseudo-normals of `mesh`.
    ///
    /// # Errors
    /// As [`PseudoNormals::build`]: an open, non-manifold or inconsistently oriented edge,
    /// named.
    pub fn of(mesh: &ValidMesh<'_>) -> Result<Self, PseudoNormalError> {
        let n = mesh.triangle_count();
        let mut vertices = vec![Vec3::ZERO; mesh.vertex_count()];
        let mut edges = vec![[Vec3::ZERO; 3]; n];
        let mut scratch = vec![(0u64, 0u32); n.saturating_mul(3)];
        PseudoNormals::build(mesh, &mut vertices, &mut edges, &mut scratch)?;
        Ok(Self { vertices, edges })
    }

    /// The pseudo-normals, to sign distances with.
    #[must_use]
    pub fn view(&self) -> PseudoNormals<'_> {
        PseudoNormals::from_parts(&self.vertices, &self.edges)
    }
}
