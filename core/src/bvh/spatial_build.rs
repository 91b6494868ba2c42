//! The builder with spatial splits: the binned-SAH builder, where a node may also cut space
//! at a plane and repeat the triangles that cross it on both sides.
//!
//! Every node owns a range of the reference buffers with room after its references; a split
//! shares that room between its children in proportion to their references (moving the right
//! child's references up), and a spatial split spends some of it on the repeated references.
//! Leaves name their references where they lie in that roomy layout; once the tree is built,
//! [`compact`](super::spatial_compact::compact) moves them down in depth-first order, so the
//! finished order array is dense. A subtree therefore depends only on its own range, which
//! lets the parallel build (feature `parallel`) build children concurrently.

use super::binning::{Binning, batches};
use super::build::{Built, FillPrims, Task, check_len, fill_prims, split_node};
use super::build_box::BuildBox;
use super::clip::{clipped, holds_something, lane};
use super::partition::bounds_of;
use super::spatial_bins::{SPLIT_FLAG, SpatialBinning, SpatialSplit, corners_of};
use super::spatial_compact::compact;
use super::{BuildConfig, BvhNode, MAX_DEPTH, PrimRef, SpatialSplits, node_capacity};
use crate::error::{BufferKind, BuildError};
use crate::mesh::ValidMesh;
use crate::query::SplitRef;

/// What the builder produced.
pub(super) struct SpatialBuilt {
    pub node_count: usize,
    pub depth: u32,
    /// Order slots used (references).
    pub slots: usize,
    /// Entries written to the split-reference buffer.
    pub split_refs: usize,
}

impl SpatialBuilt {
    /// The build of a mesh without triangles.
    pub(super) const NOTHING: Self = Self {
        node_count: 0,
        depth: 0,
        slots: 0,
        split_refs: 0,
    };
}

/// A node to build: [`Task`] plus the end of the room its subtree may use.
#[derive(Clone, Copy)]
pub(super) struct RoomTask {
    pub task: Task,
    pub room_end: usize,
}

/// Where a reference goes under a spatial split.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Side {
    Left,
    Right,
    Both,
}

/// Builds into the caller's buffers (see [`Bvh::build_spatial`](super::Bvh::build_spatial)).
pub(super) fn build_spatial_into(
    mesh: &ValidMesh<'_>,
    config: &BuildConfig,
    spatial: &SpatialSplits,
    nodes: &mut [BvhNode],
    order: &mut [u32],
    scratch: &mut [PrimRef],
    splits: &mut [SplitRef],
) -> Result<SpatialBuilt, BuildError> {
    let lens = (nodes.len(), splits.len());
    let fill = &mut |prims: &mut [PrimRef], order: &mut [u32]| {
        fill_prims(mesh, 0, prims, order);
        bounds_of(prims)
    };
    let Some((prims, order, root)) = prepare(mesh, config, spatial, lens, order, scratch, fill)?
    else {
        return Ok(SpatialBuilt::NOTHING);
    };
    let builder = Builder::new(mesh, config, spatial, &root.task.bounds);
    let built = build_subtree(builder, root, prims, order, nodes, 0)?;
    finish(built, nodes, order, splits)
}

/// The reference room of a build's scratch and order, with the root's task.
pub(super) type Prepared<'s> = (&'s mut [PrimRef], &'s mut [u32], RoomTask);

