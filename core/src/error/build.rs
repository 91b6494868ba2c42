//! Why a structure could not be built.

use core::fmt;

/// Which caller buffer a [`BuildError::BufferTooSmall`] is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum BufferKind {
    /// The node array (size it with [`Bvh::measure`](crate::bvh::Bvh::measure)).
    Nodes,
    /// The triangle order array (one `u32` per triangle).
    Order,
    /// The build scratch (one [`PrimRef`](crate::bvh::PrimRef) per triangle).
    Scratch,
    /// Packed triangles (one [`PackedTriangle`](crate::advanced::PackedTriangle) per triangle).
    Packed,
    /// Wide nodes (size it with
    /// [`CollapsePlan::node_count`](crate::advanced::CollapsePlan::node_count)).
    WideNodes,
    /// A grid's cell offsets (cells + 1; size it with
    /// [`Grid::measure`](crate::grid::Grid::measure)).
    CellOffsets,
    /// The references of a k-d tree, octree or grid (one per triangle and cell it touches;
    /// size it with the structure's `measure`).
    References,
    /// The split references of a build with spatial splits (size it with
    /// [`Bvh::measure`](crate::bvh::Bvh::measure)).
    SplitRefs,
    /// The entries of a collapse plan (one per inner binary node; size it with
    /// [`WideBvh::measure`](crate::wide::WideBvh::measure)).
    CollapsePlan,
    /// The expansions of a winding-number tree (one
    /// [`WindingNode`](crate::inside::WindingNode) per tree node).
    WindingNodes,
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
    /// that field's documentation. `split` names a
    /// [`SplitStrategy::Sweep`](crate::bvh::SplitStrategy::Sweep) asked for with spatial splits.
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
                    BufferKind::CellOffsets => "cell offset",
                    BufferKind::References => "reference",
                    BufferKind::SplitRefs => "split reference",
                    BufferKind::CollapsePlan => "collapse plan",
                    BufferKind::WindingNodes => "winding node",
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
