//! The top-down builder (binned SAH, sweep SAH or centre splits). Iterative, with a fixed task stack; writes only into the
//! caller's buffers, and only after every size and limit has been checked.

use glam::Vec3A;

use super::binning::{Binning, Split, batches, partition};
use super::build_box::BuildBox;
use super::centre::{Side, centre_split};
use super::lanes::{max_lanes, min_lanes};
use super::median::median_split;
use super::partition::bounds_of;
use super::sweep_sah::{SweepSplit, find_sweep_split};
use super::{BuildConfig, BvhNode, MAX_DEPTH, PrimRef, SplitStrategy, node_capacity};
use crate::error::{BufferKind, BuildError};
use crate::mesh::ValidMesh;

/// What the builder produced: how many nodes it used and how deep the tree is.
pub(super) struct Built {
    pub node_count: usize,
    pub depth: u32,
}

impl Built {
    /// The build of a mesh without triangles.
    pub const NOTHING: Self = Self {
        node_count: 0,
        depth: 0,
    };
}

/// A node to build: its slot, its triangles `begin..end` (positions in the build's arrays),
/// its level (the root is 1) and the bounds of its triangles and of their centroids.
#[derive(Clone, Copy)]
pub(super) struct Task {
    pub node: usize,
    pub begin: usize,
    pub end: usize,
    pub level: u32,
    pub bounds: BuildBox,
    /// Bounds of the doubled centroids ([`PrimRef::centroid2`]).
    pub centroids: BuildBox,
}

/// Refuses a `buffer` of `got` elements where `needed` are.
pub(super) fn check_len(buffer: BufferKind, needed: usize, got: usize) -> Result<(), BuildError> {
    if got < needed {
        return Err(BuildError::BufferTooSmall {
            buffer,
            needed,
            got,
        });
    }
    Ok(())
}

pub(super) fn build_into(
    mesh: &ValidMesh<'_>,
    config: &BuildConfig,
    nodes: &mut [BvhNode],
    order: &mut [u32],
    scratch: &mut [PrimRef],
) -> Result<Built, BuildError> {
    let Some((prims, order, root)) = prepare(mesh, config, nodes.len(), order, scratch)? else {
        return Ok(Built::NOTHING);
    };
    build_subtree(config, root, prims, order, nodes, 0, &mut Binning::new())
}

/// A build's triangle boxes and order (trimmed to the triangle count), with the root's task.
pub(super) type Prepared<'s> = (&'s mut [PrimRef], &'s mut [u32], Task);

/// How a node's split is searched: [`Binning::find_split`] or its parallel twin.
pub(super) type FindSplit<'f> = dyn FnMut(&[PrimRef], &BuildBox, u32) -> Option<Split> + 'f;

/// The first step of every build: checks the config, the buffer lengths and the depth limit,
/// then fills one [`PrimRef`] per triangle and the identity order. Returns them (trimmed to
/// the triangle count) with the root's task, or `None` for a mesh without triangles.
pub(super) fn prepare<'s>(
    mesh: &ValidMesh<'_>,
    config: &BuildConfig,
    nodes_len: usize,
    order: &'s mut [u32],
    scratch: &'s mut [PrimRef],
) -> Result<Option<Prepared<'s>>, BuildError> {
    prepare_with(
        mesh,
        config,
        nodes_len,
        order,
        scratch,
        &mut |prims, order| {
            fill_prims(mesh, 0, prims, order);
            bounds_of(prims)
        },
    )
}

/// How a build fills its [`PrimRef`]s and identity order and measures them (box and centroid
/// bounds): on this thread ([`fill_prims`] then [`bounds_of`]) or on the pool.
pub(super) type FillPrims<'f> = dyn FnMut(&mut [PrimRef], &mut [u32]) -> (BuildBox, BuildBox) + 'f;

/// Writes triangle `first + i`'s box into `prims[i]` and its index into `order[i]`.
pub(super) fn fill_prims(
    mesh: &ValidMesh<'_>,
    first: u32,
    prims: &mut [PrimRef],
    order: &mut [u32],
) {
    for ((tri, p), o) in (first..).zip(prims.iter_mut()).zip(order.iter_mut()) {
        *p = mesh.triangle(tri).map_or(PrimRef::EMPTY, |t| {
            let [a, b, c] = [t.a, t.b, t.c].map(Vec3A::from);
            PrimRef {
                min: min_lanes(c, min_lanes(b, a)),
                max: max_lanes(c, max_lanes(b, a)),
            }
        });
        *o = tri;
    }
}

/// [`prepare`] with the triangle boxes filled and measured by `fill`.
pub(super) fn prepare_with<'s>(
    mesh: &ValidMesh<'_>,
    config: &BuildConfig,
    nodes_len: usize,
    order: &'s mut [u32],
    scratch: &'s mut [PrimRef],
    fill: &mut FillPrims<'_>,
) -> Result<Option<Prepared<'s>>, BuildError> {
    config.check()?;
    let n = mesh.triangle_count();
    check_len(BufferKind::Nodes, node_capacity(n), nodes_len)?;
    check_len(BufferKind::Order, n, order.len())?;
    check_len(BufferKind::Scratch, n, scratch.len())?;
    if n > config.subtree_capacity(1) {
        return Err(BuildError::TooDeep {
            max_depth: config.max_depth,
            triangles: n,
        });
    }
    let (Some(prims), Some(order)) = (scratch.get_mut(..n), order.get_mut(..n)) else {
        return Ok(None);
    };
    if n == 0 {
        return Ok(None);
    }
    let (bounds, centroids) = fill(prims, order);
    let root = Task {
        node: 0,
        begin: 0,
        end: n,
        level: 1,
        bounds,
        centroids,
    };
    Ok(Some((prims, order, root)))
}

