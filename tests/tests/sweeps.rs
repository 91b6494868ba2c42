//! Sweeps ([`MeshQuery::sweep`]) against an `f64` brute force: the shape marched along its
//! motion by steps no longer than its distance to the nearest triangle of the whole mesh
//! (`meshq_tests::distance_oracle::time_of_impact`), which can pass no contact and stops
//! within 10⁻⁹ of the scene's size of the first one.

use meshq::bvh::BuildConfig;
use meshq::error::SweepError;
use meshq::math::{Obb, Vec3};
use meshq::mesh::{MeshRef, ValidMesh};
use meshq::owned::MeshBvh;
use meshq::query::{MeshQuery, SWEEP_TOLERANCE, SweepHit, SweepShape, Traverse};
use meshq_tests::distance_oracle::{
    Shape64, Tri64, point_triangle_squared, shape_mesh, time_of_impact, widen,
};
use meshq_tests::{SplitMix64, hard_inputs, load_mesh};

type Mesh = (Vec<[f32; 3]>, Vec<[u32; 3]>);

fn bundled(name: &str) -> Mesh {
    let m = load_mesh(name);
    (m.positions, m.triangles)
}

fn valid(m: &Mesh) -> ValidMesh<'_> {
    MeshRef::new(&m.0, &m.1).validate().expect("valid mesh")
}

fn shape64(shape: &SweepShape) -> Shape64 {
    match *shape {
        SweepShape::Sphere { center, radius } => {
            Shape64::Sphere(center.as_dvec3(), f64::from(radius))
        }
        SweepShape::Capsule { a, b, radius } => {
            Shape64::Capsule(a.as_dvec3(), b.as_dvec3(), f64::from(radius))
        }
        SweepShape::Box(obb) => Shape64::Box(
            obb.center.as_dvec3(),
            obb.axes.map(Vec3::as_dvec3),
            obb.half_extents.as_dvec3(),
        ),
    }
}

/// Random sweeps across the mesh's box: from outside it toward a point inside, shapes a few
/// percent of its size, turned at random.
fn sweeps(bounds: (Vec3, Vec3), count: usize, seed: u64) -> Vec<(SweepShape, Vec3)> {
    let mut rng = SplitMix64::new(seed);
    let mut unit = move || rng.next_f32();
    let (lo, hi) = bounds;
    let size = (hi - lo).length();
    let centre = (lo + hi) * 0.5;
    let mut out = Vec::new();
    for k in 0..count {
        let dir = Vec3::new(unit() - 0.5, unit() - 0.5, unit() - 0.5).normalize_or(Vec3::X);
        let start = centre + dir * size * 0.9;
        let target = lo + (hi - lo) * Vec3::new(unit(), unit(), unit());
        let motion = (target - start) * 1.2;
        let r = size * (0.01 + 0.05 * unit());
        let q = glam::Quat::from_euler(
            glam::EulerRot::XYZ,
            unit() * 6.0,
            unit() * 6.0,
            unit() * 6.0,
        );
        let shape = match k % 3 {
            0 => SweepShape::Sphere {
                center: start,
                radius: r,
            },
            1 => SweepShape::Capsule {
                a: start - q * Vec3::Y * r * 2.0,
                b: start + q * Vec3::Y * r * 2.0,
                radius: r * 0.5,
            },
            _ => SweepShape::Box(Obb::new(
                start,
                [q * Vec3::X, q * Vec3::Y, q * Vec3::Z],
                Vec3::new(r, r * 0.6, r * 0.3),
            )),
        };
        out.push((shape, motion));
    }
    out
}

