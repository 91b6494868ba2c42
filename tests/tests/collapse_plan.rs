//! The collapse plan against an exhaustive search: on small random trees no collapse into
//! four- or eight-wide nodes is cheaper than the one the plan writes, with costs evaluated
//! from the written nodes (not the plan's own numbers); on the real meshes the written nodes
//! cost what the plan says and no more than the trivial collapse (one two-lane node per inner
//! binary node). Plus the plan's buffer errors.

use meshq::MeshBvh;
use meshq::advanced::{CollapsePlan, MERGED_LEAF_MAX, NODE_COST, plan_capacity};
use meshq::advanced::{PlanEntry, WideNode, WideNode8};
use meshq::bvh::{BuildConfig, Bvh};
use meshq::error::{BufferKind, BuildError};
use meshq::math::Aabb;
use meshq::mesh::MeshRef;
use meshq::wide::WideBvh;
use meshq_tests::{MESHES, load_mesh};

/// Half the surface area of `b`, in f64 from its corners.
fn half_area(b: &Aabb) -> f64 {
    let d = (b.max - b.min).as_dvec3();
    d.x * d.y + d.y * d.z + d.z * d.x
}

/// The cost of a leaf of `count` triangles in box `b`: its batches of four.
fn leaf_cost(b: &Aabb, count: u32) -> f64 {
    half_area(b) * f64::from(count.div_ceil(4))
}

/// A wide tree's cost from its nodes alone, over the root box's area: every node's box (the
/// lane that leads to it, the binary root for the root) times the node cost, plus every leaf
/// lane's cost.
fn evaluated_cost(bvh: &Bvh<'_>, lanes: &[Vec<(Aabb, u32, u32)>]) -> f64 {
    let root = bvh.nodes()[0].aabb();
    let mut cost = 0.0;
    let mut stack = vec![(0usize, root)];
    while let Some((at, aabb)) = stack.pop() {
        cost += half_area(&aabb) * f64::from(NODE_COST);
        for &(b, child, count) in &lanes[at] {
            if count > 0 {
                cost += leaf_cost(&b, count);
            } else {
                stack.push((child as usize, b));
            }
        }
    }
    cost / half_area(&root)
}

/// Each node's used lanes as `(box, child, count)`, for four- or eight-wide nodes alike.
macro_rules! lanes {
    ($nodes:expr) => {
        $nodes
            .iter()
            .map(|n| {
                (0..n.lanes())
                    .map(|l| (n.bounds.lane(l), n.child[l], n.count[l]))
                    .collect::<Vec<(Aabb, u32, u32)>>()
            })
            .collect::<Vec<_>>()
    };
}

/// The least cost of any collapse of `bvh` into nodes of `w` lanes, by enumerating every cut
/// of every subtree (exponential: small trees only), over the root box's area.
fn exhaustive_optimum(bvh: &Bvh<'_>, w: usize) -> f64 {
    let nodes = bvh.nodes();
    let mut slots = vec![0u32; nodes.len()];
    for (i, n) in nodes.iter().enumerate().rev() {
        slots[i] = if n.is_leaf() {
            n.count
        } else {
            slots[n.first as usize] + slots[n.first as usize + 1]
        };
    }
    // Every set of at most `w` nodes below or at `i` that covers its subtree once.
    fn cuts(nodes: &[meshq::advanced::BvhNode], i: usize, w: usize) -> Vec<Vec<usize>> {
        let mut all = vec![vec![i]];
        if !nodes[i].is_leaf() {
            let f = nodes[i].first as usize;
            for a in cuts(nodes, f, w) {
                for b in cuts(nodes, f + 1, w) {
                    if a.len() + b.len() <= w {
                        all.push(a.iter().chain(&b).copied().collect());
                    }
                }
            }
        }
        all
    }
    // The cheapest wide node at inner node `i` and everything below it.
    fn node_cost(nodes: &[meshq::advanced::BvhNode], slots: &[u32], i: usize, w: usize) -> f64 {
        let f = nodes[i].first as usize;
        let mut best = f64::INFINITY;
        for a in cuts(nodes, f, w) {
            for b in cuts(nodes, f + 1, w) {
                if a.len() + b.len() > w {
                    continue;
                }
                let lanes: f64 = a
                    .iter()
                    .chain(&b)
                    .map(|&c| lane_cost(nodes, slots, c, w))
                    .sum();
                best = best.min(lanes);
            }
        }
        half_area(&nodes[i].aabb()) * f64::from(NODE_COST) + best
    }
    fn lane_cost(nodes: &[meshq::advanced::BvhNode], slots: &[u32], c: usize, w: usize) -> f64 {
        let b = nodes[c].aabb();
        if nodes[c].is_leaf() {
            return leaf_cost(&b, nodes[c].count);
        }
        let inner = node_cost(nodes, slots, c, w);
        if slots[c] <= MERGED_LEAF_MAX {
            inner.min(leaf_cost(&b, slots[c]))
        } else {
            inner
        }
    }
    if nodes[0].is_leaf() {
        // A lone leaf still gets a wide node, of one lane.
        return f64::from(NODE_COST) + f64::from(nodes[0].count.div_ceil(4));
    }
    node_cost(nodes, &slots, 0, w) / half_area(&nodes[0].aabb())
}

/// A small random triangle soup of `n` triangles (xorshift, seeded).
fn soup(n: usize, seed: u64) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let mut state = seed;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32
    };
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for t in 0..n as u32 {
        let c = [next() * 4.0, next() * 4.0, next()];
        for _ in 0..3 {
            positions.push([c[0] + next(), c[1] + next(), c[2] + next() * 0.5]);
        }
        triangles.push([3 * t, 3 * t + 1, 3 * t + 2]);
    }
    (positions, triangles)
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-5 * a.abs().max(b.abs())
}

