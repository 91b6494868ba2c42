//! The validator passes after every build across a matrix of configs, the order is a
//! permutation, builds are deterministic, answers stay exact for every config, and the
//! validator rejects corrupted structures.

use meshq::MeshBvh;
use meshq::advanced::BvhNode;
use meshq::advanced::WideNode;
use meshq::bvh::{BuildConfig, Bvh, SplitStrategy};
use meshq::error::StructureError;
use meshq::mesh::ValidMesh;
use meshq::query::RayOptions;
use meshq::{MeshQuery, Traverse};
use meshq_tests::oracle::BruteForce;
use meshq_tests::{MESHES, TreeParts, checked_bvh, load_mesh, workload};

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
    for max_leaf_size in [1, 4, 16] {
        out.push((
            format!("centre, leaf {max_leaf_size}"),
            BuildConfig {
                max_leaf_size,
                ..BuildConfig::fast()
            },
        ));
    }
    for (step, max_leaf_size) in [(SplitStrategy::SWEEP_STEP, 4), (1, 4), (7, 1), (32, 16)] {
        out.push((
            format!("sweep {step}, leaf {max_leaf_size}"),
            BuildConfig {
                split: SplitStrategy::Sweep { step },
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
            let got = bvh.with(mesh).raycast(ray).map(|h| (h.t.to_bits(), h.tri));
            assert_eq!(got, *expected, "{what}: {ray:?}");
        }
        for (p, expected) in &self.points {
            let got = bvh
                .with(mesh)
                .closest_point(*p, f32::INFINITY)
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
            let owned = MeshBvh::build(&mesh, &config).unwrap();
            let bvh = checked_bvh(&owned, &mesh).unwrap();
            bvh.check(&mesh).unwrap();
            assert_permutation(bvh.order(), mesh.triangle_count());
            assert!(bvh.nodes().len() <= Bvh::measure(mesh.triangle_count(), None).nodes);
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
    let expected = Expected::new(&mesh, &loaded.positions);
    for base in [BuildConfig::balanced(), BuildConfig::fast()] {
        let leaf = base.max_leaf_size as usize;
        // The smallest depth whose complete tree of full leaves holds the bunny.
        let min_depth = (1..=64).find(|d| leaf << (d - 1) >= n).unwrap();
        let config = BuildConfig {
            max_depth: min_depth,
            ..base
        };
        let owned = MeshBvh::build(&mesh, &config).unwrap();
        let bvh = checked_bvh(&owned, &mesh).unwrap();
        assert!(
            bvh.depth() <= min_depth,
            "{:?}: depth {} > {min_depth}",
            base.split,
            bvh.depth()
        );
        expected.assert_matches(&bvh, &mesh, &format!("tight depth, {:?}", base.split));
        let too_shallow = BuildConfig {
            max_depth: min_depth - 1,
            ..base
        };
        assert!(matches!(
            MeshBvh::build(&mesh, &too_shallow),
            Err(meshq::error::BuildError::TooDeep { .. })
        ));
    }
}

/// Bounds of the doubled centroids (`min + max` of each triangle's box, the builder's key) of
/// `tris`, computed here from the mesh independently of the builder.
fn doubled_centroid_bounds(mesh: &ValidMesh<'_>, tris: &[u32]) -> ([f32; 3], [f32; 3]) {
    let mut lo = [f32::INFINITY; 3];
    let mut hi = [f32::NEG_INFINITY; 3];
    for &t in tris {
        let c = doubled_centroid(mesh, t);
        for k in 0..3 {
            lo[k] = lo[k].min(c[k]);
            hi[k] = hi[k].max(c[k]);
        }
    }
    (lo, hi)
}

fn doubled_centroid(mesh: &ValidMesh<'_>, tri: u32) -> [f32; 3] {
    let t = mesh.triangle(tri).unwrap();
    let (a, b, c) = (t.a.to_array(), t.b.to_array(), t.c.to_array());
    std::array::from_fn(|k| a[k].min(b[k]).min(c[k]) + a[k].max(b[k]).max(c[k]))
}

/// Slots `[begin, end)` of the order array under `node` (leaf ranges tile it left to right).
fn slot_range(nodes: &[BvhNode], node: usize) -> (usize, usize) {
    let n = nodes[node];
    if n.count > 0 {
        return (n.first as usize, (n.first + n.count) as usize);
    }
    let (begin, _) = slot_range(nodes, n.first as usize);
    let (_, end) = slot_range(nodes, n.first as usize + 1);
    (begin, end)
}

#[test]
fn centre_splits_follow_the_centre_rule() {
    // Every inner node of a centre-split tree divides its triangles at the middle of their
    // centroid bounds on the longest axis (lowest axis on ties): left strictly below, right
    // at or above. Checked against the definition, recomputed from the mesh; the only
    // allowed exception is the median fallback when all centroids coincide.
    for name in MESHES {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        let config = BuildConfig::fast();
        assert_eq!(config.split, SplitStrategy::Centre);
        let owned = MeshBvh::build(&mesh, &config).unwrap();
        let bvh = checked_bvh(&owned, &mesh).unwrap();
        let (nodes, order) = (bvh.nodes(), bvh.order());
        let mut inner = 0;
        for (i, node) in nodes.iter().enumerate() {
            let (begin, end) = slot_range(nodes, i);
            if node.count > 0 {
                assert!(
                    node.count <= config.max_leaf_size,
                    "{name}: leaf {i} too big"
                );
                continue;
            }
            inner += 1;
            assert!(
                end - begin > config.max_leaf_size as usize,
                "{name}: node {i} with {} triangles was split",
                end - begin
            );
            let (lo, hi) = doubled_centroid_bounds(&mesh, &order[begin..end]);
            let e: [f32; 3] = std::array::from_fn(|k| hi[k] - lo[k]);
            if e == [0.0; 3] {
                continue;
            }
            let axis = if e[0] >= e[1] && e[0] >= e[2] {
                0
            } else if e[1] >= e[2] {
                1
            } else {
                2
            };
            let mid = (lo[axis] + hi[axis]) * 0.5;
            let (mid_slot, _) = slot_range(nodes, node.first as usize + 1);
            for (slot, &t) in order.iter().enumerate().take(end).skip(begin) {
                let below = doubled_centroid(&mesh, t)[axis] < mid;
                assert_eq!(
                    below,
                    slot < mid_slot,
                    "{name}: node {i}, triangle {t} on the wrong side"
                );
            }
        }
        assert!(inner > 0, "{name}: no inner nodes checked");
    }
}

/// Half area of the box of `tris`, from the mesh, in f64 (the box corners are f32 values).
fn half_area_f64(mesh: &ValidMesh<'_>, tris: &[u32]) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for &t in tris {
        let t = mesh.triangle(t).unwrap();
        for v in [t.a, t.b, t.c] {
            for (k, x) in v.to_array().into_iter().enumerate() {
                lo[k] = lo[k].min(f64::from(x));
                hi[k] = hi[k].max(f64::from(x));
            }
        }
    }
    let e: [f64; 3] = std::array::from_fn(|k| hi[k] - lo[k]);
    e[0] * e[1] + e[1] * e[2] + e[2] * e[0]
}

/// The sweep-SAH cost of cutting `sorted` after `k` triangles: `A_L·⌈k/4⌉ + A_R·⌈(n−k)/4⌉`.
fn cut_cost(mesh: &ValidMesh<'_>, sorted: &[u32], k: usize) -> f64 {
    let batches = |n: usize| n.div_ceil(4) as f64;
    half_area_f64(mesh, &sorted[..k]) * batches(k)
        + half_area_f64(mesh, &sorted[k..]) * batches(sorted.len() - k)
}

#[test]
fn full_sweep_splits_take_the_cheapest_cut_in_centroid_order() {
    // Every inner node of a step-1 sweep tree puts on its left the first triangles in centroid
    // order (then triangle index) on some axis, and that cut costs no more than any other cut
    // on any axis: recomputed here from the mesh in f64, over every cut. The tolerance is
    // relative (the builder sums in f32).
    let loaded = load_mesh("cow");
    let mesh = loaded.valid();
    let config = BuildConfig {
        split: SplitStrategy::Sweep { step: 1 },
        ..BuildConfig::default()
    };
    let owned = MeshBvh::build(&mesh, &config).unwrap();
    let bvh = checked_bvh(&owned, &mesh).unwrap();
    let (nodes, order) = (bvh.nodes(), bvh.order());
    let mut checked = 0;
    for (i, node) in nodes.iter().enumerate() {
        if node.is_leaf() {
            continue;
        }
        let (begin, end) = slot_range(nodes, i);
        let (mid, _) = slot_range(nodes, node.first as usize + 1);
        let tris = &order[begin..end];
        let mut left: Vec<u32> = order[begin..mid].to_vec();
        left.sort_unstable();
        let mut best = f64::INFINITY;
        let mut chosen = None;
        for axis in 0..3 {
            let mut sorted = tris.to_vec();
            sorted.sort_by(|&a, &b| {
                let (ca, cb) = (
                    doubled_centroid(&mesh, a)[axis],
                    doubled_centroid(&mesh, b)[axis],
                );
                ca.total_cmp(&cb).then(a.cmp(&b))
            });
            for k in 1..sorted.len() {
                best = best.min(cut_cost(&mesh, &sorted, k));
            }
            let mut first = sorted[..mid - begin].to_vec();
            first.sort_unstable();
            if first == left {
                let cost = cut_cost(&mesh, &sorted, mid - begin);
                chosen = Some(chosen.map_or(cost, |c: f64| c.min(cost)));
            }
        }
        let chosen = chosen.unwrap_or_else(|| panic!("node {i}: not a cut in centroid order"));
        assert!(
            chosen <= best * (1.0 + 1e-5),
            "node {i} of {} triangles: cut cost {chosen}, cheapest {best}",
            end - begin
        );
        checked += 1;
    }
    assert!(checked > 100, "only {checked} inner nodes");
}

#[test]
fn a_sweep_step_of_zero_is_a_full_sweep_and_spatial_splits_are_refused_by_name() {
    let loaded = load_mesh("cow");
    let mesh = loaded.valid();
    let with_step = |step| BuildConfig {
        split: SplitStrategy::Sweep { step },
        ..BuildConfig::default()
    };
    let zero = MeshBvh::build(&mesh, &with_step(0)).unwrap();
    let one = MeshBvh::build(&mesh, &with_step(1)).unwrap();
    assert_eq!(zero.bvh().nodes(), one.bvh().nodes());
    assert_eq!(zero.bvh().order(), one.bvh().order());
    let sweep = BuildConfig {
        split: SplitStrategy::Sweep { step: 32 },
        ..BuildConfig::default()
    };
    let spatial = meshq::bvh::SpatialSplits::DEFAULT;
    let sizes = Bvh::measure(mesh.triangle_count(), Some(&spatial));
    let mut nodes = vec![BvhNode::EMPTY; sizes.nodes];
    let mut order = vec![0; sizes.order];
    let mut scratch = vec![meshq::advanced::PrimRef::EMPTY; sizes.order];
    let mut split_refs = vec![meshq::advanced::SplitRef::default(); sizes.split_refs];
    let built = Bvh::build_spatial(
        &mesh,
        &sweep,
        &spatial,
        &mut nodes,
        &mut order,
        &mut scratch,
        &mut split_refs,
    );
    assert!(matches!(
        built,
        Err(meshq::error::BuildError::InvalidConfig { field: "split" })
    ));
}

#[test]
fn builds_are_deterministic_whatever_the_buffers_held() {
    let loaded = load_mesh("fandisk");
    let mesh = loaded.valid();
    let n = mesh.triangle_count();
    let sweep = BuildConfig {
        split: SplitStrategy::Sweep { step: 4 },
        ..BuildConfig::default()
    };
    // The sweep build keeps boxes in node slots it has not used yet: garbage there must not
    // matter either.
    for config in [BuildConfig::default(), sweep] {
        let a = MeshBvh::build(&mesh, &config).unwrap();
        let garbage = BvhNode {
            min: [1.0; 3],
            first: 7,
            max: [-3.0; 3],
            count: 9,
        };
        let mut nodes = vec![garbage; Bvh::measure(n, None).nodes + 5];
        let mut order = vec![u32::MAX; n + 3];
        let mut scratch = vec![meshq::advanced::PrimRef::EMPTY; n + 1];
        let b = Bvh::build(&mesh, &config, &mut nodes, &mut order, &mut scratch).unwrap();
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
        assert_eq!(bits(a.bvh().nodes()), bits(b.nodes()), "{:?}", config.split);
        assert_eq!(a.bvh().order(), b.order());
    }
}

#[test]
fn validator_rejects_corruption() {
    let loaded = load_mesh("cow");
    let mesh = loaded.valid();
    let good = TreeParts::of(&MeshBvh::build(&mesh, &BuildConfig::default()).unwrap());
    Bvh::from_parts(&good.nodes, &good.order, &mesh).unwrap();
    let inner = good.nodes.iter().position(|n| !n.is_leaf()).unwrap();
    let leaf = good.nodes.iter().position(BvhNode::is_leaf).unwrap();

    let corrupt = |f: &dyn Fn(&mut TreeParts)| {
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
    // Nodes no longer reached in the middle of the array: the last sibling pair moved past
    // the end.
    assert!(matches!(
        corrupt(&|b| {
            let n = b.nodes.len();
            let parent = b
                .nodes
                .iter()
                .position(|p| !p.is_leaf() && p.first as usize == n - 2)
                .unwrap();
            b.nodes.extend_from_within(n - 2..);
            b.nodes[parent].first = n as u32;
        }),
        StructureError::UnreachableNodes { .. }
    ));
    // The untrimmed buffers a build was given are fine: what follows the tree is ignored.
    let mut roomy = good.clone();
    roomy.nodes.extend([BvhNode::EMPTY, good.nodes[leaf]]);
    roomy.order.push(0);
    let trimmed = Bvh::from_parts(&roomy.nodes, &roomy.order, &mesh).unwrap();
    assert_eq!(
        (trimmed.nodes(), trimmed.order()),
        (&good.nodes[..], &good.order[..])
    );
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

#[test]
fn built_parts_are_checked_for_safety_but_not_for_boxes() {
    let loaded = load_mesh("cow");
    let mesh = loaded.valid();
    let good = TreeParts::of(&MeshBvh::build(&mesh, &BuildConfig::default()).unwrap());
    let view = Bvh::from_built_parts(&good.nodes, &good.order, &mesh).unwrap();
    assert_eq!(
        view.depth(),
        Bvh::from_parts(&good.nodes, &good.order, &mesh)
            .unwrap()
            .depth()
    );
    let inner = good.nodes.iter().position(|n| !n.is_leaf()).unwrap();
    let leaf = good.nodes.iter().position(BvhNode::is_leaf).unwrap();
    let corrupt = |f: &dyn Fn(&mut TreeParts)| {
        let mut bad = good.clone();
        f(&mut bad);
        Bvh::from_built_parts(&bad.nodes, &bad.order, &mesh).map(|_| ())
    };
    // Whatever would let a query loop or index out of bounds is refused…
    assert!(matches!(
        corrupt(&|b| b.nodes[inner].first = inner as u32),
        Err(StructureError::ChildNotAfterParent { .. })
    ));
    assert!(matches!(
        corrupt(&|b| b.nodes[inner].first = u32::MAX - 1),
        Err(StructureError::ChildOutOfRange { .. })
    ));
    let slot = good.nodes[leaf].first as usize;
    assert_eq!(
        corrupt(&|b| b.order[slot] = 1_000_000),
        Err(StructureError::TriangleOutOfRange {
            node: leaf as u32,
            tri: 1_000_000
        })
    );
    assert!(matches!(
        corrupt(&|b| {
            b.order.pop();
        }),
        Err(StructureError::LeafRangeOutOfBounds { .. }
            | StructureError::LeafRangesNotContiguous { .. })
    ));
    // …while a wrong box, which only spoils answers, is the documented blind spot.
    assert_eq!(corrupt(&|b| b.nodes[leaf].max = b.nodes[leaf].min), Ok(()));
}

/// A no_std caller keeps the buffers a build was given, sized by the sizing functions and never
/// trimmed: every view re-borrows them as they are, ignoring what follows the tree, and answers
/// as brute force does.
#[test]
fn views_accept_the_untrimmed_buffers_a_build_was_given() {
    use meshq::advanced::PackedTriangle;
    use meshq::advanced::PrimRef;
    use meshq::query::PackedTriangles;
    use meshq::wide::WideBvh;

    for name in ["cow", "spot"] {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        let n = mesh.triangle_count();
        let mut nodes = vec![BvhNode::EMPTY; Bvh::measure(n, None).nodes];
        let mut order = vec![0u32; n + 7];
        let mut scratch = vec![PrimRef::EMPTY; n];
        let config = BuildConfig::default();
        let (used, depth) = {
            let built = Bvh::build(&mesh, &config, &mut nodes, &mut order, &mut scratch).unwrap();
            (built.nodes().to_vec(), built.depth())
        };
        assert!(used.len() < nodes.len(), "{name}: the buffer has room left");
        let full = Bvh::from_parts(&nodes, &order, &mesh).unwrap();
        let quick = Bvh::from_built_parts(&nodes, &order, &mesh).unwrap();
        for view in [full, quick] {
            assert_eq!(view.nodes(), &used[..], "{name}");
            assert_eq!(view.order(), &order[..n], "{name}");
            assert_eq!(view.depth(), depth, "{name}");
        }

        let mut entries =
            vec![meshq::advanced::PlanEntry::EMPTY; meshq::advanced::plan_capacity(&full)];
        let plan = meshq::advanced::CollapsePlan::<4>::new(&full, &mut entries).unwrap();
        let mut wide_nodes = vec![WideNode::EMPTY; WideBvh::<WideNode>::measure(&full).nodes + 3];
        let written = WideBvh::from_plan(&plan, &mut wide_nodes)
            .unwrap()
            .nodes()
            .len();
        let wide = WideBvh::from_parts(&plan, &wide_nodes).unwrap();
        assert_eq!(wide.nodes().len(), written, "{name}");
        let mut packed = vec![PackedTriangle::EMPTY; n + 5];
        full.pack_triangles(&mesh, &mut packed).unwrap();
        let packed = PackedTriangles::new(&packed);

        let brute = BruteForce::new(&mesh);
        for ray in workload::random_rays(&loaded.positions, 300, 17) {
            let want = brute.raycast(&ray, &RayOptions::default());
            assert_eq!(full.with(&mesh).raycast(&ray), want, "{name}");
            assert_eq!(wide.with(&packed).raycast(&ray), want, "{name}");
        }

        // Refit works on the untrimmed buffer too and leaves what follows the tree alone.
        let mut refit_nodes = nodes.clone();
        let refit = Bvh::refit(&mut refit_nodes, &order, &mesh).unwrap();
        assert_eq!(refit.nodes().len(), used.len(), "{name}");
        refit.check(&mesh).unwrap();
        assert_eq!(&refit_nodes[used.len()..], &nodes[used.len()..], "{name}");
    }
}
