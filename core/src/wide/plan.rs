//! The collapse plan: which binary nodes become the lanes of each wide node, chosen to
//! minimise the surface-area cost of the whole wide tree.
//!
//! A greedy collapse (open the widest inner child until the node is full) leaves the bottom of
//! the tree full of nodes with two or three lanes: their subtrees hold too few leaves to fill
//! more. The plan instead solves, bottom up over the binary tree, for every node and every
//! lane budget `i ≤ W`, the cheapest way to cover the node's subtree with at most `i` lanes,
//! each lane a binary leaf, a leaf merged from a small subtree, or an inner lane over a wide
//! node of its own. This is the dynamic program of Ylitie, Karras and Laine, "Efficient
//! Incoherent Ray Traversal on GPUs Through Compressed Wide BVHs" (HPG 2017), with this
//! crate's own costs: leaves are tested four triangles at a time, so a leaf costs its surface
//! area times its number of four-triangle batches.

use super::roles::{self, CollapseRoles, MERGED_LEAF_MAX};
#[cfg(feature = "parallel")]
use super::walk::Lanes;
use super::walk::{LaneSlots, walk_wide_nodes};
use crate::bvh::{Bvh, BvhNode, MAX_DEPTH, TreeArrays};
use crate::error::{BufferKind, BuildError};

/// Cost of visiting a wide node, in units of testing one batch of up to four triangles (the
/// surface-area weights the plan minimises). Higher values give fewer, fuller nodes and larger
/// merged leaves.
pub const NODE_COST: f32 = 2.0;

/// One inner binary node's entry in a [`CollapsePlan`]: the caller-provided scratch the plan
/// is computed in (one entry per inner binary node, [`plan_capacity`]). Its contents are
/// private.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanEntry {
    /// `cost[i]`: the least cost of the node's subtree as at most `i + 1` lanes.
    cost: [f32; 8],
    /// `spread[i]`: how that least cost is reached: 0 as one lane, `j ≥ 2` spread over `j`
    /// lanes between the two children.
    spread: [u8; 8],
    /// `left[j - 1]`: of `j` lanes spread between the children, how many the left one takes.
    left: [u8; 8],
    /// The subtree's cost as an inner lane: its own wide node and everything below it.
    inner: f32,
    /// As one lane, whether the subtree becomes one merged leaf (else an inner lane).
    merged: bool,
    /// How many lanes the subtree can fill: its binary leaves, at most 8. Its costs are the
    /// same for every budget from there on.
    reach: u8,
    /// The subtree's first order slot and how many it spans.
    first: u32,
    slots: u32,
}

impl PlanEntry {
    /// A placeholder for initializing plan buffers.
    pub const EMPTY: Self = Self {
        cost: [0.0; 8],
        spread: [0; 8],
        left: [1; 8],
        inner: f32::INFINITY,
        merged: false,
        reach: 1,
        first: 0,
        slots: 0,
    };

    /// The entry of a binary leaf.
    fn leaf(node: &BvhNode) -> Self {
        Self {
            cost: [leaf_cost(node, node.count); 8],
            first: node.first,
            slots: node.count,
            ..Self::EMPTY
        }
    }
}

/// Plan entries [`CollapsePlan::new`] needs for `bvh`: one per inner binary node, half the
/// nodes rounded down (none for an empty tree or a lone leaf).
///
/// A leaf's entry follows from the leaf alone and is never stored. An inner node's is kept at
/// the place of its children's pair among the pairs that follow the root: children pairs
/// tile a valid tree's nodes after the root, so inner node `i` with children `first` and
/// `first + 1` has entry `(first − 1) / 2`, one each.
#[must_use]
pub const fn plan_capacity(bvh: &Bvh<'_>) -> usize {
    bvh.nodes().len() / 2
}

/// Where the entry of the inner node `node` is kept (see [`plan_capacity`]): `None` for a
/// node whose children's pair does not start at an odd index, which no valid tree has.
fn entry_slot(node: &BvhNode) -> Option<usize> {
    let first = node.first as usize;
    (first % 2 == 1).then_some(first / 2)
}

/// The cost of a leaf over `slots` triangles in `node`'s box.
fn leaf_cost(node: &BvhNode, slots: u32) -> f32 {
    node.aabb().half_area() * slots.div_ceil(4) as f32
}

