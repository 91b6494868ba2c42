//! How `meshq::parallel` and the parallel build scale with threads on this machine: the
//! DESIGN.md workloads on a mesh (default the bunny; `cargo run --release -p meshq-bench
//! --example scaling [mesh.obj] [subdivisions]`), batches on rayon pools of 1, 2, … up to
//! the number of cores, interleaved round by round, best of 5 rounds. The build is timed on
//! the mesh subdivided `subdivisions` times (each triangle into four; default 2, which makes the
//! bunny's 1.1M triangles), against the sequential `MeshBvh::build`. Every run's answers are
//! checked to equal the one-thread answers first.
//!
//! The speed-ups for more cores than the machine has are estimates, not measurements: Amdahl's
//! law with the serial fraction implied by the largest measured speed-up (`f = (P/S − 1) /
//! (P − 1)` for `S` on `P` threads).

use std::time::Instant;

use meshq::MeshBvh;
use meshq::bvh::BuildConfig;
use meshq::mesh::MeshRef;
use meshq::parallel;
use meshq::query::RayOptions;
use meshq_tests::{LoadedMesh, load_obj, workload};

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap_or_else(|e| panic!("threads: {e}"))
}

/// Each triangle into four through its edge midpoints (shared between neighbours).
fn subdivide(mesh: &LoadedMesh) -> LoadedMesh {
    let mut positions = mesh.positions.clone();
    let mut midpoints = std::collections::HashMap::new();
    let mut mid = |a: u32, b: u32, positions: &mut Vec<[f32; 3]>| {
        *midpoints.entry((a.min(b), a.max(b))).or_insert_with(|| {
            let (p, q) = (positions[a as usize], positions[b as usize]);
            positions.push([0, 1, 2].map(|k| (p[k] + q[k]) * 0.5));
            (positions.len() - 1) as u32
        })
    };
    let mut triangles = Vec::with_capacity(4 * mesh.triangles.len());
    for &[a, b, c] in &mesh.triangles {
        let ab = mid(a, b, &mut positions);
        let bc = mid(b, c, &mut positions);
        let ca = mid(c, a, &mut positions);
        triangles.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
    }
    LoadedMesh {
        positions,
        triangles,
        name: format!("{}-x4", mesh.name),
    }
}

