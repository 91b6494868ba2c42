//! What the k-d tree and the octree do alike with their cells: walk the nodes from the root
//! cell down, each a leaf with a range of references or an inner node whose children tile its
//! cell, to list the cells and count the tree's figures.

use super::CellStats;
use crate::query::Cell;

/// A node as the walk reads it.
pub(crate) enum CellNode {
    /// A leaf: `count` references from `first`.
    Leaf {
        /// The first reference.
        first: u32,
        /// How many.
        count: u32,
    },
    /// An inner node: its children are offered by [`CellTree::children`].
    Inner,
}

/// A tree of cells whose nodes are read by index from the root, node 0.
pub(crate) trait CellTree {
    /// The root cell.
    fn root_cell(&self) -> Cell;
    /// Node `node`, or `None` past the last.
    fn cell_node(&self, node: u32) -> Option<CellNode>;
    /// Calls `child` with each child of the inner node `node`, whose cell is `cell` at
    /// `depth`, and the child's cell: the last child first, so that a stack visits them first
    /// to last. A node the tree's depth limit forbids to open offers none.
    fn children(&self, node: u32, cell: &Cell, depth: u32, child: impl FnMut(u32, Cell));
    /// The node count.
    fn node_count(&self) -> usize;
    /// The reference count.
    fn reference_count(&self) -> usize;
}

/// The cells `tree` has cut its root into after `stop_depth` levels of splits, with their
/// depth (the root is 0): every leaf at depth `stop_depth` or less, with its `(first, count)`
/// range of references, and every inner node at depth `stop_depth`, with `None`. Together they
/// tile the root; depth first, first child first. `STACK` bounds the deferred children: the
/// tree's depth limit times its children per node less one, plus two.
pub(crate) fn for_each_cell<T: CellTree + ?Sized, const STACK: usize>(
    tree: &T,
    stop_depth: u32,
    mut each: impl FnMut(Cell, u32, Option<(u32, u32)>),
) {
    let mut stack = [(0u32, tree.root_cell(), 0u32); STACK];
    let mut top = 1usize;
    while let Some((node, cell, depth)) = top.checked_sub(1).and_then(|i| stack.get(i).copied()) {
        top -= 1;
        match tree.cell_node(node) {
            Some(CellNode::Leaf { first, count }) => each(cell, depth, Some((first, count))),
            Some(CellNode::Inner) if depth >= stop_depth => each(cell, depth, None),
            Some(CellNode::Inner) => tree.children(node, &cell, depth, |child, c| {
                if let Some(slot) = stack.get_mut(top) {
                    *slot = (child, c, depth + 1);
                    top += 1;
                }
            }),
            None => {}
        }
    }
}

/// Nodes, leaf cells, empty cells, references and depth of `tree`, over `triangles`
/// triangles.
pub(crate) fn stats<T: CellTree + ?Sized, const STACK: usize>(
    tree: &T,
    triangles: usize,
) -> CellStats {
    let mut stats = CellStats {
        nodes: tree.node_count(),
        references: tree.reference_count(),
        triangles,
        ..CellStats::default()
    };
    for_each_cell::<T, STACK>(tree, u32::MAX, |_, depth, leaf| {
        if let Some((_, count)) = leaf {
            stats.add_cell(depth, count as usize);
        }
    });
    stats
}