/// Builds the subtree of `root` (a task over all of `prims` and `order`, `root.node` = 0)
/// depth first, left child first, into `nodes`: the root at 0 and each split's children as
/// the next free pair. Leaves name their triangles by position in `order` plus `base`, the
/// position of `prims[0]` in the whole build. So a subtree built on its own is the same nodes
/// the whole build makes, moved to where it puts them (the parallel build relies on this).
pub(super) fn build_subtree(
    config: &BuildConfig,
    root: Task,
    prims: &mut [PrimRef],
    order: &mut [u32],
    nodes: &mut [BvhNode],
    base: usize,
    binning: &mut Binning,
) -> Result<Built, BuildError> {
    let n = prims.len();
    let mut stack = [None::<Task>; MAX_DEPTH as usize];
    let mut sp = 0;
    let mut next = Some(root);
    let mut node_count = 1;
    let mut depth = 0;
    while let Some(task) = next.take() {
        depth = depth.max(task.level);
        let count = task.end - task.begin;
        let (Some(range), Some(tris)) = (
            prims.get_mut(task.begin..task.end),
            order.get_mut(task.begin..task.end),
        ) else {
            break;
        };
        let spare = nodes.get_mut(node_count..).unwrap_or_default();
        let children = split_node(
            config,
            &task,
            range,
            tris,
            &mut |p, c, k| binning.find_split(p, c, k),
            spare,
        );
        let Some(slot) = nodes.get_mut(task.node) else {
            break;
        };
        match children {
            None => {
                // Leaf: base + begin < n ≤ u32::MAX and count ≤ max_leaf_size, so both fit.
                *slot = BvhNode::new(
                    task.bounds.to_aabb().padded(),
                    (base + task.begin) as u32,
                    count as u32,
                );
            }
            Some((left_count, (lb, lc), (rb, rc))) => {
                let left = node_count;
                node_count += 2;
                *slot = BvhNode::new(task.bounds.to_aabb().padded(), left as u32, 0);
                let mid = task.begin + left_count;
                let right_task = Task {
                    node: left + 1,
                    begin: mid,
                    end: task.end,
                    level: task.level + 1,
                    bounds: rb,
                    centroids: rc,
                };
                // Pending right siblings number at most one per level above, so the stack
                // (MAX_DEPTH slots) cannot fill: the level limit was checked up front.
                let Some(pending) = stack.get_mut(sp) else {
                    return Err(BuildError::TooDeep {
                        max_depth: config.max_depth,
                        triangles: n,
                    });
                };
                *pending = Some(right_task);
                sp += 1;
                next = Some(Task {
                    node: left,
                    begin: task.begin,
                    end: mid,
                    level: task.level + 1,
                    bounds: lb,
                    centroids: lc,
                });
                continue;
            }
        }
        if sp > 0 {
            sp -= 1;
            next = stack.get_mut(sp).and_then(Option::take);
        }
    }
    Ok(Built { node_count, depth })
}

/// The split a node's search found, by strategy.
enum Cut {
    Binned(Split),
    Sorted(SweepSplit),
}

/// Decides a node: `None` for a leaf, or the left count and both sides' bounds after reordering
/// `prims` (and `tris` alongside) into left-then-right. `find_split` is
/// [`Binning::find_split`] or its parallel twin, which finds the same split; `spare` is room
/// for [`find_sweep_split`] (node slots not used yet).
pub(super) fn split_node(
    config: &BuildConfig,
    task: &Task,
    prims: &mut [PrimRef],
    tris: &mut [u32],
    find_split: &mut FindSplit<'_>,
    spare: &mut [BvhNode],
) -> Option<(usize, Side, Side)> {
    let count = prims.len();
    if count <= 1 {
        return None;
    }
    let may_be_leaf = count <= config.max_leaf_size as usize;
    let child_capacity = config.subtree_capacity(task.level + 1);
    if config.split == SplitStrategy::Centre {
        if may_be_leaf {
            return None;
        }
        let centre = centre_split(prims, tris, &task.centroids)
            .filter(|&(left, ..)| left <= child_capacity && count - left <= child_capacity);
        return Some(centre.unwrap_or_else(|| median_split(prims, tris, &task.centroids)));
    }
    let area = task.bounds.half_area();
    let found = if area > 0.0 {
        match config.split {
            SplitStrategy::Sweep { step } => find_sweep_split(prims, tris, step, spare)
                .map(|s| (s.cost, s.left_count, Cut::Sorted(s))),
            _ => find_split(prims, &task.centroids, config.bins)
                .map(|s| (s.cost, s.left_count, Cut::Binned(s))),
        }
    } else {
        None
    };
    if let Some((cost, left_count, cut)) = found {
        let split_cost = config.traversal_cost + config.triangle_cost * (cost / area);
        let leaf_cost = config.triangle_cost * batches(count) as f32;
        if may_be_leaf && split_cost >= leaf_cost {
            return None;
        }
        if left_count <= child_capacity && count - left_count <= child_capacity {
            return Some(match cut {
                Cut::Binned(split) => {
                    let (left_count, left_centers, right_centers) = partition(prims, tris, &split);
                    (
                        left_count,
                        (split.left, left_centers),
                        (split.right, right_centers),
                    )
                }
                Cut::Sorted(split) => {
                    let (left, right) = split.apply(prims, tris);
                    (split.left_count, left, right)
                }
            });
        }
    }
    if may_be_leaf {
        return None;
    }
    Some(median_split(prims, tris, &task.centroids))
}
