//! Capacity errors, bad input, empty and tiny meshes, coincident centroids, degenerate
//! triangles, and extreme coordinate scales.

use glam::Vec3;
use meshq::MeshBvh;
use meshq::advanced::PackedTriangle;
use meshq::advanced::{BvhNode, PrimRef};
use meshq::bvh::{BuildConfig, Bvh};
use meshq::error::{BufferKind, BuildError, FlatSlice, MeshError};
use meshq::math::{Aabb, Ray};
use meshq::mesh::MeshRef;
use meshq::query::RayOptions;
use meshq::{MeshQuery, Traverse};
use meshq_tests::oracle::BruteForce;
use meshq_tests::{checked_bvh, load_mesh, workload};

const SENTINEL: BvhNode = BvhNode {
    min: [42.0; 3],
    first: 42,
    max: [42.0; 3],
    count: 42,
};

#[test]
fn one_element_short_buffers_are_errors_and_nothing_is_written() {
    let loaded = load_mesh("spot");
    let mesh = loaded.valid();
    let n = mesh.triangle_count();
    let cap = Bvh::measure(n, None).nodes;
    let cases = [
        (cap - 1, n, n, BufferKind::Nodes, cap),
        (cap, n - 1, n, BufferKind::Order, n),
        (cap, n, n - 1, BufferKind::Scratch, n),
    ];
    for (nodes_len, order_len, scratch_len, buffer, needed) in cases {
        let mut nodes = vec![SENTINEL; nodes_len];
        let mut order = vec![7u32; order_len];
        let mut scratch = vec![PrimRef::EMPTY; scratch_len];
        let err = Bvh::build(
            &mesh,
            &BuildConfig::default(),
            &mut nodes,
            &mut order,
            &mut scratch,
        )
        .map(|_| ())
        .unwrap_err();
        assert_eq!(
            err,
            BuildError::BufferTooSmall {
                buffer,
                needed,
                got: needed - 1
            }
        );
        assert!(
            nodes.iter().all(|n| *n == SENTINEL),
            "{buffer:?}: nodes written"
        );
        assert!(order.iter().all(|&o| o == 7), "{buffer:?}: order written");
        assert!(
            scratch.iter().all(|s| *s == PrimRef::EMPTY),
            "{buffer:?}: scratch written"
        );
    }
}

#[test]
fn invalid_configs_are_rejected_before_building() {
    let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let mesh = MeshRef::new(&positions, &[[0, 1, 2]]).validate().unwrap();
    let d = BuildConfig::default();
    for (config, field) in [
        (BuildConfig { bins: 1, ..d }, "bins"),
        (BuildConfig { bins: 65, ..d }, "bins"),
        (
            BuildConfig {
                max_leaf_size: 0,
                ..d
            },
            "max_leaf_size",
        ),
        (BuildConfig { max_depth: 0, ..d }, "max_depth"),
        (BuildConfig { max_depth: 65, ..d }, "max_depth"),
        (
            BuildConfig {
                traversal_cost: f32::NAN,
                ..d
            },
            "traversal_cost",
        ),
        (
            BuildConfig {
                triangle_cost: 0.0,
                ..d
            },
            "triangle_cost",
        ),
    ] {
        assert_eq!(
            MeshBvh::build(&mesh, &config).unwrap_err(),
            BuildError::InvalidConfig { field }
        );
    }
    let deep = BuildConfig { max_depth: 3, ..d };
    let many: Vec<[u32; 3]> = vec![[0, 1, 2]; 100];
    let mesh = MeshRef::new(&positions, &many).validate().unwrap();
    assert_eq!(
        MeshBvh::build(&mesh, &deep).unwrap_err(),
        BuildError::TooDeep {
            max_depth: 3,
            triangles: 100
        }
    );
}

