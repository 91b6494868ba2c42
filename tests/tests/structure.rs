//! The validator passes after every build across a matrix of configs, the order is a
//! permutation, builds are deterministic, answers stay exact for every config, and the
//! validator rejects corrupted structures.

use meshq::bvh::{BuildConfig, Bvh, BvhNode, RayOptions};
use meshq::error::StructureError;
use meshq::mesh::ValidMesh;
use meshq_tests::oracle::BruteForce;
use meshq_tests::{MESHES, OwnedBvh, load_mesh, workload};

fn configs() -> Vec<(String, BuildConfig)> {
    let mut out = vec![
        ("fast".to_owned(), BuildConfig::fast()),
        ("balanced".to_owned(), BuildConfig::balanced()),
        ("high_quality".to_owned(), BuildConfig::high_quality()),
    ];
    for bins in [2, 7, 64] {
        out.push((
            format!("bins {bins}"),
            BuildConfig {
                bins,
                ..BuildConfig::default()
            },
        ));
    }
    for max_leaf_size in [1, 16, 64] {
        out.push((
            format!("leaf {max_leaf_size}"),
            BuildConfig {
                max_leaf_size,
                ..BuildConfig::default()
            },
        ));
    }
    out.push((
        "costly traversal".to_owned(),
        BuildConfig {
            traversal_cost: 8.0,
            max_leaf_size: 16,
            ..BuildConfig::default()
        },
    ));
    out
}

fn assert_permutation(order: &[u32], n: usize) {
    let mut seen = vec![false; n];
    for &t in order {
        assert!(
            !std::mem::replace(&mut seen[t as usize], true),
            "triangle {t} twice"
        );
    }
    assert!(
        seen.iter().all(|&s| s),
        "a triangle is missing from the order"
    );
}

type HitKey = Option<(u32, u32)>;

/// The brute-force answers for a fixed query set, computed once per mesh.
struct Expected {
    rays: Vec<(meshq::math::Ray, HitKey)>,
    points: Vec<(glam::Vec3, HitKey)>,
}

impl Expected {
    fn new(mesh: &ValidMesh<'_>, positions: &[[f32; 3]]) -> Self {
        let brute = BruteForce::new(mesh);
        let rays = workload::random_rays(positions, 1_000, 99)
            .into_iter()
            .map(|ray| {
                (
                    ray,
                    brute
                        .raycast(&ray, &RayOptions::default())
                        .map(|h| (h.t.to_bits(), h.tri)),
                )
            })
            .collect();
        let points = workload::closest_points(positions, 200, 98)
            .into_iter()
            .map(|p| {
                let c = brute.closest_point(p, f32::INFINITY);
                (p, c.map(|c| (c.distance_squared.to_bits(), c.tri)))
            })
            .collect();
        Self { rays, points }
    }

    fn assert_matches(&self, bvh: &Bvh<'_>, mesh: &ValidMesh<'_>, what: &str) {
        for (ray, expected) in &self.rays {
            let got = bvh.raycast(mesh, ray).map(|h| (h.t.to_bits(), h.tri));
            assert_eq!(got, *expected, "{what}: {ray:?}");
        }
        for (p, expected) in &self.points {
            let got = bvh
                .closest_point(mesh, *p, f32::INFINITY)
                .map(|c| (c.distance_squared.to_bits(), c.tri));
            assert_eq!(got, *expected, "{what}: {p}");
        }
    }
}

#[test]
fn every_config_on_every_mesh_builds_a_valid_exact_tree() {
    for name in MESHES {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        let expected = Expected::new(&mesh, &loaded.positions);
        for (label, config) in configs() {
            let owned = OwnedBvh::build(&mesh, &config).unwrap();
            let bvh = owned.view(&mesh).unwrap();
            bvh.check(&mesh).unwrap();
            assert_permutation(bvh.order(), mesh.triangle_count());
            assert!(bvh.nodes().len() <= meshq::bvh::node_capacity(mesh.triangle_count()));
            let max_leaf = bvh.nodes().iter().map(|n| n.count).max().unwrap();
            assert!(
                max_leaf <= config.max_leaf_size,
                "{name} {label}: leaf of {max_leaf}"
            );
            assert!(bvh.depth() <= config.max_depth);
            expected.assert_matches(&bvh, &mesh, &format!("{name} {label}"));
        }
    }
}

