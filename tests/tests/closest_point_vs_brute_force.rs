//! Closest-point queries on every bundled mesh equal a brute-force scan (same bits, same
//! triangle under the tie rule), with and without a maximum distance, on the binary tree and
//! on the four-wide tree collapsed from it.

use meshq::bvh::{BuildConfig, PackedTriangle, WideNode};
use meshq_tests::oracle::BruteForce;
use meshq_tests::{MESHES, OwnedBvh, load_mesh, workload};

const QUERIES: usize = 10_000;
/// Queries that also run with a maximum distance.
const LIMITED_QUERIES: usize = 2_000;

#[test]
fn closest_point_matches_brute_force_on_every_mesh() {
    for name in MESHES {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        let owned = OwnedBvh::build(&mesh, &BuildConfig::default()).unwrap();
        let bvh = owned.view(&mesh).unwrap();
        let mut storage = vec![PackedTriangle::EMPTY; mesh.triangle_count()];
        let packed = bvh.pack_triangles(&mesh, &mut storage).unwrap();
        let mut wide_nodes = vec![WideNode::EMPTY; bvh.wide_node_count()];
        let wide = bvh.widen(&mut wide_nodes).unwrap();
        let brute = BruteForce::new(&mesh);
        let (_, r, _) = workload::centre_radius(&loaded.positions);
        let points = workload::closest_points(&loaded.positions, QUERIES, 0xC105E);
        let mut limited_hits = 0;
        for (i, &p) in points.iter().enumerate() {
            let key = |c: Option<meshq::math::ClosestPoint>| {
                c.map(|c| {
                    (
                        c.distance_squared.to_bits(),
                        c.tri,
                        c.point.to_array().map(f32::to_bits),
                    )
                })
            };
            let expected = brute.closest_point(p, f32::INFINITY);
            assert!(expected.is_some());
            let got = bvh.closest_point(&mesh, p, f32::INFINITY);
            assert_eq!(key(got), key(expected), "{name}: point {i} {p}");
            let from_packed = bvh.closest_point(&packed, p, f32::INFINITY);
            assert_eq!(key(from_packed), key(expected), "{name}: packed, point {i}");
            let from_wide = wide.closest_point(&mesh, p, f32::INFINITY);
            assert_eq!(key(from_wide), key(expected), "{name}: wide, point {i}");
            let wide_packed = wide.closest_point(&packed, p, f32::INFINITY);
            assert_eq!(
                key(wide_packed),
                key(expected),
                "{name}: wide packed, point {i}"
            );
            if i >= LIMITED_QUERIES {
                continue;
            }
            // A maximum distance of 5 % of the radius: some queries find nothing.
            let max = 0.05 * r;
            let expected = brute.closest_point(p, max);
            let got = bvh.closest_point(&mesh, p, max);
            assert_eq!(
                key(got),
                key(expected),
                "{name}: point {i} {p} within {max}"
            );
            let from_wide = wide.closest_point(&packed, p, max);
            assert_eq!(key(from_wide), key(expected), "{name}: wide, point {i}");
            limited_hits += usize::from(got.is_some());
        }
        assert!(
            limited_hits > 0 && limited_hits < LIMITED_QUERIES,
            "{name}: {limited_hits}"
        );
    }
}
