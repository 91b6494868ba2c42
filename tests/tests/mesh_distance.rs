//! Mesh–mesh distance ([`meshq::collide::mesh_distance`]) and the generic two-tree walk
//! ([`meshq::collide::walk_pairs`]) against `f64` brute force over every pair of triangles
//! (`meshq_tests::distance_oracle`, written apart from the crate).

use std::collections::BTreeSet;
use std::ops::ControlFlow;

use meshq::Traverse;
use meshq::bvh::{BuildConfig, SpatialSplits};
use meshq::collide::{
    Affine, DistanceLimits, MeshDistance, PairBudget, PairVisitor, TrianglePair, WalkedTriangle,
    intersecting_pairs, mesh_distance, walk_pairs,
};
use meshq::geom::{
    TriangleTriangle, closest_points_triangle_triangle, intersect_triangle_triangle,
};
use meshq::math::{Aabb, Triangle};
use meshq::mesh::{MeshRef, ValidMesh};
use meshq::owned::MeshBvh;
use meshq_tests::distance_oracle::{self, Tri64, point_triangle_squared, widen};
use meshq_tests::hard_inputs;
use meshq_tests::load_mesh;

type Mesh = (Vec<[f32; 3]>, Vec<[u32; 3]>);

fn bundled(name: &str) -> Mesh {
    let m = load_mesh(name);
    (m.positions, m.triangles)
}

fn valid(m: &Mesh) -> ValidMesh<'_> {
    MeshRef::new(&m.0, &m.1).validate().expect("valid mesh")
}

fn triangles(m: &ValidMesh<'_>) -> Vec<Triangle> {
    (0..m.triangle_count() as u32)
        .map(|t| m.triangle(t).expect("in range"))
        .collect()
}

fn bounds(tris: &[Triangle]) -> Aabb {
    tris.iter().fold(Aabb::EMPTY, |b, t| b.union(t.bounds()))
}

/// A rotation of `degrees` about the axis (1, 2, 3), a scale per axis applied first, then a
/// translation.
fn placement(degrees: f32, scale: [f32; 3], t: [f32; 3]) -> Affine {
    let axis = glam::Vec3::new(1.0, 2.0, 3.0).normalize();
    let r = glam::Mat3::from_axis_angle(axis, degrees.to_radians());
    let m = r * glam::Mat3::from_diagonal(glam::Vec3::from(scale));
    Affine {
        columns: [
            m.x_axis.to_array(),
            m.y_axis.to_array(),
            m.z_axis.to_array(),
        ],
        translation: t,
    }
}

/// Checks `got` against the oracle on the same `f32` triangles (`b`'s placed by `place`):
/// the distance within 2⁻¹⁸ of the scene's size, the points on the triangles named, and
/// their gap equal to the distance.
fn check(name: &str, a: &[Triangle], b: &[Triangle], place: &Affine, got: Option<MeshDistance>) {
    let placed: Vec<Triangle> = b.iter().map(|t| place.apply_triangle(t)).collect();
    let wa: Vec<Tri64> = a.iter().map(widen).collect();
    let wb: Vec<Tri64> = placed.iter().map(widen).collect();
    let expected = distance_oracle::mesh_mesh(&wa, &wb);
    let scene = bounds(a).union(bounds(&placed));
    let size = f64::from(scene.extent().length());
    let tol = size * 2f64.powi(-18);
    let got = got.unwrap_or_else(|| panic!("{name}: no answer"));
    let d = f64::from(got.distance);
    assert!(
        (d - expected).abs() <= tol,
        "{name}: distance {d}, brute force {expected} (tolerance {tol})"
    );
    let ta = widen(&a[got.triangle_a as usize]);
    let tb = widen(&placed[got.triangle_b as usize]);
    assert!(
        point_triangle_squared(got.on_a.as_dvec3(), &ta).sqrt() <= tol,
        "{name}: on_a off its triangle"
    );
    assert!(
        point_triangle_squared(got.on_b.as_dvec3(), &tb).sqrt() <= tol,
        "{name}: on_b off its triangle"
    );
    let gap = f64::from(got.on_a.distance(got.on_b));
    assert!(
        (gap - d).abs() <= tol,
        "{name}: the points are {gap} apart, the distance is {d}"
    );
    // The pair reported is a closest pair by the oracle too.
    let pair = distance_oracle::triangle_triangle(&ta, &tb);
    assert!(
        (pair - expected).abs() <= tol,
        "{name}: the pair named is {pair} apart, not {expected}"
    );
    if expected == 0.0 {
        assert_eq!(got.distance, 0.0, "{name}: meeting meshes are at exactly 0");
        let ta32 = a[got.triangle_a as usize];
        let tb32 = placed[got.triangle_b as usize];
        assert_ne!(
            intersect_triangle_triangle(&ta32, &tb32),
            TriangleTriangle::Disjoint
        );
    }
}

