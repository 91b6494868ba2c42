//! Blobs round-trip on every bundled mesh and layout: a view parsed from the bytes answers
//! every query exactly as brute force and the in-memory BVH do (same bits, same triangle), the
//! decoded arrays equal the originals, and the bytes are a genuine postcard message that
//! postcard's own deserializer reads back.

use std::ops::ControlFlow;

use meshq::MeshBvh;
use meshq::advanced::PackedTriangle;
use meshq::advanced::{BvhNode, FORMAT_VERSION, mesh_checksum};
use meshq::blob::{BlobView, MeshLayout, StructureKind};
use meshq::bvh::BuildConfig;
use meshq::math::{Aabb, ClosestPoint, RayHit, Vec3};
use meshq::query::RayOptions;
use meshq::{MeshQuery, Traverse};
use meshq_tests::oracle::BruteForce;
use meshq_tests::{MESHES, checked_bvh, load_mesh, workload};
use serde::Deserialize;

const RAYS: usize = 20_000;
const POINTS: usize = 3_000;
const LAYOUTS: [MeshLayout; 3] = [MeshLayout::Indexed, MeshLayout::Packed, MeshLayout::Omitted];

fn hit_key(h: Option<RayHit>) -> Option<(u32, u32, u32, u32)> {
    h.map(|h| (h.t.to_bits(), h.tri, h.u.to_bits(), h.v.to_bits()))
}

fn point_key(c: Option<ClosestPoint>) -> Option<(u32, u32, [u32; 3])> {
    c.map(|c| {
        (
            c.distance_squared.to_bits(),
            c.tri,
            c.point.to_array().map(f32::to_bits),
        )
    })
}

#[test]
fn views_answer_like_brute_force_and_the_in_memory_bvh() {
    for name in MESHES {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        let config = BuildConfig::default();
        let owned = MeshBvh::build(&mesh, &config).unwrap();
        let bvh = checked_bvh(&owned, &mesh).unwrap();
        let brute = BruteForce::new(&mesh);
        let rays = workload::random_rays(&loaded.positions, RAYS, 0xB10B);
        let points = workload::closest_points(&loaded.positions, POINTS, 0xB10C);
        let (c, r, _) = workload::centre_radius(&loaded.positions);
        for layout in LAYOUTS {
            let bytes = owned.to_blob(layout).unwrap();
            let view = match layout {
                MeshLayout::Omitted => BlobView::parse_with_mesh(&bytes, mesh).unwrap(),
                _ => BlobView::parse(&bytes).unwrap(),
            };
            let h = view.header();
            // `MeshBvh::to_blob` stores the collapse roles: version 5 (6 adds expansions).
            assert_eq!((h.version, FORMAT_VERSION), (5, 6));
            assert_eq!(h.kind, StructureKind::Bvh);
            assert_eq!(h.mesh, layout);
            assert_eq!(h.triangle_count as usize, mesh.triangle_count());
            assert_eq!(h.vertex_count as usize, mesh.vertex_count());
            assert_eq!(h.node_count as usize, bvh.nodes().len());
            assert_eq!(h.depth, bvh.depth());
            assert_eq!(h.config, meshq::blob::StructureConfig::Bvh(config));
            assert_eq!(h.reference_count, h.triangle_count);
            assert_eq!(h.total_len, bytes.len());
            assert_eq!(h.mesh_checksum, mesh_checksum(&mesh));
            assert_eq!(view.bounds(), bvh.bounds());

            for (i, ray) in rays.iter().enumerate() {
                let got = view.raycast(ray);
                assert_eq!(
                    hit_key(got),
                    hit_key(bvh.with(&mesh).raycast(ray)),
                    "{name} {layout:?} ray {i}"
                );
                assert_eq!(
                    view.raycast_any(ray),
                    got.is_some(),
                    "{name} {layout:?} any {i}"
                );
                if i % 10 == 0 {
                    let expected = brute.raycast(ray, &RayOptions::default());
                    assert_eq!(
                        hit_key(got),
                        hit_key(expected),
                        "{name} {layout:?} brute ray {i}"
                    );
                }
            }
            for (i, &p) in points.iter().enumerate() {
                let got = view.closest_point(p, f32::INFINITY);
                assert_eq!(
                    point_key(got),
                    point_key(bvh.with(&mesh).closest_point(p, f32::INFINITY)),
                    "{name} {layout:?} point {i}"
                );
                if i % 10 == 0 {
                    let expected = brute.closest_point(p, f32::INFINITY);
                    assert_eq!(
                        point_key(got),
                        point_key(expected),
                        "{name} {layout:?} brute point {i}"
                    );
                }
            }
            // Overlaps: same set as brute force (traversal order may differ from sorted).
            for (k, &centre) in points.iter().take(20).enumerate() {
                let half = Vec3::splat(0.08 * r);
                let aabb = Aabb::new(centre - half, centre + half);
                let mut got = Vec::new();
                view.overlap_aabb(&aabb, |t| {
                    got.push(t);
                    ControlFlow::Continue(())
                });
                got.sort_unstable();
                assert_eq!(got, brute.overlap_aabb(&aabb), "{name} {layout:?} box {k}");
                let mut buf = vec![0u32; 4];
                let count = view.overlap_sphere_into(centre, 0.1 * r, &mut buf);
                assert_eq!(count.total, brute.overlap_sphere(centre, 0.1 * r).len());
            }
            // The tree alone answers through the common trait with the caller's mesh.
            let ray = meshq::math::Ray::new(c + Vec3::new(0.0, 0.0, 3.0 * r), -Vec3::Z);
            assert_eq!(
                hit_key(
                    view.tree()
                        .unwrap()
                        .with(&mesh)
                        .raycast_with(&ray, &RayOptions::default())
                ),
                hit_key(bvh.with(&mesh).raycast(&ray))
            );
        }
    }
}

