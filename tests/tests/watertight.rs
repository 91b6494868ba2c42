//! Rays from points inside the closed meshes (spot, cow) must all hit with the watertight
//! test; Möller–Trumbore's leaks are counted and reported.

use std::collections::HashMap;

use glam::Vec3;
use meshq::MeshBvh;
use meshq::bvh::BuildConfig;
use meshq::geom::{CullMode, intersect_ray_triangle_watertight};
use meshq::math::{Ray, Triangle};
use meshq::query::{RayOptions, TriangleTest};
use meshq::{MeshQuery, Traverse};
use meshq_tests::{LoadedMesh, SplitMix64, checked_bvh, load_mesh, workload};

const INSIDE_POINTS: usize = 50;
const RAYS_PER_POINT: usize = 20_000;

/// Every undirected edge is shared by exactly two triangles.
fn assert_closed(m: &LoadedMesh) {
    let mut edges: HashMap<(u32, u32), u32> = HashMap::new();
    for t in &m.triangles {
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            *edges.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    let open = edges.values().filter(|&&n| n != 2).count();
    assert_eq!(
        open, 0,
        "{}: {open} edges not shared by exactly two triangles",
        m.name
    );
}

/// Inside by parity: the number of crossings along three unrelated directions is odd for all
/// three (a brute-force count, independent of any tree).
fn is_inside(tris: &[Triangle], p: Vec3, rng: &mut SplitMix64) -> bool {
    (0..3).all(|_| {
        let ray = Ray::new(p, workload::unit_sphere(rng));
        let crossings = tris
            .iter()
            .filter(|t| intersect_ray_triangle_watertight(&ray, t, CullMode::None).is_some())
            .count();
        crossings % 2 == 1
    })
}

fn run(name: &str) -> (usize, usize) {
    let loaded = load_mesh(name);
    assert_closed(&loaded);
    let mesh = loaded.valid();
    let tris: Vec<Triangle> = (0..mesh.triangle_count() as u32)
        .map(|i| mesh.triangle(i).unwrap())
        .collect();
    let owned = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
    let bvh = checked_bvh(&owned, &mesh).unwrap();
    let (_, _, bounds) = workload::centre_radius(&loaded.positions);
    let mut rng = SplitMix64::new(0x1A51DE);
    let mut inside = Vec::new();
    while inside.len() < INSIDE_POINTS {
        let p = workload::point_in_box(&mut rng, &bounds);
        if is_inside(&tris, p, &mut rng) {
            inside.push(p);
        }
    }
    let mt = RayOptions {
        test: TriangleTest::MollerTrumbore,
        cull: CullMode::None,
    };
    let (mut rays, mut mt_misses) = (0, 0);
    for &p in &inside {
        for k in 0..RAYS_PER_POINT {
            // Half the rays go in random directions; the rest aim exactly at a vertex or at a
            // point on an edge, where a non-watertight test lets rays slip between neighbours.
            let t = &loaded.triangles[rng.below(loaded.triangles.len() as u64) as usize];
            let [a, b] = [t[0], t[1]].map(|i| Vec3::from_array(loaded.positions[i as usize]));
            let dir = match k % 4 {
                0 | 1 => workload::unit_sphere(&mut rng),
                2 => a - p,
                _ => a.lerp(b, rng.next_f32()) - p,
            };
            let ray = Ray::new(p, dir);
            assert!(
                bvh.with(&mesh).raycast(&ray).is_some(),
                "{name}: watertight leak for {ray:?}"
            );
            assert!(
                bvh.with(&mesh).raycast_any(&ray),
                "{name}: watertight any-hit leak for {ray:?}"
            );
            mt_misses += usize::from(bvh.with(&mesh).raycast_with(&ray, &mt).is_none());
            rays += 1;
        }
    }
    eprintln!(
        "{name}: {rays} rays from inside, watertight misses 0, Möller–Trumbore misses {mt_misses}"
    );
    (rays, mt_misses)
}

#[test]
fn spot_is_watertight_from_inside() {
    let (rays, _) = run("spot");
    assert!(rays >= 1_000_000);
}

#[test]
fn cow_is_watertight_from_inside() {
    let (rays, _) = run("cow");
    assert!(rays >= 1_000_000);
}
