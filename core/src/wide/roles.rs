//! A collapse plan as a blob stores it: the role of every binary node, two bits each, so that
//! a loader collapses the tree with one walk instead of solving the plan again.
//!
//! A wide node starts at an inner binary node. Its lanes are found by walking down from that
//! node's children: a binary leaf is a leaf lane; an inner node is an inner lane (role
//! [`WIDE`], its own wide node), a merged leaf (role [`MERGED`]: its subtree's consecutive
//! slots as one leaf) or is opened (role [`OPEN`]: its two children are walked in its place).
//! The root, when inner, has role `WIDE`. Every node the walks never reach (those below a
//! merged leaf) and every binary leaf has role `OPEN`, and so do the padding bits of the last
//! byte: one tree and one plan give exactly one byte string.

use super::walk::{LaneSlots, walk_wide_nodes};
use crate::bvh::{BvhNode, MAX_DEPTH, TreeArrays};

/// The most order slots (triangles) a leaf merged from a binary subtree may hold: two batches
/// of four. Leaves of the binary tree keep their own size, whatever it is.
pub const MERGED_LEAF_MAX: u32 = 8;

/// The role of a node that is not a lane: opened, a binary leaf, the padding, or unreached.
pub(super) const OPEN: u8 = 0;
/// The role of an inner node that starts a wide node (the root, and every inner lane).
pub(super) const WIDE: u8 = 1;
/// The role of an inner node whose subtree is one merged leaf lane.
pub(super) const MERGED: u8 = 2;

/// The roles of a binary tree's nodes in a collapse ([`CollapsePlan::write_roles`](
/// super::plan::CollapsePlan::write_roles)): node `i`'s role is bits `2 (i mod 4)` and `2 (i mod 4) + 1`
/// of byte `i / 4`, [`CollapseRoles::len_for`] bytes in all.
///
/// A role is 1 for an inner node that starts a wide node (the root, and every inner lane), 2
/// for an inner node whose subtree becomes one leaf lane (its consecutive slots, at most
/// [`MERGED_LEAF_MAX`]), and 0 for every other node: one opened in its parent's wide node (its
/// children are walked in its place), a binary leaf (always a leaf lane), a node below a
/// merged leaf, and the padding of the last byte. So one tree and one plan give exactly one
/// byte string. Read by
/// [`CollapsePlan::from_roles`](super::plan::CollapsePlan::from_roles), which collapses a tree with
/// them without solving the plan, and checked against a tree by [`CollapseRoles::check`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CollapseRoles<'a> {
    bytes: &'a [u8],
}

impl<'a> CollapseRoles<'a> {
    /// The roles in `bytes` (not yet checked against any tree).
    #[must_use]
    pub const fn new(bytes: &'a [u8]) -> Self {
        Self { bytes }
    }

