//! Blobs of k-d trees, octrees and grids: queried in place and loaded, they answer as a scan of
//! every triangle does; their bytes follow the documented wire format (read here by an
//! independent serde mirror); damage is refused or harmless, never a panic.

use meshq::MeshBvh;
use meshq::advanced::mesh_checksum;
use meshq::blob::{self, BlobStructure, BlobView, MeshLayout};
use meshq::error::BlobError;
use meshq::math::Aabb;
use meshq::mesh::{MeshRef, ValidMesh};
use meshq::owned::{MeshIndex, StructureKind};
use meshq_tests::oracle::BruteForce;
use meshq_tests::suite::check_all;
use meshq_tests::{LoadedMesh, in_stadium, load_mesh, spot_patch};
use serde::Deserialize;

const CELL_KINDS: [StructureKind; 3] = [
    StructureKind::KdTree,
    StructureKind::Octree,
    StructureKind::Grid,
];
const LAYOUTS: [MeshLayout; 3] = [MeshLayout::Indexed, MeshLayout::Packed, MeshLayout::Omitted];

/// A view over `bytes`, with the caller's mesh when the blob has none.
fn view<'a>(bytes: &'a [u8], mesh: ValidMesh<'a>, layout: MeshLayout) -> BlobView<'a> {
    if layout == MeshLayout::Omitted {
        assert_eq!(
            BlobView::parse(bytes).unwrap_err(),
            BlobError::MeshNotIncluded
        );
        BlobView::parse_with_mesh(bytes, mesh).unwrap()
    } else {
        BlobView::parse(bytes).unwrap()
    }
}

fn check_mesh(loaded: &LoadedMesh) {
    let mesh = loaded.valid();
    let brute = BruteForce::new(&mesh);
    for kind in CELL_KINDS {
        let built = MeshIndex::build(&mesh, kind).unwrap();
        let stats = built.cell_stats().unwrap();
        for layout in LAYOUTS {
            let what = format!("{} {kind} blob, mesh {}", loaded.name, layout.name());
            let bytes = built.to_blob(layout).unwrap();
            assert_eq!(bytes.len(), built.encoded_len(layout).unwrap(), "{what}");
            assert_eq!(
                bytes,
                built.to_blob(layout).unwrap(),
                "{what}: deterministic"
            );
            let v = view(&bytes, mesh, layout);
            let h = v.header();
            // Cell structures need nothing of versions 4 and 5 (a BVH's spatial splits and
            // collapse roles).
            assert_eq!((h.version, h.kind, h.mesh), (3, kind, layout));
            assert_eq!(h.reference_count as usize, stats.references, "{what}");
            assert_eq!(h.depth as usize, stats.max_depth, "{what}");
            assert_eq!(h.mesh_checksum, mesh_checksum(&mesh));
            assert!(v.tree().is_none(), "{what}: not a BVH");
            assert_eq!(v.structure().kind(), kind);
            assert_eq!(v.structure().cell_stats(mesh.triangle_count()), Some(stats));
            check_all(&v, &brute, loaded, &format!("{what}, in place"));

            let (header, structure) = BlobStructure::parse(&bytes).unwrap();
            assert_eq!((header, structure.kind()), (*h, kind));

            let loaded_index = if layout == MeshLayout::Omitted {
                MeshIndex::from_blob_with_mesh(&bytes, &mesh).unwrap()
            } else {
                MeshIndex::from_blob(&bytes).unwrap()
            };
            assert_eq!(loaded_index.kind(), kind);
            assert_eq!(loaded_index.cell_stats(), Some(stats), "{what}");
            check_all(&loaded_index, &brute, loaded, &format!("{what}, loaded"));
            if layout != MeshLayout::Packed {
                // The indexed mesh comes back exactly, so the blob does too.
                assert_eq!(loaded_index.to_blob(layout).unwrap(), bytes, "{what}");
            }
        }
    }
}

#[test]
fn cell_blobs_answer_as_brute_force_in_place_and_loaded() {
    for name in ["cow", "fandisk"] {
        check_mesh(&load_mesh(name));
    }
    check_mesh(&in_stadium(&load_mesh("teapot")));
}

