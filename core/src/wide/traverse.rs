//! Depth-first traversal of a four- or eight-wide BVH, nearest child first: the structure's
//! half of every query (see [`Traverse`]).

use super::{CompactNode, WideNode, WideNode8};
use crate::bvh::MAX_DEPTH;
use crate::math::{Aabb, Aabb4};
use crate::query::{LeafTriangleIds, Visitor};

/// A child to visit: an inner node (`count == 0`) or a leaf.
#[derive(Clone, Copy)]
struct Child {
    /// A leaf's first order slot: the lane's child word.
    slot: u32,
    /// An inner child's node index, computed as its parent's first child plus its lane (see
    /// [`LaneNode::first_inner`]) rather than read from its lane: the next node's address then
    /// waits only on the box test, not on a load after it.
    node: u32,
    /// A leaf's triangle count; 0 for an inner node.
    count: u32,
    key: f32,
    /// Where the child's box is: its parent node's index times the lane count plus its lane
    /// (the box is only looked for, never needed, so an index too large for this is simply
    /// not found).
    parent_lane: u32,
}

impl Child {
    /// The root node (also a placeholder: it is never anyone's child).
    const ROOT: Self = Self {
        slot: 0,
        node: 0,
        count: 0,
        key: 0.0,
        parent_lane: u32::MAX,
    };
}

/// Deferred children of a four-wide walk. Each level defers at most three, and a wide tree is
/// no deeper than the binary tree it came from ([`MAX_DEPTH`]), so the stack never fills.
pub(super) const STACK4: usize = 3 * MAX_DEPTH as usize;

/// The same for an eight-wide walk: at most seven per level.
pub(super) const STACK8: usize = 7 * MAX_DEPTH as usize;

/// A node as the traversal reads it: four lanes ([`WideNode`], or a [`CompactNode`] whose
/// boxes are decoded on the way) or eight ([`WideNode8`]). Public in a private module: the
/// sealed supertrait of [`WideNodeKind`], not nameable outside.
pub trait LaneNode {
    /// Lanes per node: 4 or 8.
    const LANES: u32;
    /// Each entered lane's key, by lane.
    type Keys: Copy + AsRef<[f32]>;
    /// The lanes `visitor` enters (bit `i` for lane `i`, unused lanes cleared) and their keys.
    fn judge<V: Visitor + ?Sized>(&self, visitor: &mut V) -> (u32, Self::Keys);
    /// Lane `lane`'s key in `keys` (+∞ past the last lane).
    #[inline(always)]
    fn key(keys: &Self::Keys, lane: u32) -> f32 {
        keys.as_ref()
            .get(lane as usize)
            .copied()
            .unwrap_or(f32::INFINITY)
    }
    /// The entered lanes in `mask` sorted by key, ascending (the lower lane first on equal
    /// keys), and how many there are.
    fn by_key(mask: u32, keys: &Self::Keys) -> ([u32; 8], usize);
    /// Lane `lane`'s box.
    fn lane_box(&self, lane: usize) -> Aabb;
    /// Lane `lane`'s node index or first order slot (0 when unused).
    fn child(&self, lane: usize) -> u32;
    /// The node index of lane 0's child when it is an inner node. A collapse puts a node's
    /// inner children in its first lanes, numbered consecutively ([`wide_node`]), so inner
    /// lane `i`'s index is this plus `i`; meaningless for a node whose lanes are all leaves,
    /// where no lane is read as inner.
    ///
    /// [`wide_node`]: super::collapse::wide_node
    #[inline(always)]
    fn first_inner(&self) -> u32 {
        self.child(0)
    }
    /// Lane `lane`'s triangle count (0 for an inner or unused lane).
    fn count(&self, lane: usize) -> u32;
    /// The union of the used lanes' boxes ([`Aabb::EMPTY`] when none is used).
    fn union(&self) -> Aabb;
    /// One word from each cache line of the node that the walk reads, combined. The value
    /// means nothing: reading it starts those lines on their way (see [`WARM_TREE_BYTES`]).
    fn touch(&self) -> u32;
}