fn distance(
    a: &MeshBvh,
    b: &MeshBvh,
    place: &Affine,
    limits: DistanceLimits,
) -> Option<MeshDistance> {
    let (ta, tb, pa, pb) = (a.bvh(), b.bvh(), a.packed(), b.packed());
    let (na, nb) = (a.mesh().triangle_count(), b.mesh().triangle_count());
    mesh_distance(
        ta.with(&pa),
        tb.with(&pb),
        Some(place),
        limits,
        PairBudget::for_triangles(na, nb),
    )
    .expect("within budget")
}

/// Pairs of real meshes in placements that meet, nearly touch, nest and lie far apart, with
/// rotations, non-uniform scales and mirrors, on plain and spatial-split trees.
#[test]
fn closest_pairs_match_brute_force() {
    let spot = bundled("spot");
    let teapot = bundled("teapot");
    let sphere = bundled("uv-sphere");
    let stick = hard_inputs::cuboid(2.0, 0.1, 0.1);
    let crossing_over = {
        // Turned 80° about z, its middle 0.2 over the first stick's middle: the closest points
        // are where long edges cross over each other, far from every corner.
        let r = glam::Mat3::from_rotation_z(80f32.to_radians());
        let t = glam::Vec3::new(1.0, 0.05, 0.35) - r * glam::Vec3::new(1.0, 0.05, 0.05);
        Affine {
            columns: [
                r.x_axis.to_array(),
                r.y_axis.to_array(),
                r.z_axis.to_array(),
            ],
            translation: t.to_array(),
        }
    };
    let cases: [(&str, &Mesh, &Mesh, Affine); 9] = [
        (
            "a stick crossing over another",
            &stick,
            &stick,
            crossing_over,
        ),
        (
            "spot, copy turned and crossing",
            &spot,
            &spot,
            placement(25.0, [1.0; 3], [0.3, 0.1, 0.0]),
        ),
        (
            "spot, copy beside",
            &spot,
            &spot,
            placement(0.0, [1.0; 3], [1.0, 0.0, 0.0]),
        ),
        (
            "spot, small copy inside",
            &spot,
            &spot,
            placement(10.0, [0.2; 3], [0.0, 0.2, 0.05]),
        ),
        (
            "spot, stretched copy above",
            &spot,
            &spot,
            placement(70.0, [2.0, 0.5, 1.0], [0.0, 1.5, 0.4]),
        ),
        (
            "spot, mirrored copy",
            &spot,
            &spot,
            placement(0.0, [-1.0, 1.0, 1.0], [1.5, 0.0, 0.0]),
        ),
        (
            "teapot and sphere near its spout",
            &teapot,
            &sphere,
            placement(5.0, [0.3; 3], [3.6, 1.3, 0.0]),
        ),
        (
            "sphere and teapot far off",
            &sphere,
            &teapot,
            placement(45.0, [0.1; 3], [40.0, -7.0, 3.0]),
        ),
        (
            "teapot and a copy inside out",
            &teapot,
            &teapot,
            placement(180.0, [0.9; 3], [0.2, 0.0, 0.1]),
        ),
    ];
    let config = BuildConfig::default();
    for (name, ma, mb, place) in &cases {
        let (va, vb) = (valid(ma), valid(mb));
        let (a, b) = (triangles(&va), triangles(&vb));
        let plain_a = MeshBvh::build(&va, &config).unwrap();
        let plain_b = MeshBvh::build(&vb, &config).unwrap();
        let got = distance(&plain_a, &plain_b, place, DistanceLimits::default());
        check(name, &a, &b, place, got);
        let split_a = MeshBvh::build_spatial(&va, &config, &SpatialSplits::default()).unwrap();
        let split_b = MeshBvh::build_spatial(&vb, &config, &SpatialSplits::default()).unwrap();
        let split = distance(&split_a, &split_b, place, DistanceLimits::default());
        check(&format!("{name} (spatial splits)"), &a, &b, place, split);
        assert_eq!(
            got.map(|g| g.distance),
            split.map(|g| g.distance),
            "{name}: the trees disagree"
        );
        // Indexed and packed triangles give the same bits.
        let indexed = mesh_distance(
            plain_a.bvh().with(&va),
            plain_b.bvh().with(&vb),
            Some(place),
            DistanceLimits::default(),
            PairBudget::UNLIMITED,
        )
        .unwrap();
        assert_eq!(indexed, got, "{name}: indexed and packed differ");
    }
}