/// A packed blob copies a triangle into every cell that lists it, and loading proves each
/// copy's cells: walked copy by copy, a triangle that thousands of cells list costs the square
/// of that (the bunny's stadium floor: two triangles in 60,000 cells took minutes). A copy whose
/// first cell shows an earlier, already proved copy with the same corners stops there, so the
/// proof is linear in the references, and this test loads in a moment; it still refuses what
/// the damage tests below give it.
#[test]
fn a_packed_grid_blob_whose_triangles_fill_every_cell_loads_and_answers() {
    let loaded = in_stadium(&load_mesh("stanford-bunny"));
    let mesh = loaded.valid();
    let built = MeshIndex::build(&mesh, StructureKind::Grid).unwrap();
    let stats = built.cell_stats().unwrap();
    // The floor's two triangles are in every cell of the grid's floor layer: tens of
    // thousands of copies of each (walked one by one, minutes of work).
    assert!(
        stats.cells > 100_000 && stats.references > mesh.triangle_count() + 50_000,
        "{stats:?}"
    );
    let bytes = built.to_blob(MeshLayout::Packed).unwrap();
    let v = view(&bytes, mesh, MeshLayout::Packed);
    let brute = BruteForce::new(&mesh);
    check_all(
        &v,
        &brute,
        &loaded,
        "bunny in a stadium, packed grid, in place",
    );
    let loaded_index = MeshIndex::from_blob(&bytes).unwrap();
    assert_eq!(loaded_index.cell_stats(), Some(stats));
}

#[derive(Deserialize, Debug)]
struct CountsMirror {
    kind: u32,
    mesh: u32,
    triangle_count: u32,
    vertex_count: u32,
    node_count: u32,
    depth: u32,
    bounds_min: [f32; 3],
    bounds_max: [f32; 3],
}

