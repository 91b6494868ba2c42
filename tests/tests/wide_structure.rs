//! The four-wide BVH: its structure checked against the binary tree it was collapsed from
//! (every slot in exactly one leaf lane, each lane a binary subtree; boxes nested; children
//! after parents), its buffer and
//! validation errors, and its answers on the awkward meshes (one triangle, coincident
//! centroids, degenerate triangles, tiny and huge coordinates) against brute force.

use std::collections::BTreeMap;

use glam::Vec3;
use meshq::MeshBvh;
use meshq::advanced::{CollapsePlan, MERGED_LEAF_MAX, plan_capacity};
use meshq::advanced::{CompactNode, PlanEntry, WideNode, WideNode8};
use meshq::bvh::{BuildConfig, Bvh};
use meshq::error::{BufferKind, BuildError, StructureError};
use meshq::math::{Aabb, Ray};
use meshq::mesh::MeshRef;
use meshq::wide::WideBvh;
use meshq::{MeshQuery, Traverse};
use meshq_tests::oracle::BruteForce;
use meshq_tests::{MESHES, checked_bvh, load_mesh, workload};

/// Every binary node's slot range `(first, count)`, mapped to its box bits and whether it is a
/// leaf (children follow parents, so a reverse walk meets children first).
fn subtree_ranges(bvh: &Bvh<'_>) -> BTreeMap<(u32, u32), ([u32; 6], bool)> {
    let nodes = bvh.nodes();
    let mut range = vec![(0u32, 0u32); nodes.len()];
    for (i, n) in nodes.iter().enumerate().rev() {
        range[i] = if n.is_leaf() {
            (n.first, n.count)
        } else {
            let (l, r) = (range[n.first as usize], range[n.first as usize + 1]);
            assert_eq!(l.0 + l.1, r.0, "binary subtrees hold consecutive slots");
            (l.0, l.1 + r.1)
        };
    }
    nodes
        .iter()
        .zip(range)
        .map(|(n, r)| (r, (boxes_bits(&n.aabb()), n.is_leaf())))
        .collect()
}

fn boxes_bits(b: &Aabb) -> [u32; 6] {
    [b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z].map(f32::to_bits)
}

/// Checks `wide` against `bvh` from first principles, returning the wide depth.
fn check_against_binary(bvh: &Bvh<'_>, wide: &WideBvh<'_>, what: &str) -> usize {
    let nodes = wide.nodes();
    // Every binary subtree by its slot range, with its box and whether it is a leaf: a leaf
    // lane is one of them (a binary leaf, or a small subtree merged into one leaf).
    let subtrees = subtree_ranges(bvh);
    let mut covered: Vec<(u32, u32)> = Vec::new();
    let binary_boxes: Vec<[u32; 6]> = bvh.nodes().iter().map(|n| boxes_bits(&n.aabb())).collect();
    let mut referenced = vec![0usize; nodes.len()];
    let mut depth = vec![0usize; nodes.len()];
    if let Some(d) = depth.first_mut() {
        *d = 1;
    }
    for (index, node) in nodes.iter().enumerate() {
        let lanes = node.lanes();
        let single_leaf = bvh.nodes().len() == 1;
        assert!(
            (if single_leaf { 1..=1 } else { 2..=4 }).contains(&lanes),
            "{what}: node {index} has {lanes} lanes"
        );
        // The walk computes inner lane `l`'s node as lane 0's plus `l`: inner lanes first,
        // their nodes consecutive.
        let inner = node.count[..lanes].iter().take_while(|&&n| n == 0).count();
        assert!(
            node.count[inner..lanes].iter().all(|&n| n > 0),
            "{what}: node {index} has a leaf lane before an inner one"
        );
        for l in 0..inner {
            assert_eq!(
                node.child[l],
                node.child[0] + l as u32,
                "{what}: node {index}"
            );
        }
        for lane in lanes..4 {
            let unused = node.bounds.lane(lane);
            assert!(unused.min.x == f32::INFINITY && unused.max.x == f32::NEG_INFINITY);
            assert_eq!((node.child[lane], node.count[lane]), (0, 0), "{what}");
        }
        for lane in 0..lanes {
            let b = node.bounds.lane(lane);
            // Every lane box is one of the binary tree's boxes, bit for bit.
            assert!(
                binary_boxes.contains(&boxes_bits(&b)),
                "{what}: node {index} lane {lane}"
            );
            let (child, count) = (node.child[lane], node.count[lane]);
            if count > 0 {
                let subtree = subtrees.get(&(child, count));
                assert!(
                    subtree.is_some_and(|&(bits, _)| bits == boxes_bits(&b)),
                    "{what}: leaf lane ({child}, {count}) of node {index} is no binary subtree"
                );
                if subtree.is_some_and(|&(_, is_leaf)| !is_leaf) {
                    assert!(count <= MERGED_LEAF_MAX, "{what}: merged leaf of {count}");
                }
                covered.push((child, count));
            } else {
                let c = child as usize;
                assert!(
                    c > index && c < nodes.len(),
                    "{what}: node {index} child {c}"
                );
                referenced[c] += 1;
                depth[c] = depth[index] + 1;
                let inner = &nodes[c];
                for l in 0..inner.lanes() {
                    let cb = inner.bounds.lane(l);
                    assert!(
                        b.contains_aabb(&cb),
                        "{what}: node {c} lane {l} is outside its parent lane"
                    );
                }
            }
        }
    }
    // The leaf lanes hold every slot exactly once.
    covered.sort_unstable();
    let mut next = 0;
    for &(first, count) in &covered {
        assert_eq!(
            first, next,
            "{what}: slots {next}..{first} missing or repeated"
        );
        next = first + count;
    }
    assert_eq!(
        next as usize,
        bvh.order().len(),
        "{what}: trailing slots missing"
    );
    assert!(
        referenced.iter().skip(1).all(|&r| r == 1),
        "{what}: every non-root wide node is some lane's child exactly once"
    );
    let wide_depth = depth.iter().copied().max().unwrap_or(0);
    assert!(wide_depth <= bvh.depth() as usize, "{what}");
    wide_depth
}

