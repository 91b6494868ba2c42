//! After every single edit of a remeshing run — each split, collapse and flip, each vertex
//! moved by smoothing or by the final angle pass — the mesh is
//! checked: the half-edge structure is sound
//! ([`HalfEdgeMesh::check`]), the triangle list counted independently is manifold and
//! consistently oriented with the input's Euler characteristic and boundary loops, no
//! triangle turned over (a smoothing pass keeps every triangle facing its own way, and a
//! split, collapse or flip makes new triangles that face the way the triangles they replace
//! did together), and every triangle the edit made or moved faces the way the input does
//! under its centroid (the input triangle nearest the centroid, found by an independent
//! query, has a normal less than 90° from the triangle's).
//!
//! A full check after every edit costs time proportional to the mesh, so these runs use small
//! meshes: the UV sphere, a patch of spot (a boundary), and coarse remeshes of fandisk (creases
//! kept) and of the bunny (holes), and two hard inputs (a capsule, a stretched sphere).

use meshq::MeshBvh;
use meshq::MeshQuery;
use meshq::Vec3;
use meshq::bvh::BuildConfig;
use meshq::math::cross;
use meshq::mesh::MeshRef;
use meshq::owned::Remeshed;
use meshq::remesh::{
    EdgeTarget, HalfEdgeMesh, RemeshCapacity, RemeshConfig, RemeshObserver, RemeshReport,
    RemeshStep, RemeshStorage, remesh_observed,
};
use meshq_tests::{Topology, load_mesh, spot_patch};
use std::collections::{HashMap, HashSet};

struct Invariants<'a> {
    name: &'a str,
    /// The input, and a tree over it, to judge which way each triangle should face.
    input: (&'a [[f32; 3]], &'a [[u32; 3]]),
    reference: &'a MeshBvh,
    topology: Topology,
    /// Every triangle's corners after the last edit.
    previous: Vec<[Vec3; 3]>,
    /// Every triangle's vertices after the last edit.
    triangles: Vec<[u32; 3]>,
    edits: usize,
    steps: [usize; 5],
}

impl Invariants<'_> {
    /// Whether corners `c` face the way the input triangle nearest their centroid does.
    fn faces_input(&self, c: &[Vec3; 3]) -> bool {
        let centroid = (c[0] + c[1] + c[2]) / 3.0;
        let Some(hit) = self.reference.closest_point(centroid, f32::INFINITY) else {
            return false;
        };
        let under = self.input.1[hit.tri as usize].map(|v| Vec3::from(self.input.0[v as usize]));
        normal(c).normalize().dot(normal(&under).normalize()) > 0.0
    }
}

