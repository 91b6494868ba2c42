//! The collapse on rayon's thread pool (feature `parallel`): the nodes
//! [`collapse_vec`](super::collapse::collapse_vec) makes, bit for bit.
//!
//! The sequential collapse numbers wide nodes depth first: a node's inner children take the
//! next free indices in lane order, then the last inner child's subtree is collapsed, then the
//! one before it, and so on. So the descendants of any wide node form one consecutive block.
//! Here, nodes over [`PARALLEL_FROM`] triangles are opened on the spot and their inner
//! children's subtrees collapsed concurrently (`rayon::join` through a parallel iterator), each
//! numbered from its own root; [`place`] then lays every piece down where the sequential
//! collapse puts it, by replaying that numbering. Same lanes, same numbers: the same nodes.

use alloc::vec;
use alloc::vec::Vec;

use rayon::prelude::*;

use super::collapse::{CollapsedNode, collapse_from, collapse_planned_vec, wide_node};
use super::plan::solve_block;
use super::plan::{CollapsePlan, PlanEntry, plan_capacity};
use crate::bvh::{Bvh, BvhNode, TreeArrays};
use crate::error::BuildError;

/// Subtrees of more triangles than this are opened here and their children collapsed
/// concurrently; smaller ones are collapsed on one thread, one per task.
const PARALLEL_FROM: usize = 16 * 1024;

/// A collapsed piece of the tree, before it is laid down.
enum Piece<N, const W: usize> {
    /// A subtree collapsed on one thread: its root at 0, its descendants numbered from 1.
    Local(Vec<N>),
    /// A wide node opened here: its lanes as [`CollapsePlan::lanes`] gives them, and one piece
    /// per inner lane, in lane order.
    Open([(u32, BvhNode); W], usize, Vec<Piece<N, W>>),
}

