//! The depth-first build shared by the k-d tree and the octree: cells split until a rule says
//! stop, with every reference list kept inside the one references buffer the caller gives.
//!
//! The buffer holds, from the front, the finished leaves' references, and from the back, a stack
//! of the lists of cells still to process (the current cell's on top). A split writes its
//! children's lists into the free middle, then moves them over the parent's. A cell splits only
//! if its children's lists fit in the free middle, so the build never needs more than the buffer
//! and the tree it makes depends only on the mesh, the config and the buffer lengths.

use super::TreeSizes;
use crate::error::{BufferKind, BuildError};
use crate::query::Cell;

/// Most children a cell splits into (the octree's eight).
pub(crate) const MAX_ARITY: usize = 8;

/// Cells waiting on the build stack: a split defers at most seven siblings per level, and
/// neither tree goes deeper than [`MAX_TREE_DEPTH`].
const PENDING: usize = (MAX_ARITY - 1) * MAX_TREE_DEPTH as usize + 2;

/// The deepest either cell tree goes (the octree's limit; the k-d tree's is lower per level of
/// the stack but the same bound works for both).
pub(crate) const MAX_TREE_DEPTH: u32 = 48;

/// What a splitter decides for one cell.
#[allow(clippy::large_enum_variant)] // built and matched at once, never stored
pub(crate) enum Decision<I> {
    /// The cell stays a leaf (the rule says so).
    Leaf,
    /// The cell would split but its children's lists did not fit in the room given.
    NoRoom,
    /// The cell splits: the children's lists were written one after another, child 0 first.
    Split {
        /// What the inner node records (the k-d tree's axis and plane).
        inner: I,
        /// Each child's cell.
        cells: [Cell; MAX_ARITY],
        /// Each child's reference count (the first `ARITY` are used).
        lens: [u32; MAX_ARITY],
    },
}

/// One kind of cell tree: how a cell splits and how nodes are written.
pub(crate) trait Splitter {
    /// Children per split (2 or 8).
    const ARITY: usize;
    /// The stored node.
    type Node: Copy;
    /// What an inner node records besides its first child.
    type Inner: Copy;

    /// Decides for `cell` at `depth` holding references `refs`; on a split, writes the
    /// children's lists into `out` (child 0 first), or says [`Decision::NoRoom`] when they do
    /// not fit.
    fn split(
        &self,
        cell: &Cell,
        depth: u32,
        refs: &[u32],
        out: &mut [u32],
    ) -> Decision<Self::Inner>;

    /// An inner node whose children start at `first_child`.
    fn inner(inner: Self::Inner, first_child: u32) -> Self::Node;

    /// A leaf holding references `first..first + count`.
    fn leaf(first: u32, count: u32) -> Self::Node;
}

/// The outcome of a build (or a measuring run).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Built {
    /// Nodes written.
    pub(crate) nodes: usize,
    /// References the finished tree holds (the front of the buffer).
    pub(crate) references: usize,
    /// The most of the references buffer the build used at once: a buffer this long builds
    /// the same tree.
    pub(crate) peak: usize,
    /// False when some cell stayed a leaf only because a buffer ran out.
    pub(crate) complete: bool,
}

impl Built {
    /// The sizes a caller sees: nodes, references, the room the build used, completeness.
    pub(crate) const fn sizes(&self) -> TreeSizes {
        TreeSizes {
            nodes: self.nodes,
            items: self.references,
            work: self.peak,
            complete: self.complete,
        }
    }
}

#[derive(Clone, Copy)]
struct Pending {
    node: u32,
    cell: Cell,
    depth: u32,
    len: u32,
}

/// Builds the tree of `triangles` triangles in `root` with `splitter`, using `items` as the
/// references buffer and writing nodes to `nodes` (or only counting them when `None`).
pub(crate) fn build_tree<S: Splitter>(
    splitter: &S,
    triangles: usize,
    root: Cell,
    items: &mut [u32],
    mut nodes: Option<&mut [S::Node]>,
) -> Result<Built, BuildError> {
    // References are addressed by `u32`: a longer buffer is used up to that.
    let capacity = items.len().min(u32::MAX as usize);
    let items = items.get_mut(..capacity).unwrap_or_default();
    let node_capacity = nodes.as_ref().map_or(1 << 30, |n| n.len().min(1 << 30));
    if triangles > capacity || triangles > u32::MAX as usize >> 2 {
        return Err(BuildError::BufferTooSmall {
            buffer: BufferKind::References,
            needed: triangles,
            got: capacity,
        });
    }
    if node_capacity == 0 {
        return Err(BuildError::BufferTooSmall {
            buffer: BufferKind::Nodes,
            needed: 1,
            got: 0,
        });
    }
    let mut top = capacity - triangles;
    for (slot, tri) in items
        .get_mut(top..)
        .unwrap_or_default()
        .iter_mut()
        .zip(0u32..)
    {
        *slot = tri;
    }
    let mut front = 0usize;
    let mut built = Built {
        nodes: 1,
        references: 0,
        peak: triangles,
        complete: true,
    };
    let mut stack = [Pending {
        node: 0,
        cell: root,
        depth: 0,
        len: triangles as u32,
    }; PENDING];
    let mut pending = 1usize;
    while let Some(p) = pending.checked_sub(1).and_then(|i| stack.get(i).copied()) {
        pending -= 1;
        let len = p.len as usize;
        let room_for_nodes = built.nodes + S::ARITY <= node_capacity;
        let room_on_stack = pending + S::ARITY <= PENDING;
        let decision = {
            let (head, tail) = items.split_at_mut(top);
            let refs = tail.get(..len).unwrap_or_default();
            // Without room for the children's nodes, the splitter gets no room for their lists
            // either: it still says whether the cell would have been a leaf anyway.
            let out = match head.get_mut(front..) {
                Some(out) if room_for_nodes && room_on_stack => out,
                _ => &mut [],
            };
            splitter.split(&p.cell, p.depth, refs, out)
        };
        match decision {
            Decision::Split { inner, cells, lens } => {
                let used: usize = lens.iter().take(S::ARITY).map(|&l| l as usize).sum();
                built.peak = built.peak.max(front + (capacity - top) + used);
                let first_child = built.nodes as u32;
                if let Some(slot) = nodes
                    .as_deref_mut()
                    .and_then(|n| n.get_mut(p.node as usize))
                {
                    *slot = S::inner(inner, first_child);
                }
                built.nodes += S::ARITY;
                // The children's lists replace the parent's on the stack, child 0 on top.
                let new_top = top + len - used;
                items.copy_within(front..front + used, new_top);
                top = new_top;
                for k in (0..S::ARITY).rev() {
                    if let (Some(slot), Some(&cell), Some(&len)) =
                        (stack.get_mut(pending), cells.get(k), lens.get(k))
                    {
                        *slot = Pending {
                            node: first_child + k as u32,
                            cell,
                            depth: p.depth + 1,
                            len,
                        };
                        pending += 1;
                    }
                }
            }
            Decision::Leaf | Decision::NoRoom => {
                if matches!(decision, Decision::NoRoom) {
                    built.complete = false;
                }
                items.copy_within(top..top + len, front);
                if let Some(slot) = nodes
                    .as_deref_mut()
                    .and_then(|n| n.get_mut(p.node as usize))
                {
                    *slot = S::leaf(front as u32, p.len);
                }
                front += len;
                top += len;
            }
        }
    }
    built.references = front;
    Ok(built)
}
