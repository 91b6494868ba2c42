//! Remeshing inputs it was not tuned on: capsules with long thin side strips and
//! high-valence poles, an open tube of long strips, a coarse box with creases, a stretched
//! sphere, a patch of slivers, and random small meshes at random targets. Every result is
//! checked against the input independently of the remesher: no triangle of (relatively) zero
//! area, no two vertices at one place, no triangle facing against the input surface under it,
//! manifold and oriented with the input's Euler characteristic and boundaries, vertices on
//! the input surface, about as many triangles as the area asks for, and a peak within
//! [`RemeshCapacity::most_for`].

use meshq::MeshBvh;
use meshq::MeshQuery;
use meshq::Vec3;
use meshq::bvh::BuildConfig;
use meshq::error::RemeshError;
use meshq::mesh::MeshRef;
use meshq::owned::Remeshed;
use meshq::remesh::{EdgeTarget, RemeshCapacity, RemeshConfig};
use meshq_tests::Topology;

use meshq_tests::hard_inputs::{
    Mesh, capsule, cone, crossing, cuboid, range_scan, slivers, sphere, tube,
};

fn area(c: [Vec3; 3]) -> f32 {
    0.5 * (c[1] - c[0]).cross(c[2] - c[0]).length()
}

fn corners(mesh: &Mesh, t: [u32; 3]) -> [Vec3; 3] {
    t.map(|v| Vec3::from(mesh.0[v as usize]))
}

/// Checks `out`, a remesh of `input` toward `length`, against the input; returns the
/// smallest angle of the result in degrees.
fn check(name: &str, input: &Mesh, out: &Remeshed, length: f32) -> f32 {
    let result: Mesh = (out.positions.clone(), out.triangles.clone());
    let before = Topology::of(input.0.len(), &input.1);
    let after = Topology::of(result.0.len(), &result.1);
    assert!(after.manifold_oriented, "{name}: manifold and oriented");
    assert_eq!(
        (after.euler, after.boundary_loops),
        (before.euler, before.boundary_loops),
        "{name}: topology"
    );
    // No triangle of zero area: none below a millionth of the target's equilateral one.
    let least = (3f32.sqrt() / 4.0) * length * length * 1e-6;
    let mut min_angle = 180.0f32;
    for &t in &result.1 {
        let c = corners(&result, t);
        assert!(
            area(c) > least,
            "{name}: triangle {t:?} has area {}",
            area(c)
        );
        for k in 0..3 {
            let (p, q, r) = (c[k], c[(k + 1) % 3], c[(k + 2) % 3]);
            min_angle = min_angle.min((q - p).angle_between(r - p).to_degrees());
        }
    }
    // No two vertices at one place: none closer than a thousandth of the target (a grid of
    // cells as wide as that bound finds every close pair among neighbouring cells).
    let near = length * 1e-3;
    let mut cells: std::collections::HashMap<[i64; 3], Vec<usize>> = Default::default();
    let cell = |p: Vec3| (p / near).floor().to_array().map(|x| x as i64);
    for (i, p) in result.0.iter().enumerate() {
        cells.entry(cell(Vec3::from(*p))).or_default().push(i);
    }
    for (i, p) in result.0.iter().enumerate() {
        let p = Vec3::from(*p);
        let [x, y, z] = cell(p);
        for key in (-1..=1)
            .flat_map(|a| (-1..=1).flat_map(move |b| (-1..=1).map(move |c| [x + a, y + b, z + c])))
        {
            for &j in cells.get(&key).into_iter().flatten() {
                if j != i {
                    let d = p.distance(Vec3::from(result.0[j]));
                    assert!(d >= near, "{name}: vertices {i} and {j} are {d} apart");
                }
            }
        }
    }
    // On the input and facing its way: every vertex within a twentieth of the target of the
    // input surface, and no triangle turned against the input triangle under its centroid.
    let reference = MeshBvh::build(
        &MeshRef::new(&input.0, &input.1).validate().unwrap(),
        &BuildConfig::default(),
    )
    .unwrap();
    for (i, p) in result.0.iter().enumerate() {
        let hit = reference
            .closest_point(Vec3::from(*p), f32::INFINITY)
            .unwrap();
        assert!(
            hit.distance() <= 0.05 * length,
            "{name}: vertex {i} is {} off the input",
            hit.distance()
        );
    }
    for &t in &result.1 {
        let c = corners(&result, t);
        let normal = (c[1] - c[0]).cross(c[2] - c[0]).normalize();
        let centroid = (c[0] + c[1] + c[2]) / 3.0;
        let hit = reference.closest_point(centroid, f32::INFINITY).unwrap();
        let under = corners(input, input.1[hit.tri as usize]);
        let facing = normal.dot((under[1] - under[0]).cross(under[2] - under[0]).normalize());
        assert!(
            facing > 0.0,
            "{name}: triangle {t:?} faces {facing} against the input"
        );
    }
    // Bounded work: the peak within the stated bound, the count near what the area asks.
    let valid = MeshRef::new(&input.0, &input.1).validate().unwrap();
    let most = RemeshCapacity::most_for(&valid, EdgeTarget::Length(length));
    assert!(
        out.report.peak_triangles <= most.triangles,
        "{name}: peak {} past the bound {}",
        out.report.peak_triangles,
        most.triangles
    );
    let surface: f32 = input.1.iter().map(|&t| area(corners(input, t))).sum();
    let expected = surface / ((3f32.sqrt() / 4.0) * length * length);
    let count = result.1.len() as f32;
    if expected > 50.0 {
        assert!(
            count > 0.4 * expected && count < 2.5 * expected,
            "{name}: {count} triangles for an area of {expected} target triangles"
        );
    }
    min_angle
}

