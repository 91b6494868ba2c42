//! Trees with spatial splits: every query against brute force (each triangle reported once
//! although several leaves hold it), the split table against the tree it describes, triangle
//! pairs against brute force, and the builder's buffers and limits.

use std::collections::{BTreeMap, BTreeSet};

use meshq::advanced::SplitRef;
use meshq::advanced::{BlobHeader, BvhNode, PrimRef, reseal};
use meshq::bvh::{BuildConfig, Bvh, SpatialSplits};
use meshq::collide::{PairBudget, intersecting_pairs, self_intersecting_pairs};
use meshq::error::{BufferKind, BuildError};
use meshq::geom::triangles_meet;
use meshq::math::Triangle;
use meshq::mesh::ValidMesh;
use meshq::owned::MeshBvh;
use meshq::{MeshQuery, Traverse};
use meshq_tests::oracle::BruteForce;
use meshq_tests::suite::check_all;
use meshq_tests::{LoadedMesh, load_mesh, sticks};

/// Scenes where spatial splits repeat triangles (the sticks) and where they barely do.
fn scenes() -> Vec<LoadedMesh> {
    vec![sticks(400), load_mesh("fandisk"), load_mesh("spot")]
}

/// The table says exactly which slots hold a triangle named more than once, with the box of
/// the leaf holding each.
fn check_table(bvh: &Bvh<'_>, mesh: &ValidMesh<'_>) {
    let order = bvh.order();
    let mut slots_of: BTreeMap<u32, Vec<u32>> = BTreeMap::new();
    for (slot, &tri) in order.iter().enumerate() {
        slots_of.entry(tri).or_default().push(slot as u32);
    }
    assert_eq!(slots_of.len(), mesh.triangle_count(), "every triangle held");
    let want: Vec<(u32, u32)> = slots_of
        .iter()
        .filter(|(_, s)| s.len() > 1)
        .flat_map(|(&t, s)| s.iter().map(move |&s| (t, s)))
        .collect();
    let table: Vec<SplitRef> = bvh.split_refs().iter().collect();
    let got: Vec<(u32, u32)> = table.iter().map(|r| (r.tri, r.slot)).collect();
    assert_eq!(got, want, "table entries");
    let mut leaf_of = vec![None; order.len()];
    for node in bvh.nodes().iter().filter(|n| n.is_leaf()) {
        for s in node.first..node.first + node.count {
            leaf_of[s as usize] = Some(node.aabb());
        }
    }
    for r in &table {
        assert_eq!(
            Some(r.leaf_box),
            leaf_of[r.slot as usize],
            "leaf box of {r:?}"
        );
    }
}

#[test]
fn spatial_split_trees_answer_every_query_as_brute_force_does() {
    for loaded in scenes() {
        let mesh = loaded.valid();
        let brute = BruteForce::new(&mesh);
        let scene = MeshBvh::build_spatial(&mesh, &BuildConfig::default(), &SpatialSplits::DEFAULT)
            .unwrap();
        let name = &loaded.name;
        if name.starts_with("sticks") {
            // Not vacuous: the sticks cross, and the build repeats many of them.
            let extra = scene.reference_count() - scene.triangle_count();
            assert!(
                extra * 20 > scene.triangle_count(),
                "{name}: {extra} extra references"
            );
        }
        assert!(scene.reference_count() >= scene.triangle_count());
        let bvh = scene.bvh();
        bvh.check(&mesh).unwrap();
        check_table(&bvh, &mesh);
        check_all(&scene, &brute, &loaded, &format!("{name}, default nodes"));
        check_all(
            &bvh.with(&mesh),
            &brute,
            &loaded,
            &format!("{name}, binary"),
        );
        let four = scene.clone().with_four_wide_nodes().unwrap();
        check_all(&four, &brute, &loaded, &format!("{name}, four-wide"));
        let eight = scene.clone().with_eight_wide_nodes().unwrap();
        check_all(&eight, &brute, &loaded, &format!("{name}, eight-wide"));
        let compact = scene.clone().with_compact_nodes().unwrap();
        check_all(&compact, &brute, &loaded, &format!("{name}, compact"));
        let wide = four.wide().unwrap();
        check_all(
            &wide.with(&four.packed()),
            &brute,
            &loaded,
            &format!("{name}, wide view"),
        );
    }
}