/// How the binary tree `tree` collapses into a wide tree of `W` lanes per node (4 or 8):
/// computed once into caller scratch, then read by [`WideBvh::build`](super::WideBvh::build)
/// (four-wide nodes for `W = 4`, eight-wide for `W = 8`), which also learns from it how many
/// nodes it writes ([`node_count`](Self::node_count)).
///
/// Each wide node covers an inner binary node's subtree with at most `W` lanes, chosen to
/// minimise the tree's surface-area cost: [`NODE_COST`] times the area of every wide node,
/// plus the area of every leaf times its batches of four triangles. A lane is a leaf of the
/// binary tree, a leaf merged from a binary subtree of at most [`MERGED_LEAF_MAX`] triangles
/// (its order slots are consecutive, so the merged leaf is one slot range), or an inner node.
/// Every triangle stays in exactly the slots it had: the same answers, bit for bit, whatever
/// the plan.
///
/// Deterministic: the same tree gives the same plan and the same nodes on every target (ties
/// go to the first choice in a fixed order: one lane before several, fewer lanes before more,
/// fewer lanes on the left before more, an inner lane before a merged leaf).
#[derive(Clone, Copy, Debug)]
pub struct CollapsePlan<'a, 'p, const W: usize> {
    tree: Bvh<'a>,
    choices: Choices<'p>,
    nodes: usize,
}