#[test]
fn bad_meshes_name_the_offending_vertex_or_triangle() {
    let good = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let tri = [[0u32, 1, 2]];
    let with = |i: usize, v: [f32; 3]| {
        let mut p = good.to_vec();
        p[i] = v;
        MeshRef::new(&p, &tri).validate().map(|_| ())
    };
    assert_eq!(
        with(1, [f32::NAN, 0.0, 0.0]),
        Err(MeshError::NonFiniteCoordinate { vertex: 1 })
    );
    assert_eq!(
        with(2, [0.0, f32::INFINITY, 0.0]),
        Err(MeshError::NonFiniteCoordinate { vertex: 2 })
    );
    assert_eq!(
        with(0, [0.0, 0.0, -1e20]),
        Err(MeshError::CoordinateTooLarge { vertex: 0 })
    );
    let out_of_range = [[0u32, 1, 2], [0, 3, 1]];
    assert_eq!(
        MeshRef::new(&good, &out_of_range).validate().map(|_| ()),
        Err(MeshError::IndexOutOfRange {
            triangle: 1,
            index: 3,
            vertex_count: 3
        })
    );
    assert_eq!(
        MeshRef::from_flat(&[0.0; 8], &[0, 1, 2]).map(|_| ()),
        Err(MeshError::FlatLength {
            what: FlatSlice::Positions,
            len: 8
        })
    );
    assert_eq!(
        MeshRef::from_flat(&[0.0; 9], &[0, 1]).map(|_| ()),
        Err(MeshError::FlatLength {
            what: FlatSlice::Indices,
            len: 2
        })
    );
    // The flat form views the same memory as triples.
    let flat = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0];
    let m = MeshRef::from_flat(&flat, &[0, 1, 2]).unwrap();
    assert_eq!(m.positions(), &good);
    assert!(std::ptr::eq(
        m.positions().as_ptr().cast::<f32>(),
        flat.as_ptr()
    ));
}

#[test]
fn empty_mesh_gives_an_empty_tree_that_answers_nothing() {
    let mesh = MeshRef::new(&[], &[]).validate().unwrap();
    let bvh = Bvh::build(&mesh, &BuildConfig::default(), &mut [], &mut [], &mut []).unwrap();
    assert!(bvh.is_empty());
    assert_eq!(bvh.depth(), 0);
    bvh.check(&mesh).unwrap();
    let ray = Ray::new(Vec3::ZERO, Vec3::X);
    assert_eq!(bvh.with(&mesh).raycast(&ray), None);
    assert!(!bvh.with(&mesh).raycast_any(&ray));
    assert_eq!(
        bvh.with(&mesh).closest_point(Vec3::ZERO, f32::INFINITY),
        None
    );
    let all = Aabb::new(Vec3::splat(-1e9), Vec3::splat(1e9));
    assert_eq!(bvh.with(&mesh).overlap_aabb_into(&all, &mut []).total, 0);
    assert_eq!(bvh.bounds(), Aabb::EMPTY);
}

/// Every structure kind over no triangles builds, bakes into a blob of either layout, loads
/// back (as a view and owned) and answers nothing (a grid's blob could not be baked: its empty
/// box was refused as non-finite).
#[test]
fn every_structure_over_an_empty_mesh_bakes_and_answers_nothing() {
    use meshq::StructureKind;
    use meshq::blob::{BlobView, MeshLayout};
    use meshq::owned::MeshIndex;
    let mesh = MeshRef::new(&[], &[]).validate().unwrap();
    let ray = Ray::new(Vec3::ZERO, Vec3::X);
    for kind in StructureKind::ALL {
        let index = MeshIndex::build(&mesh, kind).unwrap();
        assert_eq!(index.raycast(&ray), None, "{kind:?}");
        for layout in [MeshLayout::Indexed, MeshLayout::Packed] {
            let bytes = index
                .to_blob(layout)
                .unwrap_or_else(|e| panic!("{kind:?} {layout:?}: {e}"));
            let view = BlobView::parse(&bytes).unwrap_or_else(|e| panic!("{kind:?}: {e}"));
            let loaded = MeshIndex::from_blob(&bytes).unwrap();
            assert_eq!(view.raycast(&ray), None, "{kind:?} {layout:?}");
            assert!(!view.raycast_any(&ray), "{kind:?} {layout:?}");
            assert_eq!(
                view.closest_point(Vec3::ZERO, f32::INFINITY),
                None,
                "{kind:?}"
            );
            assert_eq!(loaded.raycast(&ray), None, "{kind:?} {layout:?}");
            assert_eq!(
                loaded.closest_point(Vec3::ZERO, f32::INFINITY),
                None,
                "{kind:?}"
            );
        }
    }
}