#[test]
fn a_tight_depth_limit_is_met_with_median_splits() {
    let loaded = load_mesh("stanford-bunny");
    let mesh = loaded.valid();
    let n = mesh.triangle_count();
    // The smallest depth whose complete tree of 4-triangle leaves holds the bunny.
    let min_depth = (1..=64).find(|d| 4usize << (d - 1) >= n).unwrap();
    let config = BuildConfig {
        max_depth: min_depth,
        ..BuildConfig::default()
    };
    let owned = OwnedBvh::build(&mesh, &config).unwrap();
    let bvh = owned.view(&mesh).unwrap();
    assert!(
        bvh.depth() <= min_depth,
        "depth {} > {min_depth}",
        bvh.depth()
    );
    Expected::new(&mesh, &loaded.positions).assert_matches(&bvh, &mesh, "tight depth");
    let too_shallow = BuildConfig {
        max_depth: min_depth - 1,
        ..BuildConfig::default()
    };
    assert!(matches!(
        OwnedBvh::build(&mesh, &too_shallow),
        Err(meshq::error::BuildError::TooDeep { .. })
    ));
}

#[test]
fn builds_are_deterministic_whatever_the_buffers_held() {
    let loaded = load_mesh("fandisk");
    let mesh = loaded.valid();
    let n = mesh.triangle_count();
    let a = OwnedBvh::build(&mesh, &BuildConfig::default()).unwrap();
    let garbage = BvhNode {
        min: [1.0; 3],
        first: 7,
        max: [-3.0; 3],
        count: 9,
    };
    let mut nodes = vec![garbage; meshq::bvh::node_capacity(n) + 5];
    let mut order = vec![u32::MAX; n + 3];
    let mut scratch = vec![meshq::bvh::PrimRef::EMPTY; n + 1];
    let b = Bvh::build(
        &mesh,
        &BuildConfig::default(),
        &mut nodes,
        &mut order,
        &mut scratch,
    )
    .unwrap();
    let bits = |nodes: &[BvhNode]| -> Vec<u32> {
        nodes
            .iter()
            .flat_map(|n| {
                let mut v: Vec<u32> = n.min.iter().chain(&n.max).map(|f| f.to_bits()).collect();
                v.extend([n.first, n.count]);
                v
            })
            .collect()
    };
    assert_eq!(bits(&a.nodes), bits(b.nodes()));
    assert_eq!(a.order, b.order());
}

#[test]
fn validator_rejects_corruption() {
    let loaded = load_mesh("cow");
    let mesh = loaded.valid();
    let good = OwnedBvh::build(&mesh, &BuildConfig::default()).unwrap();
    good.view(&mesh).unwrap();
    let inner = good.nodes.iter().position(|n| !n.is_leaf()).unwrap();
    let leaf = good.nodes.iter().position(BvhNode::is_leaf).unwrap();

    let corrupt = |f: &dyn Fn(&mut OwnedBvh)| {
        let mut bad = good.clone();
        f(&mut bad);
        Bvh::from_parts(&bad.nodes, &bad.order, &mesh)
            .map(|_| ())
            .unwrap_err()
    };
    assert!(matches!(
        corrupt(&|b| b.nodes[inner].first = inner as u32),
        StructureError::ChildNotAfterParent { .. }
    ));
    assert!(matches!(
        corrupt(&|b| b.nodes[inner].first = u32::MAX - 1),
        StructureError::ChildOutOfRange { .. }
    ));
    assert!(matches!(
        corrupt(&|b| b.nodes[leaf].count += 1),
        StructureError::LeafRangesNotContiguous { .. }
            | StructureError::LeafRangeOutOfBounds { .. }
            | StructureError::TriangleOutsideLeaf { .. }
    ));
    assert!(matches!(
        corrupt(&|b| b.nodes[leaf].max = b.nodes[leaf].min),
        StructureError::ChildOutsideParent { .. } | StructureError::TriangleOutsideLeaf { .. }
    ));
    assert!(matches!(
        corrupt(&|b| b.nodes[0].min[1] = f32::NAN),
        StructureError::BadBounds { node: 0 }
    ));
    assert!(matches!(
        corrupt(&|b| b.order[0] = 1_000_000),
        StructureError::TriangleOutOfRange { .. }
    ));
    assert!(matches!(
        corrupt(&|b| {
            b.nodes.push(BvhNode::EMPTY);
        }),
        StructureError::UnreachableNodes { .. }
    ));
    assert!(matches!(
        corrupt(&|b| {
            b.order.pop();
        }),
        StructureError::LeafRangeOutOfBounds { .. }
            | StructureError::LeafRangesNotContiguous { .. }
    ));
    assert!(matches!(
        corrupt(&|b| b.nodes.clear()),
        StructureError::EmptyMismatch
    ));
}
