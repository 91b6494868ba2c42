//! Working out every node's expansion bottom up, streamed to a sink: written into a buffer by
//! [`WindingTree::build`](super::WindingTree::build), compared with stored ones by a blob's
//! check.

use glam::Vec3;

use super::expansion::{Moments, WindingNode, leaf_moments, leaf_triangles, merged_moments};
use crate::bvh::{BvhNode, MAX_DEPTH, TreeArrays};
use crate::math::dot;
use crate::query::{LeafTriangleIds, LeafTriangles};

/// Works out the expansion of every node of `tree` over `triangles` (corners times `scale`),
/// children before parents, and hands each to `sink` with its node index, on a few KiB of
/// stack: `O(triangles × depth)`. Stops early, returning `false`, when `sink` returns `false`;
/// `true` once every node was handed over.
pub(super) fn for_each_expansion<T, S>(
    tree: &T,
    triangles: &S,
    scale: f32,
    mut sink: impl FnMut(usize, WindingNode) -> bool,
) -> bool
where
    T: TreeArrays + ?Sized,
    S: LeafTriangles + ?Sized,
{
    // Post order on fixed stacks: a node's full moments exist only until its parent merges
    // them, so at most one per level waits (the tree is at most MAX_DEPTH deep).
    let mut work = [(0u32, false); 2 * MAX_DEPTH as usize + 2];
    let mut done = [Moments::default(); MAX_DEPTH as usize + 2];
    let (mut wp, mut dp) = (usize::from(tree.node_count() > 0), 0usize);
    while wp > 0 {
        wp -= 1;
        let (index, merge) = work.get(wp).copied().unwrap_or_default();
        let Some(node) = tree.node(index as usize) else {
            continue;
        };
        let moments = if node.is_leaf() {
            leaf_moments(leaf_triangles(tree, triangles, &node, scale))
        } else if !merge {
            // Again after both children, which run left first.
            for next in [
                (index, true),
                (node.first.wrapping_add(1), false),
                (node.first, false),
            ] {
                if let Some(slot) = work.get_mut(wp) {
                    *slot = next;
                    wp += 1;
                }
            }
            continue;
        } else {
            dp = dp.saturating_sub(2);
            let child = |k: usize| done.get(k).copied().unwrap_or_default();
            let mut merged = merged_moments(&child(dp), &child(dp + 1));
            // The children's balls bound the node loosely, more so each level up; the corners
            // themselves give the radius the far test wants small.
            merged.radius = merged.radius.min(subtree_radius(
                tree,
                triangles,
                index as usize,
                scale,
                merged.centre,
            ));
            merged
        };
        if !sink(index as usize, WindingNode::of(&moments, moments.radius)) {
            return false;
        }
        if let Some(slot) = done.get_mut(dp) {
            *slot = moments;
            dp += 1;
        }
    }
    true
}

/// The largest distance from `centre` to a corner of a triangle node `index` counts (scaled by
/// `scale`), bit for bit the root of the largest squared distance over every corner.
///
/// Node boxes hold their triangles' corners unless spatial splits clipped them, so without
/// split references a branch and bound over the subtree finds the farthest corner: a subtree
/// whose box's farthest point is no farther than the best corner so far cannot hold a farther
/// one, and is skipped. The bound is exact, not padded: it rounds the box's extremes through
/// the same operations as a corner's squared distance, and each of them (a subtraction of
/// `centre`, a square, a sum of non-negative terms) never rounds a larger input to a smaller
/// result. With split references the same walk skips nothing: every corner is measured.
fn subtree_radius<T, S>(tree: &T, triangles: &S, index: usize, scale: f32, centre: Vec3) -> f32
where
    T: TreeArrays + ?Sized,
    S: LeafTriangles + ?Sized,
{
    let boxes_hold_corners = tree.split_refs().is_empty();
    let farthest_in_box = |node: &BvhNode| {
        let low = Vec3::from_array(node.min) * scale - centre;
        let high = Vec3::from_array(node.max) * scale - centre;
        let d = low.abs().max(high.abs());
        dot(d, d)
    };
    let mut farthest = 0.0f32;
    let mut stack = [0u32; MAX_DEPTH as usize + 2];
    let (mut sp, mut next) = (0usize, Some(index as u32));
    while let Some(i) = next.take().or_else(|| {
        sp = sp.checked_sub(1)?;
        stack.get(sp).copied()
    }) {
        let Some(node) = tree.node(i as usize) else {
            return f32::INFINITY;
        };
        if boxes_hold_corners && farthest_in_box(&node) <= farthest {
            continue;
        }
        if node.is_leaf() {
            let Some(ids) = tree.leaf_triangles(node.first as usize, node.count as usize) else {
                return f32::INFINITY;
            };
            farthest = farthest.max(farthest_corner(triangles, ids, scale, centre));
            continue;
        }
        let (Some(left), Some(right)) = (
            tree.node(node.first as usize),
            tree.node(node.first.wrapping_add(1) as usize),
        ) else {
            return f32::INFINITY;
        };
        // The child reaching farther first: its corners shrink the other's chance.
        let (later, first) = if farthest_in_box(&left) > farthest_in_box(&right) {
            (node.first.wrapping_add(1), node.first)
        } else {
            (node.first, node.first.wrapping_add(1))
        };
        // A walk deeper than a valid tree gives no radius: the node is never far then.
        let Some(slot) = stack.get_mut(sp) else {
            return f32::INFINITY;
        };
        *slot = later;
        sp += 1;
        next = Some(first);
    }
    libm::sqrtf(farthest)
}

