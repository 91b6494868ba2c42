//! Corrupt, truncated and foreign blobs are refused with the right error, and no byte-level
//! damage — even damage that keeps the checksum valid — makes parsing or a query panic.

use meshq::MeshBvh;
use meshq::blob::{self, BlobView, MeshLayout};
use meshq::bvh::BuildConfig;
use meshq::error::{BlobError, BlobSection};
use meshq::mesh::MeshRef;
use meshq::owned::MeshIndex;
use meshq_tests::{bake, load_mesh};

#[test]
fn every_single_byte_corruption_and_truncation_is_handled() {
    let (positions, triangles) = meshq_tests::spot_patch();
    let mesh = MeshRef::new(&positions, &triangles).validate().unwrap();
    assert!((40..200).contains(&triangles.len()), "{}", triangles.len());
    // The last: with the winding-number expansions (format version 6), checked at load by
    // working them out again.
    for (layout, winding) in [
        (MeshLayout::Indexed, false),
        (MeshLayout::Packed, false),
        (MeshLayout::Indexed, true),
    ] {
        let bytes = if winding {
            MeshBvh::build(&mesh, &BuildConfig::default())
                .and_then(MeshBvh::with_winding_numbers)
                .unwrap()
                .to_blob(layout)
                .unwrap()
        } else {
            bake(&mesh, &BuildConfig::default(), layout).unwrap()
        };
        assert!((1_000..40_000).contains(&bytes.len()), "{}", bytes.len());
        assert_eq!(
            BlobView::parse(&bytes).unwrap().winding_tree().is_some(),
            winding
        );
        let reference = meshq_tests::suite::exercise(&BlobView::parse(&bytes).unwrap());
        assert!(reference > 0);

        let (mut refused, mut resealed_refused, mut resealed_accepted) = (0, 0, 0);
        for i in 0..bytes.len() {
            for flip in [0x01u8, 0x80, 0xFF, 0x5A] {
                let mut damaged = bytes.clone();
                damaged[i] ^= flip;
                // CRC-32 catches every error within 32 consecutive bits: raw damage is always
                // refused, by the magic, the version, the header decoding or the checksum.
                assert!(
                    BlobView::parse(&damaged).is_err(),
                    "{layout:?} byte {i} ^ {flip:#x}"
                );
                refused += 1;
                // With the checksum recomputed, validation itself must catch what matters; a
                // blob it accepts must still be safe to query.
                if meshq::advanced::reseal(&mut damaged).is_ok() {
                    // The owned loaders check boxes on their decoded copy: they must refuse
                    // exactly what the view refuses, with the same error.
                    let owned = MeshBvh::from_blob(&damaged);
                    let index = MeshIndex::from_blob(&damaged);
                    match BlobView::parse(&damaged) {
                        Ok(view) => {
                            meshq_tests::suite::exercise(&view);
                            resealed_accepted += 1;
                            for err in [owned.err(), index.err()].into_iter().flatten() {
                                assert!(
                                    matches!(err, BlobError::RepeatedTriangle { .. }),
                                    "{layout:?} byte {i} ^ {flip:#x}: {err:?}"
                                );
                            }
                        }
                        Err(err) => {
                            resealed_refused += 1;
                            assert_eq!(owned.err(), Some(err), "{layout:?} byte {i} ^ {flip:#x}");
                            assert_eq!(index.err(), Some(err), "{layout:?} byte {i} ^ {flip:#x}");
                        }
                    }
                }
            }
        }
        let mut sections = std::collections::BTreeSet::new();
        for n in 0..bytes.len() {
            let err = BlobView::parse(&bytes[..n]).unwrap_err();
            assert!(
                matches!(err, BlobError::Truncated { .. } | BlobError::BadMagic),
                "{layout:?} cut at {n}: {err:?}"
            );
            if let BlobError::Truncated { section, .. } = err {
                sections.insert(section.to_string());
            }
        }
        // A cut names the section where the bytes run out, not always the first one.
        let mesh_section = match layout {
            MeshLayout::Packed => "packed triangles",
            _ => "triangles",
        };
        for section in ["header", "nodes", "triangle order", mesh_section] {
            assert!(sections.contains(section), "{layout:?}: {sections:?}");
        }
        if winding {
            assert!(
                sections.contains("winding-number expansions"),
                "{sections:?}"
            );
        }
        let mut longer = bytes.clone();
        longer.push(0);
        assert!(matches!(
            BlobView::parse(&longer),
            Err(BlobError::TrailingBytes { offset }) if offset == bytes.len()
        ));
        println!(
            "{layout:?}: {} bytes, {refused} raw corruptions refused; resealed: {resealed_refused} refused, {resealed_accepted} accepted and queried",
            bytes.len()
        );
        assert!(resealed_refused > resealed_accepted);
    }
}