impl RemeshObserver for Invariants<'_> {
    fn edited(&mut self, step: RemeshStep, mesh: &HalfEdgeMesh<'_>) {
        self.edits += 1;
        self.steps[match step {
            RemeshStep::Split => 0,
            RemeshStep::Collapse => 1,
            RemeshStep::Flip => 2,
            RemeshStep::Smooth => 3,
            _ => 4,
        }] += 1;
        let at = || format!("{}: after edit {} ({step:?})", self.name, self.edits);
        let triangles: Vec<[u32; 3]> = (0..mesh.triangle_count() as u32)
            .map(|t| mesh.triangle(t))
            .collect();
        let corners: Vec<[Vec3; 3]> = triangles
            .iter()
            .map(|t| t.map(|v| mesh.position(v)))
            .collect();
        if matches!(step, RemeshStep::Smooth | RemeshStep::Relax) {
            // Positions move, triangles keep their slots and corners: none may turn over,
            // and each moved one faces the input.
            assert_eq!(
                triangles,
                self.triangles,
                "{}: a move changed triangles",
                at()
            );
            for (t, (old, new)) in self.previous.iter().zip(&corners).enumerate() {
                if old == new {
                    continue;
                }
                let (n0, n1) = (normal(old), normal(new));
                assert!(
                    n0 == Vec3::ZERO || n0.dot(n1) > 0.0,
                    "{}: triangle {t} turned over or flattened",
                    at()
                );
                assert!(
                    self.faces_input(new),
                    "{}: triangle {t} faces against the input under it",
                    at()
                );
            }
            self.previous = corners;
            return;
        }
        if let Err(defect) = mesh.check() {
            panic!("{}: {defect}", at());
        }
        let now = Topology::of(mesh.vertex_count(), &triangles);
        assert!(now.manifold_oriented, "{}", at());
        assert_eq!(
            (now.euler, now.boundary_loops),
            (self.topology.euler, self.topology.boundary_loops),
            "{}: Euler characteristic and boundary loops",
            at()
        );
        {
            // Triangles replaced. They are matched by their corners' coordinates, which edits
            // elsewhere (and the renumbering a collapse does) leave alone.
            {
                let before: HashMap<[[u32; 3]; 3], Vec3> =
                    self.previous.iter().map(|c| (key(c), normal(c))).collect();
                let after: HashSet<[[u32; 3]; 3]> = corners.iter().map(key).collect();
                let replaced: Vec<Vec3> = before
                    .iter()
                    .filter(|(k, _)| !after.contains(*k))
                    .map(|(_, &n)| n)
                    .collect();
                let new: Vec<&[Vec3; 3]> = corners
                    .iter()
                    .filter(|c| !before.contains_key(&key(c)))
                    .collect();
                // A collapse's neighbourhood, as it was: the old triangles at the two merged
                // vertices. (The new fan may not face against their summed normal: a
                // triangle may turn steeply there, but not over.) Those are the positions the removed triangles had and the new
                // ones lack, and the one position every new triangle shares.
                let vanished: Vec<Vec3> = self
                    .previous
                    .iter()
                    .filter(|c| !after.contains(&key(c)))
                    .flatten()
                    .filter(|p| !new.iter().any(|c| c.contains(p)))
                    .copied()
                    .collect();
                let merged: Vec<Vec3> = new
                    .first()
                    .map(|c| {
                        c.iter()
                            .filter(|p| new.iter().all(|n| n.contains(p)))
                            .copied()
                            .collect()
                    })
                    .unwrap_or_default();
                // Each triangle counted once per merged vertex it has (twice for the two on
                // the collapsed edge): the area-weighted normal of both fans.
                let sum: Vec3 = self
                    .previous
                    .iter()
                    .map(|c| {
                        let at = c
                            .iter()
                            .filter(|p| vanished.contains(p) || merged.contains(p))
                            .count();
                        normal(c) * at as f32
                    })
                    .sum();
                for c in new {
                    let n = normal(c);
                    // A triangle within a degenerate one (a split sliver) has no facing.
                    if flatness(c) < 1e-12 {
                        continue;
                    }
                    let faces = match step {
                        // Each half of a split triangle lies in it: the same normal.
                        RemeshStep::Split => replaced.iter().any(|r| n.dot(*r) > 0.0),
                        // A flipped pair faces the way both old triangles did.
                        RemeshStep::Flip => replaced.iter().all(|r| n.dot(*r) > 0.0),
                        // A collapse's new fan faces the way its old neighbourhood did
                        // together.
                        _ => n.dot(sum) > 0.0,
                    };
                    assert!(
                        faces,
                        "{}: new triangle {c:?} faces against those it replaced",
                        at()
                    );
                }
            }
        }
        // Every triangle the edit made or moved faces the input (the others were checked
        // when they were made).
        let before: HashSet<[[u32; 3]; 3]> = self.previous.iter().map(key).collect();
        for c in corners.iter().filter(|c| !before.contains(&key(c))) {
            assert!(
                self.faces_input(c),
                "{}: triangle {c:?} faces against the input under it",
                at()
            );
        }
        self.previous = corners;
        self.triangles = triangles;
    }
}

/// (Twice the area / the longest edge squared)²: about the sine of the smallest angle,
/// squared.
fn flatness(c: &[Vec3; 3]) -> f32 {
    let longest = [c[1] - c[0], c[2] - c[1], c[0] - c[2]]
        .iter()
        .map(|e| e.length_squared())
        .fold(0.0f32, f32::max);
    if longest > 0.0 {
        normal(c).length_squared() / (longest * longest)
    } else {
        0.0
    }
}

/// The normal (length: twice the area) of a triangle's corners.
fn normal(c: &[Vec3; 3]) -> Vec3 {
    cross(c[1] - c[0], c[2] - c[0])
}

/// A triangle's corners as coordinate bits, rotated to start at the least: the same key for
/// the same oriented triangle whatever its vertex numbers.
fn key(c: &[Vec3; 3]) -> [[u32; 3]; 3] {
    let bits = c.map(|p| p.to_array().map(f32::to_bits));
    let first = (0..3).min_by_key(|&k| bits[k]).unwrap_or(0);
    [bits[first], bits[(first + 1) % 3], bits[(first + 2) % 3]]
}

