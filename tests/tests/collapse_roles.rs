//! The collapse roles a version-5 blob stores (two bits per binary node): decoded here from
//! the format's description alone, they give exactly the wide tree the solved plan writes;
//! loaders collapse with them to the same nodes; other valid roles answer like brute force;
//! and roles that break a rule are refused by every loader.

use meshq::MeshBvh;
use meshq::advanced::{BlobHeader, BvhNode, reseal};
use meshq::advanced::{CollapsePlan, CollapseRoles, MERGED_LEAF_MAX, plan_capacity};
use meshq::advanced::{PlanEntry, WideNode8};
use meshq::blob::{self, BlobView, EncodeOptions, MeshLayout};
use meshq::bvh::{BuildConfig, Bvh, SpatialSplits};
use meshq::error::BlobError;
use meshq::math::Aabb;
use meshq::owned::MeshIndex;
use meshq::wide::WideBvh;
use meshq_tests::oracle::BruteForce;
use meshq_tests::suite::check_all;
use meshq_tests::{MESHES, load_mesh};

/// Node `i`'s role in `roles`, as the format lays it out.
fn role(roles: &[u8], i: usize) -> u8 {
    (roles[i / 4] >> (2 * (i % 4))) & 3
}

/// A lane as the test compares them: its box, and either the slots of a leaf or (count 0) the
/// lanes of the wide node below.
#[derive(Debug, PartialEq)]
enum Lane {
    Leaf(Aabb, u32, u32),
    Inner(Aabb, Vec<Lane>),
}

/// The lanes of the wide node at inner node `at`, from the roles by the format's rules, in the
/// order `WideNode8` documents: the inner lanes first, then the leaves, each in the tree's
/// left-to-right order.
fn decode(nodes: &[BvhNode], roles: &[u8], at: usize) -> Vec<Lane> {
    let (inner, leaves): (Vec<Lane>, Vec<Lane>) = left_to_right(nodes, roles, at)
        .into_iter()
        .partition(|lane| matches!(lane, Lane::Inner(..)));
    inner.into_iter().chain(leaves).collect()
}

/// The lanes [`decode`] orders, left to right: a leaf is a leaf lane, role 1 an inner lane,
/// role 2 a leaf over its subtree's slots, role 0 opens the node. Recursive, written from the
/// description, not from the crate's walk.
fn left_to_right(nodes: &[BvhNode], roles: &[u8], at: usize) -> Vec<Lane> {
    let mut lanes = Vec::new();
    let node = nodes[at];
    for child in [node.first as usize, node.first as usize + 1] {
        let c = nodes[child];
        if c.is_leaf() {
            lanes.push(Lane::Leaf(c.aabb(), c.first, c.count));
            continue;
        }
        match role(roles, child) {
            1 => lanes.push(Lane::Inner(c.aabb(), decode(nodes, roles, child))),
            2 => {
                let (first, end) = slot_span(nodes, child);
                lanes.push(Lane::Leaf(c.aabb(), first, end - first));
            }
            // Opened: its children's lanes in its place.
            0 => lanes.extend(left_to_right(nodes, roles, child)),
            r => panic!("role {r}"),
        }
    }
    lanes
}

/// The first and one-past-last slot of the leaves under `at`.
fn slot_span(nodes: &[BvhNode], at: usize) -> (u32, u32) {
    let n = nodes[at];
    if n.is_leaf() {
        return (n.first, n.first + n.count);
    }
    let (a, _) = slot_span(nodes, n.first as usize);
    let (_, b) = slot_span(nodes, n.first as usize + 1);
    (a, b)
}

/// The lanes of wide node `at` of `nodes`, recursively.
fn wide_lanes(nodes: &[WideNode8], at: usize) -> Vec<Lane> {
    let n = &nodes[at];
    (0..n.lanes())
        .map(|l| {
            let b = n.bounds.lane(l);
            if n.count[l] > 0 {
                Lane::Leaf(b, n.child[l], n.count[l])
            } else {
                Lane::Inner(b, wide_lanes(nodes, n.child[l] as usize))
            }
        })
        .collect()
}

/// The roles `bvh`'s solved eight-wide plan writes, with the plan's node count.
fn planned_roles(bvh: &Bvh<'_>) -> (Vec<u8>, usize) {
    let mut entries = vec![PlanEntry::EMPTY; plan_capacity(bvh)];
    let plan = CollapsePlan::<8>::new(bvh, &mut entries).unwrap();
    let mut roles = vec![0u8; CollapseRoles::len_for(bvh.nodes().len())];
    plan.write_roles(&mut roles).unwrap();
    (roles, plan.node_count())
}

/// The wide nodes of `plan`.
fn collapsed(plan: &CollapsePlan<'_, '_, 8>) -> Vec<WideNode8> {
    let mut out = vec![WideNode8::EMPTY; WideBvh::<WideNode8>::measure(plan.tree()).nodes];
    let n = WideBvh::<WideNode8>::from_plan(plan, &mut out)
        .unwrap()
        .nodes()
        .len();
    out.truncate(n);
    out
}

