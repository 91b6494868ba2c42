//! Walking an octree: at each cell, its eight octants judged four at a time and taken nearest
//! first.

use super::split::octants;
use super::tree::STACK;
use super::{Octree, OctreeConfig};
use crate::cells::{Offer, Words};
use crate::math::Aabb4;
use crate::query::{Cell, Traverse, Visitor};

impl<N: Words, W: Words> Traverse for Octree<N, W> {
    fn traverse<V: Visitor + ?Sized>(&self, visitor: &mut V) {
        let root = Cell::root(self.root);
        let Some(key) = visitor.enter(root.aabb()) else {
            return;
        };
        let mut offer = Offer::new(visitor);
        let mut stack = [(0u32, 0.0f32, root, 0u32); STACK];
        let mut top = 0usize;
        let mut current = Some((0u32, key, root, 0u32));
        loop {
            let Some((node, key, cell, depth)) = current.take().or_else(|| {
                top = top.checked_sub(1)?;
                stack.get(top).copied()
            }) else {
                return;
            };
            // Deferred cells are nearest first among siblings, not across levels: skip, do not
            // stop.
            if !visitor.revisit(key) {
                continue;
            }
            let Some(n) = self.node(node as usize) else {
                continue;
            };
            let Some(first) = n.first_child() else {
                if let Some(ids) = self.items.ids(n.a as usize, n.b as usize)
                    && offer.cell(visitor, ids, Some(cell)).is_break()
                {
                    return;
                }
                continue;
            };
            if depth >= OctreeConfig::MAX_DEPTH {
                continue;
            }
            let children = octants(&cell);
            let mut entered = [(0u32, f32::INFINITY); 8];
            let mut count = 0usize;
            for half in 0..2 {
                let mut boxes = Aabb4::EMPTY;
                for lane in 0..4 {
                    if let Some(c) = children.get(half * 4 + lane) {
                        boxes.set_lane(lane, c.aabb());
                    }
                }
                let (mask, keys) = visitor.enter_computed_lanes(&boxes);
                for (lane, &k) in keys.iter().enumerate() {
                    if mask & (1 << lane) != 0
                        && let Some(slot) = entered.get_mut(count)
                    {
                        *slot = ((half * 4 + lane) as u32, k);
                        count += 1;
                    }
                }
            }
            let entered = entered.get_mut(..count).unwrap_or_default();
            // Nearest first; equal keys keep octant order (insertion sort is stable).
            for i in 1..entered.len() {
                let mut j = i;
                while j > 0 {
                    let (Some(&a), Some(&b)) = (entered.get(j - 1), entered.get(j)) else {
                        break;
                    };
                    if b.1 < a.1 {
                        entered.swap(j - 1, j);
                        j -= 1;
                    } else {
                        break;
                    }
                }
            }
            let Some((&(nearest, nearest_key), rest)) = entered.split_first() else {
                continue;
            };
            for &(k, key) in rest.iter().rev() {
                if let (Some(slot), Some(&c)) = (stack.get_mut(top), children.get(k as usize)) {
                    *slot = (first + k, key, c, depth + 1);
                    top += 1;
                }
            }
            if let Some(&c) = children.get(nearest as usize) {
                current = Some((first + nearest, nearest_key, c, depth + 1));
            }
        }
    }
}
