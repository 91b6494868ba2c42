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

/// By an f64 scan of `triangles` over `positions`: the distance from `p` to the nearest
/// triangle, and to triangle `chosen`.
fn nearest_f64(positions: &[[f32; 3]], triangles: &[[u32; 3]], p: Vec3, chosen: u32) -> (f64, f64) {
    let p64 = p.to_array().map(f64::from);
    let dist = |t: &[u32; 3]| {
        let [a, b, c] = t.map(|v| positions[v as usize].map(f64::from));
        distance_f64(p64, a, b, c)
    };
    let nearest = triangles.iter().map(dist).fold(f64::INFINITY, f64::min);
    (nearest, dist(&triangles[chosen as usize]))
}

/// The distance from `p` to triangle `(a, b, c)` in f64, by its own method: the nearest of
/// the plane's foot (when it falls inside) and the three edges' nearest points.
fn distance_f64(p: [f64; 3], a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    let sub = |x: [f64; 3], y: [f64; 3]| [x[0] - y[0], x[1] - y[1], x[2] - y[2]];
    let dot = |x: [f64; 3], y: [f64; 3]| x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
    let cross = |x: [f64; 3], y: [f64; 3]| {
        [
            x[1] * y[2] - x[2] * y[1],
            x[2] * y[0] - x[0] * y[2],
            x[0] * y[1] - x[1] * y[0],
        ]
    };
    let segment = |s: [f64; 3], e: [f64; 3]| {
        let d = sub(e, s);
        let t = (dot(sub(p, s), d) / dot(d, d)).clamp(0.0, 1.0);
        let q = [s[0] + t * d[0], s[1] + t * d[1], s[2] + t * d[2]];
        dot(sub(p, q), sub(p, q)).sqrt()
    };
    let mut best = segment(a, b).min(segment(b, c)).min(segment(c, a));
    let n = cross(sub(b, a), sub(c, a));
    let nn = dot(n, n);
    if nn > 0.0 {
        let h = dot(sub(p, a), n) / nn;
        let foot = [p[0] - h * n[0], p[1] - h * n[1], p[2] - h * n[2]];
        let inside = [(a, b), (b, c), (c, a)]
            .iter()
            .all(|&(s, e)| dot(cross(sub(e, s), sub(foot, s)), n) >= 0.0);
        if inside {
            best = best.min(h.abs() * nn.sqrt());
        }
    }
    best
}

/// Points so far from the mesh that squared distances overflow f32 (beyond 1.8e19) are
/// answered: the same answer, bit for bit, as the ordinary search gives the whole scene scaled
/// down by 2⁻⁶⁴ (an exact scaling), the nearest triangle by an f64 scan to f32 precision, the
/// distance `distance_from` reports within f32 rounding of f64's, and the same answer from
/// every structure.
#[test]
fn points_beyond_squared_distance_overflow_are_answered() {
    use meshq::mesh::MeshRef;
    use meshq::owned::{MeshIndex, StructureKind};
    let loaded = load_mesh("spot");
    const DOWN: f32 = 1.0 / 18_446_744_073_709_551_616.0;
    // The mesh as large as a valid mesh may be (1e14 times spot, within MAX_COORDINATE), and
    // scaled down again, exactly.
    let big: Vec<[f32; 3]> = loaded
        .positions
        .iter()
        .map(|p| p.map(|x| x * 1e14))
        .collect();
    let small: Vec<[f32; 3]> = big.iter().map(|p| p.map(|x| x * DOWN)).collect();
    let big_mesh = MeshRef::new(&big, &loaded.triangles).validate().unwrap();
    let small_mesh = MeshRef::new(&small, &loaded.triangles).validate().unwrap();
    let small_bvh = MeshBvh::build(&small_mesh, &BuildConfig::default()).unwrap();
    let kinds = [
        StructureKind::Bvh,
        StructureKind::KdTree,
        StructureKind::Octree,
        StructureKind::Grid,
    ];
    let structures: Vec<MeshIndex> = kinds
        .iter()
        .map(|&k| MeshIndex::build(&big_mesh, k).unwrap())
        .collect();
    let directions = workload::closest_points(&loaded.positions, 60, 0xFA12);
    let mut answered = Vec::new();
    for (i, d) in directions.iter().enumerate() {
        let d = (*d - Vec3::splat(0.1)).normalize_or(Vec3::X);
        let far = [3e19f32, 1e21, 1e30, 3e38][i % 4];
        let p = d * far;
        let got = structures[0].closest_point(p, f32::INFINITY).unwrap();
        assert_eq!(got.distance_squared, f32::INFINITY, "{p}: overflowed");
        for (kind, s) in kinds.iter().zip(&structures) {
            assert_eq!(
                s.closest_point(p, f32::INFINITY),
                Some(got),
                "{kind:?} at {p}"
            );
        }
        let scaled = small_bvh.closest_point(p * DOWN, f32::INFINITY).unwrap();
        assert_eq!(
            (scaled.tri, scaled.point),
            (got.tri, got.point * DOWN),
            "{p}"
        );
        // f64: the chosen triangle is the nearest to f32 precision, the distance right.
        let (nearest, chosen) = nearest_f64(&big, &loaded.triangles, p, got.tri);
        assert!(
            chosen <= nearest * (1.0 + 1e-6),
            "{p}: {chosen} vs {nearest}"
        );
        let reported = f64::from(got.distance_from(p));
        assert!(
            (reported - nearest).abs() <= nearest * 1e-6,
            "{p}: {reported} vs {nearest}"
        );
        // A limit below the distance finds nothing; one above it finds the same.
        assert_eq!(
            structures[0].closest_point(p, (nearest * 0.99) as f32),
            None
        );
        assert_eq!(
            structures[0].closest_point(p, (nearest * 1.01) as f32),
            Some(got)
        );
        answered.push(p);
    }
    // The batch call answers them as one call each.
    let mut out = vec![None; answered.len()];
    let mut keys = vec![0u64; answered.len()];
    structures[0]
        .closest_points(&answered, f32::INFINITY, &mut keys, &mut out)
        .unwrap();
    for (p, o) in answered.iter().zip(&out) {
        assert_eq!(*o, structures[0].closest_point(*p, f32::INFINITY), "{p}");
    }
}

