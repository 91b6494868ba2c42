//! Proof that a cell structure read from outside answers as a fresh build of its mesh: every
//! cell a triangle touches lists it.
//!
//! A query only meets a triangle through the cells that list it, so a structure whose cells
//! miss a triangle they touch answers wrongly, however sound its nodes. The builders hand a
//! triangle to every child cell it touches ([`ReferencePad::touches`]), starting from the root,
//! which holds them all; the check walks each triangle down the same way and looks it up in
//! every cell it reaches. Extra references (a cell listing a triangle it does not touch) cost
//! time, never an answer, and are not refused.

use super::{CellNode, CellTree, ReferencePad, Words};
use crate::math::Triangle;

/// Whether references `first..end` of `items`, in ascending order as builds write them, hold
/// `tri` (a binary search: a range out of order may be judged not to).
pub(crate) fn lists<W: Words>(items: W, first: usize, end: usize, tri: u32) -> bool {
    let (mut lo, mut hi) = (first, end);
    while lo < hi {
        let mid = lo + (hi - lo) / 2;
        match items.word(mid) {
            Some(w) if w == tri => return true,
            Some(w) if w < tri => lo = mid + 1,
            Some(_) => hi = mid,
            None => return false,
        }
    }
    false
}

/// The first triangle of `0..triangles` that reaches a leaf of `tree` not listing it, walked
/// down from the root into the children whose cells it touches (padded by `pad`);
/// `triangle(i)` gives triangle `i`'s corners (`None` is treated as missing: reported).
/// `STACK` bounds the deferred children as in [`for_each_cell`](super::for_each_cell).
pub(crate) fn first_unlisted_in_tree<T, W, const STACK: usize>(
    tree: &T,
    items: W,
    pad: ReferencePad,
    triangles: usize,
    triangle: impl Fn(u32) -> Option<Triangle>,
) -> Option<u32>
where
    T: CellTree + ?Sized,
    W: Words,
{
    // One stack for every triangle's walk: filling a fresh one per triangle cost more than
    // the walk on small trees.
    let mut stack = [(0u32, tree.root_cell(), 0u32); STACK];
    (0..u32::try_from(triangles).unwrap_or(u32::MAX)).find(|&tri| {
        let Some(t) = triangle(tri) else {
            return true;
        };
        let bounds = t.bounds();
        let Some(root) = stack.first_mut() else {
            return true;
        };
        *root = (0, tree.root_cell(), 0);
        let mut top = 1usize;
        while let Some((node, cell, depth)) = top.checked_sub(1).and_then(|i| stack.get(i).copied())
        {
            top -= 1;
            match tree.cell_node(node) {
                Some(CellNode::Leaf { first, count }) => {
                    let (first, end) = (first as usize, first as usize + count as usize);
                    if !lists(items, first, end, tri) {
                        return true;
                    }
                }
                Some(CellNode::Inner) => tree.children(node, &cell, depth, |child, c| {
                    // Boxes apart rule a child out before the exact test: most children of a
                    // cell hold none of a small triangle.
                    if pad.grow(c.aabb()).overlaps(&bounds)
                        && pad.touches(&t, c.aabb())
                        && let Some(slot) = stack.get_mut(top)
                    {
                        *slot = (child, c, depth + 1);
                        top += 1;
                    }
                }),
                None => return true,
            }
        }
        false
    })
}
