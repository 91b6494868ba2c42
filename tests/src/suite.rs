//! The brute-force suite every structure runs: each query, single and batched, against a scan of
//! all triangles (same `t` bits, same triangle under the tie rule, same overlap sets).

use std::ops::ControlFlow;

use meshq::MeshQuery;
use meshq::blob::BlobView;
use meshq::geom::CullMode;
use meshq::geom::closest_point_triangle;
use meshq::math::Ray;
use meshq::math::{Aabb, Obb, Triangle, Vec3};
use meshq::query::{BoundsOverlap, RayOptions, ShapeCast, TriangleTest};

use crate::oracle::BruteForce;
use crate::{LoadedMesh, workload};

const RAYS: usize = 400;
const POINTS: usize = 150;
const OVERLAPS: usize = 12;

/// Every query of `q` against the brute-force scan `brute` of `loaded`: random rays with every
/// triangle test (single, any, batched), closest points with and without a limit (single and
/// batched), box and sphere overlaps. Panics with `what` and the query on the first mismatch.
pub fn check_all<Q: MeshQuery + ?Sized>(
    q: &Q,
    brute: &BruteForce,
    loaded: &LoadedMesh,
    what: &str,
) {
    let rays = workload::random_rays(&loaded.positions, RAYS, 5);
    let bits = |h: Option<meshq::math::RayHit>| {
        h.map(|h| (h.t.to_bits(), h.tri, h.u.to_bits(), h.v.to_bits()))
    };
    let options = [
        RayOptions::default(),
        RayOptions {
            test: TriangleTest::MollerTrumbore,
            cull: CullMode::Back,
        },
        RayOptions {
            test: TriangleTest::TwoStep,
            cull: CullMode::Front,
        },
    ];
    for o in &options {
        for (i, ray) in rays.iter().enumerate() {
            let want = brute.raycast(ray, o);
            assert_eq!(
                bits(q.raycast_with(ray, o)),
                bits(want),
                "{what}: ray {i} {o:?}"
            );
            assert_eq!(
                q.raycast_any_with(ray, o),
                want.is_some(),
                "{what}: any {i}"
            );
        }
        let mut keys = vec![0u64; rays.len()];
        let mut hits = vec![None; rays.len()];
        q.raycast_batch(&rays, o, &mut keys, &mut hits).unwrap();
        let want: Vec<_> = rays.iter().map(|r| bits(brute.raycast(r, o))).collect();
        assert_eq!(
            hits.into_iter().map(bits).collect::<Vec<_>>(),
            want,
            "{what}: batch"
        );
        let mut any = vec![false; rays.len()];
        q.raycast_any_batch(&rays, o, &mut keys, &mut any).unwrap();
        let want: Vec<_> = want.iter().map(Option::is_some).collect();
        assert_eq!(any, want, "{what}: any batch");
    }
    for (i, r) in rays.iter().take(50).enumerate() {
        assert_eq!(
            bits(q.raycast(r)),
            bits(brute.raycast(r, &RayOptions::default()))
        );
        assert_eq!(
            q.raycast_any(r),
            brute.raycast(r, &RayOptions::default()).is_some(),
            "{i}"
        );
    }

    // Every hit along each ray, into a buffer that holds them all, exactly as many, or fewer
    // (the nearest ones, and the flag). On the closed test meshes about a third of the rays hit
    // two triangles or more, and cell structures offer repeats that must be dropped.
    let hit_bits =
        |h: &[meshq::math::RayHit]| -> Vec<_> { h.iter().map(|&h| bits(Some(h))).collect() };
    for (i, r) in rays.iter().enumerate() {
        let o = &options[i % 2];
        let want = brute.raycast_all(r, o);
        for size in [
            want.len() + 2,
            want.len(),
            want.len().saturating_sub(1),
            want.len() / 2,
            1,
        ] {
            let mut out = vec![
                meshq::math::RayHit {
                    t: -1.0,
                    tri: u32::MAX,
                    u: 0.0,
                    v: 0.0
                };
                size
            ];
            let got = q.raycast_all(r, o, &mut out);
            let fits = size.min(want.len());
            assert_eq!(
                (hit_bits(&out[..got.written]), got.more),
                (hit_bits(&want[..fits]), want.len() > size),
                "{what}: all hits of ray {i} into {size}"
            );
        }
    }

    // Segments from each ray's origin to half or one and a half times its first hit (or a
    // fixed length on a miss): some end before the surface, some cross it.
    for (i, r) in rays.iter().take(100).enumerate() {
        let o = RayOptions::default();
        let reach = brute.raycast(r, &o).map_or(1.0, |h| h.t) * [0.5, 1.5][i % 2];
        let segment = Ray::segment(r.origin, r.at(reach));
        let want = brute.raycast(&segment, &o);
        assert_eq!(bits(q.raycast(&segment)), bits(want), "{what}: segment {i}");
        assert_eq!(
            q.raycast_any(&segment),
            want.is_some(),
            "{what}: segment any {i}"
        );
    }

    let (c, radius, _) = workload::centre_radius(&loaded.positions);
    let points = workload::closest_points(&loaded.positions, POINTS, 6);
    let key = |p: Option<meshq::math::ClosestPoint>| {
        p.map(|p| {
            (
                p.distance_squared.to_bits(),
                p.tri,
                p.point.to_array().map(f32::to_bits),
            )
        })
    };
    for max in [f32::INFINITY, 0.05 * radius] {
        let want: Vec<_> = points
            .iter()
            .map(|&p| key(brute.closest_point(p, max)))
            .collect();
        let got: Vec<_> = points
            .iter()
            .map(|&p| key(q.closest_point(p, max)))
            .collect();
        assert_eq!(got, want, "{what}: closest point, max {max}");
        let mut keys = vec![0u64; points.len()];
        let mut out = vec![None; points.len()];
        q.closest_points(&points, max, &mut keys, &mut out).unwrap();
        assert_eq!(
            out.into_iter().map(key).collect::<Vec<_>>(),
            want,
            "{what}: batch"
        );
    }

    let mut overlapped = 0;
    for (i, p) in workload::closest_points(&loaded.positions, OVERLAPS, 7)
        .into_iter()
        .enumerate()
    {
        let half = Vec3::splat(radius * 0.02 * (1 + i % 4) as f32);
        let aabb = Aabb::new(p - half, p + half);
        let mut want = brute.overlap_aabb(&aabb);
        want.sort_unstable();
        let mut out = vec![0u32; want.len() + 3];
        let count = q.overlap_aabb_into(&aabb, &mut out);
        assert!(count.is_complete(), "{what}: box {i}");
        let mut got = out[..count.written].to_vec();
        got.sort_unstable();
        assert_eq!(got, want, "{what}: box {i}");

        let r = radius * 0.03 * (1 + i % 3) as f32;
        let mut want = brute.overlap_sphere(p, r);
        want.sort_unstable();
        let mut got = Vec::new();
        q.overlap_sphere(p, r, |t| {
            got.push(t);
            ControlFlow::Continue(())
        });
        got.sort_unstable();
        assert_eq!(got, want, "{what}: sphere {i}");
        // A report that breaks stops the query.
        let mut seen = 0;
        q.overlap_sphere(p, r, |_| {
            seen += 1;
            ControlFlow::Break(())
        });
        assert_eq!(seen, usize::from(!want.is_empty()), "{what}: break {i}");

        // The same sphere as a shape cast of the caller's own: every triangle it offers once
        // (shapecast_once), or at least once (shapecast), and the nearest cells first.
        let mut cast = SphereCast::new(p, r);
        q.shapecast(&mut cast);
        let mut got = cast.found.clone();
        got.sort_unstable();
        got.dedup();
        assert_eq!(got, want, "{what}: sphere shape cast {i}");
        assert!(cast.contained_ok, "{what}: contained flag {i}");
        let mut cast = SphereCast::new(p, r);
        let mut seen = vec![u64::MAX; brute.triangle_count().div_ceil(64)];
        q.shapecast_once(&mut cast, &mut seen);
        let mut got = cast.found.clone();
        got.sort_unstable();
        assert_eq!(got, want, "{what}: sphere shape cast once {i}");

        // A triangle around the point, turned by the index, and an oriented box turned the
        // same way: each touching triangle reported once.
        let (sin, cos) = (0.7 * i as f32).sin_cos();
        let (u, v) = (
            Vec3::new(cos, sin, 0.3).normalize(),
            Vec3::new(-sin, cos, 0.0),
        );
        let w = u.cross(v).normalize();
        let v = w.cross(u);
        let size = radius * 0.04 * (1 + i % 3) as f32;
        let query = Triangle::new(p - u * size, p + v * size, p + (u + w) * size);
        let want = brute.overlap_triangle(&query);
        let mut out = vec![0u32; want.len() + 2];
        let count = q.overlap_triangle_into(&query, &mut out);
        let mut got = out[..count.written].to_vec();
        got.sort_unstable();
        assert_eq!(
            (got, count.total),
            (want.clone(), want.len()),
            "{what}: triangle {i}"
        );
        let obb = Obb::new(p, [u, v, w], Vec3::new(1.0, 0.5, 2.0) * size);
        let want = brute.overlap_obb(&obb);
        let mut out = vec![0u32; want.len() + 2];
        let count = q.overlap_obb_into(&obb, &mut out);
        let mut got = out[..count.written].to_vec();
        got.sort_unstable();
        assert_eq!(
            (got, count.total),
            (want.clone(), want.len()),
            "{what}: oriented box {i}"
        );
        overlapped += usize::from(!want.is_empty());
    }
    // Not vacuous: some of the boxes, placed around points of the workload, meet the mesh.
    assert!(
        overlapped >= 3,
        "{what}: {overlapped} oriented boxes met the mesh"
    );
    let _ = c;
}

