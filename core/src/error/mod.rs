//! One error type per stage. All are `#[non_exhaustive]`, `Copy`, carry small integer payloads,
//! implement `Display` and `core::error::Error`, and document when they happen and how to fix
//! them.

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

/// Which caller buffer a [`BuildError::BufferTooSmall`] is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum BufferKind {
    /// The node array (size it with [`bvh::node_capacity`](crate::bvh::node_capacity)).
    Nodes,
    /// The triangle order array (one `u32` per triangle).
    Order,
    /// The build scratch (one [`PrimRef`](crate::bvh::PrimRef) per triangle).
    Scratch,
    /// Packed triangles (one [`PackedTriangle`](crate::math::PackedTriangle) per triangle).
    Packed,
    /// Wide nodes (size it with [`Bvh::wide_node_count`](crate::bvh::Bvh::wide_node_count)).
    WideNodes,
}

/// Why a structure could not be built.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BuildError {
    /// A caller buffer is too small. Nothing was written to any buffer. Fix: size it with the
    /// structure's sizing function.
    BufferTooSmall {
        /// Which buffer.
        buffer: BufferKind,
        /// Elements needed.
        needed: usize,
        /// Elements given.
        got: usize,
    },
    /// The mesh has more triangles than a tree of `max_depth` levels with `max_leaf_size`
    /// triangles per leaf can hold. Fix: raise `max_depth` (up to
    /// [`MAX_DEPTH`](crate::bvh::MAX_DEPTH)) or `max_leaf_size`.
    TooDeep {
        /// The configured depth limit.
        max_depth: u32,
        /// The triangle count.
        triangles: usize,
    },
    /// A [`BuildConfig`](crate::bvh::BuildConfig) field is out of its documented range. Fix: see
    /// that field's documentation.
    InvalidConfig {
        /// The field's name.
        field: &'static str,
    },
}

impl fmt::Display for BuildError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::BufferTooSmall {
                buffer,
                needed,
                got,
            } => {
                let which = match buffer {
                    BufferKind::Nodes => "node",
                    BufferKind::Order => "order",
                    BufferKind::Scratch => "scratch",
                    BufferKind::Packed => "packed triangle",
                    BufferKind::WideNodes => "wide node",
                };
                write!(f, "{which} buffer too small: needed {needed}, got {got}")
            }
            Self::TooDeep {
                max_depth,
                triangles,
            } => write!(
                f,
                "{triangles} triangles do not fit in a tree of depth {max_depth} with this leaf size"
            ),
            Self::InvalidConfig { field } => {
                write!(f, "build config field `{field}` is out of range")
            }
        }
    }
}

impl core::error::Error for BuildError {}

/// Why a structure failed validation (from a validator, a refit, or later a blob load).
///
/// `node` payloads are node indices.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum StructureError {
    /// Nodes and triangle order disagree on emptiness (one is empty, the other not).
    EmptyMismatch,
    /// An inner node's children are out of the node array.
    ChildOutOfRange {
        /// The parent.
        node: u32,
    },
    /// An inner node's children do not come after it (the layout every traversal relies on to
    /// terminate).
    ChildNotAfterParent {
        /// The parent.
        node: u32,
    },
    /// The tree is deeper than [`MAX_DEPTH`](crate::bvh::MAX_DEPTH).
    TooDeep {
        /// The first node found below the limit.
        node: u32,
    },
    /// A node's box is empty or not finite.
    BadBounds {
        /// The node.
        node: u32,
    },
    /// A child's box is not inside its parent's box.
    ChildOutsideParent {
        /// The child.
        node: u32,
    },
    /// A leaf's triangle range is outside the order array.
    LeafRangeOutOfBounds {
        /// The leaf.
        node: u32,
    },
    /// Leaf ranges, visited left to right, do not tile the order array exactly once.
    LeafRangesNotContiguous {
        /// The first leaf out of place (or the node count when the ranges stop short).
        node: u32,
    },
    /// Some nodes are not reachable from the root.
    UnreachableNodes {
        /// Nodes reached.
        reached: u32,
        /// Nodes in the array.
        total: u32,
    },
    /// A leaf names a triangle the mesh does not have.
    TriangleOutOfRange {
        /// The leaf.
        node: u32,
        /// The triangle index.
        tri: u32,
    },
    /// A triangle's bounds are not inside its leaf's box (for example after vertices moved
    /// without a refit).
    TriangleOutsideLeaf {
        /// The leaf.
        node: u32,
        /// The triangle index.
        tri: u32,
    },
    /// Wide nodes are not the ones [`Bvh::widen`](crate::bvh::Bvh::widen) writes for the
    /// tree they are paired with.
    WideNodeMismatch {
        /// The first wide node that differs (or the expected count when only the count
        /// differs).
        node: u32,
    },
}

impl fmt::Display for StructureError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::EmptyMismatch => {
                f.write_str("node array and triangle order disagree on emptiness")
            }
            Self::ChildOutOfRange { node } => write!(f, "node {node}: children out of range"),
            Self::ChildNotAfterParent { node } => {
                write!(f, "node {node}: children must come after their parent")
            }
            Self::TooDeep { node } => write!(f, "node {node}: tree deeper than MAX_DEPTH"),
            Self::BadBounds { node } => write!(f, "node {node}: empty or non-finite bounds"),
            Self::ChildOutsideParent { node } => {
                write!(f, "node {node}: bounds not inside the parent's")
            }
            Self::LeafRangeOutOfBounds { node } => {
                write!(f, "leaf {node}: triangle range outside the order array")
            }
            Self::LeafRangesNotContiguous { node } => {
                write!(f, "leaf {node}: leaf ranges do not tile the order array")
            }
            Self::UnreachableNodes { reached, total } => {
                write!(
                    f,
                    "only {reached} of {total} nodes are reachable from the root"
                )
            }
            Self::TriangleOutOfRange { node, tri } => {
                write!(f, "leaf {node}: triangle {tri} is not in the mesh")
            }
            Self::TriangleOutsideLeaf { node, tri } => {
                write!(
                    f,
                    "leaf {node}: triangle {tri} lies outside the leaf's bounds"
                )
            }
            Self::WideNodeMismatch { node } => {
                write!(f, "wide node {node} does not match the binary tree")
            }
        }
    }
}

impl core::error::Error for StructureError {}

#[cfg(feature = "blob")]
mod blob;
#[cfg(feature = "blob")]
pub use blob::{BlobError, BlobSection};

mod batch;
pub use batch::{BatchBuffer, BatchError};
