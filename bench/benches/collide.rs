//! Mesh–mesh intersection against parry3d's `intersection_test` on two `TriMesh` shapes,
//! mesh–mesh distance against parry3d's `distance` (a copy 0.01 of the diagonal apart), and
//! meshq's self-intersection check, in one run on the same meshes and placements.
//!
//! `MESHQ_BENCH_MESHES` picks the mesh (the first of its comma-separated bundled names or
//! `.obj` paths; default the bunny). Three placements of a copy: overlapping (turned 20°
//! about z and moved by a quarter of the width), a copy a fifth the size about the mean vertex
//! (inside the bunny's body: the boxes overlap, the surfaces do not meet), and apart. The yes/no of both
//! libraries is checked before timing. Throughput: triangle pairs tested.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use meshq::Traverse;
use meshq::bvh::BuildConfig;
use meshq::collide::{
    Affine, DistanceLimits, PairBudget, TrianglePair, intersecting_pairs, mesh_distance,
    meshes_intersect, self_intersecting_pairs,
};
use meshq::owned::MeshBvh;
use meshq::query::{MeshQuery, SweepShape};
use meshq_tests::{LoadedMesh, load_mesh, load_obj};
use parry3d::math::{Pose, Vector};
use parry3d::query::{ShapeCastOptions, cast_shapes, distance, intersection_test};
use parry3d::shape::TriMesh;
use parry3d::shape::{Ball, Capsule, Cuboid};

fn scene() -> LoadedMesh {
    let names = std::env::var("MESHQ_BENCH_MESHES").unwrap_or_else(|_| "stanford-bunny".into());
    let first = names.split(',').next().unwrap_or("stanford-bunny");
    if first.ends_with(".obj") {
        load_obj(std::path::Path::new(first))
    } else {
        load_mesh(first)
    }
}

/// A placement of the copy: uniform `scale`, a turn of `degrees` about z, then `shift`.
struct Placement {
    name: &'static str,
    scale: f32,
    degrees: f32,
    shift: [f32; 3],
}

impl Placement {
    fn affine(&self) -> Affine {
        let (s, c) = self.degrees.to_radians().sin_cos();
        let k = self.scale;
        Affine {
            columns: [[k * c, k * s, 0.0], [-k * s, k * c, 0.0], [0.0, 0.0, k]],
            translation: self.shift,
        }
    }
}

fn parry_mesh(m: &LoadedMesh, scale: f32) -> TriMesh {
    let vertices = m
        .positions
        .iter()
        .map(|p| Vector::new(p[0], p[1], p[2]) * scale)
        .collect();
    TriMesh::new(vertices, m.triangles.clone()).unwrap_or_else(|e| panic!("parry3d: {e:?}"))
}

