//! [`Remeshed`]: a mesh remeshed in one call, with buffers sized and grown as needed.

use alloc::vec::Vec;

use super::MeshBvh;
use super::sampled_distance::{SampledDistance, sampled_distance};
use crate::bvh::BuildConfig;
use crate::collide::PairBudget;
use crate::error::{RemeshBuffer, RemeshError};
use crate::mesh::ValidMesh;
use crate::remesh::{
    HalfEdgeMesh, MeshQuality, RemeshCapacity, RemeshConfig, RemeshReport, RemeshStorage,
    remesh_with_progress,
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
    /// [`RemeshError::OutOfCapacity`], up to [`RemeshCapacity::most_for`]; every run with
    /// room enough gives the same result, so the answer does not depend on how often that
    /// happened. Memory therefore stays within a stated multiple of the input and of the
    /// result's expected size.
    ///
    /// # Errors
    /// The input's [`RemeshError`] (non-manifold edge or vertex, orientation, repeated vertex,
    /// invalid config), or [`RemeshError::OutOfCapacity`] when a run needs more room than
    /// [`RemeshCapacity::most_for`] (or than `u32` indexing allows), after at most a few
    /// doublings.
    pub fn of(mesh: &ValidMesh<'_>, config: &RemeshConfig) -> Result<Self, RemeshError> {
        Self::with_progress(mesh, config, |_| {})
    }

    /// [`Remeshed::of`], calling `progress` after each iteration with the report so far (a
    /// run restarted with larger buffers counts again from the first iteration).
    ///
    /// # Errors
    /// As [`Remeshed::of`].
    pub fn with_progress(
        mesh: &ValidMesh<'_>,
        config: &RemeshConfig,
        mut progress: impl FnMut(&RemeshReport),
    ) -> Result<Self, RemeshError> {
        config.validate()?;
        let reference = MeshBvh::build(mesh, &BuildConfig::default())
            .map_err(|error| RemeshError::ReferenceBvh { error })?;
        let mut capacity = RemeshCapacity::for_mesh(mesh, config.target);
        let most = RemeshCapacity::most_for(mesh, config.target);
        let too_big = |capacity| RemeshError::OutOfCapacity {
            buffer: RemeshBuffer::Scratch,
            capacity,
        };
        loop {
            let mut storage = RemeshStorage::new(capacity)?;
            // Pairing reads the input only: scratch for the input's size, freed before the run.
            let pairing_len = RemeshCapacity {
                vertices: mesh.vertex_count(),
                triangles: mesh.triangle_count(),
            }
            .pairing_scratch();
            let mut pairing = Vec::new();
            pairing
                .try_reserve_exact(pairing_len)
                .map_err(|_| too_big(pairing_len))?;
            pairing.resize(pairing_len, 0u32);
            let mut he = HalfEdgeMesh::from_mesh(mesh, storage.buffers(), &mut pairing)?;
            drop(pairing);
            let before = MeshQuality::of(&he);
            let mut smoothing = Vec::new();
            smoothing
                .try_reserve_exact(capacity.vertices)
                .map_err(|_| too_big(capacity.vertices))?;
            smoothing.resize(capacity.vertices, [0.0f32; 3]);
            match remesh_with_progress(&mut he, &reference, config, &mut smoothing, &mut progress) {
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
                    if capacity.triangles < most.triangles
                        && capacity.half_edges() < (u32::MAX / 4) as usize =>
                {
                    // Doubled, but never past the bound: a run that needs more than it is
                    // refused with the bound's size.
                    capacity = RemeshCapacity {
                        vertices: capacity.vertices.saturating_mul(2).min(most.vertices),
                        triangles: capacity.triangles.saturating_mul(2).min(most.triangles),
                    };
                }
                Err(e) => return Err(e),
            }
        }
    }
}

impl Remeshed {
    /// The two-sided distance between this mesh and `input`, sampled at every vertex and
    /// triangle centroid of each against the other's surface, relative to the diagonal of
    /// `input`'s bounds (see [`SampledDistance`]): an estimate of the Hausdorff distance from
    /// below.
    ///
    /// `budget` caps the point–triangle tests: on ordinary meshes each sample takes a few
    /// dozen, but where no box separates triangles (many triangles across one spot) each takes
    /// as many as the mesh has, and the run stops when the budget is spent, with the samples
    /// measured so far. [`PairBudget::for_triangles`] of the two triangle counts is the usual
    /// choice; [`PairBudget::UNLIMITED`] measures every sample however long it takes.
    ///
    /// # Errors
    /// [`RemeshError::ReferenceBvh`] when a BVH of either mesh cannot be built.
    pub fn distance_to(
        &self,
        input: &ValidMesh<'_>,
        budget: PairBudget,
    ) -> Result<SampledDistance, RemeshError> {
        let output = crate::mesh::MeshRef::new(&self.positions, &self.triangles)
            .validate()
            .map_err(|_| RemeshError::InvalidConfig {
                field: "output mesh",
            })?;
        sampled_distance(input, &output, budget)
    }
}