/// The gap of "0.01 apart" is what the case says: the copy's box starts 0.01 of the
/// diagonal past the first's, so the meshes are at least that far apart.
#[test]
fn limits_bound_and_stop_the_walk() {
    let spot = bundled("spot");
    let v = valid(&spot);
    let tris = triangles(&v);
    let bvh = MeshBvh::build(&v, &BuildConfig::default()).unwrap();
    let b = bounds(&tris);
    let diag = b.extent().length();
    let place = placement(0.0, [1.0; 3], [b.extent().x + 0.01 * diag, 0.0, 0.0]);
    let full = distance(&bvh, &bvh, &place, DistanceLimits::default()).expect("an answer");
    check("spot 0.01 apart", &tris, &tris, &place, Some(full));
    assert!(full.distance >= 0.01 * diag * (1.0 - 1e-5));
    // A bound below the distance finds nothing; at or above it, the same answer.
    let below = DistanceLimits {
        max_distance: full.distance * 0.999,
        ..DistanceLimits::default()
    };
    assert_eq!(distance(&bvh, &bvh, &place, below), None);
    let above = DistanceLimits {
        max_distance: full.distance * 1.001,
        ..DistanceLimits::default()
    };
    assert_eq!(distance(&bvh, &bvh, &place, above), Some(full));
    for bad in [f32::NAN, -1.0] {
        let limits = DistanceLimits {
            max_distance: bad,
            ..DistanceLimits::default()
        };
        assert_eq!(distance(&bvh, &bvh, &place, limits), None);
    }
    // Stopping early gives a real pair at most `stop_at` apart, or the closest.
    let stop = DistanceLimits {
        stop_at: full.distance * 3.0,
        ..DistanceLimits::default()
    };
    let early = distance(&bvh, &bvh, &place, stop).expect("an answer");
    assert!(early.distance <= full.distance * 3.0);
    assert!(early.distance >= full.distance);
    let placed = place.apply_triangle(&tris[early.triangle_b as usize]);
    let pair = closest_points_triangle_triangle(&tris[early.triangle_a as usize], &placed);
    assert_eq!(pair.distance_squared.sqrt(), early.distance);
}

/// Degenerate and far-off input: copies of one triangle, triangles at one point, slivers
/// through one spot, a placement beyond 10²⁰: bounded, and right or a typed error.
#[test]
fn degenerate_and_far_meshes_stay_bounded() {
    let cases: [(&str, Mesh, Affine); 6] = [
        // Copies scaled far up around the first: triangle normals and plane gaps of size
        // 10²⁰ and beyond must not overflow into "nothing found".
        (
            "a sphere inside a copy 1e10 its size",
            bundled("uv-sphere"),
            placement(20.0, [1e10; 3], [0.0; 3]),
        ),
        (
            "a sphere inside a copy 1e30 its size",
            bundled("uv-sphere"),
            placement(20.0, [1e30; 3], [0.0; 3]),
        ),
        (
            "200k copies of one triangle",
            hard_inputs::same(200_000),
            Affine::translation([0.0, 0.0, 2.0]),
        ),
        (
            "100k triangles at one point",
            hard_inputs::point(100_000),
            Affine::translation([3.0, 4.0, 0.0]),
        ),
        (
            "3k crossing slivers",
            hard_inputs::crossing(3_000),
            Affine::translation([0.0, 0.0, 0.5]),
        ),
        (
            "spot beyond 1e20",
            bundled("spot"),
            placement(30.0, [1.0; 3], [1e20, 0.0, 0.0]),
        ),
    ];
    for (name, m, place) in &cases {
        let v = valid(m);
        let tris = triangles(&v);
        let bvh = MeshBvh::build(&v, &BuildConfig::default()).unwrap();
        let n = v.triangle_count();
        let budget = PairBudget::for_triangles(n, n);
        let (t, p) = (bvh.bvh(), bvh.packed());
        let clock = std::time::Instant::now();
        let r = mesh_distance(
            t.with(&p),
            t.with(&p),
            Some(place),
            DistanceLimits::default(),
            budget,
        );
        eprintln!(
            "TIMING {name}: {:?} {:?}",
            clock.elapsed(),
            r.as_ref().map(|x| x.map(|y| y.distance))
        );
        match r {
            Ok(got) if tris.len() <= 20_000 => check(name, &tris, &tris, place, got),
            Ok(got) => {
                // Every triangle is the same (or a point): any pair is a closest pair.
                let got = got.expect("an answer");
                let placed = place.apply_triangle(&tris[got.triangle_b as usize]);
                let pair =
                    closest_points_triangle_triangle(&tris[got.triangle_a as usize], &placed);
                assert_eq!(pair.distance_squared.sqrt(), got.distance, "{name}");
                let t = place.translation;
                let expected = (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]).sqrt();
                assert!(
                    (got.distance - expected).abs() <= 1e-6 * expected,
                    "{name}: {}",
                    got.distance
                );
            }
            Err(spent) => assert!(spent.tested <= budget.max_tests, "{name}: {spent}"),
        }
    }
    // A budget too small for the answer is a typed error, not a wrong answer.
    let spot = bundled("spot");
    let v = valid(&spot);
    let bvh = MeshBvh::build(&v, &BuildConfig::default()).unwrap();
    let (t, p) = (bvh.bvh(), bvh.packed());
    let tiny = PairBudget { max_tests: 4 };
    let place = placement(0.0, [1.0; 3], [1.0, 0.0, 0.0]);
    let spent = mesh_distance(
        t.with(&p),
        t.with(&p),
        Some(&place),
        DistanceLimits::default(),
        tiny,
    )
    .expect_err("four pairs cannot settle it");
    assert!(spent.tested <= 4);
}

