use core::ops::ControlFlow;

use super::{Bvh, BvhNode, MAX_DEPTH};

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

    /// Visits a leaf: its triangles' mesh indices `tris`, which occupy order slots
    /// `first_slot..first_slot + tris.len()` (the slots index [`PackedTriangles`]).
    /// `Break` ends the traversal.
    ///
    /// [`PackedTriangles`]: super::PackedTriangles
    fn leaf(&mut self, first_slot: usize, tris: &[u32]) -> ControlFlow<()>;
}

impl Bvh<'_> {
    /// Runs `visitor` over the tree: depth first, nearer child (smaller key) first, with a
    /// fixed stack of [`MAX_DEPTH`] entries on the call stack and no allocation.
    pub fn traverse<V: BvhVisitor>(&self, visitor: &mut V) {
        let Some(root) = self.nodes.first() else {
            return;
        };
        if visitor.enter(root).is_none() {
            return;
        }
        let mut stack = [(0u32, 0.0f32); MAX_DEPTH as usize];
        let mut sp = 0usize;
        let mut current = 0u32;
        loop {
            let Some(node) = self.nodes.get(current as usize) else {
                return;
            };
            if node.is_leaf() {
                let first = node.first as usize;
                if let Some(tris) = self.order.get(first..first + node.count as usize)
                    && visitor.leaf(first, tris).is_break()
                {
                    return;
                }
            } else {
                let l = node.first;
                let r = l.wrapping_add(1);
                let first = l as usize;
                let Some([left, right]) = self
                    .nodes
                    .get(first..first.wrapping_add(2))
                    .and_then(|pair| <&[BvhNode; 2]>::try_from(pair).ok())
                else {
                    return;
                };
                match (visitor.enter(left), visitor.enter(right)) {
                    (Some(kl), Some(kr)) => {
                        let (near, far, far_key) = if kr < kl { (r, l, kl) } else { (l, r, kr) };
                        // A validated tree is at most MAX_DEPTH deep and holds at most one
                        // deferred node per level, so the slot always exists.
                        if let Some(slot) = stack.get_mut(sp) {
                            *slot = (far, far_key);
                            sp += 1;
                        }
                        current = near;
                        continue;
                    }
                    (Some(_), None) => {
                        current = l;
                        continue;
                    }
                    (None, Some(_)) => {
                        current = r;
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
                let Some(&(node, key)) = stack.get(sp) else {
                    return;
                };
                if visitor.revisit(key) {
                    current = node;
                    break;
                }
            }
        }
    }
}