#[test]
fn stored_roles_rebuild_the_planned_collapse() {
    for name in MESHES {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        let trees = [
            (
                "balanced",
                MeshBvh::build(&mesh, &BuildConfig::default()).unwrap(),
            ),
            ("fast", MeshBvh::build(&mesh, &BuildConfig::fast()).unwrap()),
            (
                "spatial",
                MeshBvh::build_spatial(&mesh, &BuildConfig::default(), &SpatialSplits::DEFAULT)
                    .unwrap(),
            ),
        ];
        for (what, built) in &trees {
            let bvh = built.bvh();
            let nodes = bvh.nodes();
            let (roles, count) = planned_roles(&bvh);
            assert_eq!(
                role(&roles, 0),
                1,
                "{name} {what}: the root starts a wide node"
            );
            // Decoded by the format's rules, the roles give the solved plan's wide tree.
            let mut entries = vec![PlanEntry::EMPTY; plan_capacity(&bvh)];
            let solved = CollapsePlan::<8>::new(&bvh, &mut entries).unwrap();
            let solved_nodes = collapsed(&solved);
            assert_eq!(
                decode(nodes, &roles, 0),
                wide_lanes(&solved_nodes, 0),
                "{name} {what}"
            );
            // Every merged leaf spans at most MERGED_LEAF_MAX slots.
            for (i, n) in nodes.iter().enumerate() {
                if !n.is_leaf() && role(&roles, i) == 2 {
                    let (a, b) = slot_span(nodes, i);
                    assert!(b - a <= MERGED_LEAF_MAX, "{name} {what}: node {i}");
                }
            }
            // The crate's own reading: the same node count and the same nodes, bit for bit.
            let stored = CollapseRoles::new(&roles);
            assert_eq!(stored.check(&bvh), Ok(count), "{name} {what}");
            let from_roles = CollapsePlan::<8>::from_roles(&bvh, stored).unwrap();
            assert_eq!(from_roles.node_count(), count);
            assert_eq!(collapsed(&from_roles), solved_nodes, "{name} {what}");
            // The roles of an eight-wide collapse are not a four-wide one (a node has more
            // than four lanes somewhere on these meshes).
            assert!(
                CollapsePlan::<4>::from_roles(&bvh, stored).is_err(),
                "{name} {what}"
            );
            // A blob stores them, and a loaded tree walks the very nodes the built one does.
            let bytes = built.to_blob(MeshLayout::Indexed).unwrap();
            let view = BlobView::parse(&bytes).unwrap();
            assert_eq!(view.header().version, 5);
            assert_eq!(view.tree().unwrap().collapse_roles(), Some(stored));
            if MeshBvh::EIGHT_WIDE_BY_DEFAULT {
                let loaded_tree = MeshBvh::from_blob(&bytes).unwrap();
                assert_eq!(
                    loaded_tree.eight_wide().unwrap().nodes(),
                    built.eight_wide().unwrap().nodes(),
                    "{name} {what}"
                );
            }
        }
    }
}

/// Where the roles' bytes start in a version-5 BVH blob: after the header, the nodes, the
/// order, the split references and the roles' own length (each array a varint count first).
fn roles_at(bytes: &[u8]) -> (usize, usize) {
    let h = BlobHeader::read(bytes).unwrap();
    let varint = |n: usize| (usize::BITS - n.leading_zeros()).div_ceil(7).max(1) as usize;
    let (nodes, refs, splits) = (
        h.node_count as usize,
        h.reference_count as usize,
        h.split_ref_count as usize,
    );
    let len = nodes.div_ceil(4);
    let at = h.header_len
        + varint(nodes)
        + 32 * nodes
        + varint(refs)
        + 4 * refs
        + varint(splits)
        + 32 * splits
        + varint(len);
    (at, len)
}

/// `bytes` with its roles replaced by `roles` and the checksum resealed.
fn with_roles(bytes: &[u8], roles: &[u8]) -> Vec<u8> {
    let (at, len) = roles_at(bytes);
    assert_eq!(roles.len(), len);
    let mut out = bytes.to_vec();
    out[at..at + len].copy_from_slice(roles);
    reseal(&mut out).unwrap();
    out
}

/// What every loader says of `bytes`: the view, the owned BVH and the index.
fn loads(bytes: &[u8]) -> [Result<(), BlobError>; 3] {
    [
        BlobView::parse(bytes).map(|_| ()),
        MeshBvh::from_blob(bytes).map(|_| ()),
        MeshIndex::from_blob(bytes).map(|_| ()),
    ]
}

fn set_role(roles: &mut [u8], i: usize, r: u8) {
    roles[i / 4] = (roles[i / 4] & !(3 << (2 * (i % 4)))) | (r << (2 * (i % 4)));
}