/// The size of a wide tree's nodes, in bytes, from which every walk over it reads a node's
/// first two inner children (one word of each of their cache lines) as soon as the node is
/// reached, before the node's own boxes are tested. The answers are the same either way.
///
/// Why: such a tree lives mostly beyond the second-level cache, where waiting for a node's
/// lines is most of a walk's time, and one of those children is often the next node; its
/// lines are then on their way during the box test. In smaller trees the reads were measured
/// to cost more than they gave (`docs/benchmarks.md`).
pub const WARM_TREE_BYTES: usize = 4 << 20;

/// [`LaneNode::judge`] of a four-lane node with boxes `boxes`.
#[inline(always)]
fn judge4<V: Visitor + ?Sized>(boxes: &Aabb4, visitor: &mut V) -> (u32, [f32; 4]) {
    let (mask, keys) = visitor.enter_lanes(boxes);
    (mask & kept_lanes(visitor, boxes.used_mask()) & 0xF, keys)
}

/// The lanes a verdict of `visitor` may keep: the `used` ones, or all when the visitor never
/// enters an unused lane (the mask is then never read, and the compiler drops its loads).
#[inline(always)]
fn kept_lanes<V: Visitor + ?Sized>(visitor: &V, used: u32) -> u32 {
    if visitor.hints().empty_lanes_never_entered {
        u32::MAX
    } else {
        used
    }
}

impl LaneNode for WideNode {
    const LANES: u32 = 4;
    type Keys = [f32; 4];
    #[inline(always)]
    fn judge<V: Visitor + ?Sized>(&self, visitor: &mut V) -> (u32, [f32; 4]) {
        judge4(&self.bounds, visitor)
    }
    #[inline(always)]
    fn by_key(mask: u32, keys: &[f32; 4]) -> ([u32; 8], usize) {
        by_key4(mask, *keys)
    }
    #[inline(always)]
    fn lane_box(&self, lane: usize) -> Aabb {
        self.bounds.lane(lane)
    }
    #[inline(always)]
    fn child(&self, lane: usize) -> u32 {
        self.child.get(lane).copied().unwrap_or(0)
    }
    #[inline(always)]
    fn count(&self, lane: usize) -> u32 {
        self.count.get(lane).copied().unwrap_or(0)
    }
    #[inline(always)]
    fn union(&self) -> Aabb {
        self.bounds.union()
    }
    /// Its two lines: the first holds `min_x`, the second the child words.
    #[inline(always)]
    fn touch(&self) -> u32 {
        self.bounds.min_x[0].to_bits() ^ self.child[0]
    }
}

impl LaneNode for CompactNode {
    const LANES: u32 = 4;
    type Keys = [f32; 4];
    #[inline(always)]
    fn judge<V: Visitor + ?Sized>(&self, visitor: &mut V) -> (u32, [f32; 4]) {
        // Decoded on the way: the boxes are values, not stored ones. An unused lane decodes
        // to an inverted but finite box, which a margin can widen into an entered interval:
        // it is always masked out.
        let boxes = CompactNode::boxes(self);
        let (mask, keys) = visitor.enter_computed_lanes(&boxes);
        (mask & boxes.used_mask() & 0xF, keys)
    }
    #[inline(always)]
    fn by_key(mask: u32, keys: &[f32; 4]) -> ([u32; 8], usize) {
        by_key4(mask, *keys)
    }
    #[inline(always)]
    fn lane_box(&self, lane: usize) -> Aabb {
        CompactNode::boxes(self).lane(lane)
    }
    #[inline(always)]
    fn child(&self, lane: usize) -> u32 {
        CompactNode::child(self, lane)
    }
    #[inline(always)]
    fn count(&self, lane: usize) -> u32 {
        CompactNode::count(self, lane)
    }
    #[inline(always)]
    fn union(&self) -> Aabb {
        self.boxes().union()
    }
    /// Its one line.
    #[inline(always)]
    fn touch(&self) -> u32 {
        self.child[0]
    }
}