/// The first step of both builds: checks the settings, the buffer lengths (`lens`: nodes and
/// split references) and the depth limit, then fills the first `n` references (`fill`
/// measures them too). Returns the reference room of `scratch` and `order` with the root's
/// task, or `None` for a mesh without triangles.
pub(super) fn prepare<'s>(
    mesh: &ValidMesh<'_>,
    config: &BuildConfig,
    spatial: &SpatialSplits,
    (nodes_len, splits_len): (usize, usize),
    order: &'s mut [u32],
    scratch: &'s mut [PrimRef],
    fill: &mut FillPrims<'_>,
) -> Result<Option<Prepared<'s>>, BuildError> {
    config.check()?;
    spatial.check()?;
    // Spatial splits are weighed against the binned search's best split.
    if matches!(config.split, super::SplitStrategy::Sweep { .. }) {
        return Err(BuildError::InvalidConfig { field: "split" });
    }
    let n = mesh.triangle_count();
    let room = spatial.reference_capacity(n);
    // Entries carry a flag in their top bit while building, and leaves name slots in `u32`.
    if n >= SPLIT_FLAG as usize || u32::try_from(room).is_err() {
        return Err(BuildError::InvalidConfig {
            field: "extra_references",
        });
    }
    check_len(BufferKind::Nodes, node_capacity(room), nodes_len)?;
    check_len(BufferKind::Order, room, order.len())?;
    check_len(BufferKind::Scratch, room, scratch.len())?;
    check_len(
        BufferKind::SplitRefs,
        spatial.split_ref_capacity(n),
        splits_len,
    )?;
    if n > config.subtree_capacity(1) {
        return Err(BuildError::TooDeep {
            max_depth: config.max_depth,
            triangles: n,
        });
    }
    let (Some(prims), Some(order)) = (scratch.get_mut(..room), order.get_mut(..room)) else {
        return Ok(None);
    };
    if n == 0 {
        return Ok(None);
    }
    let (Some(first_prims), Some(first_order)) = (prims.get_mut(..n), order.get_mut(..n)) else {
        return Ok(None);
    };
    let (bounds, centroids) = fill(first_prims, first_order);
    let root = RoomTask {
        task: Task {
            node: 0,
            begin: 0,
            end: n,
            level: 1,
            bounds,
            centroids,
        },
        room_end: room,
    };
    Ok(Some((prims, order, root)))
}

/// Compacts the built tree's leaves and sorts the split table: the end of every build.
pub(super) fn finish(
    built: Built,
    nodes: &mut [BvhNode],
    order: &mut [u32],
    splits: &mut [SplitRef],
) -> Result<SpatialBuilt, BuildError> {
    let (slots, split_refs) = compact(
        nodes.get_mut(..built.node_count).unwrap_or_default(),
        order,
        splits,
    );
    let table = splits.get_mut(..split_refs).unwrap_or_default();
    table.sort_unstable_by_key(|r| (r.tri, r.slot));
    Ok(SpatialBuilt {
        node_count: built.node_count,
        depth: built.depth,
        slots,
        split_refs,
    })
}

