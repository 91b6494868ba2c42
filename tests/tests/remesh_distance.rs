//! The remesher's distance report (`Remeshed::distance_to`) against an f64 scan of every
//! sample over every triangle, and its test budget on triangles no box separates: it stops
//! within the budget with a lower bound of the full answer, instead of taking the square of
//! the triangle count.

use meshq::collide::PairBudget;
use meshq::mesh::MeshRef;
use meshq::owned::Remeshed;
use meshq::remesh::{EdgeTarget, RemeshConfig};
use meshq_tests::hard_inputs::{Mesh, capsule, crossing, overlap};
use meshq_tests::load_mesh;

type P = [f64; 3];

fn sub(a: P, b: P) -> P {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: P, b: P) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn at(a: P, ab: P, s: f64, ac: P, t: f64) -> P {
    [0, 1, 2].map(|i| a[i] + s * ab[i] + t * ac[i])
}

/// The distance from `p` to triangle `a b c` in f64, by its Voronoi regions (Ericson,
/// "Real-Time Collision Detection", 5.1.5), written here independently of the crate's.
fn point_triangle_distance(p: P, [a, b, c]: [P; 3]) -> f64 {
    let (ab, ac, ap) = (sub(b, a), sub(c, a), sub(p, a));
    let (d1, d2) = (dot(ab, ap), dot(ac, ap));
    let closest = if d1 <= 0.0 && d2 <= 0.0 {
        a
    } else {
        let bp = sub(p, b);
        let (d3, d4) = (dot(ab, bp), dot(ac, bp));
        let cp = sub(p, c);
        let (d5, d6) = (dot(ab, cp), dot(ac, cp));
        let (vc, vb, va) = (d1 * d4 - d3 * d2, d5 * d2 - d1 * d6, d3 * d6 - d5 * d4);
        if d3 >= 0.0 && d4 <= d3 {
            b
        } else if d6 >= 0.0 && d5 <= d6 {
            c
        } else if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
            at(a, ab, d1 / (d1 - d3), ac, 0.0)
        } else if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
            at(a, ab, 0.0, ac, d2 / (d2 - d6))
        } else if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
            let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
            [0, 1, 2].map(|i| b[i] + w * (c[i] - b[i]))
        } else {
            let denom = 1.0 / (va + vb + vc);
            at(a, ab, vb * denom, ac, vc * denom)
        }
    };
    let d = sub(p, closest);
    dot(d, d).sqrt()
}

fn corners(mesh: &Mesh, t: [u32; 3]) -> [P; 3] {
    t.map(|v| mesh.0[v as usize].map(f64::from))
}

/// The largest distance from any corner or centroid of `from` to the surface of `to`, by a
/// scan of every triangle.
fn farthest_sample(from: &Mesh, to: &Mesh) -> f64 {
    let targets: Vec<[P; 3]> = to.1.iter().map(|&t| corners(to, t)).collect();
    let mut far = 0.0f64;
    for &t in &from.1 {
        let [a, b, c] = corners(from, t);
        // The centroid as the crate forms it, in f32: the same sample point.
        let centroid = [0, 1, 2].map(|i| {
            let v = t.map(|k| from.0[k as usize][i]);
            f64::from((v[0] + v[1] + v[2]) / 3.0)
        });
        for p in [a, b, c, centroid] {
            let near = targets
                .iter()
                .map(|&tri| point_triangle_distance(p, tri))
                .fold(f64::INFINITY, f64::min);
            far = far.max(near);
        }
    }
    far
}

fn remeshed(input: &Mesh, config: &RemeshConfig) -> Remeshed {
    let mesh = MeshRef::new(&input.0, &input.1).validate().unwrap();
    Remeshed::of(&mesh, config).unwrap()
}

fn diagonal(mesh: &Mesh) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in &mesh.0 {
        for i in 0..3 {
            lo[i] = lo[i].min(f64::from(p[i]));
            hi[i] = hi[i].max(f64::from(p[i]));
        }
    }
    dot(sub(hi, lo), sub(hi, lo)).sqrt()
}

#[test]
fn the_distance_report_is_the_farthest_sample_by_an_f64_scan() {
    let spot = load_mesh("spot");
    let cases: Vec<(&str, Mesh, RemeshConfig)> = vec![
        (
            "spot",
            (spot.positions.clone(), spot.triangles.clone()),
            RemeshConfig::default(),
        ),
        (
            "spot, ratio 2",
            (spot.positions.clone(), spot.triangles.clone()),
            RemeshConfig {
                target: EdgeTarget::MeanEdgeTimes(2.0),
                ..RemeshConfig::default()
            },
        ),
        ("capsule-32", capsule(32, 1.0, 4.0), RemeshConfig::default()),
    ];
    for (name, input, config) in cases {
        let out = remeshed(&input, &config);
        let mesh = MeshRef::new(&input.0, &input.1).validate().unwrap();
        let budget = PairBudget::for_triangles(mesh.triangle_count(), out.triangles.len());
        let report = out.distance_to(&mesh, budget).unwrap();
        let samples = 4 * (input.1.len() + out.triangles.len()) as u64;
        assert_eq!(report.samples, samples, "{name}");
        assert!(report.is_complete(), "{name}: {report:?}");
        assert!(report.tested as usize <= budget.max_tests, "{name}");
        // Each sample costs a few tests, nowhere near the budget's 64 per sample.
        assert!(report.tested < 16 * samples, "{name}: {report:?}");
        let result: Mesh = (out.positions.clone(), out.triangles.clone());
        let want = farthest_sample(&result, &input).max(farthest_sample(&input, &result))
            / diagonal(&input);
        let got = f64::from(report.relative);
        // f32 closest points on a mesh of unit-scale diagonal: a few ulps of the diagonal.
        assert!(
            (got - want).abs() <= 1e-6 + 1e-4 * want,
            "{name}: {got} against the scan's {want}"
        );
        assert!(want > 0.0, "{name}: a remesh moves off the input somewhere");
        // Unlimited gives the same samples, so the same answer, bit for bit.
        let unlimited = out.distance_to(&mesh, PairBudget::UNLIMITED).unwrap();
        assert_eq!(unlimited, report, "{name}");
        // No tests: no sample measured, nothing claimed.
        let none = out.distance_to(&mesh, PairBudget { max_tests: 0 }).unwrap();
        assert_eq!(
            (none.measured, none.samples, none.tested),
            (0, samples, 0),
            "{name}"
        );
        assert!(!none.is_complete() && none.relative == 0.0, "{name}");
    }
}

