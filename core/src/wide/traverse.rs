//! Depth-first traversal of a four-wide BVH, nearest child first: the structure's half of
//! every query (see [`Traverse`]).

use super::{CompactNode, WideBvh, WideNode};
use crate::bvh::MAX_DEPTH;
use crate::math::Aabb4;
use crate::query::{LeafTriangleIds, Traverse, Visitor};

/// A child to visit: an inner node (`count == 0`, `child` its index) or a leaf.
#[derive(Clone, Copy)]
struct Child {
    child: u32,
    count: u32,
    key: f32,
    /// Where the child's box is: its parent node's index times four plus its lane (the box is
    /// only looked for, never needed, so an index too large for this is simply not found).
    parent_lane: u32,
}

impl Child {
    /// The root node (also a placeholder: it is never anyone's child).
    const ROOT: Self = Self {
        child: 0,
        count: 0,
        key: 0.0,
        parent_lane: u32::MAX,
    };
}

/// Deferred children. Each level defers at most three, and a wide tree is no deeper than
/// the binary tree it came from ([`MAX_DEPTH`]), so the stack never fills.
const STACK: usize = 3 * MAX_DEPTH as usize;

/// A node of four lanes as the traversal reads it: a [`WideNode`], or a [`CompactNode`]
/// whose boxes are decoded on the way.
pub(super) trait LaneNode {
    /// The four child boxes: borrowed where stored, decoded where quantized.
    type Boxes<'a>: core::ops::Deref<Target = Aabb4>
    where
        Self: 'a;
    /// The four child boxes.
    fn boxes(&self) -> Self::Boxes<'_>;
    /// Lane `lane`'s node index or first order slot (0 when unused).
    fn child(&self, lane: usize) -> u32;
    /// Lane `lane`'s triangle count (0 for an inner or unused lane).
    fn count(&self, lane: usize) -> u32;
}

impl LaneNode for WideNode {
    type Boxes<'a> = &'a Aabb4;
    #[inline(always)]
    fn boxes(&self) -> &Aabb4 {
        &self.bounds
    }
    #[inline(always)]
    fn child(&self, lane: usize) -> u32 {
        self.child.get(lane).copied().unwrap_or(0)
    }
    #[inline(always)]
    fn count(&self, lane: usize) -> u32 {
        self.count.get(lane).copied().unwrap_or(0)
    }
}

/// Boxes decoded from a [`CompactNode`], owned for the visit.
pub(super) struct Decoded(Aabb4);

impl core::ops::Deref for Decoded {
    type Target = Aabb4;
    #[inline(always)]
    fn deref(&self) -> &Aabb4 {
        &self.0
    }
}

impl LaneNode for CompactNode {
    type Boxes<'a> = Decoded;
    #[inline(always)]
    fn boxes(&self) -> Decoded {
        Decoded(CompactNode::boxes(self))
    }
    #[inline(always)]
    fn child(&self, lane: usize) -> u32 {
        CompactNode::child(self, lane)
    }
    #[inline(always)]
    fn count(&self, lane: usize) -> u32 {
        CompactNode::count(self, lane)
    }
}

impl Traverse for WideBvh<'_> {
    /// Depth first, each node's four child boxes judged at once
    /// ([`Visitor::enter_lanes`]) and visited in ascending key order (the lower lane first on
    /// equal keys), with a fixed stack and no allocation.
    #[inline(always)]
    fn traverse<V: Visitor + ?Sized>(&self, visitor: &mut V) {
        traverse_wide(self.nodes, self.order, visitor);
    }

    /// Yes: boxes are judged four at a time.
    #[inline(always)]
    fn traverse_packet<V: Visitor + ?Sized>(&self, visitor: &mut V) -> bool {
        self.traverse(visitor);
        true
    }
}

/// The walk of [`Traverse`] over four-lane nodes (root first) and their leaves' order.
#[inline(always)]
pub(super) fn traverse_wide<N: LaneNode, V: Visitor + ?Sized>(
    nodes: &[N],
    order: &[u32],
    visitor: &mut V,
) {
    // Uninitialised until pushed: zeroing kilobytes per query would cost more than a node.
    let mut stack = heapless::Vec::<Child, STACK>::new();
    let mut at = Child::ROOT;
    loop {
        if at.count > 0 {
            if let Some(tris) =
                LeafTriangleIds::in_order(order, at.child as usize, at.count as usize)
            {
                let boxed = visitor.wants_leaf_boxes();
                let (parent, lane) = (at.parent_lane >> 2, at.parent_lane & 3);
                let flow = match nodes.get(parent as usize) {
                    Some(parent) if boxed => {
                        visitor.leaf_in(&parent.boxes().lane(lane as usize), tris)
                    }
                    _ => visitor.leaf(tris),
                };
                if flow.is_break() {
                    return;
                }
            }
        } else if let Some(node) = nodes.get(at.child as usize) {
            let boxes = node.boxes();
            let (mask, keys) = visitor.enter_lanes(&boxes);
            let mask = mask & boxes.used_mask() & 0xF;
            if mask != 0 {
                let parent = at.child.checked_mul(4).unwrap_or(u32::MAX - 3);
                let lane_of = |lane: u32| -> Child {
                    let at = lane as usize;
                    Child {
                        child: node.child(at),
                        count: node.count(at),
                        key: keys.get(at).copied().unwrap_or(f32::INFINITY),
                        parent_lane: parent | lane,
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