#[test]
fn one_triangle_and_invalid_queries() {
    let positions = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]];
    let mesh = MeshRef::new(&positions, &[[0, 1, 2]]).validate().unwrap();
    let (mut nodes, mut order) = ([BvhNode::EMPTY; 1], [0u32; 1]);
    let bvh = Bvh::build(
        &mesh,
        &BuildConfig::default(),
        &mut nodes,
        &mut order,
        &mut [PrimRef::EMPTY],
    )
    .unwrap();
    assert_eq!((bvh.nodes().len(), bvh.depth()), (1, 1));
    let hit = bvh
        .with(&mesh)
        .raycast(&Ray::new(
            Vec3::new(0.5, 0.5, 3.0),
            Vec3::new(0.0, 0.0, -2.0),
        ))
        .unwrap();
    assert_eq!((hit.tri, hit.t, hit.u, hit.v), (0, 1.5, 0.25, 0.25));
    let c = bvh
        .with(&mesh)
        .closest_point(Vec3::new(3.0, 0.0, 0.0), f32::INFINITY)
        .unwrap();
    assert_eq!(
        (c.point, c.distance_squared),
        (Vec3::new(2.0, 0.0, 0.0), 1.0)
    );
    assert_eq!(
        bvh.with(&mesh)
            .closest_point(Vec3::new(3.0, 0.0, 0.0), 0.999),
        None
    );
    assert!(
        bvh.with(&mesh)
            .closest_point(Vec3::new(3.0, 0.0, 0.0), 1.0)
            .is_some()
    );
    for bad in [
        Ray::new(Vec3::new(f32::NAN, 0.5, 3.0), -Vec3::Z),
        Ray::new(Vec3::new(0.5, 0.5, 3.0), Vec3::ZERO),
        Ray::new(
            Vec3::new(0.5, 0.5, 3.0),
            Vec3::new(0.0, 0.0, f32::NEG_INFINITY),
        ),
        Ray::new(Vec3::new(0.5, 0.5, 3.0), -Vec3::Z).with_range(2.0, 1.0),
        Ray::new(Vec3::new(0.5, 0.5, 3.0), -Vec3::Z).with_range(f32::NAN, 9.0),
    ] {
        assert_eq!(bvh.with(&mesh).raycast(&bad), None, "{bad:?}");
        assert!(!bvh.with(&mesh).raycast_any(&bad), "{bad:?}");
    }
    assert_eq!(
        bvh.with(&mesh).closest_point(Vec3::NAN, f32::INFINITY),
        None
    );
    assert_eq!(bvh.with(&mesh).closest_point(Vec3::ZERO, -1.0), None);
    assert_eq!(bvh.with(&mesh).closest_point(Vec3::ZERO, f32::NAN), None);
}

/// `count` triangles whose bounding boxes all have their centre exactly at the origin: each
/// spans `[-|p|, |p|]` on every axis through a corner `p` and its mirror `-p`.
fn coincident_centroids(count: usize) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for i in 0..count {
        let (s, c) = (i as f32 * 0.61).sin_cos();
        let p0 = Vec3::new(c, s, 0.3 * (i % 7) as f32 - 0.95);
        let p2 = Vec3::new(0.5 * c, -0.5 * s, -0.25 * p0.z);
        let base = positions.len() as u32;
        positions.extend([p0, -p0, p2].map(|v| v.to_array()));
        triangles.push([base, base + 1, base + 2]);
    }
    (positions, triangles)
}

#[test]
fn all_triangles_on_one_centroid_fall_back_to_index_splits() {
    let (positions, triangles) = coincident_centroids(1_000);
    let mesh = MeshRef::new(&positions, &triangles).validate().unwrap();
    let centre = |i: u32| mesh.triangle(i).unwrap().bounds().center();
    assert!((0..1_000).all(|i| centre(i) == Vec3::ZERO));
    let owned = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
    let bvh = checked_bvh(&owned, &mesh).unwrap();
    assert!(
        bvh.depth() <= 10,
        "median splits give a balanced tree, depth {}",
        bvh.depth()
    );
    let brute = BruteForce::new(&mesh);
    for ray in workload::random_rays(&positions, 2_000, 5) {
        let key = |h: Option<meshq::math::RayHit>| h.map(|h| (h.t.to_bits(), h.tri));
        assert_eq!(
            key(bvh.with(&mesh).raycast(&ray)),
            key(brute.raycast(&ray, &RayOptions::default()))
        );
    }
    for p in workload::closest_points(&positions, 300, 6) {
        let key =
            |c: Option<meshq::math::ClosestPoint>| c.map(|c| (c.distance_squared.to_bits(), c.tri));
        assert_eq!(
            key(bvh.with(&mesh).closest_point(p, f32::INFINITY)),
            key(brute.closest_point(p, f32::INFINITY))
        );
    }
}