#[test]
fn on_triangles_no_box_separates_the_report_stops_within_its_budget() {
    // 2,000 triangles that all span one box: every closest-point query meets most of them.
    let input = overlap(2000);
    let out = remeshed(&input, &RemeshConfig::default());
    let mesh = MeshRef::new(&input.0, &input.1).validate().unwrap();
    let full = out.distance_to(&mesh, PairBudget::UNLIMITED).unwrap();
    assert!(full.is_complete());
    let samples = full.samples;
    // The quadratic cost the budget exists for: hundreds of tests per sample.
    assert!(full.tested > 100 * samples, "{full:?}");
    let budget = PairBudget::for_triangles(mesh.triangle_count(), out.triangles.len());
    let bounded = out.distance_to(&mesh, budget).unwrap();
    assert!(!bounded.is_complete(), "{bounded:?}");
    assert!(bounded.tested as usize <= budget.max_tests, "{bounded:?}");
    assert!(
        bounded.measured > 0 && bounded.measured < samples,
        "{bounded:?}"
    );
    // Fewer samples: a lower bound of the full estimate, never more.
    assert!(bounded.relative <= full.relative, "{bounded:?} {full:?}");
    // A budget of exactly what the full run took measures everything, and gives its answer.
    let exact = PairBudget {
        max_tests: full.tested as usize,
    };
    assert_eq!(out.distance_to(&mesh, exact).unwrap(), full);
    // One test short stops before the last sample's query.
    let short = PairBudget {
        max_tests: full.tested as usize - 1,
    };
    let one_short = out.distance_to(&mesh, short).unwrap();
    assert!(one_short.measured < samples && one_short.tested < full.tested);
    // No budget at all: nothing measured, and nothing claimed.
    let none = out.distance_to(&mesh, PairBudget { max_tests: 0 }).unwrap();
    assert_eq!((none.measured, none.tested, none.relative), (0, 0, 0.0));
}

#[test]
fn the_report_scales_with_the_mesh() {
    // The same capsule at 2^-10 and 2^13 times its size (exact scalings): the same relative
    // distance.
    let base = capsule(16, 1.0, 3.0);
    let mut relative = Vec::new();
    for scale in [1.0 / 1024.0, 1.0, 8192.0f32] {
        let input: Mesh = (
            base.0.iter().map(|p| p.map(|x| x * scale)).collect(),
            base.1.clone(),
        );
        let out = remeshed(&input, &RemeshConfig::default());
        let mesh = MeshRef::new(&input.0, &input.1).validate().unwrap();
        let report = out.distance_to(&mesh, PairBudget::UNLIMITED).unwrap();
        assert!(report.is_complete());
        relative.push(report.relative);
    }
    for r in &relative {
        assert!(
            (r - relative[1]).abs() <= 1e-6 * relative[1],
            "{relative:?}"
        );
    }
}

#[test]
fn the_report_stays_within_a_budget_linear_in_the_meshes_at_every_size() {
    // The two families of separate triangles no box separates, at 1k and 10k (where a full
    // report, a test per sample per triangle, is far past the budget): the tests made are
    // counted against the default budget, which grows with the triangles, not their square.
    for (family, make) in [
        ("overlap", overlap as fn(u32) -> Mesh),
        ("crossing", crossing as fn(u32) -> Mesh),
    ] {
        for n in [1_000, 10_000] {
            let input = make(n);
            let out = remeshed(&input, &RemeshConfig::default());
            let mesh = MeshRef::new(&input.0, &input.1).validate().unwrap();
            let budget = PairBudget::for_triangles(mesh.triangle_count(), out.triangles.len());
            let report = out.distance_to(&mesh, budget).unwrap();
            let what = format!("{family} {n}: {report:?}");
            assert!(report.tested as usize <= budget.max_tests, "{what}");
            assert!(
                budget.max_tests <= (1 << 20) + 256 * (input.1.len() + out.triangles.len()),
                "{what}"
            );
            assert!(report.measured > 0, "{what}");
            assert_eq!(
                report.samples,
                4 * (input.1.len() + out.triangles.len()) as u64,
                "{what}"
            );
        }
    }
}