#[test]
fn wide_trees_hold_every_binary_leaf_once_under_nested_boxes() {
    let configs = [
        ("default", BuildConfig::default()),
        ("fast", BuildConfig::fast()),
        ("high_quality", BuildConfig::high_quality()),
        (
            "leaf 1",
            BuildConfig {
                max_leaf_size: 1,
                ..BuildConfig::default()
            },
        ),
    ];
    for name in MESHES {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        for (label, config) in &configs {
            let owned = MeshBvh::build(&mesh, config).unwrap();
            let bvh = checked_bvh(&owned, &mesh).unwrap();
            let mut entries = vec![PlanEntry::EMPTY; plan_capacity(&bvh)];
            let plan = CollapsePlan::<4>::new(&bvh, &mut entries).unwrap();
            let count = plan.node_count();
            assert!(count <= WideBvh::<WideNode>::measure(&bvh).nodes);
            // Exactly sized and bound-sized buffers give the same nodes.
            let mut exact = vec![WideNode::EMPTY; count];
            let wide = WideBvh::from_plan(&plan, &mut exact).unwrap();
            assert_eq!(wide.nodes().len(), count);
            let what = format!("{name} {label}");
            let depth = check_against_binary(&bvh, &wide, &what);
            let inner = bvh.nodes().iter().filter(|n| !n.is_leaf()).count();
            // Four-wide nodes take about two binary levels at a time.
            assert!(
                count * 2 <= inner + inner / 4 + 1,
                "{what}: {count} of {inner}"
            );
            assert!(depth < bvh.depth() as usize, "{what}: depth {depth}");
            let mut roomy = vec![WideNode::EMPTY; WideBvh::<WideNode>::measure(&bvh).nodes];
            let again = WideBvh::from_plan(&plan, &mut roomy).unwrap();
            assert!(
                again
                    .nodes()
                    .iter()
                    .zip(wide.nodes())
                    .all(|(a, b)| a.same_bits(b))
            );
        }
    }
}

#[test]
fn a_short_buffer_is_an_error_and_nothing_is_written() {
    let loaded = load_mesh("spot");
    let mesh = loaded.valid();
    let owned = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
    let bvh = checked_bvh(&owned, &mesh).unwrap();
    let mut entries = vec![PlanEntry::EMPTY; plan_capacity(&bvh)];
    let plan = CollapsePlan::<4>::new(&bvh, &mut entries).unwrap();
    let needed = plan.node_count();
    let mut short = vec![WideNode::EMPTY; needed - 1];
    assert_eq!(
        WideBvh::from_plan(&plan, &mut short).unwrap_err(),
        BuildError::BufferTooSmall {
            buffer: BufferKind::WideNodes,
            needed,
            got: needed - 1
        }
    );
    assert!(short.iter().all(|n| n.same_bits(&WideNode::EMPTY)));
}

