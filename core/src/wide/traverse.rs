//! Depth-first traversal of a four-wide BVH, nearest child first: the structure's half of
//! every query (see [`Traverse`]).

use super::WideBvh;
use crate::bvh::MAX_DEPTH;
use crate::query::{LeafTriangleIds, Traverse, Visitor};

/// A child to visit: an inner node (`count == 0`, `child` its index) or a leaf.
#[derive(Clone, Copy)]
struct Child {
    child: u32,
    count: u32,
    key: f32,
    /// The node whose lane `lane` this child is, for its box.
    parent: u32,
    lane: u32,
}

impl Child {
    /// The root node (also a placeholder: it is never anyone's child).
    const ROOT: Self = Self {
        child: 0,
        count: 0,
        key: 0.0,
        parent: 0,
        lane: 0,
    };
}

/// Deferred children. Each level defers at most three, and a wide tree is no deeper than
/// the binary tree it came from ([`MAX_DEPTH`]), so the stack never fills.
const STACK: usize = 3 * MAX_DEPTH as usize;

impl Traverse for WideBvh<'_> {
    /// Depth first, each node's four child boxes judged at once
    /// ([`Visitor::enter_lanes`]) and visited in ascending key order (the lower lane first on
    /// equal keys), with a fixed stack and no allocation.
    #[inline(always)]
    fn traverse<V: Visitor + ?Sized>(&self, visitor: &mut V) {
        traverse_wide(self, visitor);
    }

    /// Itself.
    #[inline(always)]
    fn wide_bvh(&self) -> Option<WideBvh<'_>> {
        Some(*self)
    }
}

#[inline(always)]
fn traverse_wide<V: Visitor + ?Sized>(tree: &WideBvh<'_>, visitor: &mut V) {
    // Uninitialised until pushed: zeroing kilobytes per query would cost more than a node.
    let mut stack = heapless::Vec::<Child, STACK>::new();
    let mut at = Child::ROOT;
    loop {
        if at.count > 0 {
            if let Some(tris) = leaf(tree, at.child, at.count) {
                let boxed = visitor.wants_leaf_boxes();
                let flow = match tree.nodes.get(at.parent as usize) {
                    Some(parent) if boxed => {
                        visitor.leaf_in(&parent.bounds.lane(at.lane as usize), tris)
                    }
                    _ => visitor.leaf(tris),
                };
                if flow.is_break() {
                    return;
                }
            }
        } else if let Some(node) = tree.nodes.get(at.child as usize) {
            let (mask, keys) = visitor.enter_lanes(&node.bounds);
            let mask = mask & node.bounds.used_mask() & 0xF;
            if mask != 0 {
                let parent = at.child;
                let lane_of = |lane: u32| -> Child {
                    let at = lane as usize;
                    Child {
                        child: node.child.get(at).copied().unwrap_or(0),
                        count: node.count.get(at).copied().unwrap_or(0),
                        key: keys.get(at).copied().unwrap_or(f32::INFINITY),
                        parent,
                        lane,
                    }
                };
                if mask & (mask - 1) == 0 {
                    at = lane_of(mask.trailing_zeros());
                    continue;
                }
                let (order, n) = by_key(mask, keys);
                // Farthest deferred first, so the nearer ones come off the stack first.
                for &lane in order.iter().take(n).skip(1).rev() {
                    let _ = stack.push(lane_of(lane));
                }
                at = lane_of(order[0]);
                continue;
            }
        }
        loop {
            let Some(next) = stack.pop() else {
                return;
            };
            if visitor.revisit(next.key) {
                at = next;
                break;
            }
        }
    }
}

/// The lanes of `mask`, sorted by key, ascending (lower lane first on equal keys), and how
/// many there are.
///
/// Branch free: each key becomes an integer with the same order (the usual sign-flip of the
/// float's bits), widened with its lane number below it so that equal keys order by lane, and
/// a five-exchange sorting network sorts the four. The order of the traversal is a coin toss
/// per node, so branches here would mispredict about half the time.
#[inline(always)]
fn by_key(mask: u32, keys: [f32; 4]) -> ([u32; 4], usize) {
    let sortable = |lane: u32| -> u64 {
        // `+ 0.0` turns −0 into +0, which compare equal as floats and so must tie here too.
        let key = keys.get(lane as usize).copied().unwrap_or(f32::INFINITY) + 0.0;
        let bits = key.to_bits();
        // Negative floats order backwards by their bits: flip them all; positive ones just
        // need the sign bit set to come after the negatives.
        let ordered = bits ^ ((((bits as i32) >> 31) as u32) | 0x8000_0000);
        if mask & (1 << lane) != 0 {
            (u64::from(ordered) << 2) | u64::from(lane)
        } else {
            u64::MAX
        }
    };
    let [mut a, mut b, mut c, mut d] = [sortable(0), sortable(1), sortable(2), sortable(3)];
    let exchange = |x: &mut u64, y: &mut u64| {
        let (lo, hi) = ((*x).min(*y), (*x).max(*y));
        *x = lo;
        *y = hi;
    };
    exchange(&mut a, &mut b);
    exchange(&mut c, &mut d);
    exchange(&mut a, &mut c);
    exchange(&mut b, &mut d);
    exchange(&mut b, &mut c);
    let lane = |v: u64| (v & 3) as u32;
    (
        [lane(a), lane(b), lane(c), lane(d)],
        (mask & 0xF).count_ones() as usize,
    )
}

#[inline(always)]
fn leaf<'t>(tree: &WideBvh<'t>, first: u32, count: u32) -> Option<LeafTriangleIds<'t>> {
    LeafTriangleIds::in_order(tree.order, first as usize, count as usize)
}