/// Remeshes `positions`/`triangles` with `config`, checking after every edit; returns the
/// run's report.
fn checked_run(
    name: &str,
    positions: &[[f32; 3]],
    triangles: &[[u32; 3]],
    config: &RemeshConfig,
) -> RemeshReport {
    let input = MeshRef::new(positions, triangles).validate().unwrap();
    let reference = MeshBvh::build(&input, &BuildConfig::default()).unwrap();
    let capacity = RemeshCapacity::most_for(&input, config.target);
    let mut storage = RemeshStorage::new(capacity).unwrap();
    let mut pairing = vec![0u32; capacity.pairing_scratch()];
    let mut mesh = HalfEdgeMesh::from_mesh(&input, storage.buffers(), &mut pairing).unwrap();
    let mut smoothing = vec![[0.0f32; 3]; capacity.vertices];
    let topology = Topology::of(positions.len(), triangles);
    assert!(topology.manifold_oriented, "{name}: input");
    let mut observer = Invariants {
        name,
        input: (positions, triangles),
        reference: &reference,
        topology,
        previous: (0..mesh.triangle_count() as u32)
            .map(|t| mesh.triangle(t).map(|v| mesh.position(v)))
            .collect(),
        triangles: (0..mesh.triangle_count() as u32)
            .map(|t| mesh.triangle(t))
            .collect(),
        edits: 0,
        steps: [0; 5],
    };
    let report = remesh_observed(&mut mesh, &reference, config, &mut smoothing, &mut observer)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    let [splits, collapses, flips, smooths, relaxed] = observer.steps;
    // Every edit was seen, and each kind happened: the checks ran on all of them.
    assert_eq!(
        (splits, collapses, flips, relaxed),
        (
            report.splits,
            report.collapses,
            report.flips,
            report.relaxed
        ),
        "{name}"
    );
    assert!(smooths > 0, "{name}: smoothing moved nothing");
    assert!(
        splits > 0 && collapses > 0 && flips > 0,
        "{name}: {report:?}"
    );
    eprintln!("{name}: {} edits checked ({report:?})", observer.edits);
    report
}

/// A coarse remesh of a bundled mesh: small enough to check in full after every edit.
fn coarse(name: &str, ratio: f32, feature_angle: Option<f32>) -> Remeshed {
    let loaded = load_mesh(name);
    let mesh = loaded.valid();
    let config = RemeshConfig {
        target: EdgeTarget::MeanEdgeTimes(ratio),
        feature_angle,
        ..RemeshConfig::default()
    };
    Remeshed::of(&mesh, &config).unwrap()
}

#[test]
fn the_sphere_stays_sound_after_every_edit() {
    let sphere = load_mesh("uv-sphere");
    checked_run(
        "uv-sphere",
        &sphere.positions,
        &sphere.triangles,
        &RemeshConfig::default(),
    );
}

#[test]
fn a_patch_with_a_boundary_stays_sound_after_every_edit() {
    let (positions, triangles) = spot_patch();
    let report = checked_run(
        "spot patch",
        &positions,
        &triangles,
        &RemeshConfig::default(),
    );
    assert!(report.relaxed > 0, "the final angle pass was checked too");
}

#[test]
fn coarse_fandisk_with_creases_stays_sound_after_every_edit() {
    let input = coarse("fandisk", 3.0, Some(45.0));
    let config = RemeshConfig {
        feature_angle: Some(45.0),
        ..RemeshConfig::default()
    };
    let report = checked_run(
        "coarse fandisk",
        &input.positions,
        &input.triangles,
        &config,
    );
    assert!(report.relaxed > 0, "the final angle pass was checked too");
}

#[test]
fn the_coarse_bunny_with_its_holes_stays_sound_after_every_edit() {
    let input = coarse("stanford-bunny", 5.0, None);
    let config = RemeshConfig {
        target: EdgeTarget::Length(0.8 * input.after.mean_edge),
        ..RemeshConfig::default()
    };
    let report = checked_run("coarse bunny", &input.positions, &input.triangles, &config);
    assert!(report.relaxed > 0, "the final angle pass was checked too");
}

/// The hard inputs that fit a check after every edit: a capsule's 16 sections with their
/// long side strips, and a sphere stretched ten to one (sharp tips under a long target edge).
#[test]
fn hard_inputs_stay_sound_after_every_edit() {
    use meshq_tests::hard_inputs::{capsule, sphere};
    for (name, (p, t)) in [
        ("capsule 16", capsule(16, 0.05, 1.0)),
        ("stretched sphere", sphere(3, [10.0, 1.0, 0.5])),
    ] {
        checked_run(name, &p, &t, &RemeshConfig::default());
    }
}
