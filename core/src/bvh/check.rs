//! The structure validator: the one place that decides whether nodes and order can be trusted.

use super::{MAX_DEPTH, TreeArrays};
use crate::error::StructureError;
use glam::Vec4;

use crate::geom::TriangleLanes;
use crate::math::{Aabb, PackedTriangle, Triangle};
use crate::query::LeafTriangles;

/// How much to check.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum CheckLevel {
    /// Topology and leaf ranges only (what refit needs before it rewrites the boxes).
    Topology,
    /// Topology, box nesting and triangle containment.
    Full,
}

/// Where a box problem goes: returned at once, or held (the first one) while the walk goes on
/// checking topology, for a caller that reports every topology problem before any box
/// problem ([`check_boxes_last`]).
enum BoxProblems<'h> {
    Return,
    // Only blob validation holds them.
    #[cfg_attr(not(feature = "blob"), allow(dead_code))]
    Hold(&'h mut Option<StructureError>),
}

impl BoxProblems<'_> {
    /// `Err(problem)` to return it now, `Ok` when it is held (or a first one already was).
    fn report(&mut self, problem: StructureError) -> Result<(), StructureError> {
        match self {
            Self::Return => Err(problem),
            Self::Hold(held) => {
                held.get_or_insert(problem);
                Ok(())
            }
        }
    }
}

/// [`check`] at [`CheckLevel::Full`] in one walk that reports topology problems first: the
/// first box problem (bad bounds, a child outside its parent, a triangle outside its leaf) is
/// returned beside the shape only when the whole tree's topology is sound, for the caller to
/// report after its own topology checks.
#[cfg(feature = "blob")]
pub(crate) fn check_boxes_last<A: TreeArrays + ?Sized, S: LeafTriangles + ?Sized>(
    tree: &A,
    mesh: Option<&S>,
    extent: Extent,
) -> Result<(Shape, Option<StructureError>), StructureError> {
    let mut held = None;
    let shape = walk(
        tree,
        mesh,
        CheckLevel::Full,
        extent,
        BoxProblems::Hold(&mut held),
    )?;
    Ok((shape, held))
}

/// Whether nodes and slots past those the tree uses are allowed (the untrimmed buffers a build
/// was given) or refused (a blob, whose counts must be exact).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Extent {
    /// Every node reachable and every slot in a leaf.
    Exact,
    /// The reachable nodes must be a prefix of the array, and the leaves must tile a prefix of
    /// the slots; anything after is ignored.
    Prefix,
}

/// What a check found: the depth and how many nodes and slots the tree uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Shape {
    pub depth: u32,
    pub nodes: usize,
    pub slots: usize,
}

/// Checks nodes and order (and, with a triangle source, the triangle indices and containment);
/// returns the shape. Walks left-first with a fixed stack, so leaf ranges must appear in order.
pub(crate) fn check<A: TreeArrays + ?Sized, S: LeafTriangles + ?Sized>(
    tree: &A,
    mesh: Option<&S>,
    level: CheckLevel,
    extent: Extent,
) -> Result<Shape, StructureError> {
    walk(tree, mesh, level, extent, BoxProblems::Return)
}