/// The walk of [`Traverse`] over wide nodes (root first) and their leaves' order, with a
/// stack of `STACK` deferred children (enough for the node's lane count).
#[inline(always)]
pub(super) fn traverse_wide<N: LaneNode, V: Visitor + ?Sized, const STACK: usize>(
    nodes: &[N],
    order: &[u32],
    visitor: &mut V,
) {
    // Uninitialised until pushed: zeroing kilobytes per query would cost more than a node.
    let mut stack = heapless::Vec::<Child, STACK>::new();
    // Lanes per node are a power of two: lane = parent_lane mod lanes.
    let (shift, lane_bits) = (N::LANES.trailing_zeros(), N::LANES - 1);
    let warm = nodes.len().saturating_mul(core::mem::size_of::<N>()) >= WARM_TREE_BYTES;
    let mut at = Child::ROOT;
    loop {
        if at.count > 0 {
            if let Some(tris) =
                LeafTriangleIds::in_order(order, at.slot as usize, at.count as usize)
            {
                let boxed = visitor.hints().leaf_boxes;
                let (parent, lane) = (at.parent_lane >> shift, at.parent_lane & lane_bits);
                let flow = match nodes.get(parent as usize) {
                    Some(parent) if boxed => visitor.leaf_in(&parent.lane_box(lane as usize), tris),
                    _ => visitor.leaf(tris),
                };
                if flow.is_break() {
                    return;
                }
            }
        } else if let Some(node) = nodes.get(at.node as usize) {
            // Read before the verdict, so that it is there when a lane is chosen.
            let first = node.first_inner();
            if warm {
                // The first two inner children, which are consecutive nodes; only read, their
                // values kept from the optimiser and not used. (Where the node has fewer inner
                // lanes, or none, and `first` names a leaf's slot, the reads are wasted.) One
                // child gained less on a 1.1M-triangle mesh's random rays, four cost its
                // camera rays more.
                for next in [first, first.wrapping_add(1)] {
                    if let Some(next) = nodes.get(next as usize) {
                        core::hint::black_box(next.touch());
                    }
                }
            }
            let (mask, keys) = node.judge(visitor);
            if mask != 0 {
                let parent = at
                    .node
                    .checked_mul(N::LANES)
                    .unwrap_or(u32::MAX - lane_bits);
                let lane_of = |lane: u32| -> Child {
                    // Masked, though every lane given is below the count: the compiler then
                    // knows it too, and reads the lane's fields without checking it.
                    let lane = lane & lane_bits;
                    let at = lane as usize;
                    Child {
                        slot: node.child(at),
                        node: first.wrapping_add(lane),
                        count: node.count(at),
                        key: N::key(&keys, lane),
                        parent_lane: parent | lane,
                    }
                };
                let rest = mask & (mask - 1);
                if rest == 0 {
                    at = lane_of(mask.trailing_zeros());
                    continue;
                }
                if !visitor.hints().nearest_first {
                    // Lane order: the lowest entered lane now, the others deferred.
                    let mut later = rest;
                    while later != 0 {
                        let _ = stack.push(lane_of(later.trailing_zeros()));
                        later &= later - 1;
                    }
                    at = lane_of(mask.trailing_zeros());
                    continue;
                }
                if rest & (rest - 1) == 0 {
                    // Two lanes, the commonest fork: one comparison orders them (the lower
                    // lane, `first`, goes first on equal keys, as `by_key` orders them).
                    let (first, second) = (mask.trailing_zeros(), rest.trailing_zeros());
                    let (near, far) = if N::key(&keys, second) < N::key(&keys, first) {
                        (second, first)
                    } else {
                        (first, second)
                    };
                    let _ = stack.push(lane_of(far));
                    at = lane_of(near);
                    continue;
                }
                let last = rest & (rest - 1);
                if last & (last - 1) == 0 {
                    // Three lanes: three compare-exchanges, lanes ascending so that the lower
                    // lane stays first on equal keys (a stable sort, as `by_key` orders them).
                    let mut l = [
                        mask.trailing_zeros(),
                        rest.trailing_zeros(),
                        last.trailing_zeros(),
                    ];
                    let key = |lane: u32| N::key(&keys, lane);
                    if key(l[1]) < key(l[0]) {
                        l.swap(0, 1);
                    }
                    if key(l[2]) < key(l[1]) {
                        l.swap(1, 2);
                        if key(l[1]) < key(l[0]) {
                            l.swap(0, 1);
                        }
                    }
                    let _ = stack.push(lane_of(l[2]));
                    let _ = stack.push(lane_of(l[1]));
                    at = lane_of(l[0]);
                    continue;
                }
                let (order, n) = N::by_key(mask, &keys);
                // Farthest deferred first, so the nearer ones come off the stack first. A
                // plain countdown: the iterator chain this replaces (take, skip, rev) cost
                // about twenty instructions of bookkeeping per deferred lane.
                let mut rank = n.min(order.len());
                while rank > 1 {
                    rank -= 1;
                    if let Some(&lane) = order.get(rank) {
                        let _ = stack.push(lane_of(lane));
                    }
                }
                let [nearest, ..] = order;
                at = lane_of(nearest);
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

/// `key` as an integer with the same order (the usual sign flip of the float's bits): negative
/// floats order backwards by their bits, so all their bits are flipped; positive ones need
/// only the sign bit set to come after them. `−0` is taken as `+0`, which compares equal as a
/// float and so must tie here too. Never given NaN (an entered lane's key is a number).
#[inline(always)]
fn ordered_bits(key: f32) -> u32 {
    let bits = (key + 0.0).to_bits();
    bits ^ ((((bits as i32) >> 31) as u32) | 0x8000_0000)
}

/// One exchange of a sorting network: the smaller of the two in `x`, the larger in `y`.
#[inline(always)]
fn exchange(x: &mut u64, y: &mut u64) {
    let (lo, hi) = ((*x).min(*y), (*x).max(*y));
    *x = lo;
    *y = hi;
}

/// The lanes of `mask` (four lanes), sorted by key, ascending (lower lane first on equal
/// keys), and how many there are.
///
/// Branch free: each key becomes an integer with the same order (the usual sign-flip of the
/// float's bits), widened with its lane number below it so that equal keys order by lane, and
/// a five-exchange sorting network sorts the four. The order of the traversal is a coin toss
/// per node, so branches here would mispredict about half the time.
#[inline(always)]
fn by_key4(mask: u32, keys: [f32; 4]) -> ([u32; 8], usize) {
    let sortable = |lane: u32| -> u64 {
        let ordered = ordered_bits(keys.get(lane as usize).copied().unwrap_or(f32::INFINITY));
        if mask & (1 << lane) != 0 {
            (u64::from(ordered) << 2) | u64::from(lane)
        } else {
            u64::MAX
        }
    };
    let [mut a, mut b, mut c, mut d] = [sortable(0), sortable(1), sortable(2), sortable(3)];
    exchange(&mut a, &mut b);
    exchange(&mut c, &mut d);
    exchange(&mut a, &mut c);
    exchange(&mut b, &mut d);
    exchange(&mut b, &mut c);
    let lane = |v: u64| (v & 3) as u32;
    (
        [lane(a), lane(b), lane(c), lane(d), 0, 0, 0, 0],
        (mask & 0xF).count_ones() as usize,
    )
}

impl LaneNode for WideNode8 {
    const LANES: u32 = 8;
    type Keys = [f32; 8];
    #[inline(always)]
    fn judge<V: Visitor + ?Sized>(&self, visitor: &mut V) -> (u32, [f32; 8]) {
        let (mask, keys) = visitor.enter_lanes8(&self.bounds);
        (
            mask & kept_lanes(visitor, self.bounds.used_mask()) & 0xFF,
            keys,
        )
    }
    #[inline(always)]
    fn by_key(mask: u32, keys: &[f32; 8]) -> ([u32; 8], usize) {
        // A ray enters one to three lanes (an insertion sort is cheapest); a closest-point
        // query often more, where the insertion sort's mispredicted branches cost most. Then,
        // where counting bits is one instruction (x86 with `popcnt`, WebAssembly), ranking the
        // lanes is quickest; else (baseline x86-64 counts bits in ten) a sorting network.
        if (mask & 0xFF).count_ones() <= 3 {
            by_key8(mask, keys)
        } else if cfg!(any(target_feature = "popcnt", target_arch = "wasm32")) {
            by_rank8(mask, keys)
        } else {
            by_network8(mask, keys)
        }
    }
    #[inline(always)]
    fn lane_box(&self, lane: usize) -> Aabb {
        self.bounds.lane(lane)
    }
    #[inline(always)]
    fn child(&self, lane: usize) -> u32 {
        self.child.get(lane).copied().unwrap_or(0)
    }
    #[inline(always)]
    fn count(&self, lane: usize) -> u32 {
        self.count.get(lane).copied().unwrap_or(0)
    }
    /// Its four lines: 64 bytes apart, two planes of eight lanes to a line, then the child
    #[inline(always)]
    fn union(&self) -> Aabb {
        (0..self.lanes()).fold(Aabb::EMPTY, |b, lane| b.union(self.bounds.lane(lane)))
    }
    /// words.
    #[inline(always)]
    fn touch(&self) -> u32 {
        let b = &self.bounds;
        b.min_x[0].to_bits() ^ b.min_z[0].to_bits() ^ b.max_y[0].to_bits() ^ self.child[0]
    }
}

/// The lanes of `mask` sorted by key, ascending (the lower lane first on equal keys), and how
/// many there are.
///
/// Each key becomes an integer with the same order (the sign-flip of the float's bits) with
/// its lane below it, and an insertion sort places them: a ray enters one to three of a
/// node's lanes, so the few branches beat a branch-free network of 19 exchanges over all
/// eight.
#[inline(always)]
fn by_key8(mut mask: u32, keys: &[f32; 8]) -> ([u32; 8], usize) {
    let mut sorted = [u64::MAX; 8];
    let mut n = 0usize;
    while mask != 0 {
        let lane = mask.trailing_zeros();
        mask &= mask - 1;
        let ordered = ordered_bits(keys.get(lane as usize).copied().unwrap_or(f32::INFINITY));
        let entry = (u64::from(ordered) << 3) | u64::from(lane);
        let mut at = n;
        while let Some(&before) = at.checked_sub(1).and_then(|i| sorted.get(i)) {
            if before <= entry {
                break;
            }
            if let Some(slot) = sorted.get_mut(at) {
                *slot = before;
            }
            at -= 1;
        }
        if let Some(slot) = sorted.get_mut(at) {
            *slot = entry;
        }
        n += 1;
    }
    (
        core::array::from_fn(|i| sorted.get(i).map_or(0, |&v| (v & 7) as u32)),
        n,
    )
}

/// [`by_key8`] for many entered lanes, without branches on the keys: each entered lane's place
/// is the number of entered lanes before it (a smaller key, or an equal key in a lower lane),
/// counted with two eight-lane compares. Entered lanes' keys are never NaN, and `−0` and `+0`
/// compare equal, as the tie rule wants.
#[inline(always)]
fn by_rank8(mask: u32, keys: &[f32; 8]) -> ([u32; 8], usize) {
    let all = wide::f32x8::new(*keys);
    let mut lanes = [0u32; 8];
    let mut left = mask & 0xFF;
    while left != 0 {
        let lane = left.trailing_zeros();
        left &= left - 1;
        let key = wide::f32x8::splat(keys.get(lane as usize).copied().unwrap_or(f32::INFINITY));
        let lower_lanes = (1u32 << lane) - 1;
        let before =
            (all.simd_lt(key).to_bitmask() | (all.simd_eq(key).to_bitmask() & lower_lanes)) & mask;
        if let Some(slot) = lanes.get_mut(before.count_ones() as usize) {
            *slot = lane;
        }
    }
    (lanes, (mask & 0xFF).count_ones() as usize)
}

/// [`by_key8`] for many entered lanes, without branches: [`by_key4`]'s sortable integers (an
/// unentered lane's is the largest, so it sorts last), put in order by a 19-exchange sorting
/// network of depth 6. Its work is fixed, where [`by_rank8`] counts bits once per entered lane
/// and mispredicts its loop's exit (a point query enters four to eight lanes at random).
#[inline(always)]
fn by_network8(mask: u32, keys: &[f32; 8]) -> ([u32; 8], usize) {
    let v: [u64; 8] = core::array::from_fn(|lane| {
        let ordered = ordered_bits(keys.get(lane).copied().unwrap_or(f32::INFINITY));
        if mask & (1 << lane) != 0 {
            (u64::from(ordered) << 3) | lane as u64
        } else {
            u64::MAX
        }
    });
    // Named values, not an indexed loop: the compiler kept the loop (nineteen rounds of loads,
    // bounds checks and stores), where the exchanges on values stay in registers.
    let [
        mut v0,
        mut v1,
        mut v2,
        mut v3,
        mut v4,
        mut v5,
        mut v6,
        mut v7,
    ] = v;
    exchange(&mut v0, &mut v2);
    exchange(&mut v1, &mut v3);
    exchange(&mut v4, &mut v6);
    exchange(&mut v5, &mut v7);
    exchange(&mut v0, &mut v4);
    exchange(&mut v1, &mut v5);
    exchange(&mut v2, &mut v6);
    exchange(&mut v3, &mut v7);
    exchange(&mut v0, &mut v1);
    exchange(&mut v2, &mut v3);
    exchange(&mut v4, &mut v5);
    exchange(&mut v6, &mut v7);
    exchange(&mut v2, &mut v4);
    exchange(&mut v3, &mut v5);
    exchange(&mut v1, &mut v4);
    exchange(&mut v3, &mut v6);
    exchange(&mut v1, &mut v2);
    exchange(&mut v3, &mut v4);
    exchange(&mut v5, &mut v6);
    (
        [v0, v1, v2, v3, v4, v5, v6, v7].map(|entry| (entry & 7) as u32),
        (mask & 0xFF).count_ones() as usize,
    )
}

#[cfg(test)]
mod lane_order_tests {
    use super::{by_key8, by_network8, by_rank8};

    /// Every way of ordering a node's lanes gives the insertion sort's order: ascending keys,
    /// the lower lane first on equal keys (−0 equal to +0), over every mask of eight lanes and
    /// keys drawn from a few values so that ties are common.
    #[test]
    fn lane_orders_agree() {
        let values = [0.0f32, -0.0, 1.0, 1.5, 2.0, f32::INFINITY, 1e-30, 3.0];
        let mut state = 0x9E37_79B9_u32;
        for round in 0..2000 {
            let keys: [f32; 8] = core::array::from_fn(|_| {
                state ^= state << 13;
                state ^= state >> 17;
                state ^= state << 5;
                values[(state % values.len() as u32) as usize]
            });
            let mask = if round < 256 { round } else { state & 0xFF };
            let (want, n) = by_key8(mask, &keys);
            for (name, (got, m)) in [
                ("network", by_network8(mask, &keys)),
                ("rank", by_rank8(mask, &keys)),
            ] {
                assert_eq!(m, n, "{name}, mask {mask:#x}");
                assert_eq!(got[..n], want[..n], "{name}, mask {mask:#x}, keys {keys:?}");
            }
        }
    }
}
