//! How much room a remeshing run needs.

use super::EdgeTarget;
#[cfg(feature = "alloc")]
use super::HalfEdgeBuffers;
use crate::math::dot;
use crate::mesh::ValidMesh;

/// Buffer sizes for remeshing a mesh toward a target edge length.
///
/// A remesh of surface area `A` toward edge length `L` ends with about `A / (√3/4 · L²)`
/// triangles (equilateral ones of side `L`). Before collapsing, splitting can leave edges as
/// short as `2/3·L`, so the count may pass that on the way (by up to half again, measured on
/// the bundled meshes refined up to tenfold): the estimate allows twice the final count on top
/// of the input's triangles, and one more vertex per added triangle (a closed mesh has about
/// half as many vertices as triangles; a boundary adds one vertex per boundary edge, up to
/// one per triangle on a strip). A run that still needs more stops with
/// [`RemeshError::OutOfCapacity`](crate::error::RemeshError::OutOfCapacity), leaving a
/// valid mesh; retry with larger buffers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RemeshCapacity {
    /// Vertices: the length of `positions`, `vertex_half_edges` and the smoothing scratch.
    pub vertices: usize,
    /// Triangles: three half-edges each (`origins`, `twins` and `creases` are three times as
    /// long).
    pub triangles: usize,
}

impl RemeshCapacity {
    /// The estimate for remeshing `mesh` toward `target` (a multiple of the mean edge length
    /// estimated here over each triangle's three edges).
    #[must_use]
    pub fn for_mesh(mesh: &ValidMesh<'_>, target: EdgeTarget) -> Self {
        // `as` saturates a huge estimate; the sums below saturate too.
        let added = ((2.0 * expected_triangles(mesh, target)) as usize).saturating_add(64);
        Self {
            vertices: mesh.positions().len().saturating_add(added),
            triangles: mesh.triangle_count().saturating_add(added),
        }
    }

    /// The most room a run remeshing `mesh` toward `target` may be given: past it, a run
    /// that still needs more is refused rather than grown. Splits bisect every triangle
    /// across its longest side until no edge is longer than `4/3·L`, so a triangle whose
    /// longest edge is `ℓ` becomes at most about `2·⌈ℓ / (4/3·L)⌉²` pieces; the bound is the
    /// sum of that over the input's triangles plus twelve times the expected count of the
    /// result (`A / (√3/4 · L²)`, see [`RemeshCapacity`]) and 256, with one vertex per
    /// triangle.
    /// Saturates instead of overflowing.
    #[must_use]
    pub fn most_for(mesh: &ValidMesh<'_>, target: EdgeTarget) -> Self {
        let high = area_and_length(mesh, target).1 * 4.0 / 3.0;
        let mut pieces = 0.0f64;
        for t in 0..mesh.triangle_count() as u32 {
            let Some(tri) = mesh.triangle(t) else {
                continue;
            };
            let longest = [(tri.a, tri.b), (tri.b, tri.c), (tri.c, tri.a)]
                .map(|(p, q)| f64::from(libm::sqrtf(dot(q - p, q - p))))
                .into_iter()
                .fold(0.0f64, f64::max);
            let per_side = if high > 0.0 {
                libm::ceil(longest / high).max(1.0)
            } else {
                1.0
            };
            pieces += 2.0 * per_side * per_side;
        }
        // `as` saturates a huge (or infinite) sum.
        let added = ((12.0 * expected_triangles(mesh, target)) as usize).saturating_add(256);
        let triangles = (pieces as usize).saturating_add(added);
        Self {
            vertices: mesh.positions().len().saturating_add(triangles),
            triangles,
        }
    }

    /// Length of the half-edge buffers (`origins`, `twins`, `creases`).
    #[must_use]
    pub const fn half_edges(&self) -> usize {
        self.triangles.saturating_mul(3)
    }

    /// Length of the scratch [`HalfEdgeMesh::from_mesh`](super::HalfEdgeMesh::from_mesh)
    /// needs for an input within this capacity.
    #[must_use]
    pub const fn pairing_scratch(&self) -> usize {
        let h = self.half_edges();
        if h > self.vertices { h } else { self.vertices }
    }
}

