//! The parallel build (feature `parallel`): the tree [`build_into`](super::build::build_into)
//! makes, bit for bit, built on rayon's thread pool.
//!
//! Large nodes bin their triangles in parallel ([`Binning::find_split_parallel`], which finds
//! the same split), and once a node is split its two children are built concurrently
//! (`rayon::join`): they own disjoint ranges of the triangle arrays. Below [`PARALLEL_FROM`]
//! triangles a subtree is left to the sequential builder, with its nodes numbered from its own
//! root. The sequential builder numbers nodes depth first, left child first, each split's
//! children taking the next free pair; so a subtree's descendants are one consecutive block,
//! and [`place`] can lay every piece down where the sequential build puts it, by replaying
//! that numbering. Same splits, same order, same numbering: the same nodes and order.

use alloc::boxed::Box;
use alloc::vec;
use alloc::vec::Vec;

use super::binning::Binning;
use super::build::{Built, Task, build_subtree, fill_prims, prepare_with, split_node};
use super::build_box::BuildBox;
use super::partition::bounds_of;
use super::{BuildConfig, BvhNode, PrimRef, SplitStrategy, node_capacity};
use crate::error::BuildError;
use crate::mesh::ValidMesh;

use rayon::prelude::*;

/// Nodes with more triangles than this are split with parallel binning and have their
/// children built concurrently; smaller subtrees are built sequentially, one per task.
pub(super) const PARALLEL_FROM: usize = 16 * 1024;

/// A built piece of the tree, before it is laid down in the node array.
pub(super) enum Piece {
    /// A subtree from the sequential builder: its root at 0, its descendants from 1.
    Subtree(Vec<BvhNode>),
    /// A node split here: its box, then its two children.
    Split(BvhNode, Box<Piece>, Box<Piece>),
}

/// [`build_into`](super::build::build_into) on rayon's pool; the same result.
pub(super) fn build_parallel(
    mesh: &ValidMesh<'_>,
    config: &BuildConfig,
    nodes: &mut [BvhNode],
    order: &mut [u32],
    scratch: &mut [PrimRef],
) -> Result<Built, BuildError> {
    let Some((prims, order, root)) = prepare_with(
        mesh,
        config,
        nodes.len(),
        order,
        scratch,
        &mut |prims, order| fill_prims_parallel(mesh, prims, order),
    )?
    else {
        return Ok(Built::NOTHING);
    };
    let (piece, depth) = build_piece(config, root, prims, order, 0)?;
    let mut next = 1;
    place(piece, 0, nodes, &mut next);
    Ok(Built {
        node_count: next,
        depth,
    })
}

/// [`fill_prims`] and [`bounds_of`] over runs of triangles on the pool: the same boxes, and
/// the same bounds (a minimum and a maximum do not depend on the order they are taken in).
pub(super) fn fill_prims_parallel(
    mesh: &ValidMesh<'_>,
    prims: &mut [PrimRef],
    order: &mut [u32],
) -> (BuildBox, BuildBox) {
    /// Triangles per task.
    const RUN: usize = 16 * 1024;
    prims
        .par_chunks_mut(RUN)
        .zip(order.par_chunks_mut(RUN))
        .enumerate()
        .map(|(run, (prims, order))| {
            // A triangle index fits in u32 (the mesh was validated), so run · RUN does too.
            fill_prims(mesh, (run * RUN) as u32, prims, order);
            bounds_of(prims)
        })
        .reduce(
            || (BuildBox::EMPTY, BuildBox::EMPTY),
            |(b0, c0), (b1, c1)| (b0.union(b1), c0.union(c1)),
        )
}

/// Builds the subtree of `task` over `prims` and `order` (all of them; `task.begin` is 0),
/// whose first triangle is at `base` in the whole build. Returns it and its depth.
fn build_piece(
    config: &BuildConfig,
    task: Task,
    prims: &mut [PrimRef],
    order: &mut [u32],
    base: usize,
) -> Result<(Piece, u32), BuildError> {
    if prims.len() <= PARALLEL_FROM {
        let mut nodes = vec![BvhNode::EMPTY; node_capacity(prims.len())];
        let built = build_subtree(
            config,
            task,
            prims,
            order,
            &mut nodes,
            base,
            &mut Binning::new(),
        )?;
        nodes.truncate(built.node_count);
        return Ok((Piece::Subtree(nodes), built.depth));
    }
    let mut binning = Binning::new();
    // Room for the sweep SAH's boxes (none needed by the other strategies).
    let mut spare = match config.split {
        SplitStrategy::Sweep { .. } => vec![BvhNode::EMPTY; prims.len()],
        _ => Vec::new(),
    };
    let children = split_node(
        config,
        &task,
        prims,
        order,
        &mut |p, c, k| binning.find_split_parallel(p, c, k),
        &mut spare,
    );
    // Freed before the children are built: kept, one per level, they would pile up down a
    // deep tree (unbalanced splits of piled-up triangles).
    drop(spare);
    let Some((left_count, (lb, lc), (rb, rc))) = children else {
        // A leaf after all (not reached with the presets: a node this large always splits);
        // the sequential builder decides it the same way.
        let mut nodes = vec![BvhNode::EMPTY; node_capacity(prims.len())];
        let built = build_subtree(config, task, prims, order, &mut nodes, base, &mut binning)?;
        nodes.truncate(built.node_count);
        return Ok((Piece::Subtree(nodes), built.depth));
    };
    let node = BvhNode::new(task.bounds.to_aabb().padded(), 0, 0);
    let (left_prims, right_prims) = prims.split_at_mut(left_count.min(prims.len()));
    let (left_order, right_order) = order.split_at_mut(left_count.min(order.len()));
    let child = |bounds, centroids, count| Task {
        node: 0,
        begin: 0,
        end: count,
        level: task.level + 1,
        bounds,
        centroids,
    };
    let (left_task, right_task) = (child(lb, lc, left_count), child(rb, rc, right_prims.len()));
    let (left, right) = rayon::join(
        || build_piece(config, left_task, left_prims, left_order, base),
        || {
            build_piece(
                config,
                right_task,
                right_prims,
                right_order,
                base + left_count,
            )
        },
    );
    let ((left, left_depth), (right, right_depth)) = (left?, right?);
    Ok((
        Piece::Split(node, Box::new(left), Box::new(right)),
        left_depth.max(right_depth),
    ))
}

/// Lays `piece` down with its root at `at`, numbering its other nodes from `*next` as the
/// sequential builder does, and moves `*next` past them.
pub(super) fn place(piece: Piece, at: usize, nodes: &mut [BvhNode], next: &mut usize) {
    match piece {
        Piece::Subtree(local) => {
            // Local node k ≥ 1 goes to base + k - 1; inner nodes' children move with them.
            let base = *next;
            let moved = |node: BvhNode| {
                if node.is_leaf() {
                    node
                } else {
                    BvhNode {
                        first: (base + node.first as usize - 1) as u32,
                        ..node
                    }
                }
            };
            let mut local = local.into_iter();
            if let (Some(root), Some(slot)) = (local.next(), nodes.get_mut(at)) {
                *slot = moved(root);
            }
            for node in local {
                if let Some(slot) = nodes.get_mut(*next) {
                    *slot = moved(node);
                }
                *next += 1;
            }
        }
        Piece::Split(node, left, right) => {
            let l = *next;
            *next += 2;
            if let Some(slot) = nodes.get_mut(at) {
                *slot = BvhNode {
                    first: l as u32,
                    ..node
                };
            }
            place(*left, l, nodes, next);
            place(*right, l + 1, nodes, next);
        }
    }
}
