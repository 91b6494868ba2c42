//! Quick A/B timing of meshq's own query paths on the bunny, interleaved round by round and
//! reported as the best round, so machine noise hits every variant alike. The criterion bench
//! (`cargo bench -p meshq-bench`) remains the measurement of record against the peers.
//!
//! `cargo run --release -p meshq-bench --example ab [substring]` (only variants whose name
//! contains the substring run, e.g. for a profiler). Environment: `MESH` an OBJ file instead
//! of the bunny, `SUBDIVIDE=k` to split its triangles in four `k` times, `RAYS` random rays
//! (200,000), `TILE=h` the 512² camera's rays in tiles of `h` rows by `8 / h` pixels instead of
//! row-major.

use std::hint::black_box;
use std::time::{Duration, Instant};

use meshq::MeshBvh;
use meshq::bvh::BuildConfig;
use meshq::{MeshQuery, Traverse};
use meshq_tests::{checked_bvh, load_mesh, workload};

const ROUNDS: usize = 11;

/// `rays` through `owned`'s batch call, `per_call` rays at a time: how many hit.
fn owned_batch(owned: &MeshBvh, rays: &[meshq::math::Ray], per_call: usize) -> usize {
    let options = meshq::query::RayOptions::default();
    let mut keys = vec![0u64; per_call.min(rays.len())];
    let mut out = vec![None; rays.len()];
    for (run, answers) in rays.chunks(per_call).zip(out.chunks_mut(per_call)) {
        owned
            .raycast_batch(run, &options, &mut keys, answers)
            .expect("batch");
    }
    out.iter().filter(|h| h.is_some()).count()
}

