//! Exact ties on `t`: a bundled mesh with every triangle twice (the copies appended in reverse
//! order, so a copy's index is sometimes the one a walk meets first and sometimes the last).
//! Every hit then ties with its twin bit for bit, and the closest hit must name the lower
//! index, as a brute-force scan does — on the four-wide, eight-wide and compact trees, with
//! both triangle tests, one ray per call and in batches (camera packets included).

use meshq::bvh::BuildConfig;
use meshq::math::{Ray, RayHit};
use meshq::query::{RayOptions, TriangleTest};
use meshq::{MeshBvh, MeshQuery};
use meshq_tests::oracle::BruteForce;
use meshq_tests::{LoadedMesh, load_mesh, workload};

/// `mesh` followed by its triangles again, last first.
fn doubled(mesh: &LoadedMesh) -> LoadedMesh {
    let mut out = mesh.clone();
    out.name = format!("{}-doubled", mesh.name);
    out.triangles.extend(mesh.triangles.iter().rev());
    out
}

/// The structures checked: each node kind the owned BVH can walk.
fn trees(mesh: &LoadedMesh) -> Vec<(&'static str, MeshBvh)> {
    let build = || MeshBvh::build(&mesh.valid(), &BuildConfig::default()).unwrap();
    vec![
        ("four-wide", build().with_four_wide_nodes().unwrap()),
        ("eight-wide", build().with_eight_wide_nodes().unwrap()),
        ("compact", build().with_compact_nodes().unwrap()),
    ]
}

fn check(name: &str, rays: &[Ray]) {
    let mesh = doubled(&load_mesh(name));
    let half = (mesh.triangles.len() / 2) as u32;
    let brute = BruteForce::new(&mesh.valid());
    for test in [TriangleTest::Watertight, TriangleTest::MollerTrumbore] {
        let options = RayOptions {
            test,
            ..RayOptions::default()
        };
        let want: Vec<Option<RayHit>> = rays.iter().map(|r| brute.raycast(r, &options)).collect();
        let hits = want.iter().flatten().count();
        assert!(hits > rays.len() / 8, "{name}: only {hits} hits");
        // Every hit is the lower of two identical triangles.
        assert!(
            want.iter().flatten().all(|h| h.tri < half),
            "{name}: a twin won"
        );
        for (kind, tree) in trees(&mesh) {
            for (i, (ray, want)) in rays.iter().zip(&want).enumerate() {
                let got = tree.raycast_with(ray, &options);
                assert_eq!(
                    got.map(|h| (h.t.to_bits(), h.tri, h.u.to_bits(), h.v.to_bits())),
                    want.map(|h| (h.t.to_bits(), h.tri, h.u.to_bits(), h.v.to_bits())),
                    "{name} {kind} {test:?} ray {i}: one per call"
                );
            }
            let mut keys = vec![0u64; rays.len()];
            let mut got = vec![None; rays.len()];
            tree.raycast_batch(rays, &options, &mut keys, &mut got)
                .unwrap();
            assert!(got == want, "{name} {kind} {test:?}: batch differs");
        }
    }
}

#[test]
fn random_rays_name_the_lower_twin() {
    for name in ["spot", "fandisk"] {
        let mesh = load_mesh(name);
        check(name, &workload::random_rays(&mesh.positions, 4_000, 7));
    }
}

#[test]
fn camera_packets_name_the_lower_twin() {
    let mesh = load_mesh("cow");
    check("cow", &workload::camera_rays(&mesh.positions, 64, 64));
}