#[test]
fn other_valid_roles_answer_exactly_and_broken_ones_are_refused() {
    let loaded = load_mesh("spot");
    let mesh = loaded.valid();
    let brute = BruteForce::new(&mesh);
    let built = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
    let bvh = built.bvh();
    let nodes = bvh.nodes();
    let n = nodes.len();
    let bytes = built.to_blob(MeshLayout::Indexed).unwrap();
    let (at, len) = roles_at(&bytes);
    let planned = bytes[at..at + len].to_vec();
    assert_eq!(planned, planned_roles(&bvh).0);

    // Another valid plan: every inner node its own two-lane wide node. Written by the
    // encoder itself, and every loader answers as brute force with it.
    let mut binary = vec![0u8; len];
    for (i, node) in nodes.iter().enumerate() {
        if !node.is_leaf() {
            set_role(&mut binary, i, 1);
        }
    }
    let options = EncodeOptions {
        collapse_roles: Some(CollapseRoles::new(&binary)),
        ..EncodeOptions::default()
    };
    let mut other = vec![0u8; blob::encoded_len(&bvh, &mesh, &options).unwrap()];
    blob::encode_into(&bvh, &mesh, &options, &mut other).unwrap();
    assert_eq!(other.len(), bytes.len());
    check_all(
        &BlobView::parse(&other).unwrap(),
        &brute,
        &loaded,
        "two-lane roles, view",
    );
    let owned = MeshBvh::from_blob(&other).unwrap();
    if let Some(wide) = owned.eight_wide() {
        assert_eq!(wide.nodes().len(), n / 2, "one wide node per inner node");
    }
    check_all(&owned, &brute, &loaded, "two-lane roles, loaded");

    // Broken roles: each refused by every loader (and by the encoder).
    let inner: Vec<usize> = (1..n).filter(|&i| !nodes[i].is_leaf()).collect();
    let leaf = (0..n).find(|&i| nodes[i].is_leaf()).unwrap();
    let big = inner
        .iter()
        .copied()
        .find(|&i| {
            let (a, b) = slot_span(nodes, i);
            b - a > MERGED_LEAF_MAX
        })
        .unwrap();
    let merged = (0..n).find(|&i| role(&planned, i) == 2).unwrap();
    let below_merged = nodes[merged].first as usize;
    let mut cases: Vec<(&str, Vec<u8>)> = Vec::new();
    let mut edit = |what, f: &dyn Fn(&mut Vec<u8>)| {
        let mut r = planned.clone();
        f(&mut r);
        cases.push((what, r));
    };
    edit("a role on a leaf", &|r| set_role(r, leaf, 1));
    edit("the root opened", &|r| set_role(r, 0, 0));
    edit("role 3", &|r| set_role(r, 0, 3));
    edit("every node opened: too many lanes", &|r| {
        r.fill(0);
        set_role(r, 0, 1);
    });
    edit("a merged leaf over too many slots", &|r| {
        set_role(r, big, 2)
    });
    edit("a role below a merged leaf", &|r| {
        set_role(r, below_merged, 1)
    });
    if n % 4 != 0 {
        edit("a padding bit", &|r| *r.last_mut().unwrap() |= 0x80);
    }
    for (what, roles) in &cases {
        let damaged = with_roles(&bytes, roles);
        assert_eq!(
            loads(&damaged),
            [Err(BlobError::BadCollapsePlan); 3],
            "{what}"
        );
        let options = EncodeOptions {
            collapse_roles: Some(CollapseRoles::new(roles)),
            ..EncodeOptions::default()
        };
        assert_eq!(
            blob::encode_into(&bvh, &mesh, &options, &mut vec![0; 1 << 22]),
            Err(BlobError::BadCollapsePlan),
            "{what}"
        );
    }

    // Random damage: refused alike by every loader, or accepted alike and then exact.
    let mut state = 0x2545_F491_4F6C_DD1Du64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let (mut refused, mut accepted) = (0, 0);
    for round in 0..200 {
        let mut roles = planned.clone();
        for _ in 0..1 + round % 3 {
            let bit = next() as usize % (8 * len);
            roles[bit / 8] ^= 1 << (bit % 8);
        }
        let damaged = with_roles(&bytes, &roles);
        match loads(&damaged) {
            [Ok(()), Ok(()), Ok(())] => {
                accepted += 1;
                check_all(
                    &MeshBvh::from_blob(&damaged).unwrap(),
                    &brute,
                    &loaded,
                    &format!("damaged roles {round}"),
                );
            }
            all => {
                assert_eq!(all, [Err(BlobError::BadCollapsePlan); 3], "round {round}");
                refused += 1;
            }
        }
    }
    println!("random role damage: {refused} refused, {accepted} accepted and exact");
    assert!(refused > 0);
}
