//! The top-down builder (binned SAH or centre splits). Iterative, with a fixed task stack; writes only into the
//! caller's buffers, and only after every size and limit has been checked.

use glam::Vec3A;

use super::binning::{Binning, partition};
use super::build_box::BuildBox;
use super::centre::{Side, centre_split};
use super::lanes::{max_lanes, min_lanes};
use super::median::median_split;
use super::partition::bounds_of;
use super::{BuildConfig, BvhNode, MAX_DEPTH, PrimRef, SplitStrategy, node_capacity};
use crate::error::{BufferKind, BuildError};
use crate::mesh::ValidMesh;

/// What the builder produced: how many nodes it used and how deep the tree is.
pub(super) struct Built {
    pub node_count: usize,
    pub depth: u32,
}

#[derive(Clone, Copy)]
struct Task {
    node: usize,
    begin: usize,
    end: usize,
    level: u32,
    bounds: BuildBox,
    /// Bounds of the doubled centroids ([`PrimRef::centroid2`]).
    centroids: BuildBox,
}

fn check_len(buffer: BufferKind, needed: usize, got: usize) -> Result<(), BuildError> {
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
    config.check()?;
    let n = mesh.triangle_count();
    check_len(BufferKind::Nodes, node_capacity(n), nodes.len())?;
    check_len(BufferKind::Order, n, order.len())?;
    check_len(BufferKind::Scratch, n, scratch.len())?;
    if n > config.subtree_capacity(1) {
        return Err(BuildError::TooDeep {
            max_depth: config.max_depth,
            triangles: n,
        });
    }
    let (Some(prims), Some(order)) = (scratch.get_mut(..n), order.get_mut(..n)) else {
        return Ok(Built {
            node_count: 0,
            depth: 0,
        });
    };
    if n == 0 {
        return Ok(Built {
            node_count: 0,
            depth: 0,
        });
    }
    for ((tri, p), o) in (0u32..).zip(prims.iter_mut()).zip(order.iter_mut()) {
        *p = mesh.triangle(tri).map_or(PrimRef::EMPTY, |t| {
            let [a, b, c] = [t.a, t.b, t.c].map(Vec3A::from);
            PrimRef {
                min: min_lanes(c, min_lanes(b, a)),
                max: max_lanes(c, max_lanes(b, a)),
            }
        });
        *o = tri;
    }
    let (bounds, centroids) = bounds_of(prims);

    let mut stack = [None::<Task>; MAX_DEPTH as usize];
    let mut sp = 0;
    let mut next = Some(Task {
        node: 0,
        begin: 0,
        end: n,
        level: 1,
        bounds,
        centroids,
    });
    let mut node_count = 1;
    let mut depth = 0;
    let mut binning = Binning::new();
    while let Some(task) = next.take() {
        depth = depth.max(task.level);
        let count = task.end - task.begin;
        let (Some(range), Some(tris)) = (
            prims.get_mut(task.begin..task.end),
            order.get_mut(task.begin..task.end),
        ) else {
            break;
        };
        let children = split_node(config, &task, range, tris, &mut binning);
        let Some(slot) = nodes.get_mut(task.node) else {
            break;
        };
        match children {
            None => {
                // Leaf: begin < n ≤ u32::MAX and count ≤ max_leaf_size, so both fit.
                *slot = BvhNode::new(
                    task.bounds.to_aabb().padded(),
                    task.begin as u32,
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

/// Decides a node: `None` for a leaf, or the left count and both sides' bounds after reordering
/// `prims` (and `tris` alongside) into left-then-right.
fn split_node(
    config: &BuildConfig,
    task: &Task,
    prims: &mut [PrimRef],
    tris: &mut [u32],
    binning: &mut Binning,
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
    if area > 0.0
        && let Some(split) = binning.find_split(prims, &task.centroids, config.bins)
    {
        {
            let split_cost = config.traversal_cost + config.triangle_cost * (split.cost / area);
            let leaf_cost = config.triangle_cost * count as f32;
            if may_be_leaf && split_cost >= leaf_cost {
                return None;
            }
            let right_count = count - split.left_count;
            if split.left_count <= child_capacity && right_count <= child_capacity {
                let (left_count, left_centers, right_centers) = partition(prims, tris, &split);
                return Some((
                    left_count,
                    (split.left, left_centers),
                    (split.right, right_centers),
                ));
            }
        }
    }
    if may_be_leaf {
        return None;
    }
    Some(median_split(prims, tris, &task.centroids))
}
