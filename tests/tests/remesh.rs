//! Remeshing bundled meshes: the result is a sound mesh of the same topology, lies on the
//! input's surface, faces the input's way, and reaches quality figures the input does not.

use std::collections::BTreeMap;

use meshq::MeshQuery;
use meshq::mesh::MeshRef;
use meshq::owned::{MeshBvh, Remeshed};
use meshq::remesh::RemeshConfig;
use meshq_tests::load_mesh;

/// Euler characteristic and boundary-edge count of a triangle list, counted independently.
fn topology(vertices: usize, triangles: &[[u32; 3]]) -> (i64, usize) {
    let mut edges: BTreeMap<(u32, u32), u32> = BTreeMap::new();
    let mut used = vec![false; vertices];
    for t in triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *edges.entry((a.min(b), a.max(b))).or_default() += 1;
            used[a as usize] = true;
        }
    }
    assert!(
        edges.values().all(|&n| n <= 2),
        "an edge has more than two triangles"
    );
    let euler =
        used.iter().filter(|&&u| u).count() as i64 - edges.len() as i64 + triangles.len() as i64;
    (euler, edges.values().filter(|&&n| n == 1).count())
}

/// The largest distance from a point of `from` (vertices and triangle centroids) to the
/// surface `to` answers for, relative to `diagonal`.
fn one_sided_distance(from: (&[[f32; 3]], &[[u32; 3]]), to: &MeshBvh, diagonal: f32) -> f32 {
    let (positions, triangles) = from;
    let p = |v: u32| meshq::Vec3::from_array(positions[v as usize]);
    let samples = positions.iter().map(|&q| meshq::Vec3::from_array(q)).chain(
        triangles
            .iter()
            .map(|t| (p(t[0]) + p(t[1]) + p(t[2])) / 3.0),
    );
    samples
        .map(|q| {
            to.closest_point(q, f32::INFINITY)
                .unwrap()
                .distance_squared
                .sqrt()
        })
        .fold(0.0f32, f32::max)
        / diagonal
}

struct Expect {
    name: &'static str,
    feature_angle: Option<f32>,
    valence_6: f32,
    min_angle: f32,
    under_30: f32,
    edge_cv: f32,
    distance: f32,
}

