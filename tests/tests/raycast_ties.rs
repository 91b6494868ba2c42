//! Exact ties on `t`: a bundled mesh with every triangle twice (the copies appended in reverse
//! order, so a copy's index is sometimes the one a walk meets first and sometimes the last).
//! Every hit then ties with its twin bit for bit, and the closest hit must name the lower
//! index, as a brute-force scan does — on the four-wide, eight-wide and compact trees, with
//! both triangle tests, one ray per call and in batches (camera packets included).
//! A structure of one's own that names a triangle `u32::MAX` still has that triangle hit.

use meshq::advanced::LeafTriangleIds;
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

/// "No hit yet" is kept as triangle `u32::MAX` at `t = +∞`; a structure of one's own may still
/// name a triangle `u32::MAX` (ids are its own), and its hit must come back as a scan's does.
#[test]
fn a_triangle_numbered_u32_max_is_still_hit() {
    use glam::Vec3;
    use meshq::Traverse;
    use meshq::advanced::PackedTriangle;
    use meshq::math::Aabb;
    use meshq::query::Visitor;

    struct OneLeaf<'a> {
        ids: &'a [u32],
        bounds: Aabb,
    }
    impl Traverse for OneLeaf<'_> {
        fn traverse<V: Visitor + ?Sized>(&self, visitor: &mut V) {
            if visitor.enter(&self.bounds).is_some() {
                let _ = visitor.leaf(LeafTriangleIds::new(0, self.ids));
            }
        }
    }

    let far = PackedTriangle {
        a: [0.0, 0.0, -1.0],
        b: [1.0, 0.0, -1.0],
        c: [0.0, 1.0, -1.0],
    };
    let near = PackedTriangle {
        a: [0.0, 0.0, 0.0],
        b: [1.0, 0.0, 0.0],
        c: [0.0, 1.0, 0.0],
    };
    let packed = [far, near];
    let bounds = Aabb::new(Vec3::new(0.0, 0.0, -1.0), Vec3::new(1.0, 1.0, 0.0));
    let ray = Ray::new(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z);
    for (ids, want) in [([7, u32::MAX], u32::MAX), ([u32::MAX, 7], 7)] {
        let leaf = OneLeaf { ids: &ids, bounds };
        let hit = leaf
            .with(&packed[..])
            .raycast(&ray)
            .expect("the ray meets both");
        assert_eq!((hit.tri, hit.t), (want, 1.0), "ids {ids:?}");
        let mut keys = [0u64; 1];
        let mut out = [None; 1];
        leaf.with(&packed[..])
            .raycast_batch(&[ray], &RayOptions::default(), &mut keys, &mut out)
            .unwrap();
        assert_eq!(out[0], Some(hit), "ids {ids:?}: batch");
    }
}
