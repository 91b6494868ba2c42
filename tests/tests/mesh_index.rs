//! `MeshIndex`'s own ray and point queries (which pick the structure once, then run its query)
//! against brute force and against the generic `MeshQuery` path through the enum, for every
//! structure kind: the same answers, bit for bit.

use meshq::MeshQuery;
use meshq::geom::CullMode;
use meshq::math::{ClosestPoint, Ray, RayHit, Vec3};
use meshq::owned::{MeshIndex, StructureKind};
use meshq::query::{RayOptions, TriangleTest};
use meshq_tests::oracle::BruteForce;
use meshq_tests::{load_mesh, workload};

type HitBits = Option<(u32, u32, u32, u32)>;

fn bits(h: Option<RayHit>) -> HitBits {
    h.map(|h| (h.t.to_bits(), h.tri, h.u.to_bits(), h.v.to_bits()))
}

fn point_bits(p: Option<ClosestPoint>) -> Option<(u32, u32, [u32; 3])> {
    p.map(|p| {
        (
            p.distance_squared.to_bits(),
            p.tri,
            p.point.to_array().map(f32::to_bits),
        )
    })
}

/// `MeshQuery`'s implementation for `MeshIndex` (every visit and leaf read through the enum),
/// reached through a generic function so that the inherent methods cannot be picked.
fn generic_raycast<Q: MeshQuery + ?Sized>(q: &Q, ray: &Ray, o: &RayOptions) -> Option<RayHit> {
    q.raycast_with(ray, o)
}

fn generic_closest<Q: MeshQuery + ?Sized>(q: &Q, p: Vec3, limit: f32) -> Option<ClosestPoint> {
    q.closest_point(p, limit)
}

#[test]
fn own_queries_answer_as_brute_force_and_the_generic_path() {
    let options = [
        RayOptions::default(),
        RayOptions {
            test: TriangleTest::MollerTrumbore,
            cull: CullMode::Back,
        },
    ];
    for name in ["cow", "fandisk", "teapot"] {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        let brute = BruteForce::new(&mesh);
        let mut rays = workload::random_rays(&loaded.positions, 300, 11);
        rays.extend(workload::camera_rays(&loaded.positions, 24, 16));
        let points = workload::closest_points(&loaded.positions, 120, 12);
        let (_, radius, _) = workload::centre_radius(&loaded.positions);
        for kind in StructureKind::ALL {
            let index = MeshIndex::build(&mesh, kind).unwrap();
            let what = format!("{name} {kind}");
            for o in &options {
                let want: Vec<HitBits> = rays.iter().map(|r| bits(brute.raycast(r, o))).collect();
                for ((i, r), &w) in rays.iter().enumerate().zip(&want) {
                    assert_eq!(bits(index.raycast_with(r, o)), w, "{what}: ray {i} {o:?}");
                    assert_eq!(
                        bits(generic_raycast(&index, r, o)),
                        w,
                        "{what}: generic {i}"
                    );
                    assert_eq!(index.raycast_any_with(r, o), w.is_some(), "{what}: any {i}");
                }
                let mut keys = vec![0u64; rays.len()];
                let mut hits = vec![None; rays.len()];
                index.raycast_batch(&rays, o, &mut keys, &mut hits).unwrap();
                assert_eq!(
                    hits.into_iter().map(bits).collect::<Vec<_>>(),
                    want,
                    "{what}: batch"
                );
                let mut any = vec![false; rays.len()];
                index
                    .raycast_any_batch(&rays, o, &mut keys, &mut any)
                    .unwrap();
                let want_any: Vec<bool> = want.iter().map(Option::is_some).collect();
                assert_eq!(any, want_any, "{what}: any batch");
            }
            for (i, r) in rays.iter().enumerate().step_by(7) {
                let want = brute.raycast(r, &RayOptions::default());
                assert_eq!(bits(index.raycast(r)), bits(want), "{what}: default {i}");
                assert_eq!(index.raycast_any(r), want.is_some(), "{what}: any {i}");
                let all = brute.raycast_all(r, &options[0]);
                let mut out = vec![
                    RayHit {
                        t: -1.0,
                        tri: u32::MAX,
                        u: 0.0,
                        v: 0.0,
                    };
                    all.len() + 1
                ];
                let found = index.raycast_all(r, &options[0], &mut out);
                assert_eq!(found.written, all.len(), "{what}: all hits of {i}");
                assert!(!found.more, "{what}: all hits of {i} fit");
                for (got, want) in out.iter().zip(&all) {
                    assert_eq!(
                        bits(Some(*got)),
                        bits(Some(*want)),
                        "{what}: all hits of {i}"
                    );
                }
            }
            for limit in [f32::INFINITY, 0.05 * radius] {
                let want: Vec<_> = points
                    .iter()
                    .map(|&p| point_bits(brute.closest_point(p, limit)))
                    .collect();
                for ((i, &p), w) in points.iter().enumerate().zip(&want) {
                    assert_eq!(
                        point_bits(index.closest_point(p, limit)),
                        *w,
                        "{what}: point {i}"
                    );
                    assert_eq!(
                        point_bits(generic_closest(&index, p, limit)),
                        *w,
                        "{what}: generic point {i}"
                    );
                }
                let mut keys = vec![0u64; points.len()];
                let mut out = vec![None; points.len()];
                index
                    .closest_points(&points, limit, &mut keys, &mut out)
                    .unwrap();
                assert_eq!(
                    out.into_iter().map(point_bits).collect::<Vec<_>>(),
                    want,
                    "{what}: point batch"
                );
            }
        }
    }
}

