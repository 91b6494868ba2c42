//! How `meshq::parallel` and the parallel build scale with threads on this machine: the
//! DESIGN.md workloads on a mesh (default the bunny; `cargo run --release -p meshq-bench
//! --example scaling [mesh.obj] [subdivisions]`), batches on rayon pools of 1, 2, … up to
//! the number of cores, interleaved round by round, best of 5 rounds. The build is timed on
//! the mesh subdivided `subdivisions` times (each triangle into four; default 2, which makes the
//! bunny's 1.1M triangles), against the sequential `MeshBvh::build`, and 1M random rays are
//! cast at that mesh too (a batch the calls sort). Every run's answers are
//! checked to equal the one-thread answers first.
//!
//! The speed-ups for more cores than the machine has are estimates, not measurements: Amdahl's
//! law with the serial fraction implied by the largest measured speed-up (`f = (P/S − 1) /
//! (P − 1)` for `S` on `P` threads).

use std::time::Instant;

use meshq::MeshBvh;
use meshq::bvh::{BuildConfig, SpatialSplits};
use meshq::mesh::MeshRef;
use meshq::parallel;
use meshq::query::RayOptions;
use meshq_tests::{load_obj, subdivided, workload};

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap_or_else(|e| panic!("threads: {e}"))
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

/// Times `batch` on every pool (each pool filling its own copy of `empty`), checks that every
/// pool's answers equal the one-thread answers, and reports.
fn batches<O: Clone + PartialEq + Send>(
    what: &str,
    pools: &[rayon::ThreadPool],
    empty: Vec<O>,
    batch: impl Fn(&mut [O]) -> Result<(), meshq::error::BatchError> + Sync,
) {
    let mut outs: Vec<Vec<O>> = pools.iter().map(|_| empty.clone()).collect();
    let batch = &batch;
    let mut runs: Vec<Box<dyn FnMut() + '_>> = pools
        .iter()
        .zip(outs.iter_mut())
        .map(|(pool, out)| {
            Box::new(move || {
                pool.install(|| batch(out))
                    .unwrap_or_else(|e| panic!("{e}"));
            }) as Box<dyn FnMut()>
        })
        .collect();
    let ms = best_of(5, &mut runs);
    drop(runs);
    assert!(
        outs.windows(2).all(|w| w[0] == w[1]),
        "{what}: answers differ between pools"
    );
    let threads: Vec<usize> = pools
        .iter()
        .map(rayon::ThreadPool::current_num_threads)
        .collect();
    report(what, &threads, &ms);
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
    let n = random.len();
    batches(
        "random rays (1M), closest hit",
        &pools,
        vec![None; n],
        |out| parallel::raycast_batch(scene, random, options, out),
    );
    batches(
        "camera rays (1024²), closest hit",
        &pools,
        vec![None; camera.len()],
        |out| parallel::raycast_batch(scene, camera, options, out),
    );
    batches("random rays (1M), any hit", &pools, vec![false; n], |out| {
        parallel::raycast_any_batch(scene, random, options, out)
    });
    batches(
        "closest points (100k)",
        &pools,
        vec![None; points.len()],
        |out| parallel::closest_points(scene, points, f32::INFINITY, out),
    );

    let mut big = loaded.clone();
    for _ in 0..subdivisions {
        big = subdivided(&big);
    }
    let big_mesh = MeshRef::new(&big.positions, &big.triangles)
        .validate()
        .unwrap_or_else(|e| panic!("{e}"));
    let config = BuildConfig::default();
    let want = MeshBvh::build(&big_mesh, &config).unwrap_or_else(|e| panic!("{e}"));
    // A large batch on a large mesh, which the batch calls answer sorted.
    let big_random = workload::random_rays(&big.positions, 1_000_000, 1);
    let (big_scene, big_random) = (&want, &big_random);
    batches(
        &format!(
            "random rays (1M) on {} triangles (sorted), closest hit",
            big_mesh.triangle_count()
        ),
        &pools,
        vec![None; big_random.len()],
        |out| parallel::raycast_batch(big_scene, big_random, options, out),
    );
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

    // The build with spatial splits, on the same mesh (best of 3: each takes seconds).
    let spatial = SpatialSplits::DEFAULT;
    let want =
        MeshBvh::build_spatial(&big_mesh, &config, &spatial).unwrap_or_else(|e| panic!("{e}"));
    let mut runs: Vec<Box<dyn FnMut()>> = vec![Box::new(|| {
        std::hint::black_box(
            MeshBvh::build_spatial(&big_mesh, &config, &spatial).unwrap_or_else(|e| panic!("{e}")),
        );
    })];
    for p in &pools {
        let (big_mesh, config, want, spatial) = (&big_mesh, &config, &want, &spatial);
        runs.push(Box::new(move || {
            let built = p
                .install(|| MeshBvh::build_spatial_parallel(big_mesh, config, spatial))
                .unwrap_or_else(|e| panic!("{e}"));
            assert!(
                built.bvh().nodes() == want.bvh().nodes(),
                "spatial build: another tree"
            );
        }));
    }
    let ms = best_of(3, &mut runs);
    println!(
        "build with spatial splits ({} references): sequential {:.1} ms",
        want.reference_count(),
        ms[0]
    );
    report("  build_spatial_parallel", &threads, &ms[1..]);
}
