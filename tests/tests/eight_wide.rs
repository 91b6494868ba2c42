//! The eight-wide BVH (`WideBvh<WideNode8>`, `MeshBvh::with_eight_wide_nodes`): the collapse keeps the
//! binary tree's leaves under boxes that hold them, and every query answers as a brute-force
//! scan does — one ray per call, batches (packets for rays from one origin), any hit, closest
//! points and overlaps.

use std::collections::BTreeSet;
use std::ops::ControlFlow;

use meshq::MeshBvh;
use meshq::advanced::{CollapsePlan, MERGED_LEAF_MAX, plan_capacity};
use meshq::advanced::{PlanEntry, WideNode8};
use meshq::bvh::BuildConfig;
use meshq::geom::CullMode;
use meshq::math::{Aabb, Ray, RayHit, Vec3};
use meshq::query::{MeshQuery, RayOptions, Traverse, TriangleTest};
use meshq::wide::WideBvh;
use meshq_tests::oracle::BruteForce;
use meshq_tests::{MESHES, load_mesh, workload};

fn bits(h: Option<RayHit>) -> Option<(u32, u32, u32, u32)> {
    h.map(|h| (h.t.to_bits(), h.tri, h.u.to_bits(), h.v.to_bits()))
}

/// Whether a vertex is a corner of some triangle (unused vertices need no box).
fn used(loaded: &meshq_tests::LoadedMesh, p: &[f32; 3]) -> bool {
    loaded
        .triangles
        .iter()
        .any(|t| t.iter().any(|&i| loaded.positions[i as usize] == *p))
}

#[test]
fn the_collapse_keeps_every_leaf_under_boxes_that_hold_it() {
    for name in MESHES {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        let owned = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
        let bvh = owned.bvh();
        let mut entries = vec![PlanEntry::EMPTY; plan_capacity(&bvh)];
        let plan = CollapsePlan::<8>::new(&bvh, &mut entries).unwrap();
        let mut storage = vec![WideNode8::EMPTY; WideBvh::<WideNode8>::measure(&bvh).nodes];
        let eight = WideBvh::<WideNode8>::from_plan(&plan, &mut storage).unwrap();
        assert_eq!(eight.nodes().len(), plan.node_count(), "{name}");
        let owned4 = owned.clone().with_four_wide_nodes().unwrap();
        let four = owned4.wide().unwrap();
        assert!(
            eight.nodes().len() < four.nodes().len(),
            "{name}: {} eight-wide nodes, {} four-wide",
            eight.nodes().len(),
            four.nodes().len()
        );

        // The binary tree's leaves, as (first slot, count): a leaf lane is one of them or
        // merges a few of them.
        let binary: BTreeSet<(u32, u32)> = bvh
            .nodes()
            .iter()
            .filter(|n| n.is_leaf())
            .map(|n| (n.first, n.count))
            .collect();
        let mut leaves = BTreeSet::new();
        let mut inner_seen = vec![false; eight.nodes().len()];
        for (i, node) in eight.nodes().iter().enumerate() {
            let used = node.lanes();
            assert!((1..=8).contains(&used), "{name} node {i}: {used} lanes");
            // The walk computes inner lane `l`'s node as lane 0's plus `l`: inner lanes first,
            // their nodes consecutive.
            let inner = node.count[..used].iter().take_while(|&&n| n == 0).count();
            assert!(
                node.count[inner..used].iter().all(|&n| n > 0),
                "{name} node {i}: a leaf lane before an inner one"
            );
            for l in 0..inner {
                assert_eq!(node.child[l], node.child[0] + l as u32, "{name} node {i}");
            }
            for lane in 0..8 {
                let aabb = node.bounds.lane(lane);
                if lane >= used {
                    assert!(
                        aabb.min.x > aabb.max.x,
                        "{name} node {i} lane {lane} unused"
                    );
                    assert_eq!((node.child[lane], node.count[lane]), (0, 0));
                    continue;
                }
                let (child, count) = (node.child[lane], node.count[lane]);
                if count > 0 {
                    assert!(leaves.insert((child, count)), "{name}: leaf twice");
                    assert!(
                        binary.contains(&(child, count)) || count <= MERGED_LEAF_MAX,
                        "{name}: merged leaf of {count}"
                    );
                    for slot in child..child + count {
                        let tri = bvh.order()[slot as usize];
                        let corners = mesh.triangle(tri).unwrap();
                        for p in [corners.a, corners.b, corners.c] {
                            assert!(aabb.contains_point(p), "{name} node {i} lane {lane}");
                        }
                    }
                } else {
                    let c = child as usize;
                    assert!(c > 0 && c < eight.nodes().len(), "{name} node {i}");
                    assert!(!inner_seen[c], "{name}: node {c} has two parents");
                    inner_seen[c] = true;
                    let below = &eight.nodes()[c];
                    for l in 0..below.lanes() {
                        assert!(
                            aabb.contains_aabb(&below.bounds.lane(l)),
                            "{name} node {i} lane {lane} misses a box below"
                        );
                    }
                }
            }
        }
        // The leaf lanes hold every slot once, and each binary leaf lies within one of them.
        let mut next = 0;
        for &(first, count) in &leaves {
            assert_eq!(first, next, "{name}: slots missing or repeated at {next}");
            next = first + count;
        }
        assert_eq!(next as usize, bvh.order().len(), "{name}: trailing slots");
        for &(first, count) in &binary {
            let (start, len) = *leaves.range(..=(first, u32::MAX)).next_back().unwrap();
            assert!(
                start + len >= first + count,
                "{name}: binary leaf {first} split"
            );
        }
        assert!(
            inner_seen.iter().skip(1).all(|&s| s),
            "{name}: orphan nodes"
        );
        // The root's lanes lie within the binary root's box.
        assert!(bvh.bounds().contains_aabb(&eight.bounds()), "{name}: root");
        for p in &loaded.positions {
            assert!(eight.bounds().contains_point(Vec3::from_array(*p)) || !used(&loaded, p));
        }

        // The owned form walks the same nodes.
        let owned8 = owned.clone().with_eight_wide_nodes().unwrap();
        assert!(owned8.wide().is_none() && owned8.compact().is_none());
        assert_eq!(owned8.eight_wide().unwrap().nodes(), eight.nodes());
        assert_eq!(
            owned8.query_node_bytes(),
            std::mem::size_of_val(eight.nodes())
        );
        // Compact from eight-wide: the four-wide tree's compact nodes.
        let compact_a = owned8.clone().with_compact_nodes().unwrap();
        let compact_b = owned.clone().with_compact_nodes().unwrap();
        assert_eq!(
            compact_a.compact().unwrap().nodes(),
            compact_b.compact().unwrap().nodes(),
            "{name}"
        );
    }
}