/// Builds the subtree of `root` (a task over all of `prims` and `order`, positions relative
/// to them; its node at 0) depth first, left child first, into `nodes`: the root at 0 and
/// each split's children as the next free pair. Leaves name their references by position in
/// the whole build's arrays, `base` plus their position here.
pub(super) fn build_subtree(
    mut builder: Builder<'_, '_>,
    root: RoomTask,
    prims: &mut [PrimRef],
    order: &mut [u32],
    nodes: &mut [BvhNode],
    base: usize,
) -> Result<Built, BuildError> {
    let mut stack = [None::<RoomTask>; MAX_DEPTH as usize];
    let mut sp = 0;
    let mut next = Some(root);
    let mut node_count = 1;
    let mut depth = 0;
    while let Some(rt) = next.take() {
        let task = rt.task;
        depth = depth.max(task.level);
        let children = builder.split(&rt, prims, order)?;
        let Some(slot) = nodes.get_mut(task.node) else {
            break;
        };
        let bounds = task.bounds.to_aabb().padded();
        match children {
            None => {
                // base + end ≤ the reference room, which fits in u32 (checked up front).
                let count = task.end - task.begin;
                *slot = BvhNode::new(bounds, (base + task.begin) as u32, count as u32);
            }
            Some((mut left, mut right)) => {
                let first = node_count;
                node_count += 2;
                *slot = BvhNode::new(bounds, first as u32, 0);
                left.task.node = first;
                right.task.node = first + 1;
                // One pending right sibling per level above at most: the stack cannot fill
                // within the depth limit checked up front.
                let Some(pending) = stack.get_mut(sp) else {
                    return Err(BuildError::TooDeep {
                        max_depth: builder.config.max_depth,
                        triangles: builder.mesh.triangle_count(),
                    });
                };
                *pending = Some(right);
                sp += 1;
                next = Some(left);
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

/// What decides a node: the mesh, the config, the spatial-split threshold, and bin storage.
pub(super) struct Builder<'m, 'c> {
    mesh: &'m ValidMesh<'m>,
    config: &'c BuildConfig,
    /// Overlap (half area) of the best object split's children above which a node tries
    /// spatial splits.
    min_overlap: f32,
    binning: Binning,
    spatial: SpatialBinning,
}

impl<'m, 'c> Builder<'m, 'c> {
    /// A builder for `mesh` whose root box is `bounds`.
    pub(super) fn new(
        mesh: &'m ValidMesh<'m>,
        config: &'c BuildConfig,
        spatial: &SpatialSplits,
        bounds: &BuildBox,
    ) -> Self {
        Self {
            mesh,
            config,
            min_overlap: spatial.min_overlap * bounds.half_area(),
            binning: Binning::new(),
            spatial: SpatialBinning::new(),
        }
    }

    /// Decides a node: `None` for a leaf, or its two children (node indices unset), their
    /// references in place.
    pub(super) fn split(
        &mut self,
        rt: &RoomTask,
        prims: &mut [PrimRef],
        order: &mut [u32],
    ) -> Result<Option<(RoomTask, RoomTask)>, BuildError> {
        let task = &rt.task;
        let (begin, end) = (task.begin, task.end);
        let count = end - begin;
        let (Some(range), Some(tris)) = (prims.get_mut(begin..end), order.get_mut(begin..end))
        else {
            return Ok(None);
        };
        let area = task.bounds.half_area();
        let sah = self.config.split == super::SplitStrategy::Sah && area > 0.0;
        let object = if sah {
            self.binning
                .find_split(range, &task.centroids, self.config.bins)
        } else {
            None
        };
        let spare = rt.room_end - end;
        let spatial = match object {
            Some(o) if spare > 0 && overlap(&o.left, &o.right) > self.min_overlap => self
                .spatial
                .find(self.mesh, range, tris, &task.bounds, spare)
                .filter(|s| s.cost < o.cost),
            _ => None,
        };
        if let Some(s) = spatial {
            let split_cost =
                self.config.traversal_cost + self.config.triangle_cost * (s.cost / area);
            let leaf_cost = self.config.triangle_cost * batches(count) as f32;
            if count <= self.config.max_leaf_size as usize && split_cost >= leaf_cost {
                return Ok(None);
            }
            if let Some(children) = self.cut(rt, &s, prims, order) {
                return Ok(Some(children));
            }
        }
        let (Some(range), Some(tris)) = (prims.get_mut(begin..end), order.get_mut(begin..end))
        else {
            return Ok(None);
        };
        let Some((left_count, (lb, lc), (rb, rc))) = split_node(
            self.config,
            task,
            range,
            tris,
            &mut |_, _, _| object,
            &mut [],
        ) else {
            return Ok(None);
        };
        // Share the room in proportion to the references, and move the right side up.
        let right_count = count - left_count;
        let left_room = share(spare, left_count, count);
        let right_begin = begin + left_count + left_room;
        prims.copy_within(begin + left_count..end, right_begin);
        order.copy_within(begin + left_count..end, right_begin);
        Ok(Some(children(
            task,
            (begin, begin + left_count, lb, lc),
            (right_begin, right_begin + right_count, rb, rc),
            rt.room_end,
        )))
    }

    /// Cuts the node's references at `s`'s plane, or `None` (nothing moved) when the cut
    /// would leave a side empty, need more room than the node has, or exceed the depth limit.
    fn cut(
        &mut self,
        rt: &RoomTask,
        s: &SpatialSplit,
        prims: &mut [PrimRef],
        order: &mut [u32],
    ) -> Option<(RoomTask, RoomTask)> {
        let task = &rt.task;
        let (begin, end) = (task.begin, task.end);
        let mesh = self.mesh;
        let side = |p: &PrimRef, entry: u32| side_of(mesh, p, entry, s);
        // Count first, so a cut that cannot be made moves nothing.
        let (mut n_left, mut n_both) = (0usize, 0usize);
        for (p, &e) in prims.get(begin..end)?.iter().zip(order.get(begin..end)?) {
            match side(p, e) {
                Side::Left => n_left += 1,
                Side::Both => n_both += 1,
                Side::Right => {}
            }
        }
        let count = end - begin;
        let n_right = count - n_left - n_both;
        let (left_n, right_n) = (n_left + n_both, n_right + n_both);
        let spare = rt.room_end - end;
        let child_capacity = self.config.subtree_capacity(task.level + 1);
        if left_n == 0
            || right_n == 0
            || n_both > spare
            || left_n > child_capacity
            || right_n > child_capacity
            || n_both == 0 && (n_left == 0 || n_right == 0)
        {
            return None;
        }
        // [left | both | right], stably enough to be deterministic.
        three_way(
            prims.get_mut(begin..end)?,
            order.get_mut(begin..end)?,
            |p, e| side(p, e),
        );
        let left_room = share(spare - n_both, left_n, left_n + right_n);
        let right_begin = begin + left_n + left_room;
        // The right-only references move up past room for the repeats.
        let rights = begin + left_n..end;
        prims.copy_within(rights.clone(), right_begin + n_both);
        order.copy_within(rights, right_begin + n_both);
        for i in 0..n_both {
            let (from, to) = (begin + n_left + i, right_begin + i);
            let (Some(&p), Some(&e)) = (prims.get(from), order.get(from)) else {
                return None;
            };
            let corners = corners_of(mesh, e)?;
            let own = p.bounds();
            let below = clipped(&corners, s.axis, f32::NEG_INFINITY, s.plane, &own);
            let above = clipped(&corners, s.axis, s.plane, f32::INFINITY, &own);
            for (at, part) in [(from, below), (to, above)] {
                if let (Some(slot), Some(entry)) = (prims.get_mut(at), order.get_mut(at)) {
                    *slot = PrimRef {
                        min: part.min,
                        max: part.max,
                    };
                    *entry = e | SPLIT_FLAG;
                }
            }
        }
        let (lb, lc) = bounds_of(prims.get(begin..begin + left_n)?);
        let (rb, rc) = bounds_of(prims.get(right_begin..right_begin + right_n)?);
        Some(children(
            task,
            (begin, begin + left_n, lb, lc),
            (right_begin, right_begin + right_n, rb, rc),
            rt.room_end,
        ))
    }
}

/// The two child tasks of `task`: each `(begin, end, bounds, centroids)`, the left one's room
/// ending where the right one begins.
fn children(
    task: &Task,
    (lbegin, lend, lb, lc): (usize, usize, BuildBox, BuildBox),
    (rbegin, rend, rb, rc): (usize, usize, BuildBox, BuildBox),
    room_end: usize,
) -> (RoomTask, RoomTask) {
    let child = |begin, end, bounds, centroids| Task {
        node: 0,
        begin,
        end,
        level: task.level + 1,
        bounds,
        centroids,
    };
    (
        RoomTask {
            task: child(lbegin, lend, lb, lc),
            room_end: rbegin,
        },
        RoomTask {
            task: child(rbegin, rend, rb, rc),
            room_end,
        },
    )
}

/// `room · part / whole`, rounded down, in 64 bits so every target agrees.
fn share(room: usize, part: usize, whole: usize) -> usize {
    if whole == 0 {
        return 0;
    }
    let s = (room as u64).saturating_mul(part as u64) / whole as u64;
    usize::try_from(s).unwrap_or(room).min(room)
}

/// Half area of the overlap of two boxes (0 when they are apart).
fn overlap(a: &BuildBox, b: &BuildBox) -> f32 {
    BuildBox {
        min: a.min.max(b.min),
        max: a.max.min(b.max),
    }
    .half_area()
}

/// Where reference `p` (order entry `entry`) goes under the cut `s`: wholly on one side by
/// its box; across the plane, both ways when the triangle has a part on each side, else to
/// the side that holds it.
fn side_of(mesh: &ValidMesh<'_>, p: &PrimRef, entry: u32, s: &SpatialSplit) -> Side {
    let (lo, hi) = (lane(p.min, s.axis), lane(p.max, s.axis));
    if hi <= s.plane {
        return Side::Left;
    }
    if lo >= s.plane {
        return Side::Right;
    }
    let Some(corners) = corners_of(mesh, entry) else {
        return Side::Left;
    };
    let own = p.bounds();
    let below = holds_something(&clipped(&corners, s.axis, f32::NEG_INFINITY, s.plane, &own));
    let above = holds_something(&clipped(&corners, s.axis, s.plane, f32::INFINITY, &own));
    match (below, above) {
        (true, true) => Side::Both,
        (false, true) => Side::Right,
        _ => Side::Left,
    }
}

/// Reorders `prims` and `tris` alike into those `side` sends left, both ways, then right.
fn three_way(prims: &mut [PrimRef], tris: &mut [u32], side: impl Fn(&PrimRef, u32) -> Side) {
    let len = prims.len().min(tris.len());
    let mut k = 0;
    for want in [Side::Left, Side::Both] {
        let start = k;
        for i in start..len {
            let (Some(p), Some(&e)) = (prims.get(i), tris.get(i)) else {
                break;
            };
            if side(p, e) == want {
                prims.swap(k, i);
                tris.swap(k, i);
                k += 1;
            }
        }
    }
}