fn main() {
    let mut loaded = std::env::var("MESH").map_or_else(
        |_| load_mesh("stanford-bunny"),
        |path| meshq_tests::load_obj(std::path::Path::new(&path)),
    );
    let subdivisions = std::env::var("SUBDIVIDE")
        .ok()
        .and_then(|k| k.parse().ok())
        .unwrap_or(0);
    for _ in 0..subdivisions {
        loaded = meshq_tests::subdivided(&loaded);
    }
    let mesh = loaded.valid();
    let count = std::env::var("RAYS")
        .ok()
        .and_then(|n| n.parse().ok())
        .unwrap_or(200_000);
    let rays = workload::random_rays(&loaded.positions, count, 1);
    let camera = workload::camera_rays(&loaded.positions, 512, 512);
    let tiled = std::env::var("TILE")
        .ok()
        .and_then(|t| t.parse::<usize>().ok());
    let camera: Vec<_> = match tiled {
        Some(h) => {
            let w = 8 / h;
            let mut out = Vec::new();
            for ty in (0..512).step_by(h) {
                for tx in (0..512).step_by(w) {
                    for y in ty..ty + h {
                        for x in tx..tx + w {
                            out.push(camera[y * 512 + x]);
                        }
                    }
                }
            }
            out
        }
        None => camera,
    };
    let points = workload::closest_points(&loaded.positions, 100_000, 2);
    let mut config = BuildConfig::default();
    if let Some(t) = std::env::var("TRAV").ok().and_then(|t| t.parse().ok()) {
        config.traversal_cost = t;
    }
    if let Some(l) = std::env::var("LEAF").ok().and_then(|l| l.parse().ok()) {
        config.max_leaf_size = l;
    }
    let owned = MeshBvh::build(&mesh, &config).expect("build");
    let bvh = checked_bvh(&owned, &mesh).expect("view");
    let owned4 = owned
        .clone()
        .with_four_wide_nodes()
        .expect("four-wide nodes");
    let (packed, wide) = (owned.packed(), owned4.wide().expect("wide nodes"));
    let mut compact_nodes = vec![meshq::advanced::CompactNode::EMPTY; wide.nodes().len()];
    let compact = meshq::wide::WideBvh::quantize(&wide, &mut compact_nodes).expect("compact");
    let per_triangle = |bytes: usize| bytes as f64 / mesh.triangle_count() as f64;
    println!(
        "{} binary nodes -> {} wide nodes: {:.1} bytes per triangle, compact {:.1}",
        bvh.nodes().len(),
        wide.nodes().len(),
        per_triangle(size_of_val(wide.nodes())),
        per_triangle(compact.node_bytes()),
    );

    type Wide8<'a> = meshq::wide::WideBvh<'a, meshq::advanced::WideNode8>;
    let sizes8 = Wide8::measure(&bvh);
    let mut plan8 = vec![meshq::advanced::PlanEntry::EMPTY; sizes8.plan];
    let mut nodes8 = vec![meshq::advanced::WideNode8::EMPTY; sizes8.nodes];
    let wide8 = Wide8::build(&bvh, &mut plan8, &mut nodes8).expect("wide8");
    println!(
        "eight-wide: {} nodes, {:.1} bytes per triangle",
        wide8.nodes().len(),
        per_triangle(size_of_val(wide8.nodes()))
    );
    // A batch of rays through the eight-wide tree: how many hit.
    let batch8 = |rays: &[meshq::math::Ray]| {
        let mut keys = vec![0u64; rays.len()];
        let mut out = vec![None; rays.len()];
        let options = meshq::query::RayOptions::default();
        wide8
            .with(&packed)
            .raycast_batch(rays, &options, &mut keys, &mut out)
            .expect("batch");
        out.iter().filter(|h| h.is_some()).count()
    };
    type Run<'a> = Box<dyn Fn() -> usize + 'a>;
    let variants: Vec<(&str, usize, Run<'_>)> = vec![
        (
            "rays binary packed",
            rays.len(),
            Box::new(|| {
                rays.iter()
                    .filter(|r| bvh.with(&packed).raycast(r).is_some())
                    .count()
            }),
        ),
        (
            "rays wide packed",
            rays.len(),
            Box::new(|| {
                rays.iter()
                    .filter(|r| wide.with(&packed).raycast(r).is_some())
                    .count()
            }),
        ),
        (
            // The random rays turned around: each misses the root, so this times a ray's
            // set-up and one node.
            "away wide packed",
            rays.len(),
            Box::new(|| {
                rays.iter()
                    .filter(|r| {
                        let away = meshq::math::Ray::new(r.origin, -r.dir);
                        wide.with(&packed).raycast(&away).is_some()
                    })
                    .count()
            }),
        ),
        (
            "rays wide batch",
            rays.len(),
            Box::new(|| {
                let mut keys = vec![0u64; rays.len()];
                let mut out = vec![None; rays.len()];
                let options = meshq::query::RayOptions::default();
                wide.with(&packed)
                    .raycast_batch(&rays, &options, &mut keys, &mut out)
                    .expect("batch");
                out.iter().filter(|h| h.is_some()).count()
            }),
        ),
        (
            // The owned structure's batch in one call: sorted by line key on large meshes.
            "rays owned batch whole",
            rays.len(),
            Box::new(|| owned_batch(&owned, &rays, rays.len())),
        ),
        (
            // The same in calls of 16,384 rays: too few to sort, so answered as given.
            "rays owned batch chunks",
            rays.len(),
            Box::new(|| owned_batch(&owned, &rays, 1 << 14)),
        ),
        (
            "rays eight-wide packed",
            rays.len(),
            Box::new(|| {
                rays.iter()
                    .filter(|r| wide8.with(&packed).raycast(r).is_some())
                    .count()
            }),
        ),
        (
            "camera eight-wide packed",
            camera.len(),
            Box::new(|| {
                camera
                    .iter()
                    .filter(|r| wide8.with(&packed).raycast(r).is_some())
                    .count()
            }),
        ),
        (
            "rays eight-wide batch",
            rays.len(),
            Box::new(|| batch8(&rays)),
        ),
        (
            "camera eight-wide batch",
            camera.len(),
            Box::new(|| batch8(&camera)),
        ),
        (
            "any eight-wide packed",
            rays.len(),
            Box::new(|| {
                rays.iter()
                    .filter(|r| wide8.with(&packed).raycast_any(r))
                    .count()
            }),
        ),
        (
            "camera any eight-wide packed",
            camera.len(),
            Box::new(|| {
                camera
                    .iter()
                    .filter(|r| wide8.with(&packed).raycast_any(r))
                    .count()
            }),
        ),
        (
            "closest eight-wide packed",
            points.len(),
            Box::new(|| {
                points
                    .iter()
                    .filter(|&&p| {
                        wide8
                            .with(&packed)
                            .closest_point(p, f32::INFINITY)
                            .is_some()
                    })
                    .count()
            }),
        ),
        (
            "rays compact packed",
            rays.len(),
            Box::new(|| {
                rays.iter()
                    .filter(|r| compact.with(&packed).raycast(r).is_some())
                    .count()
            }),
        ),
        (
            "camera compact packed",
            camera.len(),
            Box::new(|| {
                camera
                    .iter()
                    .filter(|r| compact.with(&packed).raycast(r).is_some())
                    .count()
            }),
        ),
        (
            "closest compact packed",
            points.len(),
            Box::new(|| {
                points
                    .iter()
                    .filter(|&&p| {
                        compact
                            .with(&packed)
                            .closest_point(p, f32::INFINITY)
                            .is_some()
                    })
                    .count()
            }),
        ),
        (
            "camera binary packed",
            camera.len(),
            Box::new(|| {
                camera
                    .iter()
                    .filter(|r| bvh.with(&packed).raycast(r).is_some())
                    .count()
            }),
        ),
        (
            "camera wide packed",
            camera.len(),
            Box::new(|| {
                camera
                    .iter()
                    .filter(|r| wide.with(&packed).raycast(r).is_some())
                    .count()
            }),
        ),
        (
            "camera wide batch",
            camera.len(),
            Box::new(|| {
                let mut keys = vec![0u64; camera.len()];
                let mut out = vec![None; camera.len()];
                let options = meshq::query::RayOptions::default();
                wide.with(&packed)
                    .raycast_batch(&camera, &options, &mut keys, &mut out)
                    .expect("batch");
                out.iter().filter(|h| h.is_some()).count()
            }),
        ),
        (
            "camera any wide packed",
            camera.len(),
            Box::new(|| {
                camera
                    .iter()
                    .filter(|r| wide.with(&packed).raycast_any(r))
                    .count()
            }),
        ),
        (
            "camera any wide batch",
            camera.len(),
            Box::new(|| {
                let mut keys = vec![0u64; camera.len()];
                let mut out = vec![false; camera.len()];
                let options = meshq::query::RayOptions::default();
                wide.with(&packed)
                    .raycast_any_batch(&camera, &options, &mut keys, &mut out)
                    .expect("batch");
                out.iter().filter(|&&h| h).count()
            }),
        ),
        (
            "any binary packed",
            rays.len(),
            Box::new(|| {
                rays.iter()
                    .filter(|r| bvh.with(&packed).raycast_any(r))
                    .count()
            }),
        ),
        (
            "any wide packed",
            rays.len(),
            Box::new(|| {
                rays.iter()
                    .filter(|r| wide.with(&packed).raycast_any(r))
                    .count()
            }),
        ),
        (
            "any wide batch",
            rays.len(),
            Box::new(|| {
                let mut keys = vec![0u64; rays.len()];
                let mut out = vec![false; rays.len()];
                let options = meshq::query::RayOptions::default();
                wide.with(&packed)
                    .raycast_any_batch(&rays, &options, &mut keys, &mut out)
                    .expect("batch");
                out.iter().filter(|&&h| h).count()
            }),
        ),
        (
            "closest binary packed",
            points.len(),
            Box::new(|| {
                points
                    .iter()
                    .filter(|&&p| bvh.with(&packed).closest_point(p, f32::INFINITY).is_some())
                    .count()
            }),
        ),
        (
            "closest wide packed",
            points.len(),
            Box::new(|| {
                points
                    .iter()
                    .filter(|&&p| wide.with(&packed).closest_point(p, f32::INFINITY).is_some())
                    .count()
            }),
        ),
        (
            "closest wide batch",
            points.len(),
            Box::new(|| {
                let mut keys = vec![0u64; points.len()];
                let mut out = vec![None; points.len()];
                wide.with(&packed)
                    .closest_points(&points, f32::INFINITY, &mut keys, &mut out)
                    .expect("batch");
                out.iter().filter(|c| c.is_some()).count()
            }),
        ),
        (
            "closest wide warm",
            points.len(),
            Box::new(|| {
                points
                    .iter()
                    .enumerate()
                    // The same 64 points over and over: their nodes and triangles stay in
                    // cache, so this is the query's cost without memory stalls.
                    .filter(|&(i, _)| {
                        let p = points[i % 64];
                        wide.with(&packed).closest_point(p, f32::INFINITY).is_some()
                    })
                    .count()
            }),
        ),
    ];
    let only = std::env::args().nth(1).unwrap_or_default();
    let variants: Vec<_> = variants
        .into_iter()
        .filter(|(name, _, _)| name.contains(only.as_str()))
        .collect();
    let mut best = vec![Duration::MAX; variants.len()];
    for _ in 0..ROUNDS {
        for ((_, _, run), best) in variants.iter().zip(&mut best) {
            let start = Instant::now();
            black_box(run());
            *best = (*best).min(start.elapsed());
        }
    }
    for ((name, n, _), best) in variants.iter().zip(&best) {
        println!("{name:24} {:8.3} M/s", *n as f64 / best.as_secs_f64() / 1e6);
    }
}