/// Meshes of any size within the coordinate limit — triangles from 1e-11 to 1e14 across,
/// whose products of four lengths leave `f32` — answer as at unit size: scaled by a power of
/// two, every structure gives the unit answer scaled (same triangle, same point bits times the
/// scale), and scaled by 1e14 (not a power of two) the nearest triangle by an f64 scan.
#[test]
fn meshes_of_any_size_answer_as_at_unit_size() {
    use meshq::mesh::MeshRef;
    use meshq::owned::{MeshIndex, StructureKind};
    let kinds = [
        StructureKind::Bvh,
        StructureKind::KdTree,
        StructureKind::Octree,
        StructureKind::Grid,
    ];
    for name in ["spot", "fandisk"] {
        let mut loaded = load_mesh(name);
        // First to unit size by a power of two (exact), so every scale below fits the limit.
        let largest = loaded
            .positions
            .iter()
            .flatten()
            .fold(0f32, |m, x| m.max(x.abs()));
        let to_unit = 2f32.powi(-(largest.log2().ceil() as i32));
        for p in &mut loaded.positions {
            *p = p.map(|x| x * to_unit);
        }
        let unit = MeshBvh::build(&loaded.valid(), &BuildConfig::default()).unwrap();
        let points = workload::closest_points(&loaded.positions, 300, 0x5CA1E);
        for k in [-36, 40, 49] {
            let s = 2f32.powi(k);
            let scaled: Vec<[f32; 3]> = loaded.positions.iter().map(|p| p.map(|x| x * s)).collect();
            let mesh = MeshRef::new(&scaled, &loaded.triangles).validate().unwrap();
            for kind in kinds {
                let index = MeshIndex::build(&mesh, kind).unwrap();
                for &p in &points {
                    let want = unit.closest_point(p, f32::INFINITY).unwrap();
                    let got = index.closest_point(p * s, f32::INFINITY).unwrap();
                    assert_eq!(
                        (got.tri, got.point),
                        (want.tri, want.point * s),
                        "{name} at 2^{k}, {kind:?}, {p}"
                    );
                }
            }
        }
        let big: Vec<[f32; 3]> = loaded
            .positions
            .iter()
            .map(|p| p.map(|x| x * 1e14))
            .collect();
        let mesh = MeshRef::new(&big, &loaded.triangles).validate().unwrap();
        let index = MeshIndex::build(&mesh, StructureKind::Bvh).unwrap();
        for &p in &points {
            let p = p * 1e14;
            let got = index.closest_point(p, f32::INFINITY).unwrap();
            let (nearest, chosen) = nearest_f64(&big, &loaded.triangles, p, got.tri);
            let scale = 1e14 * 1e-6;
            assert!(
                chosen <= nearest + scale,
                "{name} ×1e14 at {p}: {chosen} vs {nearest}"
            );
            let reported = f64::from(got.distance_from(p));
            assert!(
                (reported - nearest).abs() <= scale,
                "{name} ×1e14 at {p}: {reported} vs {nearest}"
            );
        }
    }
}
