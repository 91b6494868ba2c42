//! Trees whose nodes take [`WARM_TREE_BYTES`] or more are walked reading each node's first two
//! inner children early. On such trees (the bunny subdivided twice, 1,111,216 triangles),
//! eight-wide, four-wide and compact, each ray's closest hit and any hit, and each point's
//! closest point, are a brute-force scan's.

use meshq::MeshBvh;
use meshq::advanced::WARM_TREE_BYTES;
use meshq::bvh::BuildConfig;
use meshq::math::RayHit;
use meshq::query::{MeshQuery, RayOptions};
use meshq_tests::oracle::BruteForce;
use meshq_tests::{load_mesh, subdivided, workload};

fn bits(h: Option<RayHit>) -> Option<(u32, u32, u32, u32)> {
    h.map(|h| (h.t.to_bits(), h.tri, h.u.to_bits(), h.v.to_bits()))
}

#[test]
fn trees_past_the_warm_size_answer_as_the_scan() {
    let loaded = subdivided(&subdivided(&load_mesh("stanford-bunny")));
    let mesh = loaded.valid();
    let brute = BruteForce::new(&mesh);
    let eight = MeshBvh::build_parallel(&mesh, &BuildConfig::default()).expect("build");
    let four = eight.clone().with_four_wide_nodes().expect("four-wide");
    let compact = eight.clone().with_compact_nodes().expect("compact");
    let mut rays = workload::random_rays(&loaded.positions, 240, 0x1A26E);
    // A camera's rays as well: neighbours, which a walk finds in cache.
    rays.extend(
        workload::camera_rays(&loaded.positions, 64, 48)
            .into_iter()
            .step_by(97),
    );
    let points = workload::closest_points(&loaded.positions, 60, 0x1A26F);
    let options = RayOptions::default();
    let want: Vec<_> = rays.iter().map(|r| brute.raycast(r, &options)).collect();
    assert!(
        want.iter().filter(|h| h.is_some()).count() > rays.len() / 4,
        "rays hit"
    );
    let want_points: Vec<_> = points
        .iter()
        .map(|&p| brute.closest_point(p, f32::INFINITY))
        .collect();
    for (tree, what) in [
        (&eight, "eight-wide"),
        (&four, "four-wide"),
        (&compact, "compact"),
    ] {
        // Past the size, or this test would not walk the early reads at all.
        assert!(
            tree.query_node_bytes() >= WARM_TREE_BYTES,
            "{what}: {} node bytes",
            tree.query_node_bytes()
        );
        for (i, (ray, &hit)) in rays.iter().zip(&want).enumerate() {
            assert_eq!(
                bits(tree.raycast_with(ray, &options)),
                bits(hit),
                "{what}: ray {i}"
            );
            assert_eq!(
                tree.raycast_any_with(ray, &options),
                hit.is_some(),
                "{what}: ray {i}, any hit"
            );
        }
        for (i, (&p, want)) in points.iter().zip(&want_points).enumerate() {
            assert_eq!(
                tree.closest_point(p, f32::INFINITY)
                    .map(|c| (c.distance_squared.to_bits(), c.tri)),
                want.map(|c| (c.distance_squared.to_bits(), c.tri)),
                "{what}: point {i}"
            );
        }
    }
}