#[test]
fn without_the_table_a_split_triangle_would_be_reported_twice() {
    // The table is what keeps reports single: the same tree without it repeats some.
    let loaded = sticks(400);
    let mesh = loaded.valid();
    let scene =
        MeshBvh::build_spatial(&mesh, &BuildConfig::default(), &SpatialSplits::DEFAULT).unwrap();
    let bare = Bvh::from_built_parts(scene.bvh().nodes(), scene.bvh().order(), &mesh).unwrap();
    assert!(bare.split_refs().is_empty());
    let whole = meshq::math::Aabb::new(meshq::Vec3::splat(-2.0), meshq::Vec3::splat(2.0));
    let mut with_table = vec![0u32; 2 * scene.reference_count()];
    let mut without = with_table.clone();
    let n = scene
        .bvh()
        .with(&mesh)
        .overlap_aabb_into(&whole, &mut with_table);
    let m = bare.with(&mesh).overlap_aabb_into(&whole, &mut without);
    assert_eq!(n.total, mesh.triangle_count());
    assert_eq!(m.total, scene.reference_count());
    assert!(m.total > n.total);
}

#[test]
fn no_extra_room_builds_the_ordinary_tree() {
    for loaded in scenes() {
        let mesh = loaded.valid();
        for config in [
            BuildConfig::default(),
            BuildConfig::fast(),
            BuildConfig::high_quality(),
        ] {
            let plain = MeshBvh::build(&mesh, &config).unwrap();
            let none = SpatialSplits {
                extra_references: 0.0,
                ..SpatialSplits::DEFAULT
            };
            let spatial = MeshBvh::build_spatial(&mesh, &config, &none).unwrap();
            assert_eq!(
                spatial.bvh().nodes(),
                plain.bvh().nodes(),
                "{}",
                loaded.name
            );
            assert_eq!(
                spatial.bvh().order(),
                plain.bvh().order(),
                "{}",
                loaded.name
            );
            assert!(spatial.split_refs().is_empty());
        }
    }
}

#[test]
fn spatial_builds_are_deterministic_and_use_only_their_room() {
    let loaded = sticks(300);
    let mesh = loaded.valid();
    for extra in [0.2f32, 1.0, 2.0] {
        let spatial = SpatialSplits {
            extra_references: extra,
            ..SpatialSplits::DEFAULT
        };
        let a = MeshBvh::build_spatial(&mesh, &BuildConfig::default(), &spatial).unwrap();
        let b = MeshBvh::build_spatial(&mesh, &BuildConfig::default(), &spatial).unwrap();
        assert_eq!(a.bvh().nodes(), b.bvh().nodes());
        assert_eq!(a.bvh().order(), b.bvh().order());
        assert_eq!(a.split_refs(), b.split_refs());
        assert!(a.reference_count() <= Bvh::measure(mesh.triangle_count(), Some(&spatial)).order);
        assert!(a.reference_count() > mesh.triangle_count(), "extra {extra}");
    }
}

#[test]
fn the_spatial_builder_checks_its_buffers_and_settings() {
    let loaded = sticks(50);
    let mesh = loaded.valid();
    let n = mesh.triangle_count();
    let spatial = SpatialSplits::DEFAULT;
    let room = Bvh::measure(n, Some(&spatial)).order;
    assert_eq!(room, 2 * n);
    let splits_len = Bvh::measure(n, Some(&spatial)).split_refs;
    let build = |nodes: usize, order: usize, scratch: usize, splits: usize| {
        let mut nodes = vec![BvhNode::EMPTY; nodes];
        let mut order = vec![0u32; order];
        let mut scratch = vec![PrimRef::EMPTY; scratch];
        let mut split_refs = vec![SplitRef::EMPTY; splits];
        Bvh::build_spatial(
            &mesh,
            &BuildConfig::default(),
            &spatial,
            &mut nodes,
            &mut order,
            &mut scratch,
            &mut split_refs,
        )
        .map(|b| b.order().len())
    };
    let nodes = Bvh::measure(room, None).nodes;
    assert!(build(nodes, room, room, splits_len).unwrap() > n);
    let short = |buffer, needed| {
        Err(BuildError::BufferTooSmall {
            buffer,
            needed,
            got: needed - 1,
        })
    };
    assert_eq!(
        build(nodes - 1, room, room, splits_len),
        short(BufferKind::Nodes, nodes)
    );
    assert_eq!(
        build(nodes, room - 1, room, splits_len),
        short(BufferKind::Order, room)
    );
    assert_eq!(
        build(nodes, room, room - 1, splits_len),
        short(BufferKind::Scratch, room)
    );
    assert_eq!(
        build(nodes, room, room, splits_len - 1),
        short(BufferKind::SplitRefs, splits_len)
    );
    for (bad, field) in [
        (
            SpatialSplits {
                extra_references: -0.1,
                ..spatial
            },
            "extra_references",
        ),
        (
            SpatialSplits {
                extra_references: f32::NAN,
                ..spatial
            },
            "extra_references",
        ),
        (
            SpatialSplits {
                extra_references: 4.5,
                ..spatial
            },
            "extra_references",
        ),
        (
            SpatialSplits {
                min_overlap: -1.0,
                ..spatial
            },
            "min_overlap",
        ),
        (
            SpatialSplits {
                min_overlap: f32::INFINITY,
                ..spatial
            },
            "min_overlap",
        ),
    ] {
        assert_eq!(
            MeshBvh::build_spatial(&mesh, &BuildConfig::default(), &bad).err(),
            Some(BuildError::InvalidConfig { field })
        );
    }
    // An empty mesh builds an empty tree.
    let empty = meshq::mesh::MeshRef::new(&[], &[]).validate().unwrap();
    let scene = MeshBvh::build_spatial(&empty, &BuildConfig::default(), &spatial).unwrap();
    assert_eq!(scene.reference_count(), 0);
    assert!(
        scene
            .raycast(&meshq::math::Ray::new(meshq::Vec3::ZERO, meshq::Vec3::X))
            .is_none()
    );
}