#[test]
fn degenerate_triangles_are_kept_but_never_returned() {
    let loaded = load_mesh("cow");
    let mut positions = loaded.positions.clone();
    let mut triangles = loaded.triangles.clone();
    // Interleave zero-area triangles (repeated corners: exactly zero normals), lying right on
    // the surface where rays and closest points land.
    for (k, t) in loaded.triangles.iter().enumerate().step_by(3) {
        let a = Vec3::from_array(loaded.positions[t[0] as usize]);
        let b = Vec3::from_array(loaded.positions[t[1] as usize]);
        let base = positions.len() as u32;
        positions.extend([a, b, b].map(|v| v.to_array()));
        triangles.insert(k, [base, base + 1, base + 2]);
        triangles.push([t[0], t[0], t[1]]);
    }
    let mesh = MeshRef::new(&positions, &triangles).validate().unwrap();
    let degenerate: Vec<bool> = (0..mesh.triangle_count() as u32)
        .map(|i| mesh.triangle(i).unwrap().is_degenerate())
        .collect();
    assert!(degenerate.iter().filter(|&&d| d).count() > 3_000);
    let owned = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
    let bvh = checked_bvh(&owned, &mesh).unwrap();
    let brute = BruteForce::new(&mesh);
    for ray in workload::random_rays(&positions, 3_000, 11) {
        let got = bvh.with(&mesh).raycast(&ray);
        assert!(got.is_none_or(|h| !degenerate[h.tri as usize]));
        let key = |h: Option<meshq::math::RayHit>| h.map(|h| (h.t.to_bits(), h.tri));
        assert_eq!(key(got), key(brute.raycast(&ray, &RayOptions::default())));
    }
    for p in workload::closest_points(&positions, 500, 12) {
        let got = bvh.with(&mesh).closest_point(p, f32::INFINITY).unwrap();
        assert!(!degenerate[got.tri as usize]);
        assert_eq!(got.tri, brute.closest_point(p, f32::INFINITY).unwrap().tri);
    }
}

#[test]
fn tiny_and_huge_coordinate_scales_stay_exact() {
    let loaded = load_mesh("spot");
    for (scale, offset) in [(1e-6f32, 0.0f32), (1e6, 0.0), (1e-6, 3e-6), (1e6, -2.5e6)] {
        let positions: Vec<[f32; 3]> = loaded
            .positions
            .iter()
            .map(|p| p.map(|c| c * scale + offset))
            .collect();
        let mesh = MeshRef::new(&positions, &loaded.triangles)
            .validate()
            .unwrap();
        let owned = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
        let bvh = checked_bvh(&owned, &mesh).unwrap();
        let brute = BruteForce::new(&mesh);
        let mut hits = 0;
        for ray in workload::random_rays(&positions, 3_000, 21) {
            let key = |h: Option<meshq::math::RayHit>| h.map(|h| (h.t.to_bits(), h.tri));
            let expected = brute.raycast(&ray, &RayOptions::default());
            assert_eq!(
                key(bvh.with(&mesh).raycast(&ray)),
                key(expected),
                "scale {scale}"
            );
            hits += usize::from(expected.is_some());
        }
        assert!(hits > 600, "scale {scale}: {hits} hits");
        for p in workload::closest_points(&positions, 300, 22) {
            let key = |c: Option<meshq::math::ClosestPoint>| {
                c.map(|c| (c.distance_squared.to_bits(), c.tri))
            };
            assert_eq!(
                key(bvh.with(&mesh).closest_point(p, f32::INFINITY)),
                key(brute.closest_point(p, f32::INFINITY))
            );
        }
    }
}