#[test]
fn wide_view_accepts_exactly_the_widened_nodes() {
    let loaded = load_mesh("cow");
    let mesh = loaded.valid();
    let owned = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
    let bvh = checked_bvh(&owned, &mesh).unwrap();
    let mut entries = vec![PlanEntry::EMPTY; plan_capacity(&bvh)];
    let plan = CollapsePlan::<4>::new(&bvh, &mut entries).unwrap();
    let mut nodes = vec![WideNode::EMPTY; plan.node_count()];
    WideBvh::from_plan(&plan, &mut nodes).unwrap();
    let kept = nodes.clone();
    let view = WideBvh::from_parts(&plan, &kept).unwrap();
    let ray = workload::random_rays(&loaded.positions, 1, 3)[0];
    assert_eq!(
        view.with(&mesh).raycast(&ray),
        bvh.with(&mesh).raycast(&ray)
    );

    let mismatch = |node| Err(StructureError::WideNodeMismatch { node });
    let mut shrunk = kept.clone();
    shrunk[7].bounds.max_y[1] = f32::from_bits(shrunk[7].bounds.max_y[1].to_bits() - 1);
    assert_eq!(WideBvh::from_parts(&plan, &shrunk).map(|_| ()), mismatch(7));
    // A lane pointing back at the root would loop forever: refused.
    let mut cycle = kept.clone();
    let (at, lane) = (0..cycle.len())
        .rev()
        .find_map(|i| {
            (0..cycle[i].lanes())
                .find(|&l| cycle[i].count[l] == 0)
                .map(|l| (i, l))
        })
        .unwrap();
    cycle[at].child[lane] = 0;
    assert_eq!(
        WideBvh::from_parts(&plan, &cycle).map(|_| ()),
        mismatch(at as u32)
    );
    let last = kept.len() - 1;
    assert_eq!(
        WideBvh::from_parts(&plan, &kept[..last]).map(|_| ()),
        mismatch(last as u32)
    );
    // The untrimmed buffer a widening was given is accepted: the view covers the nodes
    // widening wrote, whatever follows them.
    let mut longer = kept.clone();
    longer.push(WideNode::EMPTY);
    longer.push(kept[0]);
    let roomy = WideBvh::from_parts(&plan, &longer).unwrap();
    assert_eq!(roomy.nodes().len(), kept.len());
    assert_eq!(
        roomy.with(&mesh).raycast(&ray),
        bvh.with(&mesh).raycast(&ray)
    );
}

#[test]
fn empty_and_single_triangle_trees() {
    let empty = MeshRef::new(&[], &[]).validate().unwrap();
    let owned = MeshBvh::build(&empty, &BuildConfig::default()).unwrap();
    let bvh = checked_bvh(&owned, &empty).unwrap();
    let mut entries = vec![PlanEntry::EMPTY; plan_capacity(&bvh)];
    let plan = CollapsePlan::<4>::new(&bvh, &mut entries).unwrap();
    assert_eq!(plan.node_count(), 0);
    let mut none: [WideNode; 0] = [];
    let wide = WideBvh::from_plan(&plan, &mut none).unwrap();
    assert!(wide.is_empty() && wide.bounds() == Aabb::EMPTY);
    let ray = Ray::new(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z);
    assert_eq!(wide.with(&empty).raycast(&ray), None);
    assert!(!wide.with(&empty).raycast_any(&ray));
    assert_eq!(
        wide.with(&empty).closest_point(Vec3::ZERO, f32::INFINITY),
        None
    );

    let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let one = MeshRef::new(&positions, &[[0, 1, 2]]).validate().unwrap();
    let owned = MeshBvh::build(&one, &BuildConfig::default()).unwrap();
    let bvh = checked_bvh(&owned, &one).unwrap();
    let mut entries = vec![PlanEntry::EMPTY; plan_capacity(&bvh)];
    let plan = CollapsePlan::<4>::new(&bvh, &mut entries).unwrap();
    let mut nodes = [WideNode::EMPTY; 1];
    let wide = WideBvh::from_plan(&plan, &mut nodes).unwrap();
    assert_eq!(wide.nodes()[0].lanes(), 1);
    assert_eq!(wide.bounds(), bvh.bounds());
    let hit = wide.with(&one).raycast(&ray).unwrap();
    assert_eq!((hit.tri, hit.t), (0, 1.0));
    assert!(wide.with(&one).raycast_any(&ray));
    assert!(!wide.with(&one).raycast_any(&ray.with_range(0.0, 0.5)));
    let c = wide
        .with(&one)
        .closest_point(Vec3::new(2.0, 0.0, 0.0), f32::INFINITY)
        .unwrap();
    assert_eq!((c.tri, c.distance_squared), (0, 1.0));
    assert_eq!(
        wide.with(&one).closest_point(Vec3::new(2.0, 0.0, 0.0), 0.5),
        None
    );
    assert_eq!(
        wide.with(&one).closest_point(Vec3::splat(f32::NAN), 1.0),
        None
    );
}