/// Bad input to `MeshIndex`'s own methods: NaN and zero-direction rays hit nothing, non-finite
/// points and a negative limit find nothing, and a batch with a short buffer is refused with
/// the generic path's error before anything is written.
#[test]
fn own_queries_refuse_bad_input_as_the_generic_path_does() {
    let loaded = load_mesh("cow");
    let mesh = loaded.valid();
    let rays = workload::random_rays(&loaded.positions, 8, 3);
    for kind in StructureKind::ALL {
        let index = MeshIndex::build(&mesh, kind).unwrap();
        let o = RayOptions::default();
        for bad in [
            Ray::new(Vec3::new(f32::NAN, 0.0, 0.0), Vec3::X),
            Ray::new(Vec3::ZERO, Vec3::new(0.0, f32::NAN, 1.0)),
            Ray::new(Vec3::ZERO, Vec3::ZERO),
        ] {
            assert_eq!(index.raycast(&bad), None, "{kind}");
            assert!(!index.raycast_any_with(&bad, &o), "{kind}");
            let mut out = [RayHit {
                t: 0.0,
                tri: 0,
                u: 0.0,
                v: 0.0,
            }; 4];
            assert_eq!(index.raycast_all(&bad, &o, &mut out).written, 0, "{kind}");
        }
        for (p, limit) in [
            (Vec3::new(f32::NAN, 0.0, 0.0), f32::INFINITY),
            (Vec3::splat(f32::INFINITY), f32::INFINITY),
            (Vec3::ZERO, -1.0),
            (Vec3::ZERO, f32::NAN),
        ] {
            assert_eq!(point_bits(index.closest_point(p, limit)), None, "{kind}");
        }
        let mut keys = vec![0u64; rays.len()];
        let sentinel = Some(RayHit {
            t: -7.0,
            tri: 7,
            u: 0.0,
            v: 0.0,
        });
        let mut hits = vec![sentinel; rays.len() - 1];
        let own = index.raycast_batch(&rays, &o, &mut keys, &mut hits);
        let generic = MeshQuery::raycast_batch(&index, &rays, &o, &mut keys, &mut hits);
        assert!(own.is_err(), "{kind}: short output accepted");
        assert_eq!(own, generic, "{kind}");
        assert!(hits.iter().all(|&h| bits(h) == bits(sentinel)), "{kind}");
        let mut any = vec![true; rays.len()];
        assert!(
            index
                .raycast_any_batch(&rays, &o, &mut keys[..2], &mut any)
                .is_err(),
            "{kind}: short keys accepted"
        );
        assert!(any.iter().all(|&a| a), "{kind}: written after an error");
        let points = workload::closest_points(&loaded.positions, 4, 1);
        let mut out = vec![None; 3];
        assert!(
            index
                .closest_points(&points, f32::INFINITY, &mut keys, &mut out)
                .is_err(),
            "{kind}: short point output accepted"
        );
        assert!(out.iter().all(Option::is_none), "{kind}");
    }
}
