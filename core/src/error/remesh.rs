//! Why a mesh could not be remeshed.

use core::fmt;

use super::BuildError;

/// Which caller buffer a [`RemeshError::BufferTooSmall`] is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum RemeshBuffer {
    /// Vertex positions (one per vertex).
    Positions,
    /// Half-edge origins and twins (three per triangle each).
    HalfEdges,
    /// One outgoing half-edge per vertex.
    VertexHalfEdges,
    /// The scratch that pairs half-edges (three per triangle, and at least one per vertex).
    Scratch,
}

impl RemeshBuffer {
    /// The buffer's name in messages.
    const fn name(self) -> &'static str {
        match self {
            Self::Positions => "position",
            Self::HalfEdges => "half-edge",
            Self::VertexHalfEdges => "vertex half-edge",
            Self::Scratch => "scratch",
        }
    }
}

/// Why a mesh could not be remeshed.
///
/// The topology variants name the input's vertices and triangles by their indices in the mesh
/// given, so the offending spot can be found in a modelling tool.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RemeshError {
    /// A caller buffer cannot hold the input mesh. Nothing usable was written. Fix: size the
    /// buffers as [`HalfEdgeMesh::from_mesh`](crate::remesh::HalfEdgeMesh::from_mesh) says.
    BufferTooSmall {
        /// Which buffer.
        buffer: RemeshBuffer,
        /// Elements needed.
        needed: usize,
        /// Elements given.
        got: usize,
    },
    /// A [`RemeshConfig`](crate::remesh::RemeshConfig) field is out of its documented range
    /// (or the input has no edges to take a mean length from). Fix: see that field's
    /// documentation.
    InvalidConfig {
        /// The field's name.
        field: &'static str,
    },
    /// The BVH of the input that remeshing projects onto could not be built.
    ReferenceBvh {
        /// Why.
        error: BuildError,
    },
    /// An edit needed more room than the buffers have. The mesh is left as it was before that
    /// edit: valid, with every earlier edit applied. Fix: give longer buffers.
    OutOfCapacity {
        /// Which buffer ran out.
        buffer: RemeshBuffer,
        /// Its length.
        capacity: usize,
    },
    /// A triangle uses one vertex twice, so it has no area and no orientation. Fix: drop the
    /// triangle.
    RepeatedVertex {
        /// The triangle.
        triangle: u32,
        /// The vertex it repeats.
        vertex: u32,
    },
    /// More than two triangles share the edge between `a` and `b`: the surface branches
    /// there. Fix: separate the sheets, or remove the extra triangles.
    NonManifoldEdge {
        /// One end of the edge.
        a: u32,
        /// The other end.
        b: u32,
        /// How many triangles share it.
        triangles: u32,
    },
    /// Two triangles share the edge between `a` and `b` but run along it the same way, `a` to
    /// `b` in both: their orientations disagree (or the same triangle is listed twice). Fix:
    /// flip one of them (reorder its corners).
    InconsistentOrientation {
        /// Where both triangles' edge starts.
        a: u32,
        /// Where it ends.
        b: u32,
    },
    /// The triangles around `vertex` form more than one fan: two pieces of surface touch at a
    /// single point (a "bow tie"). Fix: split the vertex into one per fan.
    NonManifoldVertex {
        /// The vertex.
        vertex: u32,
    },
}

impl fmt::Display for RemeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::BufferTooSmall {
                buffer,
                needed,
                got,
            } => {
                let which = buffer.name();
                write!(
                    f,
                    "{which} buffer too small: {needed} entries needed, {got} given"
                )
            }
            Self::ReferenceBvh { error } => {
                write!(f, "the input's BVH could not be built: {error}")
            }
            Self::InvalidConfig { field } => write!(f, "remesh setting `{field}` is out of range"),
            Self::OutOfCapacity { buffer, capacity } => {
                let which = buffer.name();
                write!(
                    f,
                    "out of room: the {which} buffer holds {capacity} entries"
                )
            }
            Self::RepeatedVertex { triangle, vertex } => {
                write!(f, "triangle {triangle} uses vertex {vertex} twice")
            }
            Self::NonManifoldEdge { a, b, triangles } => write!(
                f,
                "edge {a}–{b} is shared by {triangles} triangles (non-manifold)"
            ),
            Self::InconsistentOrientation { a, b } => write!(
                f,
                "two triangles run along edge {a}→{b} the same way (inconsistent orientation)"
            ),
            Self::NonManifoldVertex { vertex } => write!(
                f,
                "the triangles around vertex {vertex} form more than one fan (non-manifold vertex)"
            ),
        }
    }
}

impl core::error::Error for RemeshError {}
