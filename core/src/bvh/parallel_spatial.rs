//! The build with spatial splits on rayon's thread pool (feature `parallel`): the tree
//! [`build_spatial_into`](super::spatial_build::build_spatial_into) makes, bit for bit.
//!
//! Every node owns its range of the reference buffers, room included, and decides its split
//! from that range alone; so once a node is split its two children are built concurrently
//! (`rayon::join`) on the two halves of its range, and subtrees under
//! [`PARALLEL_FROM`] references are built by the sequential builder. The pieces are laid down
//! by [`place`], replaying the sequential numbering, and the leaves compacted as the
//! sequential build compacts them.

use alloc::boxed::Box;
use alloc::vec;

use super::build::{Built, Task};
use super::build_box::BuildBox;
use super::parallel_build::{PARALLEL_FROM, Piece, fill_prims_parallel, place};
use super::spatial_build::{Builder, RoomTask, SpatialBuilt, build_subtree, finish, prepare};
use super::{BuildConfig, BvhNode, PrimRef, SpatialSplits, node_capacity};
use crate::error::BuildError;
use crate::mesh::ValidMesh;
use crate::query::SplitRef;

/// What every piece's builder is made from.
#[derive(Clone, Copy)]
struct Params<'m, 'c> {
    mesh: &'m ValidMesh<'m>,
    config: &'c BuildConfig,
    spatial: &'c SpatialSplits,
    /// The root's box (the spatial-split threshold is a fraction of its area).
    root: BuildBox,
}

impl Params<'_, '_> {
    fn builder(&self) -> Builder<'_, '_> {
        Builder::new(self.mesh, self.config, self.spatial, &self.root)
    }
}

/// [`build_spatial_into`](super::spatial_build::build_spatial_into) on rayon's pool; the same
/// result.
pub(super) fn build_spatial_parallel(
    mesh: &ValidMesh<'_>,
    config: &BuildConfig,
    spatial: &SpatialSplits,
    nodes: &mut [BvhNode],
    order: &mut [u32],
    scratch: &mut [PrimRef],
    splits: &mut [SplitRef],
) -> Result<SpatialBuilt, BuildError> {
    let lens = (nodes.len(), splits.len());
    let fill =
        &mut |prims: &mut [PrimRef], order: &mut [u32]| fill_prims_parallel(mesh, prims, order);
    let Some((prims, order, root)) = prepare(mesh, config, spatial, lens, order, scratch, fill)?
    else {
        return Ok(SpatialBuilt::NOTHING);
    };
    let params = Params {
        mesh,
        config,
        spatial,
        root: root.task.bounds,
    };
    let (piece, depth) = build_piece(&params, root, prims, order, 0)?;
    let mut next = 1;
    place(piece, 0, nodes, &mut next);
    let built = Built {
        node_count: next,
        depth,
    };
    finish(built, nodes, order, splits)
}

/// The subtree of `rt` (positions relative to `prims` and `order`, which are its range, room
/// included), whose range starts at `base` in the whole build, as a piece, with its depth.
fn build_piece(
    params: &Params<'_, '_>,
    rt: RoomTask,
    prims: &mut [PrimRef],
    order: &mut [u32],
    base: usize,
) -> Result<(Piece, u32), BuildError> {
    let mut builder = params.builder();
    let children = if prims.len() <= PARALLEL_FROM {
        None
    } else {
        builder.split(&rt, prims, order)?
    };
    let Some((left, right)) = children else {
        // Small, or a leaf after all: the sequential builder decides it the same way.
        let mut nodes = vec![BvhNode::EMPTY; node_capacity(prims.len())];
        let built = build_subtree(builder, rt, prims, order, &mut nodes, base)?;
        nodes.truncate(built.node_count);
        return Ok((Piece::Subtree(nodes), built.depth));
    };
    let node = BvhNode::new(rt.task.bounds.to_aabb().padded(), 0, 0);
    // The left child's range ends where the right child's begins.
    let at = right.task.begin.min(prims.len());
    let (left_prims, right_prims) = prims.split_at_mut(at);
    let (left_order, right_order) = order.split_at_mut(at.min(order.len()));
    let local = |rt: RoomTask, shift: usize| RoomTask {
        task: Task {
            node: 0,
            begin: rt.task.begin - shift,
            end: rt.task.end - shift,
            ..rt.task
        },
        room_end: rt.room_end - shift,
    };
    let (left, right) = rayon::join(
        || build_piece(params, local(left, 0), left_prims, left_order, base),
        || {
            build_piece(
                params,
                local(right, at),
                right_prims,
                right_order,
                base + at,
            )
        },
    );
    let ((left, left_depth), (right, right_depth)) = (left?, right?);
    Ok((
        Piece::Split(node, Box::new(left), Box::new(right)),
        left_depth.max(right_depth),
    ))
}