/// A best-first distance written as a [`PairVisitor`] by a user gives the distance of
/// `mesh_distance`; an overlap visitor finds exactly the meeting pairs of
/// `intersecting_pairs`.
#[test]
fn the_generic_walk_carries_distance_and_intersection() {
    struct Nearest {
        best: f32,
    }
    impl PairVisitor for Nearest {
        fn nodes(&mut self, a: &Aabb, b: &Aabb) -> Option<f32> {
            let d = a.distance_squared_to_aabb(b);
            (d < self.best).then_some(d)
        }
        fn still_wanted(&mut self, score: f32) -> bool {
            score < self.best
        }
        fn triangles(&mut self, a: &WalkedTriangle, b: &WalkedTriangle) -> ControlFlow<()> {
            let d = closest_points_triangle_triangle(&a.corners, &b.corners).distance_squared;
            self.best = self.best.min(d);
            ControlFlow::Continue(())
        }
    }
    struct Meeting {
        pairs: BTreeSet<(u32, u32)>,
    }
    impl PairVisitor for Meeting {
        fn nodes(&mut self, a: &Aabb, b: &Aabb) -> Option<f32> {
            a.overlaps(b).then_some(0.0)
        }
        fn triangles(&mut self, a: &WalkedTriangle, b: &WalkedTriangle) -> ControlFlow<()> {
            if intersect_triangle_triangle(&a.corners, &b.corners) != TriangleTriangle::Disjoint {
                self.pairs.insert((a.index, b.index));
            }
            ControlFlow::Continue(())
        }
    }
    let spot = bundled("spot");
    let v = valid(&spot);
    let bvh = MeshBvh::build(&v, &BuildConfig::default()).unwrap();
    let (t, p) = (bvh.bvh(), bvh.packed());
    let n = v.triangle_count();
    let budget = PairBudget::for_triangles(n, n);
    for place in [
        placement(25.0, [1.0; 3], [0.3, 0.1, 0.0]),
        placement(0.0, [1.0; 3], [1.0, 0.0, 0.0]),
    ] {
        let mut nearest = Nearest {
            best: f32::INFINITY,
        };
        let flow = walk_pairs(t.with(&p), t.with(&p), Some(&place), budget, &mut nearest).unwrap();
        assert_eq!(flow, ControlFlow::Continue(()));
        let ours = distance(&bvh, &bvh, &place, DistanceLimits::default()).unwrap();
        assert_eq!(nearest.best.sqrt(), ours.distance);
        let mut meeting = Meeting {
            pairs: BTreeSet::new(),
        };
        let flow = walk_pairs(t.with(&p), t.with(&p), Some(&place), budget, &mut meeting).unwrap();
        assert_eq!(flow, ControlFlow::Continue(()));
        let mut out = vec![TrianglePair::default(); 1 << 16];
        let found =
            intersecting_pairs(t.with(&p), t.with(&p), Some(&place), budget, &mut out).unwrap();
        let listed: BTreeSet<(u32, u32)> =
            out[..found.written].iter().map(|q| (q.a, q.b)).collect();
        assert_eq!(meeting.pairs, listed);
        assert_eq!(listed.is_empty(), ours.distance > 0.0);
    }
    // A visitor that breaks stops the walk.
    struct First(usize);
    impl PairVisitor for First {
        fn nodes(&mut self, _: &Aabb, _: &Aabb) -> Option<f32> {
            Some(0.0)
        }
        fn triangles(&mut self, _: &WalkedTriangle, _: &WalkedTriangle) -> ControlFlow<()> {
            self.0 += 1;
            ControlFlow::Break(())
        }
    }
    let mut first = First(0);
    let flow = walk_pairs(
        t.with(&p),
        t.with(&p),
        None,
        PairBudget::UNLIMITED,
        &mut first,
    )
    .unwrap();
    assert_eq!((flow, first.0), (ControlFlow::Break(()), 1));
}

