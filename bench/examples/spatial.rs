//! Spatial splits against the ordinary tree: references, nodes, build time, and rays per
//! second through the default nodes, interleaved (best of 11 rounds), with every answer
//! checked equal between the trees first.
//!
//! `cargo run --release -p meshq-bench --example spatial` (env `MESH` an OBJ path, `STICKS=n`
//! a generated scene of `n` long thin boxes at random angles instead, `SUBDIVIDE`, `RAYS`,
//! `EXTRA` a comma-separated list of [`SpatialSplits::extra_references`] values, `NODES`
//! `four`/`eight`/`compact`/`default`).

use std::hint::black_box;
use std::time::{Duration, Instant};

use meshq::MeshQuery;
use meshq::bvh::{BuildConfig, SpatialSplits};
use meshq::math::Ray;
use meshq::owned::MeshBvh;
use meshq_tests::{load_mesh, sticks, workload};

const ROUNDS: usize = 11;

fn env<T: std::str::FromStr>(name: &str, default: T) -> T {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// The best of three builds, and the tree.
fn timed_build(build: impl Fn() -> MeshBvh) -> (MeshBvh, Duration) {
    let mut best = Duration::MAX;
    let mut tree = None;
    for _ in 0..3 {
        let start = Instant::now();
        let t = build();
        best = best.min(start.elapsed());
        tree = Some(t);
    }
    (tree.expect("three builds"), best)
}

fn with_nodes(tree: MeshBvh) -> MeshBvh {
    match std::env::var("NODES").as_deref() {
        Ok("four") => tree.with_four_wide_nodes().expect("four-wide"),
        Ok("eight") => tree.with_eight_wide_nodes().expect("eight-wide"),
        Ok("compact") => tree.with_compact_nodes().expect("compact"),
        _ => tree,
    }
}

fn main() {
    let mut loaded = match (std::env::var("STICKS").ok(), std::env::var("MESH")) {
        (Some(n), _) => sticks(n.parse().expect("STICKS: a count")),
        (None, Ok(path)) => meshq_tests::load_obj(std::path::Path::new(&path)),
        (None, Err(_)) => load_mesh("stanford-bunny"),
    };
    for _ in 0..env("SUBDIVIDE", 0) {
        loaded = meshq_tests::subdivided(&loaded);
    }
    let mesh = loaded.valid();
    let config = BuildConfig::default();
    let random = workload::random_rays(&loaded.positions, env("RAYS", 200_000), 1);
    let camera = workload::camera_rays(&loaded.positions, 512, 512);
    let extras: Vec<f32> = std::env::var("EXTRA")
        .unwrap_or_else(|_| "0.3,1".into())
        .split(',')
        .map(|x| x.trim().parse().expect("EXTRA: numbers"))
        .collect();

    let (plain, plain_build) = timed_build(|| MeshBvh::build(&mesh, &config).expect("build"));
    let plain = with_nodes(plain);
    println!(
        "{}: {} triangles; ordinary tree {} nodes, built in {:.1} ms",
        loaded.name,
        mesh.triangle_count(),
        plain.bvh().nodes().len(),
        plain_build.as_secs_f64() * 1e3
    );
    for extra in extras {
        let spatial = SpatialSplits {
            extra_references: extra,
            min_overlap: env("MIN_OVERLAP", SpatialSplits::DEFAULT.min_overlap),
        };
        let (split, build) = timed_build(|| {
            MeshBvh::build_spatial(&mesh, &config, &spatial).expect("spatial build")
        });
        let split = with_nodes(split);
        for r in random.iter().chain(&camera) {
            assert_eq!(split.raycast(r), plain.raycast(r), "{r:?}");
        }
        let variants: [(&str, &[Ray], &MeshBvh); 4] = [
            ("random, ordinary", &random, &plain),
            ("random, spatial", &random, &split),
            ("camera, ordinary", &camera, &plain),
            ("camera, spatial", &camera, &split),
        ];
        let mut best = [Duration::MAX; 4];
        for _ in 0..ROUNDS {
            for (i, (_, rays, tree)) in variants.iter().enumerate() {
                let start = Instant::now();
                black_box(rays.iter().filter(|r| tree.raycast(r).is_some()).count());
                best[i] = best[i].min(start.elapsed());
            }
        }
        let n = mesh.triangle_count();
        println!(
            "extra {extra}: {} references (+{:.1}%), {} split entries, {} nodes; built in {:.1} ms \
             ({:.2}× the ordinary build)",
            split.reference_count(),
            100.0 * (split.reference_count() - n) as f64 / n as f64,
            split.split_refs().len(),
            split.bvh().nodes().len(),
            build.as_secs_f64() * 1e3,
            build.as_secs_f64() / plain_build.as_secs_f64(),
        );
        for ((name, rays, _), t) in variants.iter().zip(&best) {
            println!(
                "  {name:>17}: {:>8.2} ms  {:>6.2} M rays/s",
                t.as_secs_f64() * 1e3,
                rays.len() as f64 / t.as_secs_f64() / 1e6
            );
        }
        let ratio = |a: usize, b: usize| best[a].as_secs_f64() / best[b].as_secs_f64();
        println!(
            "  speed-up: random {:.2}×, camera {:.2}×",
            ratio(0, 1),
            ratio(2, 3)
        );
    }
}