/// The largest squared distance from `centre` to a corner (times `scale`) of the triangles
/// `ids` names. The largest square, then one root: the root is monotonic and correctly
/// rounded, so the callers' root is the largest root, bit for bit.
fn farthest_corner<S: LeafTriangles + ?Sized>(
    triangles: &S,
    ids: LeafTriangleIds<'_>,
    scale: f32,
    centre: Vec3,
) -> f32 {
    let mut farthest = 0.0f32;
    for (slot, tri) in ids {
        if let Some(t) = triangles.corners(slot, tri) {
            for corner in [t.a, t.b, t.c] {
                let d = corner * scale - centre;
                farthest = farthest.max(dot(d, d));
            }
        }
    }
    farthest
}

#[cfg(test)]
mod tests {
    use std::vec::Vec;

    use super::*;
    use crate::bvh::{BuildConfig, Bvh, PrimRef, node_capacity};
    use crate::mesh::MeshRef;
    use crate::test_floats::floats;

    /// The oracle: [`subtree_radius`] by measuring every corner: the triangles of a subtree fill the order
    /// slots from its leftmost leaf's first to its rightmost leaf's last.
    fn every_corner_radius<T, S>(
        tree: &T,
        triangles: &S,
        index: usize,
        scale: f32,
        centre: Vec3,
    ) -> f32
    where
        T: TreeArrays + ?Sized,
        S: LeafTriangles + ?Sized,
    {
        let leaf_at = |mut i: usize, right: bool| {
            for _ in 0..=MAX_DEPTH {
                match tree.node(i) {
                    Some(n) if n.is_leaf() => return Some(n),
                    Some(n) => i = n.first as usize + usize::from(right),
                    None => return None,
                }
            }
            None
        };
        let (Some(low), Some(high)) = (leaf_at(index, false), leaf_at(index, true)) else {
            return f32::INFINITY;
        };
        let (first, count) = (
            low.first as usize,
            high.first
                .saturating_add(high.count)
                .saturating_sub(low.first) as usize,
        );
        // Every reference counts (a triangle held twice has the same corners twice, which leaves
        // the largest alone), so no split references are looked up.
        let Some(ids) = tree.leaf_triangles(first, count) else {
            return f32::INFINITY;
        };
        libm::sqrtf(farthest_corner(triangles, ids, scale, centre))
    }

    /// The branch and bound finds the very corner the full scan does, at every inner node of
    /// trees over triangle soups of several shapes (small and long triangles, flat and spread).
    #[test]
    fn the_bounded_radius_is_every_corners_radius() {
        for (seed, count, stretch) in [(7u64, 3000, 0.02f32), (11, 500, 0.5), (13, 64, 2.0)] {
            let values = floats(seed, count * 9);
            let mut positions = Vec::new();
            for t in values.chunks_exact(9) {
                let anchor = Vec3::new(t[0], t[1] * 0.3, t[2] * 3.0) * 40.0;
                for k in 0..3 {
                    let offset = Vec3::new(t[3 + k], t[3 + (k + 1) % 6], t[3 + (k + 2) % 6]);
                    positions.push((anchor + offset * stretch * 40.0).to_array());
                }
            }
            let triangles: Vec<[u32; 3]> = (0..count as u32)
                .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
                .collect();
            let mesh = MeshRef::new(&positions, &triangles).validate().unwrap();
            let mut nodes = std::vec![BvhNode::EMPTY; node_capacity(count)];
            let mut order = std::vec![0u32; count];
            let mut scratch = std::vec![PrimRef::EMPTY; count];
            let bvh = Bvh::build(
                &mesh,
                &BuildConfig::default(),
                &mut nodes,
                &mut order,
                &mut scratch,
            )
            .unwrap();
            let scale = super::super::expansion::unit_scale(&bvh);
            let mut inner = 0;
            for index in 0..bvh.node_count() {
                let node = bvh.node(index).unwrap();
                if node.is_leaf() {
                    continue;
                }
                inner += 1;
                for centre in [node.aabb().center() * scale, Vec3::new(0.3, -0.2, 0.1)] {
                    let bounded = subtree_radius(&bvh, &mesh, index, scale, centre);
                    let full = every_corner_radius(&bvh, &mesh, index, scale, centre);
                    assert_eq!(bounded.to_bits(), full.to_bits(), "node {index}");
                }
            }
            assert!(inner > count / 8, "{inner} inner nodes");
        }
    }
}