#[derive(Deserialize, Debug, PartialEq)]
struct Fixed(#[serde(with = "postcard::fixint::le")] u32);

#[derive(Deserialize, Debug)]
struct SealMirror {
    #[serde(with = "postcard::fixint::le")]
    mesh_checksum: u32,
    #[serde(with = "postcard::fixint::le")]
    payload_len: u64,
    checksum: Fixed,
}

#[derive(Deserialize, Debug)]
enum SectionMirror {
    Indexed(Vec<[f32; 3]>, Vec<(Fixed, Fixed, Fixed)>),
    Packed(Vec<[[f32; 3]; 3]>),
    Omitted,
}

#[derive(Deserialize, Debug)]
struct PayloadMirror {
    words: Vec<Fixed>,
    references: Vec<Fixed>,
    section: SectionMirror,
}

/// Reads one postcard value off the front of `rest`.
fn take<'a, T: Deserialize<'a>>(rest: &mut &'a [u8]) -> T {
    let (value, tail) = postcard::take_from_bytes::<T>(rest).unwrap();
    *rest = tail;
    value
}

/// The wire format as the module docs describe it, decoded field by field with serde, and
/// compared with the structure in memory.
#[test]
fn a_cell_blob_is_one_postcard_message() {
    let loaded = load_mesh("teapot");
    let mesh = loaded.valid();
    for kind in CELL_KINDS {
        for layout in LAYOUTS {
            let built = MeshIndex::build(&mesh, kind).unwrap();
            let bytes = built.to_blob(layout).unwrap();
            let mut rest = &bytes[..];
            assert_eq!(take::<[u8; 4]>(&mut rest), *b"MSHQ");
            assert_eq!(take::<u16>(&mut rest), 3);
            let c: CountsMirror = take(&mut rest);
            assert_eq!((c.kind, c.mesh), (kind.tag(), layout.tag()));
            assert_eq!(c.triangle_count as usize, mesh.triangle_count());
            assert_eq!(c.vertex_count as usize, mesh.vertex_count());
            let (words, items, bounds, references, depth): (Vec<u32>, Vec<u32>, Aabb, u32, u32) =
                match &built {
                    MeshIndex::KdTree(s) => {
                        let t = s.structure();
                        let w: (u32, u32, f32, f32, f32, u32) = take(&mut rest);
                        let k = s.config();
                        assert_eq!(
                            (w.0, w.1, w.2, w.3, w.4),
                            (
                                k.max_depth,
                                k.leaf_size,
                                k.traversal_cost,
                                k.triangle_cost,
                                k.empty_bonus
                            )
                        );
                        assert_eq!(c.node_count as usize, t.node_count());
                        let words = t.nodes().iter().flat_map(|n| [n.a, n.b]).collect();
                        let depth = s.stats().max_depth as u32;
                        (words, t.items().to_vec(), *t.bounds(), w.5, depth)
                    }
                    MeshIndex::Octree(s) => {
                        let t = s.structure();
                        let w: (u32, u32, u32) = take(&mut rest);
                        assert_eq!((w.0, w.1), (s.config().max_depth, s.config().max_items));
                        assert_eq!(c.node_count as usize, t.node_count());
                        let words = t.nodes().iter().flat_map(|n| [n.a, n.b]).collect();
                        let depth = s.stats().max_depth as u32;
                        (words, t.items().to_vec(), *t.bounds(), w.2, depth)
                    }
                    MeshIndex::Grid(s) => {
                        let g = s.structure();
                        let w: (f32, u32, [u32; 3], u32) = take(&mut rest);
                        assert_eq!(
                            (w.0, w.1, w.2),
                            (
                                s.config().cells_per_triangle,
                                s.config().max_resolution,
                                g.layout().resolution
                            )
                        );
                        assert_eq!(c.node_count as usize, g.offsets().len() - 1);
                        (
                            g.offsets().to_vec(),
                            g.items().to_vec(),
                            g.layout().bounds,
                            w.3,
                            0,
                        )
                    }
                    MeshIndex::Bvh(_) => unreachable!(),
                };
            assert_eq!(c.depth, depth, "{kind}");
            assert_eq!(
                (c.bounds_min, c.bounds_max),
                (bounds.min.to_array(), bounds.max.to_array())
            );
            assert_eq!(references as usize, items.len());
            let seal: SealMirror = take(&mut rest);
            assert_eq!(seal.mesh_checksum, mesh_checksum(&mesh));
            assert_eq!(seal.payload_len as usize, rest.len());
            assert_ne!(seal.checksum.0, 0);
            let (p, tail) = postcard::take_from_bytes::<PayloadMirror>(rest).unwrap();
            assert!(
                tail.is_empty(),
                "{kind} {layout:?}: one message, every byte used"
            );
            assert_eq!(p.words.into_iter().map(|f| f.0).collect::<Vec<_>>(), words);
            assert_eq!(
                p.references.iter().map(|f| f.0).collect::<Vec<_>>(),
                items,
                "{kind}"
            );
            match (layout, p.section) {
                (MeshLayout::Indexed, SectionMirror::Indexed(pos, tris)) => {
                    assert_eq!(pos, mesh.positions());
                    let tris: Vec<[u32; 3]> =
                        tris.into_iter().map(|(a, b, c)| [a.0, b.0, c.0]).collect();
                    assert_eq!(tris, mesh.triangles());
                }
                (MeshLayout::Packed, SectionMirror::Packed(corners)) => {
                    assert_eq!(corners.len(), items.len());
                    for (corners, &tri) in corners.iter().zip(&items) {
                        let t = mesh.triangle(tri).unwrap();
                        assert_eq!(*corners, [t.a.to_array(), t.b.to_array(), t.c.to_array()]);
                    }
                }
                (MeshLayout::Omitted, SectionMirror::Omitted) => {}
                (l, s) => panic!("{l:?} decoded as {s:?}"),
            }
        }
    }
}

/// Raw damage to any byte is refused (the checksum); damage with the checksum recomputed is
/// refused by validation or gives a view that queries safely; every truncation is refused.
#[test]
fn damaged_cell_blobs_are_refused_or_harmless() {
    let (positions, triangles) = spot_patch();
    let mesh = MeshRef::new(&positions, &triangles).validate().unwrap();
    for kind in CELL_KINDS {
        for layout in [MeshLayout::Indexed, MeshLayout::Packed] {
            let bytes = MeshIndex::build(&mesh, kind)
                .unwrap()
                .to_blob(layout)
                .unwrap();
            assert!(meshq_tests::suite::exercise(&BlobView::parse(&bytes).unwrap()) > 0);
            let (mut refused, mut accepted) = (0, 0);
            for i in 0..bytes.len() {
                for flip in [0x01u8, 0x80, 0xFF] {
                    let mut damaged = bytes.clone();
                    damaged[i] ^= flip;
                    assert!(
                        BlobView::parse(&damaged).is_err(),
                        "{kind} {layout:?} byte {i} ^ {flip:#x}"
                    );
                    if meshq::advanced::reseal(&mut damaged).is_ok() {
                        match BlobView::parse(&damaged) {
                            Ok(view) => {
                                meshq_tests::suite::exercise(&view);
                                accepted += 1;
                            }
                            Err(_) => refused += 1,
                        }
                    }
                }
            }
            for n in 0..bytes.len() {
                let err = BlobView::parse(&bytes[..n]).unwrap_err();
                assert!(
                    matches!(err, BlobError::Truncated { .. } | BlobError::BadMagic),
                    "{kind} {layout:?} cut at {n}: {err:?}"
                );
            }
            println!(
                "{kind} {layout:?}: {} bytes; resealed damage: {refused} refused, {accepted} accepted and queried",
                bytes.len()
            );
            assert!(refused > 0, "{kind} {layout:?}");
        }
    }
}

/// Headers that contradict the arrays are refused with the field named.
#[test]
fn headers_that_contradict_the_structure_are_refused() {
    let (positions, triangles) = spot_patch();
    let mesh = MeshRef::new(&positions, &triangles).validate().unwrap();
    for kind in CELL_KINDS {
        let bytes = MeshIndex::build(&mesh, kind)
            .unwrap()
            .to_blob(MeshLayout::Indexed)
            .unwrap();
        // Byte 5 starts the header counts: kind, mesh, triangles, vertices, nodes, then depth.
        assert_eq!(bytes[5], kind.tag() as u8);
        let mut rest = &bytes[5..];
        for _ in 0..5 {
            take::<u32>(&mut rest);
        }
        let depth_at = bytes.len() - rest.len();
        assert!(bytes[depth_at] < 0x7f, "a one-byte varint");
        let mut deeper = bytes.clone();
        deeper[depth_at] += 1;
        meshq::advanced::reseal(&mut deeper).unwrap();
        let err = BlobView::parse(&deeper).unwrap_err();
        assert_eq!(err, BlobError::HeaderMismatch { field: "depth" }, "{kind}");
        // A cell-structure kind tag in a version-2 blob is refused: version 2 knew only BVHs.
        let mut old = bytes.clone();
        old[4] = 2;
        meshq::advanced::reseal(&mut old).unwrap_err();
        assert_eq!(
            BlobView::parse(&old).unwrap_err(),
            BlobError::UnsupportedStructure { kind: kind.tag() }
        );
    }
}

/// Version 3 lays a BVH blob out as version 2 did: a BVH blob relabelled as version 2 loads
/// and answers the same.
#[test]
fn version_2_bvh_blobs_still_load() {
    let loaded = load_mesh("cow");
    let mesh = loaded.valid();
    let owned = MeshBvh::build(&mesh, &meshq::BuildConfig::default()).unwrap();
    // Without collapse roles a BVH blob is written as version 3.
    let options = blob::EncodeOptions::default();
    let mut bytes = vec![0; blob::encoded_len(&owned.bvh(), &mesh, &options).unwrap()];
    blob::encode_into(&owned.bvh(), &mesh, &options, &mut bytes).unwrap();
    assert_eq!(bytes[4], 3);
    bytes[4] = 2;
    meshq::advanced::reseal(&mut bytes).unwrap();
    let view = BlobView::parse(&bytes).unwrap();
    assert_eq!(view.header().version, 2);
    check_all(&view, &BruteForce::new(&mesh), &loaded, "cow as version 2");
}

/// Rays from around `bounds` towards points inside it, and points around it: the probes a
/// damaged blob's answers are compared on.
fn probes(bounds: &Aabb, count: usize) -> Vec<meshq::math::Ray> {
    let mut state = 0x9E37_79B9u32;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        state as f32 / u32::MAX as f32
    };
    let (lo, size) = (bounds.min, bounds.extent());
    let mut at = |grow: f32| {
        lo - size * (grow - 1.0) / 2.0 + size * grow * meshq::Vec3::new(next(), next(), next())
    };
    (0..count)
        .map(|_| {
            let (from, to) = (at(3.0), at(1.0));
            meshq::math::Ray::new(from, (to - from).normalize())
        })
        .collect()
}

