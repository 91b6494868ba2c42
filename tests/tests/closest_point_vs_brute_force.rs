//! Closest-point queries on every bundled mesh equal a brute-force scan (same bits, same
//! triangle under the tie rule), with and without a maximum distance, on the binary tree and
//! on the four-wide tree collapsed from it, one query at a time and in batches.

use meshq::MeshBvh;
use meshq::advanced::PackedTriangle;
use meshq::advanced::WideNode;
use meshq::bvh::BuildConfig;
use meshq::error::{BatchBuffer, BatchError};
use meshq::math::{ClosestPoint, Vec3};
use meshq::wide::WideBvh;
use meshq::{MeshQuery, Traverse};
use meshq_tests::oracle::BruteForce;
use meshq_tests::{MESHES, checked_bvh, load_mesh, workload};

const QUERIES: usize = 10_000;
/// Queries that also run with a maximum distance.
const LIMITED_QUERIES: usize = 2_000;

#[test]
fn closest_point_matches_brute_force_on_every_mesh() {
    for name in MESHES {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        let owned = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
        let bvh = checked_bvh(&owned, &mesh).unwrap();
        let mut storage = vec![PackedTriangle::EMPTY; mesh.triangle_count()];
        let packed = bvh.pack_triangles(&mesh, &mut storage).unwrap();
        let sizes = WideBvh::<WideNode>::measure(&bvh);
        let mut plan_entries = vec![meshq::advanced::PlanEntry::EMPTY; sizes.plan];
        let mut wide_nodes = vec![WideNode::EMPTY; sizes.nodes];
        let wide = WideBvh::build(&bvh, &mut plan_entries, &mut wide_nodes).unwrap();
        let brute = BruteForce::new(&mesh);
        let (_, r, _) = workload::centre_radius(&loaded.positions);
        let points = workload::closest_points(&loaded.positions, QUERIES, 0xC105E);
        let mut limited_hits = 0;
        let (mut unlimited, mut limited) = (Vec::new(), Vec::new());
        for (i, &p) in points.iter().enumerate() {
            let expected = brute.closest_point(p, f32::INFINITY);
            unlimited.push(expected);
            assert!(expected.is_some());
            let got = bvh.with(&mesh).closest_point(p, f32::INFINITY);
            assert_eq!(key(got), key(expected), "{name}: point {i} {p}");
            let from_packed = bvh.with(&packed).closest_point(p, f32::INFINITY);
            assert_eq!(key(from_packed), key(expected), "{name}: packed, point {i}");
            let from_wide = wide.with(&mesh).closest_point(p, f32::INFINITY);
            assert_eq!(key(from_wide), key(expected), "{name}: wide, point {i}");
            let wide_packed = wide.with(&packed).closest_point(p, f32::INFINITY);
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
            limited.push(expected);
            let got = bvh.with(&mesh).closest_point(p, max);
            assert_eq!(
                key(got),
                key(expected),
                "{name}: point {i} {p} within {max}"
            );
            let from_wide = wide.with(&packed).closest_point(p, max);
            assert_eq!(key(from_wide), key(expected), "{name}: wide, point {i}");
            limited_hits += usize::from(got.is_some());
        }
        assert!(
            limited_hits > 0 && limited_hits < LIMITED_QUERIES,
            "{name}: {limited_hits}"
        );

        // Batches, on both trees and sources: each answer as if alone.
        let mut keys = vec![0u64; QUERIES];
        let batch = |query: &BatchCall<'_>, max: f32, n: usize| {
            let mut out = vec![None; n];
            let mut keys = vec![0u64; n];
            query(&points[..n], max, &mut keys, &mut out).unwrap();
            out
        };
        let max = 0.05 * r;
        let runs: [(&str, &BatchCall<'_>); 3] = [
            ("binary", &|p, m, k, o| {
                bvh.with(&mesh).closest_points(p, m, k, o)
            }),
            ("wide packed", &|p, m, k, o| {
                wide.with(&packed).closest_points(p, m, k, o)
            }),
            ("wide", &|p, m, k, o| {
                wide.with(&mesh).closest_points(p, m, k, o)
            }),
        ];
        for (what, query) in runs {
            let got = batch(query, f32::INFINITY, QUERIES);
            assert!(
                got.iter()
                    .map(|&c| key(c))
                    .eq(unlimited.iter().map(|&c| key(c))),
                "{name}: {what} batch"
            );
            let got = batch(query, max, LIMITED_QUERIES);
            assert!(
                got.iter()
                    .map(|&c| key(c))
                    .eq(limited.iter().map(|&c| key(c))),
                "{name}: {what} batch within {max}"
            );
        }

        // Short buffers are errors that write nothing; non-finite points find nothing.
        let mut out = vec![None; QUERIES - 1];
        let err = wide
            .with(&packed)
            .closest_points(&points, f32::INFINITY, &mut keys, &mut out);
        assert_eq!(
            err,
            Err(BatchError::BufferTooSmall {
                buffer: BatchBuffer::Results,
                needed: QUERIES,
                got: QUERIES - 1
            })
        );
        assert!(out.iter().all(Option::is_none));
        let mut out = vec![None; QUERIES];
        let err =
            wide.with(&packed)
                .closest_points(&points, f32::INFINITY, &mut keys[1..], &mut out);
        assert!(matches!(
            err,
            Err(BatchError::BufferTooSmall {
                buffer: BatchBuffer::SortKeys,
                ..
            })
        ));
        assert!(out.iter().all(Option::is_none));
        let odd = [points[0], Vec3::NAN, points[1], Vec3::INFINITY, points[2]];
        wide.with(&packed)
            .closest_points(&odd, f32::INFINITY, &mut keys, &mut out)
            .unwrap();
        let want = [unlimited[0], None, unlimited[1], None, unlimited[2]];
        assert!(
            out[..5]
                .iter()
                .map(|&c| key(c))
                .eq(want.iter().map(|&c| key(c)))
        );
        assert!(
            out[5..].iter().all(Option::is_none),
            "{name}: past the batch"
        );
    }
}

/// A batched closest-point call over some structure and source.
type BatchCall<'a> =
    dyn Fn(&[Vec3], f32, &mut [u64], &mut [Option<ClosestPoint>]) -> Result<(), BatchError> + 'a;

/// What a test compares: distance and point bits, and the triangle.
fn key(c: Option<ClosestPoint>) -> Option<(u32, u32, [u32; 3])> {
    c.map(|c| {
        (
            c.distance_squared.to_bits(),
            c.tri,
            c.point.to_array().map(f32::to_bits),
        )
    })
}