#[test]
fn decoding_into_caller_slices_restores_the_arrays() {
    for name in MESHES {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        let config = BuildConfig::fast();
        let owned = MeshBvh::build(&mesh, &config).unwrap();
        let bvh = checked_bvh(&owned, &mesh).unwrap();
        let mut expected_packed = vec![PackedTriangle::EMPTY; mesh.triangle_count()];
        bvh.pack_triangles(&mesh, &mut expected_packed).unwrap();
        for layout in LAYOUTS {
            let bytes = owned.to_blob(layout).unwrap();
            let view = match layout {
                MeshLayout::Omitted => BlobView::parse_with_mesh(&bytes, mesh).unwrap(),
                _ => BlobView::parse(&bytes).unwrap(),
            };
            let mut nodes = vec![BvhNode::EMPTY; owned.bvh().nodes().len()];
            let mut order = vec![0u32; owned.bvh().order().len()];
            // One element short is an error, never a partial copy.
            assert!(view.decode_tree(&mut nodes[1..], &mut order).is_err());
            let tree = view.decode_tree(&mut nodes, &mut order).unwrap();
            assert_eq!(tree.depth(), bvh.depth());
            assert_eq!(tree.nodes(), owned.bvh().nodes());
            assert_eq!(tree.order(), owned.bvh().order());

            let mut packed = vec![PackedTriangle::EMPTY; mesh.triangle_count()];
            let p = view.decode_packed(&mut packed).unwrap();
            assert_eq!(p.as_slice(), &expected_packed[..], "{name} {layout:?}");

            let mut positions = vec![[0.0f32; 3]; mesh.vertex_count()];
            let mut triangles = vec![[0u32; 3]; mesh.triangle_count()];
            match layout {
                MeshLayout::Packed => {
                    assert!(view.decode_mesh(&mut positions, &mut triangles).is_err());
                }
                _ => {
                    let m = view.decode_mesh(&mut positions, &mut triangles).unwrap();
                    assert_eq!(m.positions(), mesh.positions());
                    assert_eq!(m.triangles(), mesh.triangles());
                }
            }
        }
    }
}

/// CRC-32/ISO-HDLC by its definition, one bit at a time: the reference the blob checksum is
/// checked against, apart from each of the ways meshq computes it (the `crc32fast` crate with
/// `std`, sixteen byte lanes, the `crc` crate's tables).
fn crc32_bitwise(parts: &[&[u8]]) -> u32 {
    let mut register = !0u32;
    for &byte in parts.iter().flat_map(|p| p.iter()) {
        register ^= u32::from(byte);
        for _ in 0..8 {
            let low = register & 1;
            register >>= 1;
            if low != 0 {
                register ^= 0xEDB8_8320;
            }
        }
    }
    !register
}