/// The mesh a self-contained indexed blob stores, as vectors.
fn stored_mesh(view: &BlobView<'_>) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let h = view.header();
    let m = view.mesh();
    let positions = (0..h.vertex_count)
        .map(|v| m.position(v).unwrap())
        .collect();
    let triangles = (0..h.triangle_count)
        .map(|t| m.triangle_indices(t).unwrap())
        .collect();
    (positions, triangles)
}

/// How many of the probes `view` answers otherwise than a scan of its own stored mesh (what
/// a fresh build of that mesh answers: every structure answers as the scan does). A packed
/// blob's mesh is the one its slots' corners make, as the owned loader decodes it.
fn answers_unlike_its_own_mesh(view: &BlobView<'_>, bytes: &[u8], bounds: &Aabb) -> usize {
    use meshq::MeshQuery;
    let loaded;
    let (positions, triangles) = if view.header().mesh == MeshLayout::Packed {
        loaded = MeshIndex::from_blob(bytes).unwrap();
        let m = loaded.mesh();
        (m.positions().to_vec(), m.triangles().to_vec())
    } else {
        stored_mesh(view)
    };
    let mesh = MeshRef::new(&positions, &triangles).validate().unwrap();
    let brute = BruteForce::new(&mesh);
    probes(bounds, 300)
        .iter()
        .filter(|ray| {
            view.raycast(ray) != brute.raycast(ray, &Default::default())
                || view.closest_point(ray.origin, f32::INFINITY)
                    != brute.closest_point(ray.origin, f32::INFINITY)
        })
        .count()
}