/// Where a plan's choices come from.
#[derive(Clone, Copy, Debug)]
enum Choices<'p> {
    /// Solved here: one entry per inner node.
    Solved(&'p [PlanEntry]),
    /// Read from roles checked against the tree (a blob's).
    Stored(CollapseRoles<'p>),
}

impl<'a, 'p, const W: usize> CollapsePlan<'a, 'p, W> {
    /// Plans the collapse of `tree` in `entries` (at least [`plan_capacity`] of them).
    ///
    /// # Errors
    /// - [`BuildError::BufferTooSmall`] (buffer [`BufferKind::CollapsePlan`]) when `entries`
    ///   is too small; nothing is written then.
    /// - [`BuildError::InvalidConfig`] (field `lanes`) unless `W` is 2 to 8.
    /// - [`BuildError::TooDeep`] for a tree whose children do not follow their parents or
    ///   that is deeper than [`MAX_DEPTH`](crate::bvh::MAX_DEPTH) (no checked tree is).
    pub fn new(tree: &Bvh<'a>, entries: &'p mut [PlanEntry]) -> Result<Self, BuildError> {
        if !(2..=8).contains(&W) {
            return Err(BuildError::InvalidConfig { field: "lanes" });
        }
        let n = plan_capacity(tree);
        let got = entries.len();
        let entries = entries.get_mut(..n).ok_or(BuildError::BufferTooSmall {
            buffer: BufferKind::CollapsePlan,
            needed: n,
            got,
        })?;
        let mut plan = Self::solved(tree, entries)?;
        plan.nodes = match tree.node(0) {
            None => 0,
            Some(root) if root.is_leaf() => 1,
            Some(_) => plan.for_each_node(0, |_, _, _| {})?,
        };
        Ok(plan)
    }

    /// The plan of `tree` solved in `entries` (exactly [`plan_capacity`] of them), without the
    /// walk that counts its nodes: [`node_count`](Self::node_count) is 0. For collapses into
    /// a growing vector, which need no count.
    pub(crate) fn solved(tree: &Bvh<'a>, entries: &'p mut [PlanEntry]) -> Result<Self, BuildError> {
        if !(2..=8).contains(&W) {
            return Err(BuildError::InvalidConfig { field: "lanes" });
        }
        solve::<W>(tree, entries)?;
        Ok(Self {
            tree: *tree,
            choices: Choices::Solved(entries),
            nodes: 0,
        })
    }

    /// The plan `roles` describe for `tree` (as [`write_roles`](Self::write_roles) wrote them,
    /// typically for a blob), checked as [`CollapseRoles::check`] checks them but with at most `W`
    /// lanes per node, and its nodes counted: no solving. Any roles that pass give a valid wide
    /// tree with the same answers as every other plan.
    ///
    /// # Errors
    /// [`BuildError::InvalidConfig`] (field `roles`) when the roles do not describe a collapse
    /// of `tree` into nodes of at most `W` lanes.
    pub fn from_roles(tree: &Bvh<'a>, roles: CollapseRoles<'p>) -> Result<Self, BuildError> {
        let nodes = roles
            .walk::<_, W>(tree, |_, _, _| {})
            .map_err(|()| BuildError::InvalidConfig { field: "roles" })?;
        Ok(Self {
            tree: *tree,
            choices: Choices::Stored(roles),
            nodes,
        })
    }

    /// Writes the role of every node of the tree in this plan into `out`
    /// ([`CollapseRoles::len_for`] the node count, exactly; the format is
    /// [`CollapseRoles`]'), for [`from_roles`](Self::from_roles) to collapse with later.
    ///
    /// # Errors
    /// [`BuildError::BufferTooSmall`] (buffer [`BufferKind::CollapsePlan`]) when `out` has
    /// another length; [`BuildError::TooDeep`] as [`CollapsePlan::new`].
    pub fn write_roles(&self, out: &mut [u8]) -> Result<(), BuildError> {
        let needed = CollapseRoles::len_for(self.tree.nodes().len());
        if out.len() != needed {
            return Err(BuildError::BufferTooSmall {
                buffer: BufferKind::CollapsePlan,
                needed,
                got: out.len(),
            });
        }
        out.fill(0);
        let mut mark = |node: u32, role: u8| {
            let node = node as usize;
            if let Some(byte) = out.get_mut(node / 4) {
                *byte |= role << (2 * (node % 4));
            }
        };
        match self.tree.node(0) {
            Some(root) if !root.is_leaf() => mark(0, roles::WIDE),
            _ => return Ok(()),
        }
        let nodes = self.tree.nodes();
        self.for_each_node(0, |_, lanes, _| {
            for &(index, lane) in lanes {
                let inner = nodes.get(index as usize).is_some_and(|n| !n.is_leaf());
                match (inner, lane.is_leaf()) {
                    (true, false) => mark(index, roles::WIDE),
                    (true, true) => mark(index, roles::MERGED),
                    _ => {}
                }
            }
        })?;
        Ok(())
    }

    /// A plan over `entries` already solved for `tree` (by the parallel solve).
    #[cfg(feature = "parallel")]
    pub(super) fn from_solved(tree: &Bvh<'a>, entries: &'p [PlanEntry]) -> Self {
        Self {
            tree: *tree,
            choices: Choices::Solved(entries),
            nodes: 0,
        }
    }

    /// The binary tree this plan collapses.
    #[must_use]
    pub const fn tree(&self) -> &Bvh<'a> {
        &self.tree
    }

    /// How many wide nodes the collapse writes (0 for an empty tree, 1 for a lone leaf; at most
    /// [`WideSizes::nodes`](super::WideSizes::nodes)).
    #[must_use]
    pub const fn node_count(&self) -> usize {
        self.nodes
    }

    #[cfg(feature = "alloc")]
    /// The plan `roles` describe for `tree`, to be checked by the collapse that walks it: its
    /// [`for_each_node`](Self::for_each_node) from the root fails unless the roles pass
    /// [`CollapseRoles::check`]. One walk instead of two; [`node_count`](Self::node_count) is
    /// 0.
    pub(crate) fn from_roles_unchecked(tree: &Bvh<'a>, roles: CollapseRoles<'p>) -> Self {
        Self {
            tree: *tree,
            choices: Choices::Stored(roles),
            nodes: 0,
        }
    }

    /// Whether the plan was read from roles (whose walk from the root checks them).
    pub(super) const fn is_stored(&self) -> bool {
        matches!(self.choices, Choices::Stored(_))
    }

    #[cfg(feature = "alloc")]
    /// How many nodes the collapse writes, for reserving room: exact for a solved plan and for
    /// stored roles that pass their check (roles that do not fail the collapse).
    pub(crate) fn node_bound(&self) -> usize {
        match self.choices {
            Choices::Stored(roles) if self.nodes == 0 => roles.node_bound(),
            _ => self.nodes,
        }
    }

    /// The planned cost of the wide tree (see the type's docs), in units of the root box's
    /// half surface area times a batch test: the expected work of a ray through the root, as
    /// far as surface areas predict it. NaN for a plan read from roles
    /// ([`from_roles`](Self::from_roles)), which do not keep it.
    #[must_use]
    pub fn cost(&self) -> f32 {
        let Choices::Solved(entries) = self.choices else {
            return f32::NAN;
        };
        let root = self.tree.nodes().first();
        let entry = root.and_then(entry_slot).and_then(|at| entries.get(at));
        match (root, entry) {
            (Some(root), Some(entry)) if !root.is_leaf() => entry.inner / root.aabb().half_area(),
            // A lone leaf still gets a wide node, of one lane.
            (Some(root), _) => NODE_COST + root.count.div_ceil(4) as f32,
            _ => 0.0,
        }
    }

    /// Walks the wide nodes of the subtree under the inner binary node `root` in the
    /// collapse's numbering, handing `each` every node's index, its lanes (from
    /// [`lanes`](Self::lanes)) and the index its first inner lane gets; returns how many nodes
    /// there are. `root`'s node is 0 and the others are numbered from 1, depth first: a node's
    /// inner lanes take the next free indices in lane order, then the last one's subtree comes
    /// first. So every subtree's nodes form one consecutive block, which the parallel collapse
    /// relies on.
    ///
    /// # Errors
    /// [`BuildError::TooDeep`] for a tree the plan cannot have come from (unreachable for a
    /// planned tree); [`BuildError::InvalidConfig`] (field `roles`) for a walk from the root of
    /// roles that fail [`CollapseRoles::check`].
    pub(super) fn for_each_node(
        &self,
        root: u32,
        each: impl FnMut(u32, &[(u32, BvhNode)], u32),
    ) -> Result<usize, BuildError> {
        let too_deep = BuildError::TooDeep {
            max_depth: MAX_DEPTH,
            triangles: self.tree.slot_count(),
        };
        match self.choices {
            // The whole walk checks the roles as it goes.
            Choices::Stored(roles) if root == 0 => roles
                .walk::<_, W>(&self.tree, each)
                .map_err(|()| BuildError::InvalidConfig { field: "roles" }),
            _ => walk_wide_nodes::<W>(root, |binary, slots| self.lanes_into(binary, slots), each)
                .ok_or(too_deep),
        }
    }

    /// The lanes of the wide node at the inner binary node `inner` (left to right), as
    /// `(binary index, node)`: a merged leaf is a leaf node over its subtree's box and slots.
    /// `None` for a node the tree does not have.
    #[cfg(feature = "parallel")]
    pub(super) fn lanes(&self, inner: u32) -> Option<Lanes<W>> {
        let mut slots = [(0u32, BvhNode::EMPTY); W];
        let len = self.lanes_into(inner, &mut slots)?;
        Some((slots, len))
    }

    /// [`lanes`](Self::lanes) written into `slots`; returns how many.
    fn lanes_into(&self, inner: u32, slots: &mut LaneSlots<W>) -> Option<usize> {
        let entries = match self.choices {
            Choices::Solved(entries) => entries,
            Choices::Stored(roles) => {
                return roles
                    .lanes::<_, W>(&self.tree, inner, slots)
                    .map(|(len, _)| len);
            }
        };
        let node = self.tree.nodes().get(inner as usize)?;
        let entry = entries.get(entry_slot(node)?)?;
        let mut len = 0usize;
        // (binary index, lane budget), the left child on top. Each step pops one and pushes
        // at most two whose budgets sum to its own, so at most W + 1 wait at once.
        let left = usize::from(*entry.left.get(W - 1)?);
        let mut stack = [(0u32, 0usize); 9];
        let [right_half, left_half, ..] = &mut stack;
        *right_half = (node.first.checked_add(1)?, W.checked_sub(left)?);
        *left_half = (node.first, left);
        let mut depth = 2usize;
        while let Some(top) = depth.checked_sub(1) {
            depth = top;
            let (at, budget) = *stack.get(top)?;
            let child = self.tree.nodes().get(at as usize)?;
            if child.is_leaf() {
                *slots.get_mut(len)? = (at, *child);
                len += 1;
                continue;
            }
            let plan = entries.get(entry_slot(child)?)?;
            let spread = usize::from(*plan.spread.get(budget.checked_sub(1)?)?);
            if spread == 0 {
                let lane = if plan.merged {
                    BvhNode::new(child.aabb(), plan.first, plan.slots)
                } else {
                    *child
                };
                *slots.get_mut(len)? = (at, lane);
                len += 1;
            } else {
                let left = usize::from(*plan.left.get(spread - 1)?);
                *stack.get_mut(depth)? = (child.first.checked_add(1)?, spread.checked_sub(left)?);
                *stack.get_mut(depth + 1)? = (child.first, left);
                depth += 2;
            }
        }
        Some(len)
    }
}