/// The reference above agrees with CRC-32/ISO-HDLC's published check value (the CRC of the
/// ASCII digits "123456789").
#[test]
fn the_reference_crc_gives_the_published_check_value() {
    assert_eq!(crc32_bitwise(&[b"12345", b"6789"]), 0xCBF4_3926);
}

/// The checksum a blob carries is CRC-32/ISO-HDLC of every other byte, on every bundled mesh
/// and layout (blobs large enough for the fast paths and small ones), and the mesh checksum
/// the CRC of the mesh's words.
#[test]
fn the_blob_checksum_is_the_crc_of_every_other_byte() {
    for name in MESHES {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        for layout in LAYOUTS {
            let bytes = meshq_tests::bake(&mesh, &BuildConfig::default(), layout).unwrap();
            let header = match layout {
                MeshLayout::Omitted => *BlobView::parse_with_mesh(&bytes, mesh).unwrap().header(),
                _ => *BlobView::parse(&bytes).unwrap().header(),
            };
            let at = header.header_len - 4;
            let want = crc32_bitwise(&[&bytes[..at], &bytes[header.header_len..]]);
            let stored = u32::from_le_bytes(bytes[at..header.header_len].try_into().unwrap());
            assert_eq!(stored, header.checksum, "{name} {layout:?}");
            assert_eq!(stored, want, "{name} {layout:?}");
        }
        // The mesh checksum: every coordinate, then every index, as little-endian words.
        let words: Vec<u8> = mesh
            .positions()
            .iter()
            .flatten()
            .map(|c| c.to_bits())
            .chain(mesh.triangles().iter().flatten().copied())
            .flat_map(u32::to_le_bytes)
            .collect();
        assert_eq!(mesh_checksum(&mesh), crc32_bitwise(&[&words]), "{name}");
    }
}

#[test]
fn blobs_are_deterministic_and_sized_exactly() {
    let loaded = load_mesh("spot");
    let mesh = loaded.valid();
    for config in [
        BuildConfig::fast(),
        BuildConfig::balanced(),
        BuildConfig::high_quality(),
    ] {
        for layout in LAYOUTS {
            let a = meshq_tests::bake(&mesh, &config, layout).unwrap();
            let b = meshq_tests::bake(&mesh, &config, layout).unwrap();
            assert_eq!(a, b, "{config:?} {layout:?}");
        }
    }
    // Sizes follow the record widths: 32 bytes per node, 4 per order entry, and 12 per vertex
    // plus 12 per triangle (indexed) or 36 per triangle (packed), plus small varint lengths.
    let config = BuildConfig::default();
    let owned = MeshBvh::build(&mesh, &config).unwrap();
    let bvh = checked_bvh(&owned, &mesh).unwrap();
    let (n, t, v) = (
        bvh.nodes().len(),
        mesh.triangle_count(),
        mesh.vertex_count(),
    );
    let omitted = owned.to_blob(MeshLayout::Omitted).unwrap().len();
    let indexed = owned.to_blob(MeshLayout::Indexed).unwrap().len();
    let packed = owned.to_blob(MeshLayout::Packed).unwrap().len();
    // Nodes, order, and the collapse roles: two bits per node.
    let arrays = 32 * n + 4 * t + n.div_ceil(4);
    assert!(
        omitted > arrays && omitted < arrays + 128,
        "{omitted} vs {arrays}"
    );
    assert!(indexed - omitted >= 12 * v + 12 * t && indexed - omitted < 12 * v + 12 * t + 16);
    assert!(packed - omitted >= 36 * t && packed - omitted < 36 * t + 16);
}