/// A named mesh: positions and triangles.
type Case = (String, Vec<[f32; 3]>, Vec<[u32; 3]>);

/// Meshes the binary tree's edge-case tests use, answered by the wide tree.
#[test]
fn awkward_meshes_match_brute_force() {
    let spot = load_mesh("spot");
    let mut cases: Vec<Case> = Vec::new();
    for (scale, offset) in [(1e-6f32, 0.0f32), (1e6, -2.5e6)] {
        let positions = spot
            .positions
            .iter()
            .map(|p| p.map(|c| c * scale + offset))
            .collect();
        cases.push((format!("spot x{scale}"), positions, spot.triangles.clone()));
    }
    // Coincident centroids: every triangle is symmetric about the origin.
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for i in 0..500u32 {
        let (s, c) = (i as f32 * 0.61).sin_cos();
        let p0 = Vec3::new(c, s, 0.3 * (i % 7) as f32 - 0.95);
        let p2 = Vec3::new(0.5 * c, -0.5 * s, -0.25 * p0.z);
        positions.extend([p0, -p0, p2].map(|v| v.to_array()));
        triangles.push([3 * i, 3 * i + 1, 3 * i + 2]);
        // And a zero-area one at the same place, never to be returned.
        triangles.push([3 * i, 3 * i, 3 * i + 1]);
    }
    cases.push(("coincident centroids".into(), positions, triangles));
    for (what, positions, triangles) in &cases {
        let mesh = MeshRef::new(positions, triangles).validate().unwrap();
        let owned = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
        let bvh = checked_bvh(&owned, &mesh).unwrap();
        let mut entries = vec![PlanEntry::EMPTY; plan_capacity(&bvh)];
        let plan = CollapsePlan::<4>::new(&bvh, &mut entries).unwrap();
        let mut nodes = vec![WideNode::EMPTY; plan.node_count()];
        let wide = WideBvh::from_plan(&plan, &mut nodes).unwrap();
        check_against_binary(&bvh, &wide, what);
        let brute = BruteForce::new(&mesh);
        let mut hits = 0;
        for ray in workload::random_rays(positions, 3_000, 31) {
            let key = |h: Option<meshq::math::RayHit>| h.map(|h| (h.t.to_bits(), h.tri));
            let expected = brute.raycast(&ray, &Default::default());
            assert_eq!(key(wide.with(&mesh).raycast(&ray)), key(expected), "{what}");
            assert_eq!(
                wide.with(&mesh).raycast_any(&ray),
                expected.is_some(),
                "{what}"
            );
            hits += usize::from(expected.is_some());
        }
        assert!(hits > 300, "{what}: {hits} hits");
        for p in workload::closest_points(positions, 300, 32) {
            let key = |c: Option<meshq::math::ClosestPoint>| {
                c.map(|c| (c.distance_squared.to_bits(), c.tri))
            };
            assert_eq!(
                key(wide.with(&mesh).closest_point(p, f32::INFINITY)),
                key(brute.closest_point(p, f32::INFINITY)),
                "{what}"
            );
        }
    }
}

