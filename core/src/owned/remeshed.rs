//! [`Remeshed`]: a mesh remeshed in one call, with buffers sized and grown as needed.

use alloc::vec;
use alloc::vec::Vec;

use super::MeshBvh;
use crate::bvh::BuildConfig;
use crate::error::RemeshError;
use crate::mesh::ValidMesh;
use crate::remesh::{
    HalfEdgeMesh, MeshQuality, RemeshCapacity, RemeshConfig, RemeshReport, RemeshStorage, remesh,
};

/// A remeshed copy of a mesh: its vertices and triangles, what the run did, and the quality
/// figures before and after.
#[derive(Clone, Debug)]
pub struct Remeshed {
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Triangles, as indices into `positions`, oriented as the input.
    pub triangles: Vec<[u32; 3]>,
    /// Splits, collapses, flips, creases, iterations.
    pub report: RemeshReport,
    /// The input's quality figures.
    pub before: MeshQuality,
    /// The result's quality figures.
    pub after: MeshQuality,
}

impl Remeshed {
    /// Remeshes `mesh` with `config`, projecting onto a BVH of the input. Buffers start at
    /// [`RemeshCapacity::for_mesh`] and double while a run reports
    /// [`RemeshError::OutOfCapacity`]; every run with room enough gives the same result, so
    /// the answer does not depend on how often that happened.
    ///
    /// # Errors
    /// The input's [`RemeshError`] (non-manifold edge or vertex, orientation, repeated vertex,
    /// invalid config), or [`RemeshError::OutOfCapacity`] once buffers would pass `u32`
    /// indexing.
    pub fn of(mesh: &ValidMesh<'_>, config: &RemeshConfig) -> Result<Self, RemeshError> {
        config.validate()?;
        let reference = MeshBvh::build(mesh, &BuildConfig::default())
            .map_err(|error| RemeshError::ReferenceBvh { error })?;
        let mut capacity = RemeshCapacity::for_mesh(mesh, config.target_length);
        loop {
            let mut storage = RemeshStorage::new(capacity);
            let mut pairing = vec![0u32; capacity.pairing_scratch()];
            let mut he = HalfEdgeMesh::from_mesh(mesh, storage.buffers(), &mut pairing)?;
            let before = MeshQuality::of(&he);
            let mut smoothing = vec![[0.0f32; 3]; capacity.vertices];
            match remesh(&mut he, &reference, config, &mut smoothing) {
                Ok(report) => {
                    return Ok(Self {
                        positions: he.used_positions().to_vec(),
                        triangles: (0..he.triangle_count() as u32)
                            .map(|t| he.triangle(t))
                            .collect(),
                        report,
                        before,
                        after: MeshQuality::of(&he),
                    });
                }
                Err(RemeshError::OutOfCapacity { .. })
                    if capacity.half_edges() < (u32::MAX / 4) as usize =>
                {
                    capacity = RemeshCapacity {
                        vertices: capacity.vertices.saturating_mul(2),
                        triangles: capacity.triangles.saturating_mul(2),
                    };
                }
                Err(e) => return Err(e),
            }
        }
    }
}