fn walk<A: TreeArrays + ?Sized, S: LeafTriangles + ?Sized>(
    tree: &A,
    mesh: Option<&S>,
    level: CheckLevel,
    extent: Extent,
    mut boxes: BoxProblems<'_>,
) -> Result<Shape, StructureError> {
    let (node_count, slot_count) = (tree.node_count(), tree.slot_count());
    let empty = Shape {
        depth: 0,
        nodes: 0,
        slots: 0,
    };
    if node_count == 0 || slot_count == 0 {
        return if node_count == 0 && slot_count == 0 {
            Ok(empty)
        } else {
            Err(StructureError::EmptyMismatch)
        };
    }
    let total = u32::try_from(node_count).map_err(|_| StructureError::UnreachableNodes {
        reached: 0,
        total: u32::MAX,
    })?;
    // The right children still to visit and their depths (at most `MAX_DEPTH`, so a byte), in
    // two arrays rather than padded pairs: the stack the firmware's validation peaks on.
    let mut stack_node = [0u32; MAX_DEPTH as usize];
    let mut stack_depth = [0u8; MAX_DEPTH as usize];
    let mut sp = 0usize;
    let mut current = Some((0u32, 1u32));
    let mut reached = 0u32;
    let mut highest = 0u32;
    let mut next_slot = 0usize;
    let mut depth = 0u32;
    while let Some((index, node_depth)) = current.take() {
        if node_depth > MAX_DEPTH {
            return Err(StructureError::TooDeep { node: index });
        }
        depth = depth.max(node_depth);
        highest = highest.max(index);
        reached = reached.saturating_add(1);
        if reached > total {
            // Only a shared subtree can be reached more often than there are nodes.
            return Err(StructureError::LeafRangesNotContiguous { node: index });
        }
        let node = tree
            .node(index as usize)
            .ok_or(StructureError::ChildOutOfRange { node: index })?;
        let bounds = node.aabb();
        if level == CheckLevel::Full && (bounds.is_empty() || !bounds.is_finite()) {
            boxes.report(StructureError::BadBounds { node: index })?;
        }
        if node.is_leaf() {
            let first = node.first as usize;
            let tris = tree
                .leaf_triangles(first, node.count as usize)
                .ok_or(StructureError::LeafRangeOutOfBounds { node: index })?;
            if first != next_slot {
                return Err(StructureError::LeafRangesNotContiguous { node: index });
            }
            next_slot = first + tris.len();
            if let Some(mesh) = mesh {
                // A run of stored triangles is checked four at a time first; only a triangle
                // its lanes do not find inside goes through the test below.
                let run = match level {
                    CheckLevel::Full => mesh.run(first, tris.entries()),
                    CheckLevel::Topology => None,
                };
                let mut inside = 0u32;
                for (slot, tri) in tris {
                    let lane = slot.wrapping_sub(first);
                    if lane % 4 == 0 {
                        inside = run
                            .and_then(|r| r.get(lane..))
                            .map_or(0, |rest| held_lanes(&bounds, rest));
                    }
                    if inside & (1 << (lane % 4)) != 0 {
                        continue;
                    }
                    // A triangle the source does not have is a problem of the mesh, not of
                    // the tree's shape: held with the box problems, so a blob's order problems
                    // (which a packed mesh's missing corners follow from) come first.
                    let Some(t) = mesh.corners(slot, tri) else {
                        boxes.report(StructureError::TriangleOutOfRange { node: index, tri })?;
                        continue;
                    };
                    // A reference of a split triangle holds only its part of it: its leaf
                    // box need only meet the triangle's.
                    if level == CheckLevel::Full
                        && !holds(&bounds, &t)
                        && (tree.split_refs().range_of(tri).is_empty()
                            || !bounds.overlaps(&t.bounds()))
                    {
                        boxes.report(StructureError::TriangleOutsideLeaf { node: index, tri })?;
                    }
                }
            }
            current = sp.checked_sub(1).and_then(|top| {
                sp = top;
                Some((*stack_node.get(top)?, u32::from(*stack_depth.get(top)?)))
            });
        } else {
            let left = node.first;
            if left <= index {
                return Err(StructureError::ChildNotAfterParent { node: index });
            }
            let right = left
                .checked_add(1)
                .filter(|&r| r < total)
                .ok_or(StructureError::ChildOutOfRange { node: index })?;
            if level == CheckLevel::Full {
                for child in [left, right] {
                    let inside = tree
                        .node(child as usize)
                        .is_some_and(|c| bounds.contains_aabb(&c.aabb()));
                    if !inside {
                        boxes.report(StructureError::ChildOutsideParent { node: child })?;
                    }
                }
            }
            let too_deep = StructureError::TooDeep { node: index };
            // `node_depth` is at most `MAX_DEPTH` here (checked on entry).
            let child_depth = u8::try_from(node_depth + 1).map_err(|_| too_deep)?;
            *stack_node.get_mut(sp).ok_or(too_deep)? = right;
            *stack_depth.get_mut(sp).ok_or(too_deep)? = child_depth;
            sp += 1;
            current = Some((left, node_depth + 1));
        }
    }
    // Each node is reached at most once (a shared subtree repeats a leaf range, refused above),
    // so the reached nodes are a prefix exactly when the highest index is one below their count.
    let prefix = highest.checked_add(1) == Some(reached);
    let exact = reached == total;
    if !exact && (extent == Extent::Exact || !prefix) {
        return Err(StructureError::UnreachableNodes { reached, total });
    }
    if next_slot != slot_count && extent == Extent::Exact {
        return Err(StructureError::LeafRangesNotContiguous { node: total });
    }
    Ok(Shape {
        depth,
        nodes: reached as usize,
        slots: next_slot,
    })
}

/// Bit `i` set when `bounds` holds `tris[i]` ([`holds`], the same compares four triangles at
/// a time), for the first four of `tris`; 0 for none.
#[inline(always)]
fn held_lanes(bounds: &Aabb, tris: &[PackedTriangle]) -> u32 {
    let Some(lanes) = TriangleLanes::from_packed(tris) else {
        return 0;
    };
    let (min, max) = (bounds.min.to_array(), bounds.max.to_array());
    let mut inside = glam::BVec4A::splat(true);
    for corner in [lanes.a, lanes.b, lanes.c] {
        for ((row, lo), hi) in corner.rows.iter().zip(min).zip(max) {
            inside &= row.cmpge(Vec4::splat(lo)) & row.cmple(Vec4::splat(hi));
        }
    }
    let used = (1u32 << tris.len().min(4)) - 1;
    inside.bitmask() & used
}

/// Whether `bounds` holds the triangle: every corner inside, which for the finite corners of
/// a validated mesh is the same as holding the triangle's box. Without short-circuits, so the
/// test is a few vector compares rather than a chain of branches.
#[inline(always)]
fn holds(bounds: &Aabb, t: &Triangle) -> bool {
    let inside = |p: glam::Vec3| (p.cmpge(bounds.min) & p.cmple(bounds.max)).all();
    inside(t.a) & inside(t.b) & inside(t.c)
}