#[test]
fn a_lone_leaf_and_a_too_small_buffer() {
    let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let mesh = meshq::mesh::MeshRef::new(&positions, &[[0, 1, 2]])
        .validate()
        .unwrap();
    let owned = MeshBvh::build(&mesh, &BuildConfig::default())
        .unwrap()
        .with_eight_wide_nodes()
        .unwrap();
    let ray = Ray::new(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z);
    assert_eq!(owned.raycast(&ray).map(|h| h.tri), Some(0));
    assert_eq!(owned.eight_wide().unwrap().nodes().len(), 1);
    // Bad rays (NaN, zero direction) miss, as on the four-wide tree.
    for bad in [
        Ray::new(Vec3::new(f32::NAN, 0.2, 1.0), -Vec3::Z),
        Ray::new(Vec3::new(0.2, 0.2, 1.0), Vec3::ZERO),
        Ray::new(Vec3::new(0.2, 0.2, 1.0), Vec3::new(0.0, f32::NAN, -1.0)),
    ] {
        assert!(owned.raycast(&bad).is_none() && !owned.raycast_any(&bad));
    }

    // No triangles: no nodes, and every query answers nothing.
    let empty = meshq::mesh::MeshRef::new(&[], &[]).validate().unwrap();
    let none = MeshBvh::build(&empty, &BuildConfig::default())
        .unwrap()
        .with_eight_wide_nodes()
        .unwrap();
    assert_eq!(none.query_node_bytes(), 0);
    assert!(none.eight_wide().unwrap().is_empty());
    assert!(none.raycast(&ray).is_none());
    assert!(none.closest_point(Vec3::ZERO, f32::INFINITY).is_none());
    let mut no_nodes: [WideNode8; 0] = [];
    let none_bvh = none.bvh();
    let mut no_entries = vec![PlanEntry::EMPTY; plan_capacity(&none_bvh)];
    let none_plan = CollapsePlan::<8>::new(&none_bvh, &mut no_entries).unwrap();
    assert_eq!(
        WideBvh::<WideNode8>::from_plan(&none_plan, &mut no_nodes)
            .unwrap()
            .nodes()
            .len(),
        0
    );

    let loaded = load_mesh("spot");
    let big = MeshBvh::build(&loaded.valid(), &BuildConfig::default()).unwrap();
    let big_bvh = big.bvh();
    let mut big_entries = vec![PlanEntry::EMPTY; plan_capacity(&big_bvh)];
    let big_plan = CollapsePlan::<8>::new(&big_bvh, &mut big_entries).unwrap();
    let needed = big_plan.node_count();
    let mut short = vec![WideNode8::EMPTY; needed - 1];
    assert!(WideBvh::<WideNode8>::from_plan(&big_plan, &mut short).is_err());
    let mut exact = vec![WideNode8::EMPTY; needed];
    assert_eq!(
        WideBvh::<WideNode8>::from_plan(&big_plan, &mut exact)
            .unwrap()
            .nodes()
            .len(),
        needed
    );
}