#[test]
fn no_collapse_of_a_small_tree_is_cheaper_than_the_planned_one() {
    let mut trees = 0;
    for seed in 1..=60u64 {
        let n = 2 + (seed as usize * 7) % 13;
        let (positions, triangles) = soup(n, seed.wrapping_mul(0x9E37_79B9_7F4A_7C15));
        let mesh = MeshRef::new(&positions, &triangles).validate().unwrap();
        for leaf in [1u32, 2, 4] {
            let config = BuildConfig {
                max_leaf_size: leaf,
                ..BuildConfig::default()
            };
            let owned = MeshBvh::build(&mesh, &config).unwrap();
            let bvh = owned.bvh();
            let what = format!("seed {seed}, {n} triangles, leaves of {leaf}");

            let mut entries = vec![PlanEntry::EMPTY; plan_capacity(&bvh)];
            let plan = CollapsePlan::<4>::new(&bvh, &mut entries).unwrap();
            let mut nodes = vec![WideNode::EMPTY; plan.node_count()];
            let four = WideBvh::from_plan(&plan, &mut nodes).unwrap();
            let written = evaluated_cost(&bvh, &lanes!(four.nodes()));
            let optimum = exhaustive_optimum(&bvh, 4);
            assert!(
                close(written, optimum),
                "{what}, four lanes: {written} vs {optimum}"
            );
            assert!(
                close(written, f64::from(plan.cost())),
                "{what}: the plan's own cost"
            );

            let mut entries = vec![PlanEntry::EMPTY; plan_capacity(&bvh)];
            let plan = CollapsePlan::<8>::new(&bvh, &mut entries).unwrap();
            let mut nodes = vec![WideNode8::EMPTY; plan.node_count()];
            let eight = WideBvh::<WideNode8>::from_plan(&plan, &mut nodes).unwrap();
            let written = evaluated_cost(&bvh, &lanes!(eight.nodes()));
            let optimum = exhaustive_optimum(&bvh, 8);
            assert!(
                close(written, optimum),
                "{what}, eight lanes: {written} vs {optimum}"
            );
            trees += 1;
        }
    }
    assert_eq!(trees, 180);
}

#[test]
fn the_planned_collapse_of_real_meshes_costs_what_it_says_and_beats_the_trivial_one() {
    for name in MESHES {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        let owned = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
        let bvh = owned.bvh();
        // One two-lane node per inner binary node: a valid collapse, so never cheaper.
        let trivial = bvh
            .nodes()
            .iter()
            .map(|n| {
                if n.is_leaf() {
                    leaf_cost(&n.aabb(), n.count)
                } else {
                    half_area(&n.aabb()) * f64::from(NODE_COST)
                }
            })
            .sum::<f64>()
            / half_area(&bvh.nodes()[0].aabb());

        let mut entries = vec![PlanEntry::EMPTY; plan_capacity(&bvh)];
        let plan = CollapsePlan::<8>::new(&bvh, &mut entries).unwrap();
        let mut nodes = vec![WideNode8::EMPTY; plan.node_count()];
        let eight = WideBvh::<WideNode8>::from_plan(&plan, &mut nodes).unwrap();
        let written = evaluated_cost(&bvh, &lanes!(eight.nodes()));
        assert!(close(written, f64::from(plan.cost())), "{name}: {written}");
        assert!(written < trivial, "{name}: {written} vs trivial {trivial}");
        // The owned type walks the very nodes the plan gives.
        let owned8 = owned.clone().with_eight_wide_nodes().unwrap();
        assert_eq!(
            owned8.eight_wide().unwrap().nodes(),
            eight.nodes(),
            "{name}"
        );
    }
}

#[test]
fn a_short_plan_buffer_is_an_error_and_nothing_is_written() {
    let loaded = load_mesh("spot");
    let mesh = loaded.valid();
    let owned = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
    let bvh = owned.bvh();
    let needed = plan_capacity(&bvh);
    // One entry per inner node: a binary tree of n nodes has (n − 1) / 2 of them.
    let inner = bvh.nodes().iter().filter(|n| !n.is_leaf()).count();
    assert_eq!(needed, inner);
    assert_eq!(needed, (bvh.nodes().len() - 1) / 2);
    let mut short = vec![PlanEntry::EMPTY; needed - 1];
    assert_eq!(
        CollapsePlan::<8>::new(&bvh, &mut short).unwrap_err(),
        BuildError::BufferTooSmall {
            buffer: BufferKind::CollapsePlan,
            needed,
            got: needed - 1
        }
    );
    assert!(short.iter().all(|e| *e == PlanEntry::EMPTY));
    // A roomier buffer plans the same collapse as an exact one.
    let mut exact = vec![PlanEntry::EMPTY; needed];
    let mut roomy = vec![PlanEntry::EMPTY; needed + 9];
    let (a, b) = (
        CollapsePlan::<8>::new(&bvh, &mut exact).unwrap(),
        CollapsePlan::<8>::new(&bvh, &mut roomy).unwrap(),
    );
    assert_eq!(a.node_count(), b.node_count());
    assert_eq!(a.cost().to_bits(), b.cost().to_bits());
    // Lane counts outside 2..=8 are refused.
    assert_eq!(
        CollapsePlan::<9>::new(&bvh, &mut exact).unwrap_err(),
        BuildError::InvalidConfig { field: "lanes" }
    );
}
