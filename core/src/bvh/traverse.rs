//! Depth-first traversal of a binary BVH, nearer child first: the structure's half of every
//! query (see [`Traverse`]).

use super::{MAX_DEPTH, TreeArrays};
use crate::query::{Traverse, Visitor};

/// Every binary tree — a [`Bvh`](super::Bvh) in slices, a blob's tree read in place, any
/// [`TreeArrays`] storage — walks the same way, so it answers every query with the same
/// bits.
impl<A: TreeArrays + ?Sized> Traverse for A {
    /// Depth first, the child with the smaller key first (the left one on equal keys), the
    /// other deferred with its key on a fixed stack of [`MAX_DEPTH`] entries; no allocation.
    #[inline(always)]
    fn traverse<V: Visitor + ?Sized>(&self, visitor: &mut V) {
        traverse(self, visitor);
    }

    #[inline(always)]
    fn split_refs(&self) -> crate::query::SplitRefs<'_> {
        TreeArrays::split_refs(self)
    }
}

/// A validated tree is at most [`MAX_DEPTH`] deep, so the stack never fills; on anything else
/// (which validation rules out) the walk just stops.
#[inline(always)]
fn traverse<A: TreeArrays + ?Sized, V: Visitor + ?Sized>(tree: &A, visitor: &mut V) {
    let Some(root) = tree.node(0) else {
        return;
    };
    if visitor.enter(&root.aabb()).is_none() {
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
            match (visitor.enter(&left.aabb()), visitor.enter(&right.aabb())) {
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
