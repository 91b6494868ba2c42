//! Why a structure failed validation.

use core::fmt;

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
    /// The leaves holding a triangle that spatial splits cut leave part of it outside their
    /// boxes: a corner, or a stretch of an edge, lies in none of them (so queries could miss
    /// it there).
    SplitTriangleUncovered {
        /// The triangle index.
        tri: u32,
    },
    /// Wide nodes are not the ones [`WideBvh::build`](crate::wide::WideBvh::build) writes for the
    /// tree they are paired with.
    WideNodeMismatch {
        /// The first wide node that differs (or the expected count when only the count
        /// differs).
        node: u32,
    },
    /// A grid's resolution is zero or above
    /// [`GridConfig::MAX_RESOLUTION`](crate::grid::GridConfig::MAX_RESOLUTION) on some axis, or
    /// its offsets are not one more than its cells.
    BadResolution,
    /// A grid's cell offsets do not start at 0, decrease, or do not end at the reference count.
    BadCellOffsets {
        /// The first cell out of order.
        cell: u32,
    },
    /// A k-d tree or octree node is malformed: a split plane outside its cell or not finite, an
    /// axis out of range, or a reserved bit set.
    BadNode {
        /// The node.
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
            Self::SplitTriangleUncovered { tri } => {
                write!(
                    f,
                    "triangle {tri} reaches outside the leaves its split references name"
                )
            }
            Self::WideNodeMismatch { node } => {
                write!(f, "wide node {node} does not match the binary tree")
            }
            Self::BadResolution => f.write_str("grid resolution out of range"),
            Self::BadCellOffsets { cell } => write!(f, "cell {cell}: offsets out of order"),
            Self::BadNode { node } => write!(f, "node {node}: malformed split or leaf"),
        }
    }
}

impl core::error::Error for StructureError {}