/// [`collapse_vec`](super::collapse::collapse_vec) on rayon's pool; the same nodes. The
/// plan is solved on the pool too where the tree is numbered as the builders number it
/// ([`solve_parallel`]), else on this thread.
pub(crate) fn collapse_vec_parallel<N, const W: usize>(tree: &Bvh<'_>) -> Result<Vec<N>, BuildError>
where
    N: CollapsedNode<W> + Clone + Send,
{
    // Filled on the pool, as the owned build's other large buffers are: for 1.1M triangles
    // this is 36 MB of fresh pages, whose first writes took 20 ms on one thread here, more
    // than solving the plan.
    let mut entries: Vec<PlanEntry> =
        rayon::iter::repeat_n(PlanEntry::EMPTY, plan_capacity(tree)).collect();
    if solve_parallel::<W>(tree, &mut entries).is_err() {
        // A numbering the blocks do not fit: the same entries, solved on this thread.
        CollapsePlan::<W>::solved(tree, &mut entries)?;
    }
    let plan = CollapsePlan::<W>::from_solved(tree, &entries);
    match tree.node(0) {
        Some(root) if !root.is_leaf() && tree.slot_count() > PARALLEL_FROM => {
            let piece = collapse_piece::<N, W>(&plan, 0)?;
            let mut nodes = vec![N::EMPTY; piece_len(&piece)];
            let mut next = 1;
            place(piece, 0, &mut nodes, &mut next);
            Ok(nodes)
        }
        _ => collapse_planned_vec::<N, W>(&plan),
    }
}

/// Solves the plan of `tree` in `entries` ([`plan_capacity`] of them) on the pool: the entries
/// the sequential solve computes, bit for bit, as each is a function of its children's alone.
///
/// The builders number a split's children as the next free pair, then the left child's
/// descendants, then the right one's. So the descendants of any node are one consecutive
/// block of nodes, and as an inner node's entry is kept at the place of its children's pair,
/// the entries of a subtree's inner nodes are one consecutive block of entries too: the
/// subtree's root's, then its left child's subtree's, then its right child's. Each node of
/// more than [`PARALLEL_FROM`] triangles has its children's subtrees solved concurrently, then
/// its own entry; smaller subtrees are solved on one thread. Any tree numbered otherwise (a
/// blob's may be) is refused with an error, before or while it is solved, and the caller
/// solves it on one thread.
fn solve_parallel<const W: usize>(
    tree: &Bvh<'_>,
    entries: &mut [PlanEntry],
) -> Result<(), BuildError> {
    match tree.node(0) {
        Some(root) if !root.is_leaf() => {
            solve_subtree::<W>(tree, 0, entries, 0, 1..tree.nodes().len())
        }
        _ => Ok(()),
    }
}

/// Solves the entries of the inner node `root` and its inner descendants, which are `block`
/// (entries `offset..offset + block.len()`), when its descendants are the nodes `descendants`
/// (see [`solve_parallel`]).
fn solve_subtree<const W: usize>(
    tree: &Bvh<'_>,
    root: usize,
    block: &mut [PlanEntry],
    offset: usize,
    descendants: core::ops::Range<usize>,
) -> Result<(), BuildError> {
    let malformed = BuildError::TooDeep {
        max_depth: crate::bvh::MAX_DEPTH,
        triangles: tree.slot_count(),
    };
    let (first, end) = (descendants.start, descendants.end);
    let node = tree.node(root).ok_or(malformed)?;
    // The root's entry opens the block; its children's pair opens its descendants.
    if node.first as usize != first || first / 2 != offset {
        return Err(malformed);
    }
    if subtree_slots(tree, root as u32) > PARALLEL_FROM {
        let (l, r) = (
            tree.node(first).ok_or(malformed)?,
            tree.node(first + 1).ok_or(malformed)?,
        );
        // The left child's descendants start after the pair, the right child's after them.
        let mid = if r.is_leaf() { end } else { r.first as usize };
        if !(first + 2..=end).contains(&mid) || (l.is_leaf() && mid != first + 2) {
            return Err(malformed);
        }
        // After the root's entry: the left subtree's entries, one per pair in its
        // descendants, then the right one's.
        let (left_block, right_block) = block
            .get_mut(1..)
            .and_then(|rest| rest.split_at_mut_checked((mid - first - 2) / 2))
            .ok_or(malformed)?;
        let (solved_left, solved_right) = rayon::join(
            || {
                if l.is_leaf() {
                    Ok(())
                } else {
                    solve_subtree::<W>(tree, first, left_block, offset + 1, first + 2..mid)
                }
            },
            || {
                if r.is_leaf() {
                    Ok(())
                } else {
                    let right_offset = offset + 1 + (mid - first - 2) / 2;
                    solve_subtree::<W>(tree, first + 1, right_block, right_offset, mid..end)
                }
            },
        );
        solved_left?;
        solved_right?;
    } else {
        solve_block::<W>(tree, block, offset, descendants)?;
    }
    // The root last: its entry needs its children's, in the block just solved.
    solve_block::<W>(tree, block, offset, root..root + 1)
}

/// The piece of the subtree under the inner binary node `binary`.
fn collapse_piece<N, const W: usize>(
    plan: &CollapsePlan<'_, '_, W>,
    binary: u32,
) -> Result<Piece<N, W>, BuildError>
where
    N: CollapsedNode<W> + Clone + Send,
{
    let tree = plan.tree();
    let opened = if subtree_slots(tree, binary) > PARALLEL_FROM {
        plan.lanes(binary)
    } else {
        None
    };
    let Some((children, lanes)) = opened else {
        let mut nodes = Vec::new();
        let count = collapse_from::<N, W>(plan, binary, |index, node| {
            if index >= nodes.len() {
                nodes.resize(index + 1, N::EMPTY);
            }
            if let Some(slot) = nodes.get_mut(index) {
                *slot = node;
            }
        })?;
        nodes.truncate(count);
        return Ok(Piece::Local(nodes));
    };
    let pieces = children
        .iter()
        .take(lanes)
        .filter(|(_, child)| !child.is_leaf())
        .map(|&(index, _)| index)
        .collect::<Vec<_>>()
        .into_par_iter()
        .map(|index| collapse_piece::<N, W>(plan, index))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Piece::Open(children, lanes, pieces))
}

