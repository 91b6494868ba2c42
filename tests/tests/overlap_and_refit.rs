//! Box and sphere overlap against brute force, buffer truncation, and refit after the
//! vertices move.

use std::ops::ControlFlow;

use glam::Vec3;
use meshq::MeshBvh;
use meshq::bvh::{BuildConfig, Bvh};
use meshq::math::Aabb;
use meshq::mesh::MeshRef;
use meshq::query::RayOptions;
use meshq::{MeshQuery, Traverse};
use meshq_tests::oracle::BruteForce;
use meshq_tests::{SplitMix64, TreeParts, checked_bvh, load_mesh, workload};

#[test]
fn box_and_sphere_overlap_match_brute_force() {
    for name in ["stanford-bunny", "teapot"] {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        let owned = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
        let bvh = checked_bvh(&owned, &mesh).unwrap();
        let brute = BruteForce::new(&mesh);
        let (_, r, bounds) = workload::centre_radius(&loaded.positions);
        let mut rng = SplitMix64::new(404);
        let mut nonempty = 0;
        for i in 0..300 {
            let c = workload::point_in_box(&mut rng, &bounds);
            let size = r * [0.01, 0.05, 0.2][i % 3];
            let half = Vec3::new(
                rng.range(0.2, 1.0),
                rng.range(0.2, 1.0),
                rng.range(0.2, 1.0),
            ) * size;
            let query = Aabb::new(c - half, c + half);
            let mut got = Vec::new();
            bvh.with(&mesh).overlap_aabb(&query, |t| {
                got.push(t);
                ControlFlow::Continue(())
            });
            got.sort_unstable();
            let expected = brute.overlap_aabb(&query);
            assert_eq!(got, expected, "{name} box {i}");
            let radius = size;
            let mut got = Vec::new();
            bvh.with(&mesh).overlap_sphere(c, radius, |t| {
                got.push(t);
                ControlFlow::Continue(())
            });
            got.sort_unstable();
            assert_eq!(got, brute.overlap_sphere(c, radius), "{name} sphere {i}");
            nonempty += usize::from(!expected.is_empty());
        }
        assert!(
            nonempty > 50,
            "{name}: only {nonempty} boxes touched the mesh"
        );
    }
}

#[test]
fn into_buffers_report_the_full_count_and_break_stops_early() {
    let loaded = load_mesh("spot");
    let mesh = loaded.valid();
    let owned = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
    let bvh = checked_bvh(&owned, &mesh).unwrap();
    let (c, r, _) = workload::centre_radius(&loaded.positions);
    let total = BruteForce::new(&mesh).overlap_sphere(c, 0.6 * r).len();
    assert!(total > 100);
    let mut small = [u32::MAX; 10];
    let count = bvh.with(&mesh).overlap_sphere_into(c, 0.6 * r, &mut small);
    assert_eq!((count.written, count.total), (10, total));
    assert!(!count.is_complete());
    assert!(small.iter().all(|&t| (t as usize) < mesh.triangle_count()));
    let mut big = vec![0; total];
    assert!(
        bvh.with(&mesh)
            .overlap_sphere_into(c, 0.6 * r, &mut big)
            .is_complete()
    );
    let mut seen = 0;
    bvh.with(&mesh).overlap_sphere(c, 0.6 * r, |_| {
        seen += 1;
        if seen == 3 {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    });
    assert_eq!(seen, 3);
}

#[test]
fn refit_after_deformation_is_valid_and_exact() {
    let loaded = load_mesh("stanford-bunny");
    let mesh = loaded.valid();
    let owned = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
    let (c, r, _) = workload::centre_radius(&loaded.positions);
    // Twist around the vertical axis and swell: every box changes.
    let moved: Vec<[f32; 3]> = loaded
        .positions
        .iter()
        .map(|&p| {
            let q = Vec3::from_array(p) - c;
            let (s, k) = (q.y / r * 1.5).sin_cos();
            let twisted = Vec3::new(q.x * k - q.z * s, q.y * 1.3, q.x * s + q.z * k);
            (c + twisted).to_array()
        })
        .collect();
    let moved_mesh = MeshRef::new(&moved, &loaded.triangles).validate().unwrap();
    // The old boxes no longer hold the moved triangles.
    assert!(checked_bvh(&owned, &moved_mesh).is_err());
    let mut parts = TreeParts::of(&owned);
    let bvh = Bvh::refit(&mut parts.nodes, &parts.order, &moved_mesh).unwrap();
    bvh.check(&moved_mesh).unwrap();
    let brute = BruteForce::new(&moved_mesh);
    for ray in workload::random_rays(&moved, 3_000, 31) {
        let key = |h: Option<meshq::math::RayHit>| h.map(|h| (h.t.to_bits(), h.tri));
        assert_eq!(
            key(bvh.with(&moved_mesh).raycast(&ray)),
            key(brute.raycast(&ray, &RayOptions::default()))
        );
    }
    for p in workload::closest_points(&moved, 300, 32) {
        let key =
            |c: Option<meshq::math::ClosestPoint>| c.map(|c| (c.distance_squared.to_bits(), c.tri));
        assert_eq!(
            key(bvh.with(&moved_mesh).closest_point(p, f32::INFINITY)),
            key(brute.closest_point(p, f32::INFINITY))
        );
    }
}

#[test]
fn refit_of_a_broken_tree_fails_and_changes_nothing() {
    let loaded = load_mesh("cow");
    let mesh = loaded.valid();
    let mut owned = TreeParts::of(&MeshBvh::build(&mesh, &BuildConfig::default()).unwrap());
    let inner = owned.nodes.iter().position(|n| !n.is_leaf()).unwrap();
    owned.nodes[inner].first = 0;
    let before = owned.nodes.clone();
    assert!(Bvh::refit(&mut owned.nodes, &owned.order, &mesh).is_err());
    assert_eq!(owned.nodes, before);
    // A mesh with fewer triangles than the tree names.
    let fixed = TreeParts::of(&MeshBvh::build(&mesh, &BuildConfig::default()).unwrap());
    let mut nodes = fixed.nodes.clone();
    let fewer = MeshRef::new(&loaded.positions, &loaded.triangles[..100])
        .validate()
        .unwrap();
    assert!(Bvh::refit(&mut nodes, &fixed.order, &fewer).is_err());
    assert_eq!(nodes, fixed.nodes);
}