/// Buffers of a [`RemeshCapacity`], owned (feature `alloc`).
#[cfg(feature = "alloc")]
#[derive(Clone, Debug, Default)]
pub struct RemeshStorage {
    positions: alloc::vec::Vec<[f32; 3]>,
    origins: alloc::vec::Vec<u32>,
    twins: alloc::vec::Vec<u32>,
    vertex_half_edges: alloc::vec::Vec<u32>,
    creases: alloc::vec::Vec<bool>,
}

#[cfg(feature = "alloc")]
impl RemeshStorage {
    /// Buffers of `capacity`.
    ///
    /// # Errors
    /// [`RemeshError::OutOfCapacity`](crate::error::RemeshError::OutOfCapacity) when the
    /// capacity passes `u32` indexing or the allocator refuses the memory (nothing is left
    /// allocated then).
    pub fn new(capacity: RemeshCapacity) -> Result<Self, crate::error::RemeshError> {
        use crate::error::{RemeshBuffer, RemeshError};
        let limit = super::half_edges::NO_HALF_EDGE as usize - 1;
        let refuse = |buffer, capacity| RemeshError::OutOfCapacity { buffer, capacity };
        if capacity.vertices > limit {
            return Err(refuse(RemeshBuffer::Positions, limit));
        }
        if capacity.half_edges() > limit {
            return Err(refuse(RemeshBuffer::HalfEdges, limit));
        }
        fn filled<T: Clone>(len: usize, value: T) -> Option<alloc::vec::Vec<T>> {
            let mut v = alloc::vec::Vec::new();
            v.try_reserve_exact(len).ok()?;
            v.resize(len, value);
            Some(v)
        }
        let (v, h) = (capacity.vertices, capacity.half_edges());
        let positions = filled(v, [0.0f32; 3]).ok_or(refuse(RemeshBuffer::Positions, v))?;
        let vertex_half_edges = filled(v, 0u32).ok_or(refuse(RemeshBuffer::VertexHalfEdges, v))?;
        let origins = filled(h, 0u32).ok_or(refuse(RemeshBuffer::HalfEdges, h))?;
        let twins = filled(h, 0u32).ok_or(refuse(RemeshBuffer::HalfEdges, h))?;
        let creases = filled(h, false).ok_or(refuse(RemeshBuffer::HalfEdges, h))?;
        Ok(Self {
            positions,
            origins,
            twins,
            vertex_half_edges,
            creases,
        })
    }

    /// The buffers, for [`HalfEdgeMesh::from_mesh`](super::HalfEdgeMesh::from_mesh).
    pub fn buffers(&mut self) -> HalfEdgeBuffers<'_> {
        HalfEdgeBuffers {
            positions: &mut self.positions,
            origins: &mut self.origins,
            twins: &mut self.twins,
            vertex_half_edges: &mut self.vertex_half_edges,
            creases: &mut self.creases,
        }
    }
}

/// The count of equilateral triangles of side `L` (the target) that cover the area of `mesh`:
/// about what a run ends with. Zero for a target of no length.
fn expected_triangles(mesh: &ValidMesh<'_>, target: EdgeTarget) -> f64 {
    let (area, length) = area_and_length(mesh, target);
    if length > 0.0 {
        area / (libm::sqrt(3.0) / 4.0 * length * length)
    } else {
        0.0
    }
}

/// The surface area of `mesh` and the edge length `target` names (a multiple of the mean edge
/// length estimated over each triangle's three edges), in `f64`.
fn area_and_length(mesh: &ValidMesh<'_>, target: EdgeTarget) -> (f64, f64) {
    let (mut area, mut edge_sum, mut edges) = (0.0f64, 0.0f64, 0usize);
    for t in 0..mesh.triangle_count() as u32 {
        let Some(tri) = mesh.triangle(t) else {
            continue;
        };
        area += f64::from(tri.area());
        for (p, q) in [(tri.a, tri.b), (tri.b, tri.c), (tri.c, tri.a)] {
            let d = q - p;
            edge_sum += f64::from(libm::sqrtf(dot(d, d)));
            edges += 1;
        }
    }
    let mean = if edges > 0 {
        edge_sum / edges as f64
    } else {
        0.0
    };
    let length = match target {
        EdgeTarget::Length(length) => f64::from(length),
        EdgeTarget::MeanEdgeTimes(ratio) => f64::from(ratio) * mean,
    };
    (area, length)
}