/// How many order slots the leaves under binary node `binary` span: from its leftmost leaf's
/// first slot to its rightmost leaf's last (a subtree's leaves hold consecutive slots).
fn subtree_slots(tree: &Bvh<'_>, binary: u32) -> usize {
    let edge = |right: bool| -> Option<usize> {
        let mut node = tree.node(binary as usize)?;
        // A valid tree's children come after their parents, so this ends within its depth.
        while !node.is_leaf() {
            node = tree.node(node.first as usize + usize::from(right))?;
        }
        Some(if right {
            node.first as usize + node.count as usize
        } else {
            node.first as usize
        })
    };
    match (edge(false), edge(true)) {
        (Some(first), Some(end)) => end.saturating_sub(first),
        _ => 0,
    }
}

/// Nodes in `piece`.
fn piece_len<N, const W: usize>(piece: &Piece<N, W>) -> usize {
    match piece {
        Piece::Local(nodes) => nodes.len(),
        Piece::Open(_, _, pieces) => 1 + pieces.iter().map(piece_len).sum::<usize>(),
    }
}

/// Lays `piece` down with its root at `at`, numbering its other nodes from `*next` as the
/// sequential collapse does, and moves `*next` past them.
fn place<N: CollapsedNode<W>, const W: usize>(
    piece: Piece<N, W>,
    at: usize,
    out: &mut [N],
    next: &mut usize,
) {
    match piece {
        Piece::Local(nodes) => {
            // Local node k ≥ 1 goes to next + k − 1: every inner child index moves by next − 1.
            let by = (*next as u32).wrapping_sub(1);
            let mut nodes = nodes.into_iter().map(|mut node| {
                node.shift_inner(by);
                node
            });
            if let (Some(root), Some(slot)) = (nodes.next(), out.get_mut(at)) {
                *slot = root;
            }
            for node in nodes {
                if let Some(slot) = out.get_mut(*next) {
                    *slot = node;
                }
                *next += 1;
            }
        }
        Piece::Open(children, lanes, pieces) => {
            let first = *next;
            *next += pieces.len();
            if let Some(slot) = out.get_mut(at) {
                *slot = wide_node(children.get(..lanes).unwrap_or_default(), first as u32);
            }
            // The last inner child's subtree first, as the sequential collapse's stack pops.
            for (k, piece) in pieces.into_iter().enumerate().rev() {
                place(piece, first + k, out, next);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use alloc::vec;
    use alloc::vec::Vec;

    use super::{PARALLEL_FROM, collapse_vec_parallel, solve_parallel};
    use crate::bvh::{BuildConfig, Bvh, BvhNode, PrimRef, node_capacity};
    use crate::mesh::MeshRef;
    use crate::wide::collapse::collapse_vec;
    use crate::wide::plan::PlanEntry;
    use crate::wide::plan::{CollapsePlan, plan_capacity};
    use crate::wide::{WideNode, WideNode8};

    /// A wavy grid of `side × side` quads (two triangles each), with a pseudo-random
    /// height per vertex so the tree is uneven.
    fn grid(side: u32) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
        let mut positions = Vec::new();
        let mut state = 0x2545_F491_u32;
        for y in 0..=side {
            for x in 0..=side {
                state ^= state << 13;
                state ^= state >> 17;
                state ^= state << 5;
                let h = (state >> 8) as f32 / (1u32 << 24) as f32;
                positions.push([x as f32, y as f32, h * 3.0]);
            }
        }
        let mut triangles = Vec::new();
        let at = |x: u32, y: u32| y * (side + 1) + x;
        for y in 0..side {
            for x in 0..side {
                triangles.push([at(x, y), at(x + 1, y), at(x + 1, y + 1)]);
                triangles.push([at(x, y), at(x + 1, y + 1), at(x, y + 1)]);
            }
        }
        (positions, triangles)
    }

    #[test]
    fn the_parallel_collapse_is_the_sequential_collapse() {
        // 2·150² = 45,000 triangles: the root and its largest subtrees are opened on the
        // pool, the rest collapsed per task.
        let (positions, triangles) = grid(150);
        let mesh = MeshRef::new(&positions, &triangles)
            .validate()
            .expect("valid");
        let n = triangles.len();
        assert!(n > 2 * PARALLEL_FROM);
        for config in [BuildConfig::balanced(), BuildConfig::fast()] {
            let mut nodes = vec![BvhNode::EMPTY; node_capacity(n)];
            let (mut order, mut scratch) = (vec![0u32; n], vec![PrimRef::EMPTY; n]);
            let bvh =
                Bvh::build(&mesh, &config, &mut nodes, &mut order, &mut scratch).expect("build");
            let four = collapse_vec::<WideNode, 4>(&bvh).expect("collapse");
            let eight = collapse_vec::<WideNode8, 8>(&bvh).expect("collapse");
            for threads in [1, 2, 3] {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .expect("pool");
                let (four_p, eight_p) = pool.install(|| {
                    (
                        collapse_vec_parallel::<WideNode, 4>(&bvh).expect("collapse"),
                        collapse_vec_parallel::<WideNode8, 8>(&bvh).expect("collapse"),
                    )
                });
                assert_eq!(four_p.len(), four.len(), "{threads} threads");
                assert!(four.iter().zip(&four_p).all(|(a, b)| a.same_bits(b)));
                assert_eq!(eight_p.len(), eight.len(), "{threads} threads");
                assert!(eight.iter().zip(&eight_p).all(|(a, b)| a.same_bits(b)));
            }
        }
    }

    /// The parallel solve takes the builder's numbering without falling back, and writes the
    /// sequential solve's entries; the same tree numbered breadth first is refused, and the
    /// collapse, solving it on one thread instead, still makes the sequential collapse's nodes.
    #[test]
    fn the_parallel_solve_is_the_sequential_solve() {
        let (positions, triangles) = grid(150);
        let mesh = MeshRef::new(&positions, &triangles)
            .validate()
            .expect("valid");
        let n = triangles.len();
        let mut nodes = vec![BvhNode::EMPTY; node_capacity(n)];
        let (mut order, mut scratch) = (vec![0u32; n], vec![PrimRef::EMPTY; n]);
        let bvh = Bvh::build(
            &mesh,
            &BuildConfig::default(),
            &mut nodes,
            &mut order,
            &mut scratch,
        )
        .expect("build");
        let mut sequential = vec![PlanEntry::EMPTY; plan_capacity(&bvh)];
        CollapsePlan::<8>::solved(&bvh, &mut sequential).expect("plan");
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .expect("pool");
        let mut parallel = vec![PlanEntry::EMPTY; plan_capacity(&bvh)];
        pool.install(|| solve_parallel::<8>(&bvh, &mut parallel))
            .expect("builder's numbering");
        assert!(sequential == parallel);

        // Breadth-first renumbering: each inner node's children are still a pair after it,
        // but the descendants of a node are no longer one block.
        let tree = bvh.nodes();
        let mut renumbered = vec![tree[0]];
        let mut new_index = vec![0usize; tree.len()];
        let mut queue = std::collections::VecDeque::from([0usize]);
        while let Some(old) = queue.pop_front() {
            let node = tree[old];
            if !node.is_leaf() {
                renumbered[new_index[old]].first = renumbered.len() as u32;
                for child in [node.first as usize, node.first as usize + 1] {
                    new_index[child] = renumbered.len();
                    renumbered.push(tree[child]);
                    queue.push_back(child);
                }
            }
        }
        let order = bvh.order().to_vec();
        let bfs = Bvh::from_parts(&renumbered, &order, &mesh).expect("a valid tree");
        let mut refused = vec![PlanEntry::EMPTY; plan_capacity(&bfs)];
        assert!(
            pool.install(|| solve_parallel::<8>(&bfs, &mut refused))
                .is_err()
        );
        // The collapse still gives the sequential collapse's nodes, solved on one thread.
        let eight = collapse_vec::<WideNode8, 8>(&bfs).expect("collapse");
        let eight_p = pool
            .install(|| collapse_vec_parallel::<WideNode8, 8>(&bfs))
            .expect("collapse");
        assert_eq!(eight.len(), eight_p.len());
        assert!(eight.iter().zip(&eight_p).all(|(a, b)| a.same_bits(b)));
    }
}