/// The one-call build (`measure`, then `build` with plan scratch) gives, for every node kind,
/// exactly the nodes of a collapse planned by hand (the compact kind: the four-wide nodes
/// quantized), within the measured sizes; short buffers are typed errors naming the buffer.
#[test]
fn measure_and_build_match_a_planned_collapse_for_every_node_kind() {
    for name in MESHES {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        let owned = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
        let bvh = checked_bvh(&owned, &mesh).unwrap();
        let sizes = WideBvh::<WideNode>::measure(&bvh);
        assert_eq!(sizes, WideBvh::<WideNode8>::measure(&bvh), "{name}");
        assert_eq!(sizes.plan, plan_capacity(&bvh), "{name}");
        assert!(sizes.nodes < mesh.triangle_count().max(2), "{name}");

        let mut entries = vec![PlanEntry::EMPTY; sizes.plan];
        let plan4 = CollapsePlan::<4>::new(&bvh, &mut entries).unwrap();
        let mut by_hand4 = vec![WideNode::EMPTY; plan4.node_count()];
        let by_hand4 = WideBvh::from_plan(&plan4, &mut by_hand4)
            .unwrap()
            .nodes()
            .to_vec();
        let mut scratch = vec![PlanEntry::EMPTY; sizes.plan];
        let mut out4 = vec![WideNode::EMPTY; sizes.nodes];
        let four = WideBvh::build(&bvh, &mut scratch, &mut out4).unwrap();
        assert_eq!(four.nodes().len(), by_hand4.len(), "{name}");
        assert!(
            four.nodes()
                .iter()
                .zip(&by_hand4)
                .all(|(a, b)| a.same_bits(b)),
            "{name}"
        );

        let mut entries8 = vec![PlanEntry::EMPTY; sizes.plan];
        let plan8 = CollapsePlan::<8>::new(&bvh, &mut entries8).unwrap();
        let mut by_hand8 = vec![WideNode8::EMPTY; plan8.node_count()];
        let by_hand8 = WideBvh::<WideNode8>::from_plan(&plan8, &mut by_hand8).unwrap();
        let mut out8 = vec![WideNode8::EMPTY; sizes.nodes];
        let eight = WideBvh::<WideNode8>::build(&bvh, &mut scratch, &mut out8).unwrap();
        assert_eq!(eight.nodes().len(), by_hand8.nodes().len(), "{name}");
        let same8 = eight
            .nodes()
            .iter()
            .zip(by_hand8.nodes())
            .all(|(a, b)| a.same_bits(b));
        assert!(same8, "{name}");

        let mut quantized = vec![CompactNode::EMPTY; four.nodes().len()];
        let quantized = WideBvh::quantize(&four, &mut quantized).unwrap();
        let mut out_c = vec![CompactNode::EMPTY; sizes.nodes];
        let compact = WideBvh::<CompactNode>::build(&bvh, &mut scratch, &mut out_c).unwrap();
        assert_eq!(compact.nodes(), quantized.nodes(), "{name}");

        // Every kind answers as the binary tree does.
        let brute = BruteForce::new(&mesh);
        for ray in workload::random_rays(&loaded.positions, 300, 7) {
            let want = brute.raycast(&ray, &Default::default());
            assert_eq!(four.with(&mesh).raycast(&ray), want, "{name}");
            assert_eq!(eight.with(&mesh).raycast(&ray), want, "{name}");
            assert_eq!(compact.with(&mesh).raycast(&ray), want, "{name}");
        }

        if sizes.plan > 0 {
            let mut short_plan = vec![PlanEntry::EMPTY; sizes.plan - 1];
            let err = WideBvh::build(&bvh, &mut short_plan, &mut out4).unwrap_err();
            assert!(
                matches!(
                    err,
                    BuildError::BufferTooSmall {
                        buffer: BufferKind::CollapsePlan,
                        ..
                    }
                ),
                "{name}: {err:?}"
            );
        }
        let needed = by_hand4.len();
        if needed > 0 {
            let mut short = vec![CompactNode::EMPTY; needed - 1];
            let err = WideBvh::<CompactNode>::build(&bvh, &mut scratch, &mut short).unwrap_err();
            assert_eq!(
                err,
                BuildError::BufferTooSmall {
                    buffer: BufferKind::WideNodes,
                    needed,
                    got: needed - 1
                },
                "{name}"
            );
            assert!(
                short.iter().all(|n| *n == CompactNode::EMPTY),
                "{name}: nothing written"
            );
        }
    }
}