/// The mean length of the input's edges, each counted once.
fn mean_edge(input: &Mesh) -> f32 {
    let mut edges = std::collections::HashSet::new();
    for t in &input.1 {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            edges.insert((a.min(b), a.max(b)));
        }
    }
    let sum: f64 = edges
        .iter()
        .map(|&(a, b)| {
            f64::from(Vec3::from(input.0[a as usize]).distance(Vec3::from(input.0[b as usize])))
        })
        .sum();
    (sum / edges.len() as f64) as f32
}

fn remesh(input: &Mesh, config: &RemeshConfig) -> Result<Remeshed, RemeshError> {
    Remeshed::of(
        &MeshRef::new(&input.0, &input.1).validate().unwrap(),
        config,
    )
}

/// The corpus at the mean edge length: the result is clean, and the smallest angle away from
/// boundaries and creases is at least what gpytoolbox's `remesh_botsch` reaches on the
/// 16-section capsule (21°, measured for the issue).
#[test]
fn the_hard_corpus_remeshes_clean_at_the_mean_edge_length() {
    let cases: [(&str, Mesh, Option<f32>, bool); 4] = [
        ("capsule 16", capsule(16, 0.05, 1.0), None, true),
        (
            "coarse box, creases kept",
            cuboid(1.0, 0.3, 0.1),
            Some(45.0),
            false,
        ),
        ("patch of slivers", slivers(12), None, false),
        ("coarse box, no creases", cuboid(1.0, 1.0, 1.0), None, false),
    ];
    for (name, input, feature_angle, smooth_closed) in cases {
        let config = RemeshConfig {
            feature_angle,
            ..RemeshConfig::default()
        };
        let out = remesh(&input, &config).unwrap();
        let length = mean_edge(&input);
        let min_angle = check(name, &input, &out, length);
        if smooth_closed {
            assert!(min_angle >= 21.0, "{name}: smallest angle {min_angle}°");
        }
    }
}

/// An open range scan of jittered samples (slivers under a degree standing upright across a
/// jump edge, a tenth of the triangles under 30°) on hills: with its jump kept as a crease,
/// clean at its mean edge length.
#[test]
fn an_open_range_scan_of_slivers_remeshes_clean_with_creases_kept() {
    range_scan_remeshes_clean(Some(45.0), 1.0);
}

/// The same scan without creases kept (the jump edge, ten target edges high, remeshed as
/// smooth surface), and with them at twice the mean edge.
#[test]
fn an_open_range_scan_of_slivers_remeshes_clean() {
    range_scan_remeshes_clean(None, 1.0);
    range_scan_remeshes_clean(None, 2.0);
    range_scan_remeshes_clean(Some(45.0), 2.0);
}