/// The sweep's method kept: every byte of an indexed cell blob damaged three ways with the
/// checksum recomputed, and the two damages it found answering wrongly (an octree header
/// whose `bounds_min.x` is doubled, a k-d tree blob with two stored vertices swapped). Each
/// mutant is refused, or answers exactly as a fresh build of the mesh it stores.
#[test]
fn resealed_cell_blobs_are_refused_or_answer_as_a_fresh_build() {
    resealed_mutants_are_refused_or_right(MeshLayout::Indexed);
}

/// The same for packed cell blobs, whose corners are stored per reference slot: a slot's
/// corners changed, a slot naming another triangle, a triangle left with no slot.
#[test]
fn resealed_packed_cell_blobs_are_refused_or_answer_as_a_fresh_build() {
    resealed_mutants_are_refused_or_right(MeshLayout::Packed);
}

fn resealed_mutants_are_refused_or_right(layout: MeshLayout) {
    let (positions, triangles) = spot_patch();
    let mesh = MeshRef::new(&positions, &triangles).validate().unwrap();
    let bounds = mesh.bounds();
    for kind in CELL_KINDS {
        let bytes = MeshIndex::build(&mesh, kind)
            .unwrap()
            .to_blob(layout)
            .unwrap();
        let mut mutants: Vec<(String, Vec<u8>)> = Vec::new();
        for i in 0..bytes.len() {
            for flip in [0x01u8, 0x10, 0x80] {
                let mut damaged = bytes.clone();
                damaged[i] ^= flip;
                mutants.push((format!("byte {i} ^ {flip:#x}"), damaged));
            }
        }
        // The header's bounds follow its six varint counts: min x is the first f32.
        let mut rest = &bytes[5..];
        for _ in 0..6 {
            take::<u32>(&mut rest);
        }
        let min_x = bytes.len() - rest.len();
        let mut doubled = bytes.clone();
        let x = f32::from_le_bytes(doubled[min_x..min_x + 4].try_into().unwrap());
        // The mesh's bounds, or for an octree the cube around them.
        assert!(
            x <= bounds.min.x && x > bounds.min.x - bounds.extent().max_element(),
            "{kind}: {x}"
        );
        doubled[min_x..min_x + 4].copy_from_slice(&(2.0 * x).to_le_bytes());
        mutants.push(("bounds_min.x doubled".into(), doubled));
        let encode = |p: [f32; 3]| -> Vec<u8> { p.iter().flat_map(|c| c.to_le_bytes()).collect() };
        if layout == MeshLayout::Indexed {
            // Vertices 0 and 1 swapped where they are stored.
            let (v0, v1) = (encode(positions[0]), encode(positions[1]));
            let at = bytes
                .windows(24)
                .position(|w| w[..12] == v0[..] && w[12..] == v1[..]);
            let at = at.expect("vertices 0 and 1 stored side by side");
            let mut swapped = bytes.clone();
            swapped[at..at + 12].copy_from_slice(&v1);
            swapped[at + 12..at + 24].copy_from_slice(&v0);
            mutants.push(("vertices 0 and 1 swapped".into(), swapped));
        } else {
            // The corners of a slot moved by a whole shift in one place, and two slots' corners
            // exchanged: damage of whole values, not bits.
            let first = encode(positions[triangles[0][0] as usize]);
            let at = bytes
                .windows(12)
                .position(|w| w == &first[..])
                .expect("a corner of triangle 0 stored");
            let mut moved = bytes.clone();
            let shifted = positions[triangles[0][0] as usize].map(|c| c + 0.5 * bounds.extent().x);
            moved[at..at + 12].copy_from_slice(&encode(shifted));
            mutants.push(("a slot's corner moved".into(), moved));
            let corners_start = bytes.len() - 8 - 36 * count_slots(&bytes, kind);
            let mut exchanged = bytes.clone();
            let (a, b) = (corners_start, corners_start + 36 * 7);
            let tmp: Vec<u8> = exchanged[a..a + 36].to_vec();
            exchanged.copy_within(b..b + 36, a);
            exchanged[b..b + 36].copy_from_slice(&tmp);
            mutants.push(("two slots' corners exchanged".into(), exchanged));
        }

        let (mut refused, mut accepted) = (0, 0);
        for (what, mut damaged) in mutants {
            if meshq::advanced::reseal(&mut damaged).is_err() {
                continue;
            }
            let Ok(view) = BlobView::parse(&damaged) else {
                refused += 1;
                continue;
            };
            accepted += 1;
            let wrong = answers_unlike_its_own_mesh(&view, &damaged, &bounds);
            assert_eq!(
                wrong, 0,
                "{kind} {what}: accepted, and {wrong} answers differ"
            );
            // The owned loader accepts what the view accepts.
            assert!(MeshIndex::from_blob(&damaged).is_ok(), "{kind} {what}");
        }
        println!(
            "{kind} {layout:?}: resealed mutants {refused} refused, {accepted} accepted and answering right"
        );
        assert!(refused > 0 && accepted > 0, "{kind}: {refused} {accepted}");
    }
}

/// The reference slots of a cell blob (its header's reference count): a packed blob stores
/// 36 bytes of corners per slot just before its 8-byte seal.
fn count_slots(bytes: &[u8], kind: StructureKind) -> usize {
    let (header, structure) = BlobStructure::parse(bytes).unwrap();
    assert_eq!(structure.kind(), kind);
    header.reference_count as usize
}