/// Checks one sweep: a hit must touch (within the stated tolerance) at its `t` and come no
/// later than the brute force's first contact; a miss must be the brute force's too (or a
/// near miss within the tolerance).
fn check(
    name: &str,
    k: usize,
    tris: &[Tri64],
    shape: &SweepShape,
    motion: Vec3,
    got: Option<SweepHit>,
    size: f64,
) {
    let s = shape64(shape);
    let m = motion.as_dvec3();
    let sweep_size = {
        let b = shape.bounds();
        f64::from(b.extent().length()) + m.length()
    };
    let tol = sweep_size * f64::from(SWEEP_TOLERANCE) + size * 1e-6;
    let expected = time_of_impact(&s, m, tris, size * 1e-9);
    match (got, expected) {
        (None, None) => {}
        (Some(hit), want) => {
            let t = f64::from(hit.t);
            let at = s.moved(m * t);
            let gap = shape_mesh(&at, tris);
            assert!(
                gap <= tol,
                "{name} sweep {k}: {gap} from the mesh at t = {t} (tolerance {tol})"
            );
            if let Some(w) = want {
                // Never later than the first contact (in the motion's fraction, by the distance
                // a tolerance's worth of travel takes).
                assert!(
                    t <= w + tol / m.length().max(1e-30),
                    "{name} sweep {k}: t = {t}, first contact at {w}"
                );
            }
            // The point is on the triangle named, the normal a unit vector, the point within
            // the tolerance of the shape.
            let tri = &tris[hit.tri as usize];
            assert!(
                point_triangle_squared(hit.point.as_dvec3(), tri).sqrt() <= size * 1e-6,
                "{name} sweep {k}: point off its triangle"
            );
            assert!(
                (f64::from(hit.normal.length()) - 1.0).abs() <= 1e-5,
                "{name} sweep {k}: normal {:?}",
                hit.normal
            );
            let point_tri: Tri64 = [hit.point.as_dvec3(); 3];
            assert!(
                at.distance(&point_tri) <= tol,
                "{name} sweep {k}: the point is {} from the shape at t = {t} (gap {gap}, tolerance {tol}, {shape:?})",
                at.distance(&point_tri)
            );
        }
        (None, Some(w)) => panic!("{name} sweep {k}: missed, the brute force touches at t = {w}"),
    }
}

#[test]
fn sweeps_touch_where_the_brute_force_does() {
    for name in ["spot", "teapot", "uv-sphere", "uv-sphere ×1e12"] {
        // The last one 10¹² times the size (far beyond where products of four lengths fit
        // in `f32`), and its sweeps with it.
        let mesh = match name.split_once(" ×") {
            Some((base, factor)) => {
                let k: f32 = factor.parse().unwrap();
                let (p, t) = bundled(base);
                (p.iter().map(|v| v.map(|x| x * k)).collect(), t)
            }
            None => bundled(name),
        };
        let v = valid(&mesh);
        let tris: Vec<Tri64> = (0..v.triangle_count() as u32)
            .map(|t| widen(&v.triangle(t).unwrap()))
            .collect();
        let bounds = (0..v.triangle_count() as u32).fold(meshq::math::Aabb::EMPTY, |b, t| {
            b.union(v.triangle(t).unwrap().bounds())
        });
        let size = f64::from(bounds.extent().length());
        let bvh = MeshBvh::build(&v, &BuildConfig::default()).unwrap();
        let (tree, packed) = (bvh.bvh(), bvh.packed());
        let kd = meshq::owned::MeshIndex::build(&v, meshq::owned::StructureKind::KdTree).unwrap();
        let (mut hits, mut misses) = (0, 0);
        for (k, (shape, motion)) in sweeps((bounds.min, bounds.max), 45, 0x5eed_5ee9)
            .into_iter()
            .enumerate()
        {
            let got = tree.with(&packed).sweep(&shape, motion).unwrap();
            check(name, k, &tris, &shape, motion, got, size);
            // Every structure and triangle source gives the same answer.
            assert_eq!(
                tree.with(&v).sweep(&shape, motion).unwrap(),
                got,
                "{name} sweep {k}: indexed"
            );
            assert_eq!(
                kd.sweep(&shape, motion).unwrap(),
                got,
                "{name} sweep {k}: k-d tree"
            );
            if got.is_some() {
                hits += 1
            } else {
                misses += 1
            }
        }
        assert!(
            hits >= 20 && misses >= 3,
            "{name}: {hits} hits, {misses} misses"
        );
    }
}

