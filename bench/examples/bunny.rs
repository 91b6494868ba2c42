//! In-process figures on the bundled bunny: build times per preset, the DESIGN.md random-ray
//! and camera workloads and closest-point queries on the in-memory BVH, and random rays from
//! blob views queried in place (`cargo run --release -p meshq-bench --example bunny`). The
//! random rays are those of `meshq workload --kind random-rays` (seed 1), so `meshq raycast`
//! figures compare directly.

use std::time::Instant;

use meshq::MeshBvh;
use meshq::blob::{BlobView, MeshLayout};
use meshq::bvh::BuildConfig;
use meshq::{MeshQuery, Traverse};
use meshq_tests::{checked_bvh, load_mesh, workload};

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
        let owned = MeshBvh::build(&mesh, &config).unwrap_or_else(|e| panic!("build: {e}"));
        let seconds = start.elapsed().as_secs_f64();
        let bvh = checked_bvh(&owned, &mesh).unwrap_or_else(|e| panic!("check: {e}"));
        println!(
            "build {name:>12}: {:7.2} ms, {} nodes ({} KiB), depth {}",
            seconds * 1e3,
            bvh.nodes().len(),
            (bvh.nodes().len() * 32 + bvh.order().len() * 4) / 1024,
            bvh.depth()
        );
    }
    let owned = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap_or_else(|e| panic!("{e}"));
    let bvh = checked_bvh(&owned, &mesh).unwrap_or_else(|e| panic!("{e}"));
    let rays = workload::random_rays(&loaded.positions, 1_000_000, 1);
    let camera = workload::camera_rays(&loaded.positions, 1024, 1024);
    for (name, rays) in [("random rays", &rays), ("camera rays", &camera)] {
        let start = Instant::now();
        let hits = rays
            .iter()
            .filter(|r| bvh.with(&mesh).raycast(r).is_some())
            .count();
        let seconds = start.elapsed().as_secs_f64();
        println!(
            "{name}: {} rays, {hits} hits, {:.2} M rays/s (closest hit, one thread)",
            rays.len(),
            rays.len() as f64 / seconds / 1e6
        );
    }
    let start = Instant::now();
    let hits = rays
        .iter()
        .filter(|r| bvh.with(&mesh).raycast_any(r))
        .count();
    println!(
        "random rays, any hit: {hits} hits, {:.2} M rays/s",
        rays.len() as f64 / start.elapsed().as_secs_f64() / 1e6
    );
    let points = workload::closest_points(&loaded.positions, 100_000, 2);
    let start = Instant::now();
    let found = points
        .iter()
        .filter(|&&p| bvh.with(&mesh).closest_point(p, f32::INFINITY).is_some())
        .count();
    println!(
        "closest point: {found} queries, {:.2} M queries/s",
        points.len() as f64 / start.elapsed().as_secs_f64() / 1e6
    );
    for layout in [MeshLayout::Indexed, MeshLayout::Packed] {
        let bytes = owned
            .to_blob(layout)
            .unwrap_or_else(|e| panic!("encode: {e}"));
        let parse = median_seconds(|| {
            BlobView::parse(&bytes).unwrap_or_else(|e| panic!("parse: {e}"));
        });
        let load = median_seconds(|| {
            MeshBvh::from_blob(&bytes).unwrap_or_else(|e| panic!("load: {e}"));
        });
        let view = BlobView::parse(&bytes).unwrap_or_else(|e| panic!("parse: {e}"));
        let start = Instant::now();
        let hits = rays.iter().filter(|r| view.raycast(r).is_some()).count();
        println!(
            "blob {layout:?}: {} bytes ({:.1} per triangle), validated in {:.2} ms, loaded into a MeshBvh in {:.2} ms (medians of 15); random rays in place: {hits} hits, {:.2} M rays/s",
            bytes.len(),
            bytes.len() as f64 / mesh.triangle_count() as f64,
            parse * 1e3,
            load * 1e3,
            rays.len() as f64 / start.elapsed().as_secs_f64() / 1e6
        );
    }
}

/// The median wall time of 15 runs of `f`, in seconds.
fn median_seconds(mut f: impl FnMut()) -> f64 {
    let mut times: Vec<f64> = (0..15)
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64()
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}
