//! The main job until the CLI lands: load the bundled bunny, build its BVH, cast the DESIGN.md
//! random-ray and camera workloads and closest-point queries, and print the figures.

use std::time::Instant;

use meshq::bvh::BuildConfig;
use meshq_tests::{OwnedBvh, load_mesh, workload};

fn main() {
    let loaded = load_mesh("stanford-bunny");
    let mesh = loaded.valid();
    println!(
        "mesh: assets/stanford-bunny.obj, {} triangles, {} vertices",
        mesh.triangle_count(),
        mesh.vertex_count()
    );
    for (name, config) in [
        ("fast", BuildConfig::fast()),
        ("balanced", BuildConfig::balanced()),
        ("high_quality", BuildConfig::high_quality()),
    ] {
        let start = Instant::now();
        let owned = OwnedBvh::build(&mesh, &config).unwrap_or_else(|e| panic!("build: {e}"));
        let seconds = start.elapsed().as_secs_f64();
        let bvh = owned.view(&mesh).unwrap_or_else(|e| panic!("check: {e}"));
        println!(
            "build {name:>12}: {:7.2} ms, {} nodes ({} KiB), depth {}",
            seconds * 1e3,
            bvh.nodes().len(),
            (bvh.nodes().len() * 32 + bvh.order().len() * 4) / 1024,
            bvh.depth()
        );
    }
    let owned = OwnedBvh::build(&mesh, &BuildConfig::default()).unwrap_or_else(|e| panic!("{e}"));
    let bvh = owned.view(&mesh).unwrap_or_else(|e| panic!("{e}"));
    let rays = workload::random_rays(&loaded.positions, 1_000_000, 1);
    let camera = workload::camera_rays(&loaded.positions, 1024, 1024);
    for (name, rays) in [("random rays", &rays), ("camera rays", &camera)] {
        let start = Instant::now();
        let hits = rays
            .iter()
            .filter(|r| bvh.raycast(&mesh, r).is_some())
            .count();
        let seconds = start.elapsed().as_secs_f64();
        println!(
            "{name}: {} rays, {hits} hits, {:.2} M rays/s (closest hit, one thread)",
            rays.len(),
            rays.len() as f64 / seconds / 1e6
        );
    }
    let start = Instant::now();
    let hits = rays.iter().filter(|r| bvh.raycast_any(&mesh, r)).count();
    println!(
        "random rays, any hit: {hits} hits, {:.2} M rays/s",
        rays.len() as f64 / start.elapsed().as_secs_f64() / 1e6
    );
    let points = workload::closest_points(&loaded.positions, 100_000, 2);
    let start = Instant::now();
    let found = points
        .iter()
        .filter(|&&p| bvh.closest_point(&mesh, p, f32::INFINITY).is_some())
        .count();
    println!(
        "closest point: {found} queries, {:.2} M queries/s",
        points.len() as f64 / start.elapsed().as_secs_f64() / 1e6
    );
}