    /// The bytes.
    #[must_use]
    pub const fn bytes(&self) -> &'a [u8] {
        self.bytes
    }

    /// Bytes of the roles of a tree of `nodes` nodes: one per four nodes, rounded up.
    #[must_use]
    pub const fn len_for(nodes: usize) -> usize {
        nodes.div_ceil(4)
    }

    /// Node `node`'s role; 3 (no role) past the end.
    pub(super) fn role(&self, node: usize) -> u8 {
        self.bytes
            .get(node / 4)
            .map_or(3, |byte| (byte >> (2 * (node % 4))) & 3)
    }

    /// How many nodes (padding included) have a role other than [`OPEN`].
    fn marked(&self) -> usize {
        self.bytes
            .iter()
            .map(|&b| ((b | (b >> 1)) & 0x55).count_ones() as usize)
            .sum()
    }

    /// Checks that these roles describe a collapse of `tree` into nodes of at most eight lanes (the
    /// collapse blobs store), exactly as the module's docs lay it out: as many bytes as the tree
    /// needs, the root `WIDE` (when inner), no wide node of more than eight lanes, no role on a
    /// leaf, merged leaves over at most [`MERGED_LEAF_MAX`] consecutive slots, and no role below a
    /// merged leaf or in the padding. Returns how many wide nodes the collapse has (0 for an empty
    /// tree, 1 for a lone leaf).
    ///
    /// One pass over the binary nodes with a stack of [`MAX_DEPTH`] entries and a counter per
    /// level of wide nodes: a wide node and the nodes it opens are the inner nodes of a binary
    /// subtree whose leaves are its lanes, so it has one lane more than them.
    ///
    /// # Errors
    /// `Err(())` when any of that fails, or when a child does not follow its parent or the
    /// tree is deeper than [`MAX_DEPTH`] (no checked tree is).
    #[allow(clippy::result_unit_err)]
    pub fn check<T: TreeArrays>(&self, tree: &T) -> Result<usize, ()> {
        const W: usize = 8;
        let n = tree.node_count();
        if self.bytes.len() != Self::len_for(n) {
            return Err(());
        }
        if (n..4 * self.bytes.len()).any(|i| self.role(i) != OPEN) {
            return Err(());
        }
        let Some(root) = tree.node(0) else {
            return Ok(0);
        };
        if root.is_leaf() {
            return if self.role(0) == OPEN { Ok(1) } else { Err(()) };
        }
        if self.role(0) != WIDE {
            return Err(());
        }
        // `inner[l]`: the inner nodes so far of the wide node at level `l` (wide nodes above
        // it) whose subtree the walk is in.
        let mut inner = [0u8; MAX_DEPTH as usize + 1];
        // The right children still to visit and their levels, in two arrays (a pair would be
        // padded to eight bytes): this stack is most of the firmware validation's peak.
        let mut pending_node = [0u32; MAX_DEPTH as usize];
        let mut pending_level = [0u8; MAX_DEPTH as usize];
        let mut len = 0usize;
        let mut wide = 0usize;
        // (node, the level of the wide node its parent belongs to); the root starts level 0.
        let mut next = Some((0u32, 0u8));
        while let Some((at, level)) = next.take() {
            let node = tree.node(at as usize).ok_or(())?;
            let mut descend = |level: u8| -> Result<(), ()> {
                if node.first <= at {
                    return Err(());
                }
                *pending_node.get_mut(len).ok_or(())? = node.first.checked_add(1).ok_or(())?;
                *pending_level.get_mut(len).ok_or(())? = level;
                len += 1;
                next = Some((node.first, level));
                Ok(())
            };
            match (node.is_leaf(), self.role(at as usize)) {
                (true, OPEN) => {}
                (false, WIDE) => {
                    let level = if at == 0 {
                        0
                    } else {
                        level.checked_add(1).ok_or(())?
                    };
                    *inner.get_mut(usize::from(level)).ok_or(())? = 1;
                    wide += 1;
                    descend(level)?;
                }
                (false, OPEN) if at != 0 => {
                    let count = inner.get_mut(usize::from(level)).ok_or(())?;
                    *count += 1;
                    if usize::from(*count) >= W {
                        return Err(());
                    }
                    descend(level)?;
                }
                (false, MERGED) if at != 0 => {
                    self.merged_leaf(tree, &node).ok_or(())?;
                }
                _ => return Err(()),
            }
            if next.is_none() {
                next = len.checked_sub(1).and_then(|top| {
                    len = top;
                    Some((*pending_node.get(top)?, *pending_level.get(top)?))
                });
            }
        }
        Ok(wide)
    }

    /// The rules of [`check`](Self::check) with at most `W` lanes per node, checked along the
    /// walk a collapse makes (each node's lanes, then that the marked nodes are exactly the
    /// wide nodes and the merged leaves), handing every wide node on the way to `each` as
    /// [`CollapsePlan::for_each_node`](super::CollapsePlan) does (a lone leaf's node too, as
    /// one leaf lane), so that a collapse checks the roles as it goes. After an error `each`
    /// may have seen some nodes.
    pub(super) fn walk<T: TreeArrays, const W: usize>(
        &self,
        tree: &T,
        mut each: impl FnMut(u32, &[(u32, BvhNode)], u32),
    ) -> Result<usize, ()> {
        if self.bytes.len() != Self::len_for(tree.node_count()) || !(2..=8).contains(&W) {
            return Err(());
        }
        let Some(root) = tree.node(0) else {
            return if self.marked() == 0 { Ok(0) } else { Err(()) };
        };
        if root.is_leaf() {
            each(0, &[(0, root)], 1);
            return if self.marked() == 0 { Ok(1) } else { Err(()) };
        }
        if self.role(0) != WIDE {
            return Err(());
        }
        let mut merged = 0usize;
        let nodes = walk_wide_nodes::<W>(
            0,
            |inner, slots| {
                let (len, merged_here) = self.lanes::<T, W>(tree, inner, slots)?;
                merged += merged_here;
                Some(len)
            },
            each,
        )
        .ok_or(())?;
        if self.marked() != nodes + merged {
            return Err(());
        }
        Ok(nodes)
    }

    #[cfg(feature = "alloc")]
    /// The wide nodes of the collapse these roles describe, for roles that pass
    /// [`check`](Self::check) (the `WIDE` roles, or 1 for a lone leaf): the capacity to reserve
    /// for them, so that the nodes fill it exactly (roles that break the rules fail the
    /// collapse, which may write more).
    pub(super) fn node_bound(&self) -> usize {
        self.bytes
            .iter()
            .map(|&b| (b & !(b >> 1) & 0x55).count_ones() as usize)
            .sum::<usize>()
            .max(1)
    }

    /// Writes the lanes of the wide node at the inner node `inner` into `slots` (left to
    /// right, as [`CollapsePlan::lanes`](super::CollapsePlan) gives them: a merged leaf as a
    /// leaf node over its subtree's box and slots) and returns how many, and how many of them
    /// are merged leaves. `None` when the roles break a rule of the module's docs on the way.
    pub(super) fn lanes<T: TreeArrays, const W: usize>(
        &self,
        tree: &T,
        inner: u32,
        slots: &mut LaneSlots<W>,
    ) -> Option<(usize, usize)> {
        let node = tree.node(inner as usize)?;
        if node.is_leaf() {
            return None;
        }
        let (mut len, mut merged) = (0usize, 0usize);
        // Nodes still to walk, the leftmost on top: each lane taken or still waiting needs a
        // place of its own, so more than W at once is already too many.
        let mut stack = [0u32; 9];
        let [right, left, ..] = &mut stack;
        (*right, *left) = (node.first.checked_add(1)?, node.first);
        let mut depth = 2usize;
        while let Some(top) = depth.checked_sub(1) {
            depth = top;
            let at = *stack.get(top)?;
            let child = tree.node(at as usize)?;
            let lane = match (child.is_leaf(), self.role(at as usize)) {
                (true, OPEN) | (false, WIDE) => child,
                (false, MERGED) => {
                    merged += 1;
                    self.merged_leaf(tree, &child)?
                }
                (false, OPEN) => {
                    if len + depth + 2 > W {
                        return None;
                    }
                    *stack.get_mut(depth)? = child.first.checked_add(1)?;
                    *stack.get_mut(depth + 1)? = child.first;
                    depth += 2;
                    continue;
                }
                _ => return None,
            };
            *slots.get_mut(len)? = (at, lane);
            len += 1;
        }
        Some((len, merged))
    }
}