fn triangles_of(mesh: &ValidMesh<'_>) -> Vec<Triangle> {
    (0..mesh.triangle_count() as u32)
        .map(|t| mesh.triangle(t).unwrap())
        .collect()
}

#[test]
fn triangle_pairs_come_once_from_spatial_split_trees() {
    // Sticks cross each other: self-intersection pairs by brute force, and pairs between the
    // scene and a second scene shifted a little, each tree with spatial splits.
    let loaded = sticks(250);
    let mesh = loaded.valid();
    let tris = triangles_of(&mesh);
    let scene =
        MeshBvh::build_spatial(&mesh, &BuildConfig::default(), &SpatialSplits::DEFAULT).unwrap();
    assert!(!scene.split_refs().is_empty());
    let mut want = BTreeSet::new();
    for i in 0..tris.len() {
        for j in i + 1..tris.len() {
            // Two triangles of one stick share an edge or a corner: those are not crossings.
            if i / 12 == j / 12 {
                continue;
            }
            if triangles_meet(&tris[i], &tris[j]) {
                want.insert((i as u32, j as u32));
            }
        }
    }
    assert!(want.len() > 50, "{} crossings", want.len());
    let mut out = vec![meshq::collide::TrianglePair { a: 0, b: 0 }; 4 * want.len()];
    let n = mesh.triangle_count();
    let budget = PairBudget::for_triangles(n, n);
    let found = self_intersecting_pairs(&scene.bvh(), &mesh, budget, &mut out).unwrap();
    let got: Vec<(u32, u32)> = out[..found.written]
        .iter()
        .map(|p| (p.a, p.b))
        .filter(|&(a, b)| a / 12 != b / 12)
        .collect();
    let unique: BTreeSet<_> = got.iter().copied().collect();
    assert_eq!(unique.len(), got.len(), "a pair reported twice");
    assert_eq!(unique, want);

    let shifted: Vec<[f32; 3]> = loaded
        .positions
        .iter()
        .map(|p| [p[0] + 0.013, p[1] - 0.007, p[2] + 0.005])
        .collect();
    let other_mesh = meshq::mesh::MeshRef::new(&shifted, &loaded.triangles)
        .validate()
        .unwrap();
    let other_tris = triangles_of(&other_mesh);
    let other = MeshBvh::build_spatial(
        &other_mesh,
        &BuildConfig::default(),
        &SpatialSplits::DEFAULT,
    )
    .unwrap();
    let mut want = BTreeSet::new();
    for (i, a) in tris.iter().enumerate() {
        for (j, b) in other_tris.iter().enumerate() {
            if triangles_meet(a, b) {
                want.insert((i as u32, j as u32));
            }
        }
    }
    let mut out = vec![meshq::collide::TrianglePair { a: 0, b: 0 }; 4 * want.len() + 8];
    let found = intersecting_pairs(
        scene.bvh().with(&mesh),
        other.bvh().with(&other_mesh),
        None,
        PairBudget::for_triangles(n, other_mesh.triangle_count()),
        &mut out,
    )
    .unwrap();
    let got: Vec<(u32, u32)> = out[..found.written].iter().map(|p| (p.a, p.b)).collect();
    let unique: BTreeSet<_> = got.iter().copied().collect();
    assert_eq!(unique.len(), got.len(), "a pair reported twice");
    assert_eq!(found.total, found.written);
    assert_eq!(unique, want);
}

