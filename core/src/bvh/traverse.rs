use core::ops::ControlFlow;

use super::wide::traverse::LaneVisitor;
use super::{Bvh, BvhNode, LeafTriangleIds, MAX_DEPTH, TreeArrays};

/// A query over a BVH, driven by [`Bvh::traverse`]: the tree supplies boxes and triangle
/// indices, the visitor decides where to go and does the triangle work.
///
/// Every built-in query (closest hit, any hit, closest point, box and sphere overlap) is such a
/// visitor; write your own for anything else.
pub trait BvhVisitor {
    /// Whether to enter `node`: `None` skips it and its subtree, `Some(key)` enters it. Of two
    /// children entered, the one with the smaller key is visited first (the left one on
    /// equal keys), the other is deferred with its key.
    fn enter(&mut self, node: &BvhNode) -> Option<f32>;

    /// Whether a deferred node is still worth visiting when it comes off the stack, given the
    /// key [`enter`](Self::enter) returned for it (for example, skip it when a closer hit has
    /// been found since). The default visits it.
    fn revisit(&self, key: f32) -> bool {
        let _ = key;
        true
    }

    /// Visits a leaf: its triangles as `(order slot, mesh triangle index)` pairs (the slots
    /// index [`PackedTriangles`]). `Break` ends the traversal.
    ///
    /// [`PackedTriangles`]: super::PackedTriangles
    fn leaf(&mut self, tris: LeafTriangleIds<'_>) -> ControlFlow<()>;
}

/// A tree the built-in queries can walk: binary arrays (in slices or a blob) or a
/// [`WideBvh`](super::WideBvh). One query visitor serves both.
pub(crate) trait Walk {
    /// Runs `visitor` over the tree, nearer children first.
    fn walk<V: LaneVisitor>(&self, visitor: &mut V);
}

impl<A: TreeArrays + ?Sized> Walk for A {
    #[inline(always)]
    fn walk<V: LaneVisitor>(&self, visitor: &mut V) {
        traverse(self, visitor);
    }
}

impl Bvh<'_> {
    /// Runs `visitor` over the tree: depth first, nearer child (smaller key) first, with a
    /// fixed stack of [`MAX_DEPTH`] entries on the call stack and no allocation.
    pub fn traverse<V: BvhVisitor>(&self, visitor: &mut V) {
        traverse(self, visitor);
    }
}

/// [`Bvh::traverse`] over any storage. A validated tree is at most [`MAX_DEPTH`] deep, so the
/// stack never fills; on anything else (which validation rules out) the walk just stops.
#[inline(always)]
pub(crate) fn traverse<A: TreeArrays + ?Sized, V: BvhVisitor>(tree: &A, visitor: &mut V) {
    let Some(root) = tree.node(0) else {
        return;
    };
    if visitor.enter(&root).is_none() {
        return;
    }
    let mut stack = [(0u32, 0.0f32); MAX_DEPTH as usize];
    let mut sp = 0usize;
    let mut node = root;
    loop {
        if node.is_leaf() {
            if let Some(tris) = tree.leaf_triangles(node.first as usize, node.count as usize)
                && visitor.leaf(tris).is_break()
            {
                return;
            }
        } else {
            let l = node.first;
            let Some([left, right]) = tree.node_pair(l as usize) else {
                return;
            };
            match (visitor.enter(&left), visitor.enter(&right)) {
                (Some(kl), Some(kr)) => {
                    let (near, far, far_key) = if kr < kl {
                        (right, l, kl)
                    } else {
                        (left, l.wrapping_add(1), kr)
                    };
                    // At most one deferred node per level: the slot always exists.
                    if let Some(slot) = stack.get_mut(sp) {
                        *slot = (far, far_key);
                        sp += 1;
                    }
                    node = near;
                    continue;
                }
                (Some(_), None) => {
                    node = left;
                    continue;
                }
                (None, Some(_)) => {
                    node = right;
                    continue;
                }
                (None, None) => {}
            }
        }
        loop {
            if sp == 0 {
                return;
            }
            sp -= 1;
            let Some(&(index, key)) = stack.get(sp) else {
                return;
            };
            if visitor.revisit(key) {
                let Some(next) = tree.node(index as usize) else {
                    return;
                };
                node = next;
                break;
            }
        }
    }
}