/// The closest pairs of each bundled mesh against copies of itself in the golden placements.
fn golden_pairs(name: &str) -> Vec<Option<meshq_workload::distance_golden::DigestedPair>> {
    let mesh = bundled(name);
    let v = valid(&mesh);
    let positions = &mesh.0;
    let bvh = MeshBvh::build(&v, &BuildConfig::default()).unwrap();
    let (c, r, _) = meshq_workload::centre_radius(positions);
    let (t, p) = (bvh.bvh(), bvh.packed());
    let n = v.triangle_count();
    meshq_workload::DISTANCE_PLACEMENTS
        .iter()
        .map(|&placement| {
            let matrix = meshq_workload::placement_for(c.to_array(), r, placement);
            let place = Affine::from_cols_4x4(&matrix).unwrap();
            let found = mesh_distance(
                t.with(&p),
                t.with(&p),
                Some(&place),
                DistanceLimits::default(),
                PairBudget::for_triangles(n, n),
            )
            .unwrap();
            if let Some(f) = found {
                check(name, &triangles(&v), &triangles(&v), &place, Some(f));
            }
            found.map(|f| {
                (
                    f.distance,
                    f.on_a.to_array(),
                    f.on_b.to_array(),
                    f.triangle_a,
                    f.triangle_b,
                )
            })
        })
        .collect()
}

/// The golden sweeps of each bundled mesh, as digested pairs: (t, point, normal, triangle, 0).
fn golden_sweeps(name: &str) -> Vec<Option<meshq_workload::distance_golden::DigestedPair>> {
    use meshq::query::MeshQuery;
    let mesh = bundled(name);
    let v = valid(&mesh);
    let bvh = MeshBvh::build(&v, &BuildConfig::default()).unwrap();
    let (c, r, _) = meshq_workload::centre_radius(&mesh.0);
    let hits: Vec<_> = meshq_workload::golden_sweeps(c.to_array(), r)
        .map(|(shape, motion)| {
            bvh.sweep(&shape, motion)
                .unwrap()
                .map(|h| (h.t, h.point.to_array(), h.normal.to_array(), h.tri, 0))
        })
        .collect();
    let touching = hits.iter().flatten().count();
    assert!(
        touching >= 6,
        "{name}: {touching} of the golden sweeps touch"
    );
    hits
}

#[test]
fn the_golden_distance_file_holds_every_bundled_mesh() {
    // The WebAssembly tests check the same digests (wasm/tests/parity.rs); each pair is
    // checked against brute force first.
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("golden/distance.txt");
    let mut file = String::from(
        "# meshq mesh-distance golden file: see meshq_workload::distance_golden. Rewrite with\n\
         # MESHQ_BLESS_GOLDEN=1 cargo test -p meshq-tests --test integration mesh_distance::\n",
    );
    let recorded = std::fs::read_to_string(&path).unwrap_or_default();
    for name in ["spot", "fandisk", "cow"] {
        let digests = [
            (
                name.to_string(),
                meshq_workload::DistanceDigest::of(&golden_pairs(name)),
            ),
            (
                format!("{name}-sweeps"),
                meshq_workload::DistanceDigest::of(&golden_sweeps(name)),
            ),
        ];
        for (line, digest) in digests {
            file += &format!("{line} {digest}\n");
            if std::env::var_os("MESHQ_BLESS_GOLDEN").is_none() {
                let golden = meshq_workload::find_distance_golden(&recorded, &line)
                    .unwrap_or_else(|e| panic!("{line}: {e}; bless with MESHQ_BLESS_GOLDEN=1"));
                assert_eq!(
                    digest, golden,
                    "{line}: answers changed; bless on purpose only"
                );
            }
        }
    }
    if std::env::var_os("MESHQ_BLESS_GOLDEN").is_some() {
        std::fs::write(&path, file).unwrap();
    }
}