#[test]
fn spatial_split_trees_round_trip_through_blobs() {
    use meshq::blob::{BlobTree, BlobView, MeshLayout};
    let loaded = sticks(300);
    let mesh = loaded.valid();
    let brute = BruteForce::new(&mesh);
    let scene =
        MeshBvh::build_spatial(&mesh, &BuildConfig::default(), &SpatialSplits::DEFAULT).unwrap();
    let slots = scene.reference_count();
    assert!(slots > mesh.triangle_count());
    for layout in [MeshLayout::Indexed, MeshLayout::Packed, MeshLayout::Omitted] {
        let bytes = scene.to_blob(layout).unwrap();
        assert_eq!(bytes.len(), scene.encoded_len(layout).unwrap());
        let view = if layout == MeshLayout::Omitted {
            BlobView::parse_with_mesh(&bytes, mesh).unwrap()
        } else {
            BlobView::parse(&bytes).unwrap()
        };
        let h = view.header();
        // With the collapse roles `MeshBvh::to_blob` stores: version 5.
        assert_eq!(h.version, 5);
        assert_eq!(h.reference_count as usize, slots);
        assert_eq!(h.split_ref_count as usize, scene.split_refs().len());
        let what = format!("blob {layout:?}");
        check_all(&view, &brute, &loaded, &format!("{what}, in place"));
        let (_, tree) = BlobTree::parse(&bytes).unwrap();
        check_all(&tree.with(&mesh), &brute, &loaded, &format!("{what}, tree"));
        let owned = if layout == MeshLayout::Omitted {
            MeshBvh::from_blob_with_mesh(&bytes, &mesh).unwrap()
        } else {
            MeshBvh::from_blob(&bytes).unwrap()
        };
        assert_eq!(owned.split_refs(), scene.split_refs());
        check_all(&owned, &brute, &loaded, &format!("{what}, loaded"));
        if layout != MeshLayout::Packed {
            // The packed layout gives the mesh vertices of its own: another indexed mesh.
            assert_eq!(owned.to_blob(layout).unwrap(), bytes, "{what}: bytes again");
        }
        let mut nodes = vec![BvhNode::EMPTY; h.node_count as usize];
        let mut order = vec![0u32; slots];
        let copy = view.decode_tree(&mut nodes, &mut order).unwrap();
        assert_eq!(copy.split_refs(), scene.split_refs());
        assert_eq!(copy.order(), scene.bvh().order());
    }

    // Damage the table, reseal, and the loaders refuse it.
    let bytes = scene.to_blob(MeshLayout::Indexed).unwrap();
    let h = meshq::advanced::BlobHeader::read(&bytes).unwrap();
    // Each array is a varint count, then its records.
    let varint = |n: u32| (32 - n.leading_zeros()).div_ceil(7).max(1) as usize;
    let order_at = h.header_len + varint(h.node_count) + 32 * h.node_count as usize;
    let table_at = order_at
        + varint(h.reference_count)
        + 4 * h.reference_count as usize
        + varint(h.split_ref_count);
    let entries = h.split_ref_count as usize;
    let damaged = |entry: usize, word: usize, value: u32| {
        let mut b = bytes.clone();
        let at = table_at + 32 * entry + 4 * word;
        b[at..at + 4].copy_from_slice(&value.to_le_bytes());
        reseal(&mut b).unwrap();
        b
    };
    let read = |b: &[u8]| (BlobView::parse(b).err(), MeshBvh::from_blob(b).err());
    let first = scene.split_refs().get(0).unwrap();
    let second = scene.split_refs().get(1).unwrap();
    for (what, b) in [
        ("slot of another triangle", damaged(0, 1, first.slot ^ 1)),
        ("out of order", damaged(0, 1, second.slot + 1)),
        (
            "triangle out of range",
            damaged(0, 0, mesh.triangle_count() as u32),
        ),
        ("box", damaged(3, 2, 0.123f32.to_bits())),
        (
            "last entry's box",
            damaged(entries - 1, 6, 7.5f32.to_bits()),
        ),
    ] {
        let (view, owned) = read(&b);
        assert!(
            matches!(view, Some(meshq::error::BlobError::BadSplitRef { .. })),
            "{what}: {view:?}"
        );
        assert_eq!(view, owned, "{what}");
    }
    // A packed blob whose two slots of one split triangle hold its corners in another order:
    // the same points, other bytes. Found by the fuzzer (the view and the owned loader, which
    // keeps one corner triple per triangle, disagreed); now both refuse it alike.
    let packed = scene.to_blob(MeshLayout::Packed).unwrap();
    let hp = meshq::advanced::BlobHeader::read(&packed).unwrap();
    let corners_at = {
        let order_at = hp.header_len + varint(hp.node_count) + 32 * hp.node_count as usize;
        let table_at = order_at + varint(hp.reference_count) + 4 * hp.reference_count as usize;
        let roles_at = table_at + varint(hp.split_ref_count) + 32 * hp.split_ref_count as usize;
        // The collapse roles (version 5): two bits per node.
        let roles = (hp.node_count as usize).div_ceil(4);
        let mesh_at = roles_at + varint(roles as u32) + roles;
        // The layout tag, then the corner triples' count.
        mesh_at + 1 + varint(hp.reference_count)
    };
    let mut b = packed.clone();
    let at = corners_at + 36 * second.slot as usize;
    b[at..at + 36].rotate_left(12);
    reseal(&mut b).unwrap();
    let (view, owned) = read(&b);
    assert_eq!(
        view,
        Some(meshq::error::BlobError::BadSplitRef { entry: 1 })
    );
    assert_eq!(owned, view);

    // A slot naming a split triangle once more than its entries say.
    let order_at = order_at + varint(h.reference_count);
    let mut b = bytes.clone();
    let lone = scene
        .bvh()
        .order()
        .iter()
        .position(|&t| scene.split_refs().range_of(t).is_empty())
        .unwrap();
    b[order_at + 4 * lone..order_at + 4 * lone + 4].copy_from_slice(&first.tri.to_le_bytes());
    reseal(&mut b).unwrap();
    let (view, owned) = read(&b);
    assert!(view.is_some(), "repeat without an entry: {view:?}");
    assert!(owned.is_some());
}