/// Runs every kind of query on a blob view (rays, any-hit, closest points, overlaps); the
/// point is that none of them panics or hangs. Returns how many found something.
pub fn exercise(view: &BlobView<'_>) -> usize {
    let b = view.bounds();
    let (c, r) = if b.is_empty() || !b.is_finite() {
        (Vec3::ZERO, 1.0)
    } else {
        (b.center(), (0.5 * b.extent().length()).max(1e-3))
    };
    let mut found = 0;
    for k in 0..16u32 {
        let angle = k as f32 * 0.39;
        let origin = c + Vec3::new(angle.cos(), angle.sin(), 0.5) * (2.0 * r);
        let ray = Ray::new(origin, c - origin);
        found += usize::from(view.raycast(&ray).is_some());
        found += usize::from(view.raycast_any(&ray));
        found += usize::from(view.closest_point(origin, f32::INFINITY).is_some());
    }
    let mut out = [0u32; 8];
    found += view
        .overlap_aabb_into(&Aabb::new(c - Vec3::splat(r), c + Vec3::splat(r)), &mut out)
        .total;
    view.overlap_sphere(c, 0.5 * r, |_| ControlFlow::Continue(()));
    found
}

/// A sphere cast through [`ShapeCast`], recording the triangles within its radius and whether
/// every triangle offered as contained really lies inside.
struct SphereCast {
    center: Vec3,
    radius: f32,
    found: Vec<u32>,
    contained_ok: bool,
}