impl CollapseRoles<'_> {
    /// The leaf lane merged from the subtree under the inner node `node`: its box and the
    /// slots of its leaves, which must follow each other and number at most
    /// [`MERGED_LEAF_MAX`], and no node below it may have a role. `None` otherwise.
    fn merged_leaf<T: TreeArrays>(&self, tree: &T, node: &BvhNode) -> Option<BvhNode> {
        // Leaves hold a slot at least, so at most eight slots make at most seven inner nodes:
        // a valid subtree never has more than eight nodes waiting here.
        let mut stack = [0u32; 9];
        let [right, left, ..] = &mut stack;
        (*right, *left) = (node.first.checked_add(1)?, node.first);
        let mut depth = 2usize;
        // The slots covered so far, `first..end`.
        let mut covered: Option<(u32, u32)> = None;
        while let Some(top) = depth.checked_sub(1) {
            depth = top;
            let at = *stack.get(top)?;
            let child = tree.node(at as usize)?;
            if self.role(at as usize) != OPEN {
                return None;
            }
            if child.is_leaf() {
                let first = match covered {
                    None => child.first,
                    Some((first, end)) if end == child.first => first,
                    Some(_) => return None,
                };
                let end = child.first.checked_add(child.count)?;
                if end - first > MERGED_LEAF_MAX {
                    return None;
                }
                covered = Some((first, end));
            } else {
                *stack.get_mut(depth)? = child.first.checked_add(1)?;
                *stack.get_mut(depth + 1)? = child.first;
                depth += 2;
            }
        }
        let (first, end) = covered?;
        Some(BvhNode::new(node.aabb(), first, end - first))
    }
}