/// Mirror types: the blob decoded by postcard itself into owned values.
#[derive(Deserialize, Debug)]
struct WholeBlob {
    magic: [u8; 4],
    version: u16,
    kind: u32,
    mesh: u32,
    triangle_count: u32,
    vertex_count: u32,
    node_count: u32,
    depth: u32,
    bounds_min: [f32; 3],
    bounds_max: [f32; 3],
    config: ConfigMirror,
    slots: u32,
    split_ref_count: u32,
    #[serde(with = "postcard::fixint::le")]
    mesh_checksum: u32,
    #[serde(with = "postcard::fixint::le")]
    payload_len: u64,
    #[serde(with = "postcard::fixint::le")]
    checksum: u32,
    nodes: Vec<NodeMirror>,
    order: Vec<Fixed>,
    split_refs: Vec<[u8; 32]>,
    roles: Vec<u8>,
    /// Version 6: the 28 floats of each node's winding-number expansion.
    winding: Vec<[f32; 28]>,
    section: SectionMirror,
}

/// The config as the format documents it: the split tag, then the rest.
#[derive(Deserialize, Debug, PartialEq)]
struct ConfigMirror {
    split: u32,
    bins: u32,
    max_leaf_size: u32,
    max_depth: u32,
    traversal_cost: f32,
    triangle_cost: f32,
}

#[derive(Deserialize, Debug, PartialEq)]
struct NodeMirror {
    min: [f32; 3],
    #[serde(with = "postcard::fixint::le")]
    first: u32,
    max: [f32; 3],
    #[serde(with = "postcard::fixint::le")]
    count: u32,
}