/// Fills `entries` (one per inner node of `tree`, [`plan_capacity`]) bottom up: children
/// follow their parents in a valid tree, so a reverse walk meets both children of a node
/// before the node.
fn solve<const W: usize>(tree: &Bvh<'_>, entries: &mut [PlanEntry]) -> Result<(), BuildError> {
    solve_block::<W>(tree, entries, 0, 0..tree.nodes().len())
}

/// Fills the entries of the inner nodes of `range` bottom up, in `block`, which holds entries
/// `offset..offset + block.len()` (see [`plan_capacity`]): the children of every inner node of
/// `range` must be leaves or have their entries in the block, solved here (they follow their
/// parents) or before. The parallel solve hands each task the block of one subtree.
///
/// # Errors
/// [`BuildError::TooDeep`] when a child does not follow its parent or an entry lies outside
/// the block.
pub(super) fn solve_block<const W: usize>(
    tree: &Bvh<'_>,
    block: &mut [PlanEntry],
    offset: usize,
    range: core::ops::Range<usize>,
) -> Result<(), BuildError> {
    let malformed = BuildError::TooDeep {
        max_depth: crate::bvh::MAX_DEPTH,
        triangles: tree.order().len(),
    };
    let nodes = tree.nodes();
    let in_block = |node: &BvhNode| entry_slot(node)?.checked_sub(offset);
    let entry_of = |block: &[PlanEntry], at: usize| -> Option<PlanEntry> {
        let node = nodes.get(at)?;
        if node.is_leaf() {
            Some(PlanEntry::leaf(node))
        } else {
            block.get(in_block(node)?).copied()
        }
    };
    for (index, node) in range.clone().zip(nodes.get(range).ok_or(malformed)?).rev() {
        if node.is_leaf() {
            continue;
        }
        let first = node.first as usize;
        if first <= index {
            return Err(malformed);
        }
        let (Some(left), Some(right)) = (entry_of(block, first), entry_of(block, first + 1)) else {
            return Err(malformed);
        };
        *in_block(node)
            .and_then(|at| block.get_mut(at))
            .ok_or(malformed)? = inner_entry::<W>(node, &left, &right);
    }
    Ok(())
}