#[test]
fn eight_wide_queries_match_brute_force() {
    for name in ["spot", "fandisk", "stanford-bunny"] {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        let brute = BruteForce::new(&mesh);
        let owned = MeshBvh::build(&mesh, &BuildConfig::default())
            .unwrap()
            .with_eight_wide_nodes()
            .unwrap();
        let view = owned.eight_wide().unwrap();
        let packed = owned.packed();
        let mut rays = workload::random_rays(&loaded.positions, 20_000, 43);
        let camera = workload::camera_rays(&loaded.positions, 64, 48);
        rays.extend(&camera);
        for options in [
            RayOptions::default(),
            RayOptions {
                test: TriangleTest::MollerTrumbore,
                cull: CullMode::Back,
            },
            RayOptions {
                test: TriangleTest::Watertight,
                cull: CullMode::Front,
            },
        ] {
            for (i, ray) in rays.iter().enumerate() {
                let want = brute.raycast(ray, &options);
                assert_eq!(
                    bits(owned.raycast_with(ray, &options)),
                    bits(want),
                    "{name} ray {i} {options:?}"
                );
                assert_eq!(
                    bits(view.with(&packed).raycast_with(ray, &options)),
                    bits(want),
                    "{name} ray {i}"
                );
                assert_eq!(
                    owned.raycast_any_with(ray, &options),
                    want.is_some(),
                    "{name} any {i}"
                );
            }
            // Batches: the camera's rays share an origin and walk in packets.
            let mut keys = vec![0u64; rays.len()];
            let mut out = vec![None; rays.len()];
            owned
                .raycast_batch(&rays, &options, &mut keys, &mut out)
                .unwrap();
            let mut any = vec![false; rays.len()];
            owned
                .raycast_any_batch(&rays, &options, &mut keys, &mut any)
                .unwrap();
            for (i, ray) in rays.iter().enumerate() {
                let want = brute.raycast(ray, &options);
                assert_eq!(bits(out[i]), bits(want), "{name} batch {i} {options:?}");
                assert_eq!(any[i], want.is_some(), "{name} any batch {i}");
            }
        }
        // Every hit along a few rays.
        for ray in rays.iter().step_by(997) {
            let blank = RayHit {
                t: 0.0,
                tri: 0,
                u: 0.0,
                v: 0.0,
            };
            let mut hits = [blank; 64];
            let n = owned
                .raycast_all(ray, &RayOptions::default(), &mut hits)
                .written;
            let want = brute.raycast_all(ray, &RayOptions::default());
            let got: Vec<_> = hits[..n].iter().map(|h| bits(Some(*h))).collect();
            let want: Vec<_> = want.iter().take(64).map(|h| bits(Some(*h))).collect();
            assert_eq!(got, want, "{name} every hit");
        }
        for (i, p) in workload::closest_points(&loaded.positions, 3_000, 44)
            .into_iter()
            .enumerate()
        {
            let want = brute.closest_point(p, f32::INFINITY);
            let got = owned.closest_point(p, f32::INFINITY);
            assert_eq!(
                got.map(|c| (c.distance_squared.to_bits(), c.tri)),
                want.map(|c| (c.distance_squared.to_bits(), c.tri)),
                "{name} point {i}"
            );
        }
        let (c, r, _) = workload::centre_radius(&loaded.positions);
        for (lo, hi) in [(0.3, 0.2), (0.05, 0.6), (1.5, 1.5)] {
            let query = Aabb::new(c - Vec3::splat(lo * r), c + Vec3::splat(hi * r));
            let mut found = Vec::new();
            owned.overlap_aabb(&query, |t| {
                found.push(t);
                ControlFlow::Continue(())
            });
            found.sort_unstable();
            assert_eq!(found, brute.overlap_aabb(&query), "{name} box overlap");
            let mut in_sphere = Vec::new();
            owned.overlap_sphere(c, lo * r, |t| {
                in_sphere.push(t);
                ControlFlow::Continue(())
            });
            in_sphere.sort_unstable();
            assert_eq!(in_sphere, brute.overlap_sphere(c, lo * r), "{name} sphere");
        }
        // The four-wide tree over the same leaves agrees on every ray too (a cross-check that
        // needs no oracle of its own).
        let four = MeshBvh::build(&mesh, &BuildConfig::default())
            .unwrap()
            .with_four_wide_nodes()
            .unwrap();
        let four_view: WideBvh<'_> = four.wide().unwrap();
        for ray in rays.iter().step_by(7) {
            assert_eq!(
                bits(four_view.with(&four.packed()).raycast(ray)),
                bits(view.with(&packed).raycast(ray))
            );
        }
    }
}