#[test]
fn remeshed_meshes_are_sound_on_the_surface_and_better_shaped() {
    // Thresholds: what this remesher reaches (deterministic), with a little room. Distances
    // are two-sided, sampled at vertices and triangle centroids, relative to the diagonal;
    // the bunny's is the target (3.5e-3).
    let cases = [
        Expect {
            name: "spot",
            feature_angle: None,
            valence_6: 80.0,
            min_angle: 38.0,
            under_30: 0.0,
            edge_cv: 0.09,
            distance: 1.0e-2,
        },
        Expect {
            name: "fandisk",
            feature_angle: None,
            valence_6: 85.5,
            min_angle: 38.0,
            under_30: 0.0,
            edge_cv: 0.1,
            distance: 1.0e-2,
        },
        // Splits bisect across the longest side since the hard-input fixes (issue 65): the
        // bunny went from 84.6 % valence 6 and 0.017 % under 30° to 84.3 % and 0.022 %, still
        // above gpytoolbox's 83.2 % and 0.065 % on the same target.
        Expect {
            name: "stanford-bunny",
            feature_angle: None,
            valence_6: 84.2,
            min_angle: 32.0,
            under_30: 0.025,
            edge_cv: 0.11,
            distance: 3.5e-3,
        },
        // Creases sharper than 45° kept: no slivers where creases meet, and the issue's
        // distance target (3.8e-3). Two of fandisk's creases meet at 19.4°, an angle any
        // mesh keeping them inherits: the smallest angle can be little more.
        Expect {
            name: "fandisk",
            feature_angle: Some(45.0),
            valence_6: 84.0,
            min_angle: 20.0,
            under_30: 0.05,
            edge_cv: 0.12,
            distance: 3.8e-3,
        },
    ];
    for e in cases {
        let loaded = load_mesh(e.name);
        let mesh = loaded.valid();
        let config = RemeshConfig {
            feature_angle: e.feature_angle,
            ..RemeshConfig::default()
        };
        let out = Remeshed::of(&mesh, &config).unwrap();
        let again = Remeshed::of(&mesh, &config).unwrap();
        assert_eq!(
            (&out.positions, &out.triangles),
            (&again.positions, &again.triangles),
            "{}: deterministic",
            e.name
        );
        // Topology: the same Euler characteristic, and as many boundary edges only where the
        // input has none (boundaries are split, so they gain edges).
        let before = topology(mesh.positions().len(), mesh.triangles());
        let after = topology(out.positions.len(), &out.triangles);
        assert_eq!(after.0, before.0, "{}: Euler characteristic", e.name);
        assert_eq!(after.1 == 0, before.1 == 0, "{}: boundary", e.name);
        let remeshed = MeshRef::new(&out.positions, &out.triangles)
            .validate()
            .unwrap();
        let q = out.after;
        let independent = independent_quality(&out.positions, &out.triangles);
        assert_eq!(q.triangles, out.triangles.len());
        assert!(independent.0 >= e.valence_6, "{}: {q:?}", e.name);
        assert!(independent.1 >= e.min_angle, "{}: {q:?}", e.name);
        assert!(q.under_30_percent <= e.under_30, "{}: {q:?}", e.name);
        assert!(q.edge_cv <= e.edge_cv, "{}: {q:?}", e.name);
        assert!(
            q.edge_cv < out.before.edge_cv,
            "{}: more even than the input",
            e.name
        );
        let bounds = mesh.bounds();
        let diagonal = (bounds.max - bounds.min).length();
        let input = MeshBvh::build(&mesh, &Default::default()).unwrap();
        let output = MeshBvh::build(&remeshed, &Default::default()).unwrap();
        let out_to_in = one_sided_distance((&out.positions, &out.triangles), &input, diagonal);
        let in_to_out = one_sided_distance((mesh.positions(), mesh.triangles()), &output, diagonal);
        let distance_ok = out_to_in <= e.distance && in_to_out <= e.distance;
        // Facing: each triangle's normal agrees with the input's at its centroid.
        let mut against = 0usize;
        for t in &out.triangles {
            let p = t.map(|v| meshq::Vec3::from_array(out.positions[v as usize]));
            let n = (p[1] - p[0]).cross(p[2] - p[0]);
            let c = input
                .closest_point((p[0] + p[1] + p[2]) / 3.0, f32::INFINITY)
                .unwrap();
            let tri = mesh.triangle(c.tri).unwrap();
            against += usize::from(n.dot((tri.b - tri.a).cross(tri.c - tri.a)) <= 0.0);
        }
        eprintln!(
            "{}: {q:?}; distance out→in {out_to_in:.2e}, in→out {in_to_out:.2e}, {against} \
             triangles facing against the input",
            e.name
        );
        assert!(distance_ok, "{}: distances {out_to_in} {in_to_out}", e.name);
        assert!(
            against * 1000 <= out.triangles.len(),
            "{}: {against} triangles face against the input",
            e.name
        );
        // The remesher's own figures agree with the independent count.
        assert!(
            (q.valence_6_percent - independent.0).abs() < 1e-3,
            "{}",
            e.name
        );
        assert!(
            (q.min_angle_off_boundary - independent.1).abs() < 1e-2,
            "{}",
            e.name
        );
    }
}

/// Percentage of interior vertices with six neighbours, and the smallest angle of triangles
/// with no boundary vertex, in degrees, counted from the triangle list alone.
fn independent_quality(positions: &[[f32; 3]], triangles: &[[u32; 3]]) -> (f32, f32) {
    let mut directed = std::collections::BTreeSet::new();
    let mut neighbours: BTreeMap<u32, std::collections::BTreeSet<u32>> = BTreeMap::new();
    for t in triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            directed.insert((a, b));
            neighbours.entry(a).or_default().insert(b);
            neighbours.entry(b).or_default().insert(a);
        }
    }
    let boundary: std::collections::BTreeSet<u32> = directed
        .iter()
        .filter(|&&(a, b)| !directed.contains(&(b, a)))
        .flat_map(|&(a, b)| [a, b])
        .collect();
    let interior: Vec<usize> = neighbours
        .iter()
        .filter(|(v, _)| !boundary.contains(v))
        .map(|(_, n)| n.len())
        .collect();
    let six = interior.iter().filter(|&&n| n == 6).count();
    let mut min_angle = 180.0f64;
    for t in triangles
        .iter()
        .filter(|t| !t.iter().any(|v| boundary.contains(v)))
    {
        let p = t.map(|v| positions[v as usize].map(f64::from));
        for k in 0..3 {
            let (a, b, c) = (p[k], p[(k + 1) % 3], p[(k + 2) % 3]);
            let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
            let w = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
            let dot = u[0] * w[0] + u[1] * w[1] + u[2] * w[2];
            let len = (u.iter().map(|x| x * x).sum::<f64>() * w.iter().map(|x| x * x).sum::<f64>())
                .sqrt();
            min_angle = min_angle.min((dot / len).clamp(-1.0, 1.0).acos().to_degrees());
        }
    }
    (100.0 * six as f32 / interior.len() as f32, min_angle as f32)
}