/// Best time in ms of each closure over `rounds` rounds, the closures interleaved.
fn best_of(rounds: usize, runs: &mut [Box<dyn FnMut() + '_>]) -> Vec<f64> {
    let mut best = vec![f64::INFINITY; runs.len()];
    for _ in 0..rounds {
        for (b, run) in best.iter_mut().zip(runs.iter_mut()) {
            let start = Instant::now();
            run();
            *b = b.min(start.elapsed().as_secs_f64() * 1e3);
        }
    }
    best
}

fn report(what: &str, threads: &[usize], ms: &[f64]) {
    let one = ms[0];
    let cells: Vec<String> = threads
        .iter()
        .zip(ms)
        .map(|(t, m)| format!("{t}: {m:.1} ms ({:.2}×)", one / m))
        .collect();
    let (p, s) = (
        *threads.last().unwrap_or(&1) as f64,
        one / ms.last().copied().unwrap_or(one),
    );
    let estimate = if p > 1.0 {
        let f = ((p / s - 1.0) / (p - 1.0)).clamp(0.0, 1.0);
        let amdahl = |n: f64| 1.0 / (f + (1.0 - f) / n);
        format!(
            "; estimated 8: {:.1}×, 16: {:.1}× (serial fraction {:.3})",
            amdahl(8.0),
            amdahl(16.0),
            f
        )
    } else {
        String::new()
    };
    println!("{what}: {}{estimate}", cells.join(", "));
}

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args.next().map_or_else(
        || meshq_tests::assets_dir().join("stanford-bunny.obj"),
        Into::into,
    );
    let subdivisions: usize = args.next().map_or(2, |s| s.parse().unwrap_or(2));
    let loaded = load_obj(&path);
    let mesh = MeshRef::new(&loaded.positions, &loaded.triangles)
        .validate()
        .unwrap_or_else(|e| panic!("{e}"));
    let scene = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap_or_else(|e| panic!("{e}"));
    let cores = std::thread::available_parallelism().map_or(1, usize::from);
    let threads: Vec<usize> = (1..=cores).collect();
    let pools: Vec<_> = threads.iter().map(|&t| pool(t)).collect();
    println!(
        "{}: {} triangles; {cores} cores; pools of {threads:?} threads, best of 5 interleaved rounds",
        loaded.name,
        mesh.triangle_count()
    );

    let random = workload::random_rays(&loaded.positions, 1_000_000, 1);
    let camera = workload::camera_rays(&loaded.positions, 1024, 1024);
    let points = workload::closest_points(&loaded.positions, 100_000, 1);
    let options = RayOptions::default();
    // Borrowed by every timed closure.
    let (scene, random, camera, points, options) = (&scene, &random, &camera, &points, &options);
    for (what, rays) in [
        ("random rays (1M), closest hit", random),
        ("camera rays (1024²), closest hit", camera),
    ] {
        let mut want = vec![None; rays.len()];
        pools[0]
            .install(|| parallel::raycast_batch(scene, rays, options, &mut want))
            .unwrap_or_else(|e| panic!("{e}"));
        let mut outs: Vec<_> = pools.iter().map(|_| vec![None; rays.len()]).collect();
        let mut runs: Vec<Box<dyn FnMut()>> = pools
            .iter()
            .zip(outs.iter_mut())
            .map(|(p, out)| {
                Box::new(move || {
                    p.install(|| parallel::raycast_batch(scene, rays, options, out))
                        .unwrap_or_else(|e| panic!("{e}"));
                }) as Box<dyn FnMut()>
            })
            .collect();
        let ms = best_of(5, &mut runs);
        drop(runs);
        assert!(
            outs.iter().all(|o| *o == want),
            "{what}: answers differ between pools"
        );
        report(what, &threads, &ms);
    }
    {
        let mut outs: Vec<_> = pools.iter().map(|_| vec![false; random.len()]).collect();
        let mut runs: Vec<Box<dyn FnMut()>> = pools
            .iter()
            .zip(outs.iter_mut())
            .map(|(p, out)| {
                Box::new(move || {
                    p.install(|| parallel::raycast_any_batch(scene, random, options, out))
                        .unwrap_or_else(|e| panic!("{e}"));
                }) as Box<dyn FnMut()>
            })
            .collect();
        let ms = best_of(5, &mut runs);
        drop(runs);
        assert!(
            outs.windows(2).all(|w| w[0] == w[1]),
            "any hit: answers differ"
        );
        report("random rays (1M), any hit", &threads, &ms);
    }
    {
        let mut outs: Vec<_> = pools.iter().map(|_| vec![None; points.len()]).collect();
        let mut runs: Vec<Box<dyn FnMut()>> = pools
            .iter()
            .zip(outs.iter_mut())
            .map(|(p, out)| {
                Box::new(move || {
                    p.install(|| parallel::closest_points(scene, points, f32::INFINITY, out))
                        .unwrap_or_else(|e| panic!("{e}"));
                }) as Box<dyn FnMut()>
            })
            .collect();
        let ms = best_of(5, &mut runs);
        drop(runs);
        assert!(
            outs.windows(2).all(|w| w[0] == w[1]),
            "closest points: answers differ"
        );
        report("closest points (100k)", &threads, &ms);
    }

    let mut big = loaded.clone();
    for _ in 0..subdivisions {
        big = subdivide(&big);
    }
    let big_mesh = MeshRef::new(&big.positions, &big.triangles)
        .validate()
        .unwrap_or_else(|e| panic!("{e}"));
    let config = BuildConfig::default();
    let want = MeshBvh::build(&big_mesh, &config).unwrap_or_else(|e| panic!("{e}"));
    let mut runs: Vec<Box<dyn FnMut()>> = vec![Box::new(|| {
        std::hint::black_box(MeshBvh::build(&big_mesh, &config).unwrap_or_else(|e| panic!("{e}")));
    })];
    for p in &pools {
        let (big_mesh, config, want) = (&big_mesh, &config, &want);
        runs.push(Box::new(move || {
            let built = p
                .install(|| MeshBvh::build_parallel(big_mesh, config))
                .unwrap_or_else(|e| panic!("{e}"));
            assert!(
                built.bvh().nodes() == want.bvh().nodes(),
                "build: another tree"
            );
        }));
    }
    let ms = best_of(5, &mut runs);
    println!(
        "build of {} triangles ({}; owned: tree, packed triangles, wide collapse): sequential {:.1} ms",
        big_mesh.triangle_count(),
        big.name,
        ms[0]
    );
    report("  build_parallel", &threads, &ms[1..]);
}