fn range_scan_remeshes_clean(feature_angle: Option<f32>, ratio: f32) {
    let input = range_scan(48);
    let config = RemeshConfig {
        target: EdgeTarget::MeanEdgeTimes(ratio),
        feature_angle,
        ..RemeshConfig::default()
    };
    let out = remesh(&input, &config).unwrap();
    let name = format!("range scan, ratio {ratio}, creases {feature_angle:?}");
    let min_angle = check(&name, &input, &out, ratio * mean_edge(&input));
    println!("{name}: smallest angle {min_angle}°");
}

/// An open tube of 24 strips as long as the tube, remeshed toward a twelfth of its
/// circumference (at the mean edge length, dominated by the strips, one target edge would be
/// longer than the whole ring): clean, with its two boundary loops.
#[test]
fn an_open_tube_of_long_strips_remeshes_clean() {
    let input = tube(24, 0.05, 1.0);
    let length = std::f32::consts::TAU * 0.05 / 12.0;
    let config = RemeshConfig {
        target: EdgeTarget::Length(length),
        ..RemeshConfig::default()
    };
    let out = remesh(&input, &config).unwrap();
    check("open tube of strips", &input, &out, length);
}

/// Refining hard: the capsule and the stretched sphere at a fifth of the mean edge, clean and
/// in proportion to the area.
#[test]
fn refining_the_hard_corpus_stays_clean_and_in_proportion() {
    for (name, input) in [
        ("capsule 32", capsule(32, 0.05, 1.0)),
        ("stretched sphere", sphere(2, [6.0, 1.0, 1.0])),
    ] {
        let config = RemeshConfig {
            target: EdgeTarget::MeanEdgeTimes(0.2),
            ..RemeshConfig::default()
        };
        let out = remesh(&input, &config).unwrap();
        let length = 0.2 * mean_edge(&input);
        let min_angle = check(name, &input, &out, length);
        assert!(min_angle >= 21.0, "{name}: smallest angle {min_angle}°");
    }
}

/// A sphere stretched ten to one at the mean edge length, whose tips curve more sharply than
/// one target edge spans.
#[test]
fn a_stretched_sphere_remeshes_clean_at_the_mean_edge_length() {
    let input = sphere(3, [10.0, 1.0, 0.5]);
    let out = remesh(&input, &RemeshConfig::default()).unwrap();
    let min_angle = check("stretched sphere", &input, &out, mean_edge(&input));
    assert!(min_angle >= 21.0, "smallest angle {min_angle}°");
}

/// The capsule of 64 sections (8,192 triangles, side strips 200 times longer than wide).
#[test]
fn the_capsule_of_64_sections_remeshes_clean() {
    let input = capsule(64, 0.05, 1.0);
    let out = remesh(&input, &RemeshConfig::default()).unwrap();
    let min_angle = check("capsule 64", &input, &out, mean_edge(&input));
    assert!(min_angle >= 21.0, "smallest angle {min_angle}°");
}

/// Random small meshes (stretched, jittered spheres) at random targets from a third to three
/// times the mean edge: every result is clean.
#[test]
fn random_small_meshes_at_random_targets_stay_clean() {
    let mut state = 0x9E37_79B9_u32;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        state as f32 / u32::MAX as f32
    };
    for case in 0..24 {
        let scale = [0.2 + 5.0 * next(), 0.2 + 5.0 * next(), 0.2 + 5.0 * next()];
        let (mut positions, triangles) = sphere(1 + case % 3, scale);
        for p in &mut positions {
            for x in p.iter_mut() {
                *x *= 1.0 + 0.1 * (next() - 0.5);
            }
        }
        let input = (positions, triangles);
        let ratio = 1.0 / 3.0 + (3.0 - 1.0 / 3.0) * next();
        let config = RemeshConfig {
            target: EdgeTarget::MeanEdgeTimes(ratio),
            ..RemeshConfig::default()
        };
        let name = format!("case {case}: scale {scale:?}, ratio {ratio}");
        let out = remesh(&input, &config).unwrap();
        let length = ratio * mean_edge(&input);
        check(&name, &input, &out, length);
    }
}

/// A target far below what memory allows is refused at once with a typed error, not grown
/// into.
#[test]
fn a_target_too_small_for_memory_is_refused() {
    let input = capsule(16, 0.05, 1.0);
    let config = RemeshConfig {
        target: EdgeTarget::MeanEdgeTimes(1e-5),
        ..RemeshConfig::default()
    };
    let err = remesh(&input, &config).unwrap_err();
    assert!(matches!(err, RemeshError::OutOfCapacity { .. }), "{err:?}");
}