/// The tree a built or loaded `MeshBvh` walks is the target's default (eight-wide where the
/// target has AVX2 or is wasm32), each choice can be switched to and back, and every choice
/// holds exactly the nodes its collapse gives and answers as brute force does.
#[test]
fn the_default_tree_is_the_targets_and_every_choice_answers_alike() {
    let loaded = load_mesh("fandisk");
    let mesh = loaded.valid();
    let built = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
    let blob = built.to_blob(meshq::blob::MeshLayout::Indexed).unwrap();
    let loaded_blob = MeshBvh::from_blob(&blob).unwrap();
    let bvh = built.bvh();
    let mut storage4 = vec![
        meshq::advanced::WideNode::EMPTY;
        WideBvh::<meshq::advanced::WideNode>::measure(&bvh).nodes
    ];
    let mut entries4 = vec![PlanEntry::EMPTY; plan_capacity(&bvh)];
    let plan4 = CollapsePlan::<4>::new(&bvh, &mut entries4).unwrap();
    let four = WideBvh::from_plan(&plan4, &mut storage4).unwrap();
    let mut entries8 = vec![PlanEntry::EMPTY; plan_capacity(&bvh)];
    let plan8 = CollapsePlan::<8>::new(&bvh, &mut entries8).unwrap();
    let mut storage8 = vec![WideNode8::EMPTY; WideBvh::<WideNode8>::measure(&bvh).nodes];
    let eight = WideBvh::<WideNode8>::from_plan(&plan8, &mut storage8).unwrap();
    let eight_by_default = cfg!(any(
        target_feature = "sse2",
        target_feature = "neon",
        target_arch = "wasm32"
    ));
    assert_eq!(MeshBvh::EIGHT_WIDE_BY_DEFAULT, eight_by_default);
    for (what, owned) in [("built", &built), ("loaded", &loaded_blob)] {
        assert_eq!(owned.eight_wide().is_some(), eight_by_default, "{what}");
        assert_eq!(owned.wide().is_some(), !eight_by_default, "{what}");
        let default_bytes = if eight_by_default {
            std::mem::size_of_val(eight.nodes())
        } else {
            std::mem::size_of_val(four.nodes())
        };
        assert_eq!(owned.query_node_bytes(), default_bytes, "{what}");
        // Four-wide, eight-wide, four-wide again: each the nodes of its collapse.
        let as_four = owned.clone().with_four_wide_nodes().unwrap();
        assert_eq!(as_four.wide().unwrap().nodes(), four.nodes(), "{what}");
        assert!(as_four.eight_wide().is_none() && as_four.compact().is_none());
        let as_eight = as_four.clone().with_eight_wide_nodes().unwrap();
        assert_eq!(
            as_eight.eight_wide().unwrap().nodes(),
            eight.nodes(),
            "{what}"
        );
        let back = as_eight.clone().with_four_wide_nodes().unwrap();
        assert_eq!(back.wide().unwrap().nodes(), four.nodes(), "{what}");
        let compact = as_eight.clone().with_compact_nodes().unwrap();
        assert_eq!(
            compact
                .clone()
                .with_four_wide_nodes()
                .unwrap()
                .wide()
                .unwrap()
                .nodes(),
            four.nodes(),
            "{what}: four-wide from compact"
        );
        // Every choice answers as brute force does.
        let brute = BruteForce::new(&mesh);
        let rays = workload::random_rays(&loaded.positions, 2_000, 11);
        let options = RayOptions::default();
        for choice in [owned, &as_four, &as_eight, &compact] {
            for ray in &rays {
                assert_eq!(
                    bits(choice.raycast(ray)),
                    bits(brute.raycast(ray, &options)),
                    "{what}"
                );
            }
        }
    }
}