#[test]
fn blob_versions_follow_what_the_tree_needs() {
    use meshq::blob::{self, BlobView, EncodeOptions, MeshLayout};
    let loaded = load_mesh("spot");
    let mesh = loaded.valid();
    let brute = BruteForce::new(&mesh);
    let plain = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
    let split =
        MeshBvh::build_spatial(&mesh, &BuildConfig::default(), &SpatialSplits::DEFAULT).unwrap();
    // With collapse roles (`MeshBvh::to_blob`): version 5, which counts slots and split
    // references whether or not there are any.
    let bytes = plain.to_blob(MeshLayout::Indexed).unwrap();
    let h = BlobHeader::read(&bytes).unwrap();
    assert_eq!((h.version, h.split_ref_count), (5, 0));
    assert_eq!(h.reference_count as usize, mesh.triangle_count());
    // Without them (`encode_into` with the default options): version 3 for a tree without
    // spatial splits, 4 for one with them, and each answers as brute force.
    for (tree, version) in [(&plain, 3), (&split, 4)] {
        let options = EncodeOptions::default();
        let mut bytes = vec![0; blob::encoded_len(&tree.bvh(), &mesh, &options).unwrap()];
        blob::encode_into(&tree.bvh(), &mesh, &options, &mut bytes).unwrap();
        let view = BlobView::parse(&bytes).unwrap();
        assert_eq!(view.header().version, version);
        assert!(view.tree().unwrap().collapse_roles().is_none());
        check_all(
            &view,
            &brute,
            &loaded,
            &format!("version {version}, in place"),
        );
        let owned = MeshBvh::from_blob(&bytes).unwrap();
        check_all(
            &owned,
            &brute,
            &loaded,
            &format!("version {version}, loaded"),
        );
    }
}

/// Found by the fuzz target (`fuzz/fuzz_targets/blob_parse.rs`), which compares
/// `MeshBvh::from_blob` with the view: a blob with spatial splits whose triangle 18 had a
/// corner moved far from both leaves its split references name (their boxes overlap the
/// triangle's box, which was all the containment check asked of a split triangle). The view
/// and the owned copy then walked to different closest points, and neither matched a scan of
/// the triangles. Both loaders now refuse it: the leaves of a split triangle must hold its
/// corners and edges.
#[test]
fn a_split_triangle_outside_its_leaves_is_refused() {
    use meshq::blob::BlobView;
    use meshq::error::{BlobError, StructureError};
    let bytes = meshq_tests::fuzz_blob("fuzz-split-uncovered.bin");
    let want = BlobError::InvalidNode(StructureError::SplitTriangleUncovered { tri: 18 });
    assert_eq!(BlobView::parse(&bytes).unwrap_err(), want);
    assert_eq!(MeshBvh::from_blob(&bytes).unwrap_err(), want);
}
