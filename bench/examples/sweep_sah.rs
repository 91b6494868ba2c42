//! Sweep SAH against the binned build: SAH cost, nodes, build time and rays per second through
//! the default query nodes, interleaved (best of 7 rounds), every answer checked equal between
//! the trees first. Leaf size and costs are the default config's for every tree, so only the
//! split search differs.
//!
//! `cargo run --release -p meshq-bench --example sweep_sah` (env `MESHES` a comma-separated
//! list of bundled mesh names, default all five plus the bunny subdivided twice, 1.1M
//! triangles; `RAYS`; `STEPS` a comma-separated list of sweep steps, default `32,1`; `JSON=1`
//! prints one JSON object per mesh instead of text).

use std::hint::black_box;
use std::time::{Duration, Instant};

use meshq::MeshQuery;
use meshq::advanced::TreeStats;
use meshq::bvh::{BuildConfig, SplitStrategy};
use meshq::math::Ray;
use meshq::owned::MeshBvh;
use meshq_tests::{LoadedMesh, MESHES, load_mesh, subdivided, workload};

const ROUNDS: usize = 7;

fn env<T: std::str::FromStr>(name: &str, default: T) -> T {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// The best of `times` builds, and the tree.
fn timed_build(times: usize, build: impl Fn() -> MeshBvh) -> (MeshBvh, Duration) {
    let mut best = Duration::MAX;
    let mut tree = None;
    for _ in 0..times {
        let start = Instant::now();
        let t = build();
        best = best.min(start.elapsed());
        tree = Some(t);
    }
    (tree.expect("a build"), best)
}

/// The cost both builders minimise: [`TreeStats`]'s SAH cost with each leaf's triangles
/// counted in batches of four (`⌈N/4⌉`), as queries test them.
fn batched_sah(tree: &MeshBvh, config: &BuildConfig) -> f64 {
    let nodes = tree.bvh().nodes();
    let area = |n: &meshq::advanced::BvhNode| {
        let e: [f64; 3] = std::array::from_fn(|k| f64::from(n.max[k]) - f64::from(n.min[k]));
        e[0] * e[1] + e[1] * e[2] + e[2] * e[0]
    };
    let root = nodes.first().map_or(0.0, area);
    if root <= 0.0 {
        return 0.0;
    }
    nodes
        .iter()
        .map(|n| {
            let weight = if n.is_leaf() {
                f64::from(n.count.div_ceil(4)) * f64::from(config.triangle_cost)
            } else {
                f64::from(config.traversal_cost)
            };
            area(n) / root * weight
        })
        .sum()
}

fn meshes() -> Vec<LoadedMesh> {
    let names = std::env::var("MESHES").unwrap_or_else(|_| {
        let mut all: Vec<String> = MESHES.iter().map(|s| (*s).to_owned()).collect();
        all.push("stanford-bunny-x16".to_owned());
        all.join(",")
    });
    names
        .split(',')
        .map(|name| match name.strip_suffix("-x16") {
            Some(base) => {
                let mut m = subdivided(&subdivided(&load_mesh(base)));
                m.name = name.to_owned();
                m
            }
            None => load_mesh(name),
        })
        .collect()
}

fn main() {
    let json = std::env::var_os("JSON").is_some();
    let steps: Vec<u32> = std::env::var("STEPS")
        .unwrap_or_else(|_| "32,1".into())
        .split(',')
        .map(|x| x.trim().parse().expect("STEPS: whole numbers"))
        .collect();
    for loaded in meshes() {
        let mesh = loaded.valid();
        let n = mesh.triangle_count();
        let random = workload::random_rays(&loaded.positions, env("RAYS", 200_000), 1);
        let camera = workload::camera_rays(&loaded.positions, 512, 512);
        let binned_config = BuildConfig::default();
        let builds = if n > 500_000 { 1 } else { 3 };
        let mut configs = vec![("binned".to_owned(), binned_config)];
        for &step in &steps {
            configs.push((
                format!("sweep {step}"),
                BuildConfig {
                    split: SplitStrategy::Sweep { step },
                    ..binned_config
                },
            ));
        }
        let trees: Vec<(String, MeshBvh, Duration)> = configs
            .iter()
            .map(|(name, config)| {
                let (tree, time) =
                    timed_build(builds, || MeshBvh::build(&mesh, config).expect("build"));
                (name.clone(), tree, time)
            })
            .collect();
        let binned = &trees[0].1;
        for (name, tree, _) in &trees[1..] {
            for r in random.iter().chain(&camera) {
                assert_eq!(tree.raycast(r), binned.raycast(r), "{name}: {r:?}");
            }
        }
        // Interleaved rounds: each tree's best time on each ray set.
        let mut best = vec![[Duration::MAX; 2]; trees.len()];
        for _ in 0..ROUNDS {
            for (b, (_, tree, _)) in best.iter_mut().zip(&trees) {
                for (slot, rays) in b.iter_mut().zip([&random, &camera] as [&Vec<Ray>; 2]) {
                    let start = Instant::now();
                    black_box(rays.iter().filter(|r| tree.raycast(r).is_some()).count());
                    *slot = (*slot).min(start.elapsed());
                }
            }
        }
        let rows: Vec<serde_json::Value> = trees
            .iter()
            .zip(&best)
            .map(|((name, tree, build), [r, c])| {
                let stats = TreeStats::of(&tree.bvh(), &binned_config);
                serde_json::json!({
                    "build": name,
                    "sah_cost": stats.sah_cost,
                    "batched_sah_cost": batched_sah(tree, &binned_config),
                    "nodes": stats.nodes,
                    "build_ms": build.as_secs_f64() * 1e3,
                    "random_mrays": random.len() as f64 / r.as_secs_f64() / 1e6,
                    "camera_mrays": camera.len() as f64 / c.as_secs_f64() / 1e6,
                })
            })
            .collect();
        if json {
            println!(
                "{}",
                serde_json::json!({
                    "mesh": loaded.name,
                    "triangles": n,
                    "random_rays": random.len(),
                    "camera_rays": camera.len(),
                    "rows": rows,
                })
            );
            continue;
        }
        println!("{}: {n} triangles", loaded.name);
        for row in &rows {
            println!(
                "  {:>9}: SAH {:>7.2} (batched {:>6.2})  {:>8} nodes  build {:>9.1} ms  random {:>6.2} M rays/s  camera {:>6.2} M rays/s",
                row["build"].as_str().unwrap_or(""),
                row["sah_cost"].as_f64().unwrap_or(0.0),
                row["batched_sah_cost"].as_f64().unwrap_or(0.0),
                row["nodes"],
                row["build_ms"].as_f64().unwrap_or(0.0),
                row["random_mrays"].as_f64().unwrap_or(0.0),
                row["camera_mrays"].as_f64().unwrap_or(0.0),
            );
        }
    }
}
