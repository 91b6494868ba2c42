//! The four structures side by side — BVH, k-d tree, octree, grid — on a mesh and on the same
//! mesh in a stadium (a ground plane a hundred times wider): build time, random-ray and
//! camera-ray throughput, closest points per second. Every structure is queried through its
//! owned form (packed triangles), with the same rays and points.
//!
//! `MESHQ_BENCH_MESHES` picks the meshes (comma-separated bundled names or `.obj` paths;
//! default the bunny); each also runs in its stadium. `scripts/structure_table.py` prints the
//! README table from criterion's JSON; `cargo run --release -p meshq-bench --example
//! structures` prints the sizes.

use std::hint::black_box;
use std::time::Duration;

use criterion::{
    BenchmarkGroup, Criterion, Throughput, criterion_group, criterion_main, measurement::WallTime,
};
use meshq::owned::{MeshIndex, StructureKind};
use meshq::query::MeshQuery;
use meshq_tests::{LoadedMesh, in_stadium, load_mesh, load_obj, workload};

const RANDOM_RAYS: usize = 50_000;
const CAMERA: (usize, usize) = (256, 256);
const CLOSEST_POINTS: usize = 20_000;

/// The meshes to run: `MESHQ_BENCH_MESHES` or the bunny, each followed by its stadium.
fn scenes() -> Vec<LoadedMesh> {
    let names = std::env::var("MESHQ_BENCH_MESHES").unwrap_or_else(|_| "stanford-bunny".into());
    names
        .split(',')
        .filter(|n| !n.is_empty())
        .flat_map(|n| {
            let m = if n.ends_with(".obj") {
                load_obj(std::path::Path::new(n))
            } else {
                load_mesh(n)
            };
            let s = in_stadium(&m);
            [m, s]
        })
        .collect()
}

fn configure(group: &mut BenchmarkGroup<'_, WallTime>, elements: usize) {
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(500));
    group.measurement_time(Duration::from_secs(2));
    group.throughput(Throughput::Elements(elements as u64));
}

fn structures(c: &mut Criterion) {
    for scene in scenes() {
        let mesh = scene.valid();
        let random = workload::random_rays(&scene.positions, RANDOM_RAYS, 1);
        let camera = workload::camera_rays(&scene.positions, CAMERA.0, CAMERA.1);
        let points = workload::closest_points(&scene.positions, CLOSEST_POINTS, 2);
        let built: Vec<(StructureKind, MeshIndex)> = StructureKind::ALL
            .into_iter()
            .map(|k| (k, MeshIndex::build(&mesh, k).expect("builds")))
            .collect();
        // Same answers first: a benchmark of wrong answers measures nothing.
        for (kind, index) in &built[1..] {
            for r in random.iter().take(2000) {
                assert_eq!(
                    index.raycast(r),
                    built[0].1.raycast(r),
                    "{kind} on {}",
                    scene.name
                );
            }
        }
        let mut group = c.benchmark_group(format!("build/{}", scene.name));
        configure(&mut group, mesh.triangle_count());
        for kind in StructureKind::ALL {
            group.bench_function(kind.name(), |b| {
                b.iter(|| black_box(MeshIndex::build(&mesh, kind).map(|i| i.kind()).ok()))
            });
        }
        group.finish();
        for (what, rays) in [("random", &random), ("camera", &camera)] {
            let mut group = c.benchmark_group(format!("{what}/{}", scene.name));
            configure(&mut group, rays.len());
            for (kind, index) in &built {
                group.bench_function(kind.name(), |b| {
                    b.iter(|| {
                        let mut hits = 0u32;
                        for r in rays.iter() {
                            hits += u32::from(index.raycast(r).is_some());
                        }
                        black_box(hits)
                    })
                });
            }
            group.finish();
        }
        let mut group = c.benchmark_group(format!("closest/{}", scene.name));
        configure(&mut group, points.len());
        for (kind, index) in &built {
            group.bench_function(kind.name(), |b| {
                b.iter(|| {
                    let mut sum = 0.0f32;
                    for &p in &points {
                        sum += index
                            .closest_point(p, f32::INFINITY)
                            .map_or(0.0, |c| c.distance_squared);
                    }
                    black_box(sum)
                })
            });
        }
        group.finish();
    }
}

criterion_group!(benches, structures);
criterion_main!(benches);