/// The entry of an inner node whose children's entries are `left` and `right`.
///
/// Every choice is a select on the costs, never a branch: the comparisons of one node's costs
/// go either way at random, and mispredicted branches made planning the bunny's tree take
/// about as long as loading its blob.
fn inner_entry<const W: usize>(node: &BvhNode, left: &PlanEntry, right: &PlanEntry) -> PlanEntry {
    let mut entry = PlanEntry {
        first: left.first,
        slots: left.slots.saturating_add(right.slots),
        ..PlanEntry::EMPTY
    };
    let (lc, rc) = (left.cost, right.cost);
    let (l_reach, r_reach) = (usize::from(left.reach), usize::from(right.reach));
    entry.reach = (l_reach + r_reach).min(W) as u8;
    // spread[j]: the least cost of `j` lanes or fewer shared by the two children, each taking
    // at least one; `entry.left[j - 1]` records the left child's share (the first of equal
    // costs). A child's costs stop falling at its reach, so a larger share of the left one
    // never costs less (it can only tie, later in the order), and beyond both reaches every
    // budget repeats the last: those are not tried, and the choices are the same.
    let mut spread = [f32::INFINITY; 9];
    let last = usize::from(entry.reach);
    for j in 2..=W {
        if j > last {
            let (s, l) = (
                spread.get(last).copied().unwrap_or(f32::INFINITY),
                entry.left.get(last.wrapping_sub(1)).copied().unwrap_or(1),
            );
            if let (Some(sj), Some(lj)) = (spread.get_mut(j), entry.left.get_mut(j - 1)) {
                (*sj, *lj) = (s, l);
            }
            continue;
        }
        let (mut best, mut share) = (f32::INFINITY, 1u8);
        for k in 1..j.min(l_reach + 1) {
            let cost = lc.get(k - 1).copied().unwrap_or(f32::INFINITY)
                + rc.get(j - k - 1).copied().unwrap_or(f32::INFINITY);
            let better = cost < best;
            best = if better { cost } else { best };
            share = if better { k as u8 } else { share };
        }
        if let (Some(s), Some(l)) = (spread.get_mut(j), entry.left.get_mut(j - 1)) {
            (*s, *l) = (best, share);
        }
    }
    let full = spread.get(W).copied().unwrap_or(f32::INFINITY);
    let area = node.aabb().half_area();
    let as_inner = area * NODE_COST + full;
    let consecutive = left.first.checked_add(left.slots) == Some(right.first);
    let mergeable = consecutive && entry.slots <= MERGED_LEAF_MAX;
    let as_leaf = if mergeable {
        leaf_cost(node, entry.slots)
    } else {
        f32::INFINITY
    };
    entry.inner = as_inner;
    entry.merged = as_leaf < as_inner;
    // With infinite or NaN costs every comparison fails and each choice stays the first,
    // always a valid one (one lane; one lane to the left).
    let mut best = if entry.merged { as_leaf } else { as_inner };
    let mut how = 0u8;
    for j in 1..=W {
        let s = if j >= 2 {
            spread.get(j).copied().unwrap_or(f32::INFINITY)
        } else {
            f32::INFINITY
        };
        let better = s < best;
        best = if better { s } else { best };
        how = if better { j as u8 } else { how };
        if let (Some(c), Some(h)) = (entry.cost.get_mut(j - 1), entry.spread.get_mut(j - 1)) {
            (*c, *h) = (best, how);
        }
    }
    entry
}
