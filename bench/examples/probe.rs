//! Profiling aid: random rays and closest points on the bunny with packed triangles.
use meshq::bvh::{BuildConfig, PackedTriangle};
use meshq_tests::{OwnedBvh, load_mesh, workload};
fn main() {
    let what = std::env::args().nth(1).unwrap_or_default();
    let l = load_mesh("stanford-bunny");
    let mesh = l.valid();
    let env = |k: &str, d: f32| {
        std::env::var(k)
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(d)
    };
    let config = BuildConfig {
        traversal_cost: env("TRAV", 1.0),
        max_leaf_size: env("LEAF", 4.0) as u32,
        bins: env("BINS", 32.0) as u32,
        ..BuildConfig::default()
    };
    let o = OwnedBvh::build(&mesh, &config).unwrap();
    let bvh = o.view(&mesh).unwrap();
    let leaves = bvh.nodes().iter().filter(|n| n.is_leaf()).count();
    print!(
        "nodes {} tris/leaf {:.2} ",
        bvh.nodes().len(),
        mesh.triangle_count() as f64 / leaves as f64
    );
    let mut storage = vec![PackedTriangle::EMPTY; mesh.triangle_count()];
    let packed = bvh.pack_triangles(&mesh, &mut storage).unwrap();
    let t = std::time::Instant::now();
    if what == "closest" {
        let pts = workload::closest_points(&l.positions, 100_000, 2);
        let t = std::time::Instant::now();
        let n = pts
            .iter()
            .filter(|&&p| bvh.closest_point(&packed, p, f32::INFINITY).is_some())
            .count();
        println!(
            "{n} closest: {:.0} K/s",
            pts.len() as f64 / t.elapsed().as_secs_f64() / 1e3
        );
    } else {
        let rays = workload::random_rays(&l.positions, 1_000_000, 1);
        let t = std::time::Instant::now();
        let n = rays
            .iter()
            .filter(|r| bvh.raycast(&packed, r).is_some())
            .count();
        println!(
            "{n} hits: {:.0} K rays/s",
            rays.len() as f64 / t.elapsed().as_secs_f64() / 1e3
        );
    }
    let _ = t;
}