impl SphereCast {
    fn new(center: Vec3, radius: f32) -> Self {
        Self {
            center,
            radius,
            found: Vec::new(),
            contained_ok: true,
        }
    }
}

impl ShapeCast for SphereCast {
    fn bounds(&mut self, aabb: &Aabb) -> BoundsOverlap {
        let near = self.center.clamp(aabb.min, aabb.max);
        let far = Vec3::select(
            (self.center - aabb.min).cmpgt(aabb.max - self.center),
            aabb.min,
            aabb.max,
        );
        let r2 = self.radius * self.radius;
        if near.distance_squared(self.center) > r2 {
            BoundsOverlap::Outside
        } else if far.distance_squared(self.center) <= r2 {
            BoundsOverlap::Inside
        } else {
            BoundsOverlap::Crosses
        }
    }

    fn score(&mut self, aabb: &Aabb) -> f32 {
        self.center
            .clamp(aabb.min, aabb.max)
            .distance_squared(self.center)
    }

    fn triangle(&mut self, tri: u32, corners: &Triangle, contained: bool) -> ControlFlow<()> {
        if closest_point_triangle(self.center, corners).distance_squared
            <= self.radius * self.radius
        {
            self.found.push(tri);
        }
        if contained {
            let r2 = self.radius * self.radius;
            self.contained_ok &= [corners.a, corners.b, corners.c]
                .iter()
                .all(|c| c.distance_squared(self.center) <= r2);
        }
        ControlFlow::Continue(())
    }
}