/// Slivers through one point, which no box separates: near the point every exact search
/// visits every sliver, so a run that searched there would take the square of their number.
/// Through 5,000 of them the input is crowded (more triangles in the leaves holding the
/// point than 1,024 plus four times the highest valence, here 1) and every edit that would
/// be judged there is refused: the run makes none and returns the input. Through 100, the
/// same slivers are split as usual.
#[test]
fn edits_where_the_input_is_crowded_are_refused() {
    let input = crossing(5_000);
    let out = remesh(&input, &RemeshConfig::default()).unwrap();
    let r = out.report;
    assert_eq!(
        (r.splits, r.collapses, r.flips, r.relaxed),
        (0, 0, 0, 0),
        "{r:?}"
    );
    assert_eq!((&out.positions, &out.triangles), (&input.0, &input.1));

    let sparse = crossing(100);
    let out = remesh(&sparse, &RemeshConfig::default()).unwrap();
    assert!(out.report.splits > 0, "{:?}", out.report);
}

/// A closed cone of 1,024 sections: its apex and its base centre are vertices of valence
/// 1,024, and the points near the base centre lie in the boxes of both fans (about 2,048
/// triangles). Fans are real geometry, not tangles: the crowding bound grows with the
/// input's valence, so both fans are remeshed (at a fifth of the mean edge, no vertex keeps
/// a valence anywhere near theirs).
///
/// Its side facets are needles (a third of a degree at the apex), where closest points once
/// came out on a facet's edge instead of its face: splits then made triangles of zero area,
/// and the result had angles of 0°. Now it is clean, with an angle no smaller than the
/// capsule's bound (gpytoolbox reaches 33° here, and 14° at a twentieth of the mean edge).
#[test]
fn high_valence_fans_are_not_crowded() {
    let input = cone(1024, 0.5, 1.0);
    let config = RemeshConfig {
        target: EdgeTarget::MeanEdgeTimes(0.2),
        ..RemeshConfig::default()
    };
    let out = remesh(&input, &config).unwrap();
    let min_angle = check("cone 1024", &input, &out, 0.2 * mean_edge(&input));
    assert!(min_angle >= 21.0, "smallest angle {min_angle}°");
    let mut valence = vec![0u32; out.positions.len()];
    for t in &out.triangles {
        for &v in t {
            valence[v as usize] += 1;
        }
    }
    let highest = valence.iter().copied().max().unwrap_or(0);
    assert!(highest <= 64, "highest valence {highest}: {:?}", out.report);
}

/// Needles far longer than the target (a cone's side facets, a range scan's jump edge) refine
/// in proportion to their area, not to the square of their length over the target: bisecting
/// a needle leaves its new vertex in a flat triangle beside the next long edge, and without
/// the flips that follow long splits every such edge was bisected in turn (the cone of 1,024
/// sections at a twentieth of its mean edge peaked at 331,776 triangles for 7,686; the
/// 160-sample scan at 151,686 for 37,650). The peak stays within three times the larger of
/// the input and the result, the splits within twice the result, and the result is clean
/// (the cone's smallest angle at least the corpus bound; the scan's smallest angle, 18° with
/// or without the flips, sits where the jump edge meets the hills).
#[test]
fn needles_refine_in_proportion_to_their_area() {
    for (name, input, ratio, least_angle) in [
        ("cone 1024", cone(1024, 0.5, 1.0), 0.05, 21.0),
        ("range scan 160", range_scan(160), 1.0, 0.0),
    ] {
        let config = RemeshConfig {
            target: EdgeTarget::MeanEdgeTimes(ratio),
            ..RemeshConfig::default()
        };
        let out = remesh(&input, &config).unwrap();
        let length = ratio * mean_edge(&input);
        let min_angle = check(name, &input, &out, length);
        let (made, report) = (out.triangles.len(), &out.report);
        println!("{name}: {made} triangles, smallest angle {min_angle}°, {report:?}");
        assert!(
            min_angle >= least_angle,
            "{name}: smallest angle {min_angle}°"
        );
        assert!(
            report.peak_triangles <= 3 * made.max(input.1.len()),
            "{name}: peak {} for {made} triangles from {}",
            report.peak_triangles,
            input.1.len()
        );
        assert!(
            report.splits <= 2 * made,
            "{name}: {} splits for {made} triangles",
            report.splits
        );
    }
}