#[test]
fn packing_needs_one_slot_per_triangle() {
    let loaded = load_mesh("cow");
    let mesh = loaded.valid();
    let owned = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
    let bvh = checked_bvh(&owned, &mesh).unwrap();
    let n = mesh.triangle_count();
    let mut short = vec![PackedTriangle::EMPTY; n - 1];
    assert_eq!(
        bvh.pack_triangles(&mesh, &mut short).map(|_| ()),
        Err(BuildError::BufferTooSmall {
            buffer: BufferKind::Packed,
            needed: n,
            got: n - 1
        })
    );
    assert!(short.iter().all(|t| *t == PackedTriangle::EMPTY));
    let mut storage = vec![PackedTriangle::EMPTY; n];
    let packed = bvh.pack_triangles(&mesh, &mut storage).unwrap();
    // Slot i holds triangle order[i].
    for (slot, &tri) in bvh.order().iter().enumerate() {
        let t = mesh.triangle(tri).unwrap();
        assert_eq!(packed.as_slice()[slot].b, t.b.to_array());
    }
}

/// Every structure and every triangle test on spot moved to 2⁴⁵ times its size (coordinates
/// near 10¹⁴, where a triangle test's products of three lengths pass `f32`'s range) with the
/// rays' origins scaled and their directions not: each ray's answer is the unit-size answer
/// with `t` times 2⁴⁵ and the same triangle, `u` and `v`, bit for bit — closest hits, any hits
/// and batches. (Multiplying by a power of two rounds nothing, so an exact implementation must
/// agree; one whose products overflow answers `t = ∞` or misses.)
#[test]
fn power_of_two_scales_past_f32_products_give_the_unit_hits_scaled() {
    use meshq::owned::{MeshIndex, StructureKind};
    use meshq::query::TriangleTest;
    let loaded = load_mesh("spot");
    let scale = 2f32.powi(45);
    let big: Vec<[f32; 3]> = loaded
        .positions
        .iter()
        .map(|p| p.map(|c| c * scale))
        .collect();
    let unit_mesh = loaded.valid();
    let big_mesh = MeshRef::new(&big, &loaded.triangles).validate().unwrap();
    let rays = workload::random_rays(&loaded.positions, 2_000, 31);
    let big_rays: Vec<Ray> = rays
        .iter()
        .map(|r| Ray::new(r.origin * scale, r.dir).with_range(r.t_min * scale, r.t_max * scale))
        .collect();
    let bits = |h: Option<meshq::math::RayHit>, by: f32| {
        h.map(|h| ((h.t * by).to_bits(), h.tri, h.u.to_bits(), h.v.to_bits()))
    };
    for kind in StructureKind::ALL {
        let unit = MeshIndex::build(&unit_mesh, kind).unwrap();
        let index = MeshIndex::build(&big_mesh, kind).unwrap();
        for test in TriangleTest::ALL {
            let o = RayOptions {
                test,
                ..RayOptions::default()
            };
            let what = format!("{kind} {}", test.name());
            let mut hits = 0;
            for (i, (r, b)) in rays.iter().zip(&big_rays).enumerate() {
                let want = unit.raycast_with(r, &o);
                hits += usize::from(want.is_some());
                assert_eq!(
                    bits(index.raycast_with(b, &o), 1.0),
                    bits(want, scale),
                    "{what}: ray {i}"
                );
                assert_eq!(
                    index.raycast_any_with(b, &o),
                    want.is_some(),
                    "{what}: any {i}"
                );
            }
            assert!(hits > 400, "{what}: {hits} hits");
            let mut keys = vec![0u64; rays.len()];
            let mut got = vec![None; rays.len()];
            index
                .raycast_batch(&big_rays, &o, &mut keys, &mut got)
                .unwrap();
            let mut want = vec![None; rays.len()];
            unit.raycast_batch(&rays, &o, &mut keys, &mut want).unwrap();
            assert_eq!(
                got.into_iter().map(|h| bits(h, 1.0)).collect::<Vec<_>>(),
                want.into_iter().map(|h| bits(h, scale)).collect::<Vec<_>>(),
                "{what}: batch"
            );
        }
    }
}
