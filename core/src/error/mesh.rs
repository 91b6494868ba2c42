//! Why a mesh was rejected.

use core::fmt;

/// Why a mesh was rejected by [`MeshRef::validate`](crate::mesh::MeshRef::validate) or a flat
/// constructor.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MeshError {
    /// A flat position or index slice's length is not a multiple of 3. Fix: pass whole
    /// `xyz` triples and whole triangles.
    FlatLength {
        /// Which slice.
        what: FlatSlice,
        /// Its length.
        len: usize,
    },
    /// More than `u32::MAX` vertices. Fix: split the mesh.
    TooManyVertices {
        /// The vertex count given.
        count: usize,
    },
    /// More than `u32::MAX` triangles. Fix: split the mesh.
    TooManyTriangles {
        /// The triangle count given.
        count: usize,
    },
    /// A triangle names a vertex that does not exist. Fix: check the index buffer.
    IndexOutOfRange {
        /// The triangle.
        triangle: u32,
        /// The offending vertex index.
        index: u32,
        /// How many vertices there are.
        vertex_count: u32,
    },
    /// A vertex coordinate is NaN or infinite. Fix: clean the input.
    NonFiniteCoordinate {
        /// The vertex.
        vertex: u32,
    },
    /// A vertex coordinate's magnitude exceeds [`MAX_COORDINATE`](crate::math::MAX_COORDINATE),
    /// beyond which products in the kernels could overflow. Fix: rescale or re-centre the mesh.
    CoordinateTooLarge {
        /// The vertex.
        vertex: u32,
    },
}

/// Which flat slice a [`MeshError::FlatLength`] is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FlatSlice {
    /// The `f32` positions.
    Positions,
    /// The `u32` triangle indices.
    Indices,
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::FlatLength { what, len } => {
                let what = match what {
                    FlatSlice::Positions => "positions",
                    FlatSlice::Indices => "indices",
                };
                write!(f, "{what} length {len} is not a multiple of 3")
            }
            Self::TooManyVertices { count } => {
                write!(f, "{count} vertices exceed the limit of u32::MAX")
            }
            Self::TooManyTriangles { count } => {
                write!(f, "{count} triangles exceed the limit of u32::MAX")
            }
            Self::IndexOutOfRange {
                triangle,
                index,
                vertex_count,
            } => write!(
                f,
                "triangle {triangle} uses vertex {index} but there are only {vertex_count} vertices"
            ),
            Self::NonFiniteCoordinate { vertex } => {
                write!(f, "vertex {vertex} has a NaN or infinite coordinate")
            }
            Self::CoordinateTooLarge { vertex } => write!(
                f,
                "vertex {vertex} has a coordinate beyond ±{:e}",
                crate::math::MAX_COORDINATE
            ),
        }
    }
}

impl core::error::Error for MeshError {}