#[derive(Deserialize, Debug, PartialEq)]
struct Fixed(#[serde(with = "postcard::fixint::le")] u32);

#[derive(Deserialize, Debug)]
enum SectionMirror {
    Indexed(Vec<[f32; 3]>, Vec<(Fixed, Fixed, Fixed)>),
    Packed(Vec<[[f32; 3]; 3]>),
    Omitted,
}

#[test]
fn a_blob_is_one_postcard_message() {
    let loaded = load_mesh("teapot");
    let mesh = loaded.valid();
    for (config, split_tag, layout) in [
        (BuildConfig::default(), 0, MeshLayout::Indexed),
        (BuildConfig::default(), 0, MeshLayout::Packed),
        (BuildConfig::default(), 0, MeshLayout::Omitted),
        (BuildConfig::fast(), 1, MeshLayout::Indexed),
    ] {
        // With its winding-number expansions: the newest version, every section present.
        let owned = MeshBvh::build(&mesh, &config)
            .and_then(MeshBvh::with_winding_numbers)
            .unwrap();
        let bvh = checked_bvh(&owned, &mesh).unwrap();
        let bytes = owned.to_blob(layout).unwrap();
        let whole: WholeBlob = postcard::from_bytes(&bytes).unwrap();
        // from_bytes ignores trailing bytes; the message must use every byte.
        let (_, rest) = postcard::take_from_bytes::<WholeBlob>(&bytes).unwrap();
        assert!(rest.is_empty(), "{layout:?}");
        assert_eq!(&whole.magic, b"MSHQ");
        assert_eq!(whole.version, FORMAT_VERSION);
        assert_eq!((whole.kind, whole.mesh), (0, layout.tag()));
        assert_eq!(whole.triangle_count as usize, mesh.triangle_count());
        assert_eq!(whole.vertex_count as usize, mesh.vertex_count());
        assert_eq!(whole.node_count as usize, owned.bvh().nodes().len());
        assert_eq!(whole.depth, bvh.depth());
        assert_eq!(whole.bounds_min, bvh.bounds().min.to_array());
        assert_eq!(whole.bounds_max, bvh.bounds().max.to_array());
        let c = &whole.config;
        assert_eq!(
            (c.split, c.bins, c.max_leaf_size, c.max_depth),
            (
                split_tag,
                config.bins,
                config.max_leaf_size,
                config.max_depth
            )
        );
        assert_eq!(
            (c.traversal_cost, c.triangle_cost),
            (config.traversal_cost, config.triangle_cost)
        );
        assert_eq!(whole.mesh_checksum, mesh_checksum(&mesh));
        assert!(whole.payload_len > 0);
        assert_ne!(whole.checksum, 0);
        let nodes: Vec<NodeMirror> = owned
            .bvh()
            .nodes()
            .iter()
            .map(|n| NodeMirror {
                min: n.min,
                first: n.first,
                max: n.max,
                count: n.count,
            })
            .collect();
        assert_eq!(whole.nodes, nodes);
        assert_eq!(
            whole.order,
            owned
                .bvh()
                .order()
                .iter()
                .map(|&i| Fixed(i))
                .collect::<Vec<_>>()
        );
        // A tree without spatial splits: as many slots as triangles, no split references.
        assert_eq!(whole.slots as usize, mesh.triangle_count());
        assert_eq!(whole.split_ref_count, 0);
        assert!(whole.split_refs.is_empty());
        // Two bits per node, the root (inner) starting a wide node (`tests/collapse_roles.rs`
        // decodes them in full).
        assert_eq!(whole.roles.len(), whole.nodes.len().div_ceil(4));
        assert_eq!(whole.roles[0] & 3, 1);
        // Each expansion's fields in order: centre, radius, normal, area, first, second.
        let expansions: Vec<[f32; 28]> = owned
            .winding()
            .unwrap()
            .nodes()
            .iter()
            .map(|n| {
                let mut words = [0.0; 28];
                let fields = n.centre.iter().chain([&n.radius]).chain(&n.normal);
                let fields = fields.chain([&n.area]).chain(&n.first).chain(&n.second);
                for (w, x) in words.iter_mut().zip(fields) {
                    *w = *x;
                }
                words
            })
            .collect();
        assert_eq!(whole.winding.len(), whole.nodes.len());
        assert!(
            whole
                .winding
                .iter()
                .map(|w| w.map(f32::to_bits))
                .eq(expansions.iter().map(|w| w.map(f32::to_bits)))
        );
        match (layout, whole.section) {
            (MeshLayout::Indexed, SectionMirror::Indexed(p, t)) => {
                assert_eq!(p, mesh.positions());
                let t: Vec<[u32; 3]> = t.into_iter().map(|(a, b, c)| [a.0, b.0, c.0]).collect();
                assert_eq!(t, mesh.triangles());
            }
            (MeshLayout::Packed, SectionMirror::Packed(p)) => {
                for (slot, corners) in p.iter().enumerate() {
                    let t = mesh.triangle(owned.bvh().order()[slot]).unwrap();
                    assert_eq!(*corners, [t.a.to_array(), t.b.to_array(), t.c.to_array()]);
                }
            }
            (MeshLayout::Omitted, SectionMirror::Omitted) => {}
            (l, s) => panic!("{l:?} decoded as {s:?}"),
        }
    }
}

#[test]
fn format_1_blobs_still_load_and_answer_exactly() {
    // Baked by the format-1 writer (before the split strategy was recorded) from the OBJ next
    // to it; this build must still read it, as binned SAH, and answer like brute force.
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures");
    let bytes = std::fs::read(dir.join("wavy-grid-format1.msq")).unwrap();
    let loaded = meshq_tests::load_obj(&dir.join("wavy-grid.obj"));
    let mesh = loaded.valid();
    let view = BlobView::parse(&bytes).unwrap();
    let h = view.header();
    assert_eq!(h.version, 1);
    assert_ne!(h.version, FORMAT_VERSION);
    // The balanced preset of the day it was baked.
    assert_eq!(
        h.config,
        meshq::blob::StructureConfig::Bvh(BuildConfig {
            split: meshq::bvh::SplitStrategy::Sah,
            bins: 32,
            max_leaf_size: 4,
            max_depth: meshq::bvh::MAX_DEPTH,
            traversal_cost: 1.0,
            triangle_cost: 1.0,
        })
    );
    assert_eq!(h.mesh_checksum, mesh_checksum(&mesh));
    assert_eq!(h.triangle_count as usize, mesh.triangle_count());
    let brute = BruteForce::new(&mesh);
    let options = RayOptions::default();
    let rays = workload::random_rays(&loaded.positions, 2_000, 0xF1);
    let hits = rays
        .iter()
        .filter(|r| {
            let got = view.raycast_with(r, &options);
            assert_eq!(hit_key(got), hit_key(brute.raycast(r, &options)), "{r:?}");
            got.is_some()
        })
        .count();
    assert!(hits > 100, "only {hits} hits: the rays miss the grid");
    for p in workload::closest_points(&loaded.positions, 500, 0xF2) {
        assert_eq!(
            point_key(view.closest_point(p, f32::INFINITY)),
            point_key(brute.closest_point(p, f32::INFINITY)),
            "{p}"
        );
    }
}