#[test]
fn foreign_versions_and_mismatched_meshes_are_refused_with_clear_errors() {
    let loaded = load_mesh("teapot");
    let mesh = loaded.valid();
    let bytes = bake(&mesh, &BuildConfig::default(), MeshLayout::Indexed).unwrap();

    let mut future = bytes.clone();
    // A BVH blob with its collapse roles: version 5.
    assert_eq!(future[4], 5, "the version varint follows the magic");
    future[4] = 7;
    meshq::advanced::reseal(&mut future).unwrap_err(); // the header of version 7 is not read at all
    let err = BlobView::parse(&future).unwrap_err();
    assert_eq!(
        err,
        BlobError::UnsupportedVersion {
            found: 7,
            oldest: 1,
            newest: 6
        }
    );
    assert!(err.to_string().contains("versions 1 to 6"), "{err}");
    let mut past = bytes.clone();
    past[4] = 0;
    assert!(matches!(
        BlobView::parse(&past).unwrap_err(),
        BlobError::UnsupportedVersion { found: 0, .. }
    ));

    let mut foreign = bytes.clone();
    foreign[0] = b'X';
    assert_eq!(BlobView::parse(&foreign).unwrap_err(), BlobError::BadMagic);
    assert!(BlobView::parse(b"").is_err());

    let mut flipped = bytes.clone();
    let last = flipped.len() - 1;
    flipped[last] ^= 1;
    assert!(matches!(
        BlobView::parse(&flipped),
        Err(BlobError::ChecksumMismatch { .. })
    ));

    let omitted = bake(&mesh, &BuildConfig::default(), MeshLayout::Omitted).unwrap();
    assert_eq!(
        BlobView::parse(&omitted).unwrap_err(),
        BlobError::MeshNotIncluded
    );
    // Same counts, one coordinate nudged: the mesh checksum tells them apart.
    let mut moved = loaded.positions.clone();
    moved[7][1] = f32::from_bits(moved[7][1].to_bits() + 1);
    let other = MeshRef::new(&moved, &loaded.triangles).validate().unwrap();
    assert_eq!(
        BlobView::parse_with_mesh(&omitted, other).unwrap_err(),
        BlobError::MeshMismatch
    );
    assert!(BlobView::parse_with_mesh(&omitted, mesh).is_ok());
}

#[test]
fn encode_into_a_short_buffer_writes_nothing() {
    let loaded = load_mesh("teapot");
    let mesh = loaded.valid();
    let owned = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
    let bvh = meshq_tests::checked_bvh(&owned, &mesh).unwrap();
    let options = blob::EncodeOptions::default();
    let n = blob::encoded_len(&bvh, &mesh, &options).unwrap();
    let mut short = vec![0xAAu8; n - 1];
    let err = blob::encode_into(&bvh, &mesh, &options, &mut short).unwrap_err();
    assert_eq!(
        err,
        BlobError::BufferTooSmall {
            section: BlobSection::Header,
            needed: n,
            got: n - 1
        }
    );
    assert!(short.iter().all(|&b| b == 0xAA));
    // A tree that does not belong to the mesh is never encoded.
    let spot = load_mesh("spot");
    assert!(matches!(
        blob::encode_into(&bvh, &spot.valid(), &options, &mut vec![0; 1 << 22]),
        Err(BlobError::InvalidNode(_))
    ));
}

#[test]
fn an_empty_mesh_round_trips() {
    let mesh = MeshRef::new(&[], &[]).validate().unwrap();
    for layout in [MeshLayout::Indexed, MeshLayout::Packed] {
        let bytes = bake(&mesh, &BuildConfig::default(), layout).unwrap();
        let view = BlobView::parse(&bytes).unwrap();
        assert_eq!(view.header().node_count, 0);
        assert_eq!(meshq_tests::suite::exercise(&view), 0);
    }
}

/// Found by the fuzz target (`fuzz/fuzz_targets/blob_parse.rs`) once it compared
/// `MeshBvh::from_blob` with the view: a packed blob whose order names triangle 0 in both
/// slots, with different corners in each. Such an order hides a triangle from every query, so
/// the view refuses it (the order is not a permutation), and so does the owned copy.
#[test]
fn an_order_naming_a_triangle_twice_is_refused() {
    let bytes = meshq_tests::fuzz_blob("fuzz-repeated-triangle.bin");
    assert_eq!(
        BlobView::parse(&bytes).unwrap_err(),
        BlobError::OrderNotPermutation
    );
    assert_eq!(
        MeshBvh::from_blob(&bytes).unwrap_err(),
        BlobError::OrderNotPermutation
    );

    // The same damage made on purpose to a real blob: one order entry repeated, over the
    // next one or (as in the report that found this) over a neighbour with the index one less.
    let (positions, triangles) = meshq_tests::spot_patch();
    let mesh = MeshRef::new(&positions, &triangles).validate().unwrap();
    let good = bake(&mesh, &BuildConfig::default(), MeshLayout::Packed).unwrap();
    let scene = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
    let order = scene.bvh().order();
    let at = (0..good.len() - 8)
        .find(|&i| {
            (0..order.len()).all(|k| good[i + 4 * k..i + 4 * k + 4] == order[k].to_le_bytes())
        })
        .unwrap();
    let mut damaged = good.clone();
    damaged.copy_within(at..at + 4, at + 4);
    meshq::advanced::reseal(&mut damaged).unwrap();
    assert_eq!(
        BlobView::parse(&damaged).unwrap_err(),
        BlobError::OrderNotPermutation
    );
    assert!(MeshBvh::from_blob(&damaged).is_err());
    let slot = (0..order.len())
        .find(|&k| order[k] > 0 && order.contains(&(order[k] - 1)))
        .unwrap();
    let mut damaged = good.clone();
    damaged[at + 4 * slot..at + 4 * slot + 4].copy_from_slice(&(order[slot] - 1).to_le_bytes());
    meshq::advanced::reseal(&mut damaged).unwrap();
    assert_eq!(
        BlobView::parse(&damaged).unwrap_err(),
        BlobError::OrderNotPermutation
    );
    assert!(BlobView::parse(&good).is_ok());
    assert!(MeshBvh::from_blob(&good).is_ok());
}