fn collide(c: &mut Criterion) {
    let scene = scene();
    let mesh = scene.valid();
    let bvh = MeshBvh::build(&mesh, &BuildConfig::default()).expect("builds");
    let (lo, hi) = scene
        .positions
        .iter()
        .fold(([f32::MAX; 3], [f32::MIN; 3]), |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1]), lo[2].min(p[2])],
                [hi[0].max(p[0]), hi[1].max(p[1]), hi[2].max(p[2])],
            )
        });
    let extent = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
    // The mean vertex: inside a closed body like the bunny's.
    let n = scene.positions.len() as f32;
    let mean = scene.positions.iter().fold([0.0f32; 3], |m, p| {
        [m[0] + p[0] / n, m[1] + p[1] / n, m[2] + p[2] / n]
    });
    const SMALL: f32 = 0.2;
    let placements = [
        Placement {
            name: "overlapping",
            scale: 1.0,
            degrees: 20.0,
            shift: [extent[0] / 4.0, extent[1] / 10.0, 0.0],
        },
        Placement {
            name: "small copy inside",
            scale: SMALL,
            degrees: 0.0,
            shift: mean.map(|m| m * (1.0 - SMALL)),
        },
        Placement {
            name: "apart",
            scale: 1.0,
            degrees: 0.0,
            shift: [extent[0] * 1.5, 0.0, 0.0],
        },
    ];
    let tree = bvh.bvh();
    let packed = bvh.packed();
    let ours = tree.with(&packed);
    let parry_a = parry_mesh(&scene, 1.0);
    let n = mesh.triangle_count();
    let budget = PairBudget::for_triangles(n, n);
    for p in &placements {
        let place = p.affine();
        let parry_b = parry_mesh(&scene, p.scale);
        let pose_b = Pose::new(
            Vector::from_array(p.shift),
            Vector::new(0.0, 0.0, p.degrees.to_radians()),
        );
        let parry_says = |b: &TriMesh| {
            intersection_test(&Pose::IDENTITY, &parry_a, &pose_b, b)
                .expect("parry3d supports two meshes")
                .intersecting
        };
        let meshq_says = meshes_intersect(ours, ours, Some(&place), budget).expect("within budget");
        assert_eq!(
            meshq_says,
            parry_says(&parry_b),
            "{}: the libraries disagree",
            p.name
        );
        let mut pairs = vec![TrianglePair::default(); 1 << 16];
        let found = intersecting_pairs(ours, ours, Some(&place), budget, &mut pairs)
            .expect("within budget");
        eprintln!(
            "{} / {}: meets {meshq_says}, {} pairs of {} tested",
            scene.name, p.name, found.total, found.tested
        );
        let mut group = c.benchmark_group(format!("collide/{}/{}", scene.name, p.name));
        group.sample_size(10);
        group.warm_up_time(Duration::from_millis(500));
        group.measurement_time(Duration::from_secs(2));
        group.bench_function("meshq_intersects", |b| {
            b.iter(|| black_box(meshes_intersect(ours, ours, Some(&place), budget)))
        });
        group.bench_function("parry3d_intersection_test", |b| {
            b.iter(|| black_box(parry_says(&parry_b)))
        });
        group.throughput(Throughput::Elements(found.tested.max(1) as u64));
        group.bench_function("meshq_all_pairs", |b| {
            b.iter(|| {
                black_box(intersecting_pairs(
                    ours,
                    ours,
                    Some(&place),
                    budget,
                    &mut pairs,
                ))
            })
        });
        group.finish();
    }
    // Distance: a copy moved along x until its box starts 0.01 of the diagonal past the
    // first's (the "two bunnies 0.01 diagonal apart").
    let diagonal = extent.iter().map(|e| e * e).sum::<f32>().sqrt();
    let shift = [extent[0] + 0.01 * diagonal, 0.0, 0.0];
    let place = Affine::translation(shift);
    let pose_b = Pose::translation(shift[0], shift[1], shift[2]);
    let parry_distance = || {
        distance(&Pose::IDENTITY, &parry_a, &pose_b, &parry_a)
            .expect("parry3d supports two meshes")
            .distance
    };
    let ours_distance = || {
        mesh_distance(ours, ours, Some(&place), DistanceLimits::default(), budget)
            .expect("within budget")
            .expect("an answer")
    };
    let (theirs, found) = (parry_distance(), ours_distance());
    eprintln!(
        "{} / 0.01 apart: meshq {} (triangles {} and {}), parry3d {theirs}",
        scene.name, found.distance, found.triangle_a, found.triangle_b
    );
    assert!(
        (found.distance - theirs).abs() <= 1e-4 * diagonal,
        "the libraries disagree on the distance"
    );
    let mut group = c.benchmark_group(format!("distance/{}/0.01 apart", scene.name));
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(500));
    group.measurement_time(Duration::from_secs(2));
    group.bench_function("meshq_mesh_distance", |b| {
        b.iter(|| black_box(ours_distance()))
    });
    group.bench_function("parry3d_distance", |b| {
        b.iter(|| black_box(parry_distance()))
    });
    group.finish();

    // Sweeps: 1,000 spheres, capsules and boxes (a few percent of the mesh's size) moved from
    // a ring around the mesh through near its middle, as parry3d's `cast_shapes` and meshq's
    // `sweep`; the hits and times of impact are compared first.
    let centre = [
        (lo[0] + hi[0]) / 2.0,
        (lo[1] + hi[1]) / 2.0,
        (lo[2] + hi[2]) / 2.0,
    ];
    let size = diagonal * 0.02;
    let sweeps: Vec<(u32, [f32; 3], [f32; 3])> = (0..1000u32)
        .map(|k| {
            let a = k as f32 * 0.618_034 * std::f32::consts::TAU;
            let b = (k as f32 / 1000.0) * 2.0 - 1.0;
            let r = (1.0 - b * b).sqrt();
            let dir = [r * a.cos(), b, r * a.sin()];
            let start = [0, 1, 2].map(|i| centre[i] + dir[i] * diagonal * 0.75);
            let aim = [0, 1, 2].map(|i| centre[i] + dir[(i + 1) % 3] * diagonal * 0.05);
            (k % 3, start, [0, 1, 2].map(|i| (aim[i] - start[i]) * 1.5))
        })
        .collect();
    let ours_shape = |kind: u32, start: [f32; 3]| {
        let c = glam::Vec3::from_array(start);
        match kind {
            0 => SweepShape::Sphere {
                center: c,
                radius: size,
            },
            1 => SweepShape::Capsule {
                a: c - glam::Vec3::Y * size,
                b: c + glam::Vec3::Y * size,
                radius: size * 0.5,
            },
            _ => SweepShape::Box(meshq::math::Obb::new(
                c,
                [glam::Vec3::X, glam::Vec3::Y, glam::Vec3::Z],
                glam::Vec3::new(size, size * 0.5, size * 0.25),
            )),
        }
    };
    let (ball, capsule, cuboid) = (
        Ball::new(size),
        Capsule::new_y(size, size * 0.5),
        Cuboid::new(Vector::new(size, size * 0.5, size * 0.25)),
    );
    let parry_sweep = |kind: u32, start: [f32; 3], motion: [f32; 3]| {
        let shape: &dyn parry3d::shape::Shape = match kind {
            0 => &ball,
            1 => &capsule,
            _ => &cuboid,
        };
        cast_shapes(
            &Pose::translation(start[0], start[1], start[2]),
            Vector::from_array(motion),
            shape,
            &Pose::IDENTITY,
            Vector::ZERO,
            &parry_a,
            ShapeCastOptions::with_max_time_of_impact(1.0),
        )
        .expect("parry3d casts shapes at meshes")
    };
    // The hits are compared both ways and the times one way: where parry3d's contact comes
    // earlier than meshq's, meshq's own test must find the shape clear of the mesh at parry3d's
    // time (a near miss parry3d counts as contact), else the bench stops.
    let (mut same_hit, mut touching, mut later, mut early) = (0usize, 0usize, 0f32, 0usize);
    for &(kind, start, motion) in &sweeps {
        let m = glam::Vec3::from_array(motion);
        let ours = bvh.sweep(&ours_shape(kind, start), m).expect("valid");
        let theirs = parry_sweep(kind, start, motion);
        touching += usize::from(ours.is_some());
        same_hit += usize::from(ours.is_some() == theirs.is_some());
        if let (Some(o), Some(t)) = (ours, theirs) {
            if o.t > t.time_of_impact + 1e-4 {
                let clear = bvh
                    .sweep(
                        &ours_shape(kind, start).moved(m * t.time_of_impact),
                        glam::Vec3::ZERO,
                    )
                    .expect("valid")
                    .is_none();
                assert!(clear, "meshq's contact comes after one parry3d found");
                early += 1;
            }
            later = later.max(t.time_of_impact - o.t);
        }
    }
    eprintln!(
        "{} / sweeps: {touching} of {} touch; hit or miss the same in parry3d for {same_hit}; \
         parry3d's contact up to {later} of the motion later, and {early} earlier where the \
         shape is still clear of the mesh",
        scene.name,
        sweeps.len()
    );
    assert!(
        same_hit * 100 >= sweeps.len() * 98,
        "the libraries disagree on {} sweeps",
        sweeps.len() - same_hit
    );
    let mut group = c.benchmark_group(format!("sweep/{}/1000 shapes", scene.name));
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(500));
    group.measurement_time(Duration::from_secs(2));
    group.throughput(Throughput::Elements(sweeps.len() as u64));
    group.bench_function("meshq_sweep", |b| {
        b.iter(|| {
            for &(kind, start, motion) in &sweeps {
                black_box(
                    bvh.sweep(&ours_shape(kind, start), glam::Vec3::from_array(motion))
                        .ok(),
                );
            }
        })
    });
    group.bench_function("parry3d_cast_shapes", |b| {
        b.iter(|| {
            for &(kind, start, motion) in &sweeps {
                black_box(parry_sweep(kind, start, motion));
            }
        })
    });
    group.finish();

    let mut out = vec![TrianglePair::default(); 1 << 16];
    let found = self_intersecting_pairs(&tree, &mesh, budget, &mut out).expect("within budget");
    eprintln!(
        "{} / self: {} pairs of {} tested",
        scene.name, found.total, found.tested
    );
    let mut group = c.benchmark_group(format!("collide/{}/self", scene.name));
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(500));
    group.measurement_time(Duration::from_secs(3));
    group.throughput(Throughput::Elements(found.tested as u64));
    group.bench_function("meshq_self_pairs", |b| {
        b.iter(|| black_box(self_intersecting_pairs(&tree, &mesh, budget, &mut out)))
    });
    group.finish();
}

criterion_group!(benches, collide);
criterion_main!(benches);