#[test]
fn contact_at_the_start_zero_motion_and_bad_input() {
    let mesh = hard_inputs::cuboid(1.0, 1.0, 1.0);
    let v = valid(&mesh);
    let bvh = MeshBvh::build(&v, &BuildConfig::default()).unwrap();
    let q = bvh.bvh();
    let w = q.with(&v);
    // A sphere straddling the top face: t = 0, the normal up (toward its centre).
    let straddling = SweepShape::Sphere {
        center: Vec3::new(0.5, 0.5, 1.05),
        radius: 0.1,
    };
    let hit = w
        .sweep(&straddling, Vec3::new(0.0, 0.0, -1.0))
        .unwrap()
        .unwrap();
    assert_eq!(hit.t, 0.0);
    assert!(hit.normal.z > 0.99, "{:?}", hit.normal);
    // A sphere dropped onto the top face lands when its bottom reaches it.
    let above = SweepShape::Sphere {
        center: Vec3::new(0.5, 0.5, 2.0),
        radius: 0.25,
    };
    let hit = w.sweep(&above, Vec3::new(0.0, 0.0, -2.0)).unwrap().unwrap();
    assert!((hit.t - 0.375).abs() <= 1e-5, "{}", hit.t);
    assert!((hit.point - Vec3::new(0.5, 0.5, 1.0)).length() <= 1e-5);
    assert!((hit.normal - Vec3::Z).length() <= 1e-5);
    // Moving away, or past: nothing.
    assert_eq!(w.sweep(&above, Vec3::new(0.0, 0.0, 2.0)).unwrap(), None);
    assert_eq!(w.sweep(&above, Vec3::new(3.0, 0.0, 0.0)).unwrap(), None);
    // No motion: whether it touches now.
    assert_eq!(w.sweep(&above, Vec3::ZERO).unwrap(), None);
    assert_eq!(
        w.sweep(&straddling, Vec3::ZERO).unwrap().map(|h| h.t),
        Some(0.0)
    );
    // A box turned 45° about x, dropped edge first onto the top face.
    let r = glam::Quat::from_rotation_x(std::f32::consts::FRAC_PI_4);
    let edge_down = SweepShape::Box(Obb::new(
        Vec3::new(0.5, 0.5, 2.0),
        [r * Vec3::X, r * Vec3::Y, r * Vec3::Z],
        Vec3::splat(0.1),
    ));
    let hit = w
        .sweep(&edge_down, Vec3::new(0.0, 0.0, -2.0))
        .unwrap()
        .unwrap();
    let expected = (1.0 - 0.1 * std::f32::consts::SQRT_2) / 2.0;
    assert!((hit.t - expected).abs() <= 1e-5, "{} vs {expected}", hit.t);
    // Bad input is a typed error.
    let nan = SweepShape::Sphere {
        center: Vec3::NAN,
        radius: 1.0,
    };
    assert_eq!(w.sweep(&nan, Vec3::X), Err(SweepError::InvalidShape));
    let negative = SweepShape::Capsule {
        a: Vec3::ZERO,
        b: Vec3::X,
        radius: -1.0,
    };
    assert_eq!(w.sweep(&negative, Vec3::X), Err(SweepError::InvalidShape));
    assert_eq!(
        w.sweep(&above, Vec3::new(f32::INFINITY, 0.0, 0.0)),
        Err(SweepError::InvalidMotion)
    );
    // Degenerate and piled-up meshes stay bounded and right.
    for (name, m) in [
        ("200k copies", hard_inputs::same(200_000)),
        ("slivers", hard_inputs::crossing(2_000)),
    ] {
        let v = valid(&m);
        let bvh = MeshBvh::build(&v, &BuildConfig::default()).unwrap();
        let t = bvh.bvh();
        let tris: Vec<Tri64> = (0..v.triangle_count() as u32)
            .map(|i| widen(&v.triangle(i).unwrap()))
            .collect();
        let shape = SweepShape::Sphere {
            center: Vec3::new(0.2, 0.2, 3.0),
            radius: 0.1,
        };
        let got = t.with(&v).sweep(&shape, Vec3::new(0.0, 0.0, -6.0)).unwrap();
        check(name, 0, &tris, &shape, Vec3::new(0.0, 0.0, -6.0), got, 3.0);
        assert!(got.is_some(), "{name}");
    }
}
