//! meshq against obvhs (BVH2 and CWBVH), parry3d and bvh on the bunny, with the DESIGN.md
//! workloads and identical inputs for every library, in one run. Each benchmark's throughput is in elements
//! (rays or points); `scripts/bench_ratios.py` turns criterion's JSON into ratios.
//!
//! Every peer gets its best documented usage: obvhs's triangles are reordered by its primitive
//! order (no indirection), parry3d's `TriMesh` is queried in local space, and the bvh crate's
//! nearest-first iterator stops at the first box beyond the best hit.

use std::hint::black_box;
use std::time::Duration;

use criterion::{
    BenchmarkGroup, Criterion, Throughput, criterion_group, criterion_main, measurement::WallTime,
};
use glam::{Vec3, Vec3A};
use meshq::MeshBvh;
use meshq::advanced::{BvhNode, PrimRef};
use meshq::bvh::{BuildConfig, Bvh};
use meshq::math::Ray;
use meshq::query::{RayOptions, TriangleTest};
use meshq::{MeshQuery, Traverse};
use meshq_tests::{LoadedMesh, checked_bvh, load_mesh, workload};

/// Rays per random-ray iteration (the DESIGN.md set is 1,000,000; a prefix keeps criterion's
/// sampling affordable while staying far above timer resolution).
const RANDOM_RAYS: usize = 200_000;
const CAMERA: (usize, usize) = (1024, 1024);
/// The whole DESIGN.md closest-point workload: a batch's speed depends on how densely its
/// points cover the mesh, so a subset would understate it.
const CLOSEST_POINTS: usize = 100_000;

struct Scene {
    mesh: LoadedMesh,
    random: Vec<Ray>,
    camera: Vec<Ray>,
    points: Vec<Vec3>,
}

fn scene() -> Scene {
    let mesh = load_mesh("stanford-bunny");
    let random = workload::random_rays(&mesh.positions, 1_000_000, 1)[..RANDOM_RAYS].to_vec();
    let camera = workload::camera_rays(&mesh.positions, CAMERA.0, CAMERA.1);
    let points = workload::closest_points(&mesh.positions, 100_000, 2)[..CLOSEST_POINTS].to_vec();
    Scene {
        mesh,
        random,
        camera,
        points,
    }
}

fn corners(m: &LoadedMesh) -> impl Iterator<Item = [Vec3; 3]> + '_ {
    m.triangles
        .iter()
        .map(|t| t.map(|i| Vec3::from_array(m.positions[i as usize])))
}

mod obvhs_peer {
    use super::*;
    use obvhs::BvhBuildParams;
    use obvhs::bvh2::Bvh2;
    use obvhs::bvh2::builder::build_bvh2_from_tris;
    use obvhs::ray::{Ray as ORay, RayHit as OHit};
    use obvhs::triangle::Triangle as OTri;

    pub struct Peer {
        pub bvh: Bvh2,
        /// Triangles in BVH primitive order, so a leaf index needs no indirection.
        pub tris: Vec<OTri>,
        /// Mesh triangle index of each reordered triangle.
        pub original: Vec<u32>,
    }

    pub fn tris(m: &LoadedMesh) -> Vec<OTri> {
        corners(m)
            .map(|[a, b, c]| OTri {
                v0: a.into(),
                v1: b.into(),
                v2: c.into(),
            })
            .collect()
    }

    pub fn build(tris: &[OTri], params: BvhBuildParams) -> Bvh2 {
        build_bvh2_from_tris(tris, params, &mut Duration::default())
    }

    pub fn peer(m: &LoadedMesh, params: BvhBuildParams) -> Peer {
        let all = tris(m);
        let bvh = build(&all, params);
        let reordered = bvh
            .primitive_indices
            .iter()
            .map(|&i| all[i as usize])
            .collect();
        Peer {
            original: bvh.primitive_indices.clone(),
            bvh,
            tris: reordered,
        }
    }

    pub fn ray(r: &Ray) -> ORay {
        ORay::new(Vec3A::from(r.origin), Vec3A::from(r.dir), r.t_min, r.t_max)
    }

    pub fn closest_hit(p: &Peer, r: &Ray) -> Option<(f32, u32)> {
        let mut hit = OHit::none();
        p.bvh
            .ray_traverse(ray(r), &mut hit, |ray, id| p.tris[id].intersect(ray))
            .then(|| (hit.t, p.original[hit.primitive_id as usize]))
    }

    pub fn any_hit(p: &Peer, r: &Ray) -> bool {
        !p.bvh
            .ray_traverse_miss(ray(r), |ray, id| p.tris[id].intersect(ray))
    }
}

/// obvhs's compressed wide tree (CWBVH, eight children per node, quantized boxes): its
/// fastest tree for rays.
mod obvhs_cwbvh_peer {
    use super::*;
    use obvhs::BvhBuildParams;
    use obvhs::cwbvh::CwBvh;
    use obvhs::cwbvh::builder::build_cwbvh_from_tris;
    use obvhs::ray::RayHit as OHit;
    use obvhs::triangle::Triangle as OTri;

    pub struct Peer {
        pub bvh: CwBvh,
        /// Triangles in BVH primitive order.
        pub tris: Vec<OTri>,
        /// Mesh triangle index of each reordered triangle.
        pub original: Vec<u32>,
    }

    pub fn peer(m: &LoadedMesh, params: BvhBuildParams) -> Peer {
        let all = obvhs_peer::tris(m);
        let bvh = build_cwbvh_from_tris(&all, params, &mut Duration::default());
        let tris = bvh
            .primitive_indices
            .iter()
            .map(|&i| all[i as usize])
            .collect();
        Peer {
            original: bvh.primitive_indices.clone(),
            bvh,
            tris,
        }
    }

    pub fn closest_hit(p: &Peer, r: &Ray) -> Option<(f32, u32)> {
        let mut hit = OHit::none();
        p.bvh
            .ray_traverse(obvhs_peer::ray(r), &mut hit, |ray, id| {
                p.tris[id].intersect(ray)
            })
            .then(|| (hit.t, p.original[hit.primitive_id as usize]))
    }
}

mod parry_peer {
    use super::*;
    use parry3d::math::Vector;
    use parry3d::query::{PointQuery, Ray as PRay, RayCast};
    use parry3d::shape::TriMesh;

    pub fn build(m: &LoadedMesh) -> TriMesh {
        let vertices = m
            .positions
            .iter()
            .map(|p| Vector::new(p[0], p[1], p[2]))
            .collect();
        TriMesh::new(vertices, m.triangles.clone()).unwrap_or_else(|e| panic!("parry3d: {e:?}"))
    }

    pub fn closest_hit(mesh: &TriMesh, r: &Ray) -> Option<f32> {
        let ray = PRay::new(
            Vector::new(r.origin.x, r.origin.y, r.origin.z),
            Vector::new(r.dir.x, r.dir.y, r.dir.z),
        );
        mesh.cast_local_ray(&ray, f32::MAX, true)
    }

    pub fn closest_point(mesh: &TriMesh, p: Vec3) -> f32 {
        let q = mesh
            .project_local_point(Vector::new(p.x, p.y, p.z), false)
            .point;
        (Vec3::new(q.x, q.y, q.z) - p).length()
    }
}

mod bvh_peer {
    use super::*;
    use bvh::aabb::{Aabb, Bounded};
    use bvh::bounding_hierarchy::BHShape;
    use bvh::bvh::Bvh as BBvh;
    use bvh::ray::Ray as BRay;
    use nalgebra::{Point3, Vector3};

    pub struct Tri {
        corners: [Point3<f32>; 3],
        node: usize,
    }

    impl Bounded<f32, 3> for Tri {
        fn aabb(&self) -> Aabb<f32, 3> {
            let [a, b, c] = self.corners;
            Aabb::empty().grow(&a).grow(&b).grow(&c)
        }
    }

    impl BHShape<f32, 3> for Tri {
        fn set_bh_node_index(&mut self, index: usize) {
            self.node = index;
        }
        fn bh_node_index(&self) -> usize {
            self.node
        }
    }

    pub fn shapes(m: &LoadedMesh) -> Vec<Tri> {
        corners(m)
            .map(|c| Tri {
                corners: c.map(|v| Point3::new(v.x, v.y, v.z)),
                node: 0,
            })
            .collect()
    }

    pub fn build(shapes: &mut [Tri]) -> BBvh<f32, 3> {
        BBvh::build(shapes)
    }

    pub fn closest_hit(bvh: &BBvh<f32, 3>, shapes: &[Tri], r: &Ray) -> Option<f32> {
        let ray = BRay::new(
            Point3::new(r.origin.x, r.origin.y, r.origin.z),
            Vector3::new(r.dir.x, r.dir.y, r.dir.z),
        );
        let mut best = f32::INFINITY;
        for shape in bvh.nearest_traverse_iterator(&ray, shapes) {
            // Shapes come in order of their box's entry distance: stop past the best hit.
            if ray
                .intersection_slice_for_aabb(&shape.aabb())
                .is_some_and(|(entry, _)| entry > best)
            {
                break;
            }
            let [a, b, c] = &shape.corners;
            let hit = ray.intersects_triangle(a, b, c);
            best = best.min(hit.distance);
        }
        best.is_finite().then_some(best)
    }
}

fn configure(group: &mut BenchmarkGroup<'_, WallTime>, elements: usize) {
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(4));
    group.throughput(Throughput::Elements(elements as u64));
}

fn build(c: &mut Criterion) {
    let s = scene();
    let mesh = s.mesh.valid();
    let n = mesh.triangle_count();
    let mut group = c.benchmark_group("build");
    configure(&mut group, n);
    let mut nodes = vec![BvhNode::EMPTY; Bvh::measure(n, None).nodes];
    let mut order = vec![0u32; n];
    let mut scratch = vec![PrimRef::EMPTY; n];
    for (name, config) in [
        ("meshq_fast", BuildConfig::fast()),
        ("meshq_balanced", BuildConfig::balanced()),
        ("meshq_high_quality", BuildConfig::high_quality()),
    ] {
        group.bench_function(name, |b| {
            b.iter(|| {
                let bvh = Bvh::build(&mesh, &config, &mut nodes, &mut order, &mut scratch);
                black_box(bvh.map(|b| b.nodes().len()).ok());
            });
        });
    }
    let otris = obvhs_peer::tris(&s.mesh);
    for (name, params) in [
        ("obvhs_fast", obvhs::BvhBuildParams::fast_build()),
        ("obvhs_medium", obvhs::BvhBuildParams::medium_build()),
    ] {
        group.bench_function(name, |b| {
            b.iter(|| black_box(obvhs_peer::build(&otris, params).nodes.len()))
        });
    }
    group.bench_function("parry3d_trimesh", |b| {
        b.iter(|| black_box(parry_peer::build(&s.mesh)))
    });
    let mut shapes = bvh_peer::shapes(&s.mesh);
    group.bench_function("bvh_crate", |b| {
        b.iter(|| black_box(bvh_peer::build(&mut shapes)))
    });
    group.finish();
}

fn raycast(c: &mut Criterion) {
    let s = scene();
    let mesh = s.mesh.valid();
    let owned = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap_or_else(|e| panic!("{e}"));
    let bvh = checked_bvh(&owned, &mesh).unwrap_or_else(|e| panic!("{e}"));
    let mt = RayOptions {
        test: TriangleTest::MollerTrumbore,
        ..RayOptions::default()
    };
    let owned4 = owned
        .clone()
        .with_four_wide_nodes()
        .expect("four-wide nodes");
    let (packed, wide) = (owned.packed(), owned4.wide().expect("wide nodes"));
    let eight_owned = owned
        .clone()
        .with_eight_wide_nodes()
        .unwrap_or_else(|e| panic!("{e}"));
    let eight = eight_owned.eight_wide().expect("eight-wide nodes");
    let obvhs_medium = obvhs_peer::peer(&s.mesh, obvhs::BvhBuildParams::medium_build());
    let obvhs_fast = obvhs_peer::peer(&s.mesh, obvhs::BvhBuildParams::fast_build());
    let obvhs_cwbvh = obvhs_cwbvh_peer::peer(&s.mesh, obvhs::BvhBuildParams::medium_build());
    let parry = parry_peer::build(&s.mesh);
    let mut shapes = bvh_peer::shapes(&s.mesh);
    let bvh_crate = bvh_peer::build(&mut shapes);
    // The peers must answer the same question: same hits, same distances (to rounding).
    let names = ["obvhs BVH2", "obvhs CWBVH", "parry3d", "bvh"];
    let mut disagreements = [0usize; 4];
    for r in &s.random {
        let ours = bvh.with(&mesh).raycast(r).map(|h| h.t);
        let theirs = [
            obvhs_peer::closest_hit(&obvhs_medium, r).map(|h| h.0),
            obvhs_cwbvh_peer::closest_hit(&obvhs_cwbvh, r).map(|h| h.0),
            parry_peer::closest_hit(&parry, r),
            bvh_peer::closest_hit(&bvh_crate, &shapes, r),
        ];
        let agree = |t: Option<f32>| match (ours, t) {
            (Some(a), Some(b)) => (a - b).abs() <= 1e-4 * a.max(1.0),
            (None, None) => true,
            _ => false,
        };
        for (count, t) in disagreements.iter_mut().zip(theirs) {
            *count += usize::from(!agree(t));
        }
    }
    let listed: Vec<String> = names
        .iter()
        .zip(disagreements)
        .map(|(name, n)| format!("{name} {n}"))
        .collect();
    eprintln!(
        "peer disagreements on {} random rays: {}",
        s.random.len(),
        listed.join(", ")
    );
    for (group_name, rays) in [("raycast_random", &s.random), ("raycast_camera", &s.camera)] {
        let mut group = c.benchmark_group(group_name);
        configure(&mut group, rays.len());
        group.bench_function("meshq_watertight", |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| bvh.with(&mesh).raycast(r).is_some())
                    .count()
            })
        });
        group.bench_function("meshq_moller_trumbore", |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| bvh.with(&mesh).raycast_with(r, &mt).is_some())
                    .count()
            })
        });
        group.bench_function("meshq_packed_watertight", |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| bvh.with(&packed).raycast(r).is_some())
                    .count()
            })
        });
        group.bench_function("meshq_packed_moller_trumbore", |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| bvh.with(&packed).raycast_with(r, &mt).is_some())
                    .count()
            })
        });
        group.bench_function("meshq_wide_watertight", |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| wide.with(&mesh).raycast(r).is_some())
                    .count()
            })
        });
        group.bench_function("meshq_wide_packed_watertight", |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| wide.with(&packed).raycast(r).is_some())
                    .count()
            })
        });
        group.bench_function("meshq_eight_wide_packed_watertight", |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| eight.with(&packed).raycast(r).is_some())
                    .count()
            })
        });
        group.bench_function("obvhs_medium", |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| obvhs_peer::closest_hit(&obvhs_medium, r).is_some())
                    .count()
            })
        });
        group.bench_function("obvhs_fast", |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| obvhs_peer::closest_hit(&obvhs_fast, r).is_some())
                    .count()
            })
        });
        group.bench_function("obvhs_cwbvh_medium", |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| obvhs_cwbvh_peer::closest_hit(&obvhs_cwbvh, r).is_some())
                    .count()
            })
        });
        group.bench_function("parry3d", |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| parry_peer::closest_hit(&parry, r).is_some())
                    .count()
            })
        });
        group.bench_function("bvh_crate", |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| bvh_peer::closest_hit(&bvh_crate, &shapes, r).is_some())
                    .count()
            })
        });
        group.finish();
    }
    let mut group = c.benchmark_group("raycast_any_random");
    configure(&mut group, s.random.len());
    group.bench_function("meshq_watertight", |b| {
        b.iter(|| {
            s.random
                .iter()
                .filter(|r| bvh.with(&mesh).raycast_any(r))
                .count()
        })
    });
    group.bench_function("meshq_packed_watertight", |b| {
        b.iter(|| {
            s.random
                .iter()
                .filter(|r| bvh.with(&packed).raycast_any(r))
                .count()
        })
    });
    group.bench_function("meshq_wide_watertight", |b| {
        b.iter(|| {
            s.random
                .iter()
                .filter(|r| wide.with(&mesh).raycast_any(r))
                .count()
        })
    });
    group.bench_function("meshq_wide_packed_watertight", |b| {
        b.iter(|| {
            s.random
                .iter()
                .filter(|r| wide.with(&packed).raycast_any(r))
                .count()
        })
    });
    group.bench_function("obvhs_medium", |b| {
        b.iter(|| {
            s.random
                .iter()
                .filter(|r| obvhs_peer::any_hit(&obvhs_medium, r))
                .count()
        })
    });
    group.finish();
}

fn closest_point(c: &mut Criterion) {
    let s = scene();
    let mesh = s.mesh.valid();
    let owned = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap_or_else(|e| panic!("{e}"));
    let bvh = checked_bvh(&owned, &mesh).unwrap_or_else(|e| panic!("{e}"));
    let parry = parry_peer::build(&s.mesh);
    let owned4 = owned
        .clone()
        .with_four_wide_nodes()
        .expect("four-wide nodes");
    let (packed, wide) = (owned.packed(), owned4.wide().expect("wide nodes"));
    // The tree `MeshBvh` walks on SIMD targets.
    let eight_owned = owned
        .clone()
        .with_eight_wide_nodes()
        .unwrap_or_else(|e| panic!("{e}"));
    let eight = eight_owned.eight_wide().expect("eight-wide nodes");
    let mut group = c.benchmark_group("closest_point");
    configure(&mut group, s.points.len());
    group.bench_function("meshq", |b| {
        b.iter(|| {
            s.points
                .iter()
                .map(|&p| {
                    bvh.with(&mesh)
                        .closest_point(p, f32::INFINITY)
                        .map_or(0.0, |c| c.distance_squared)
                })
                .sum::<f32>()
        })
    });
    group.bench_function("meshq_packed", |b| {
        b.iter(|| {
            s.points
                .iter()
                .map(|&p| {
                    bvh.with(&packed)
                        .closest_point(p, f32::INFINITY)
                        .map_or(0.0, |c| c.distance_squared)
                })
                .sum::<f32>()
        })
    });
    group.bench_function("meshq_wide_packed", |b| {
        b.iter(|| {
            s.points
                .iter()
                .map(|&p| {
                    wide.with(&packed)
                        .closest_point(p, f32::INFINITY)
                        .map_or(0.0, |c| c.distance_squared)
                })
                .sum::<f32>()
        })
    });
    // The batch call, buffers included: the same answers, in Morton order with seeded searches.
    group.bench_function("meshq_wide_packed_batch", |b| {
        b.iter(|| {
            let mut keys = vec![0u64; s.points.len()];
            let mut out = vec![None; s.points.len()];
            wide.with(&packed)
                .closest_points(&s.points, f32::INFINITY, &mut keys, &mut out)
                .unwrap_or_else(|e| panic!("{e}"));
            out.iter()
                .map(|c| c.map_or(0.0, |c| c.distance_squared))
                .sum::<f32>()
        })
    });
    group.bench_function("meshq_eight_wide_packed", |b| {
        b.iter(|| {
            s.points
                .iter()
                .map(|&p| {
                    eight
                        .with(&packed)
                        .closest_point(p, f32::INFINITY)
                        .map_or(0.0, |c| c.distance_squared)
                })
                .sum::<f32>()
        })
    });
    group.bench_function("meshq_eight_wide_packed_batch", |b| {
        b.iter(|| {
            let mut keys = vec![0u64; s.points.len()];
            let mut out = vec![None; s.points.len()];
            eight
                .with(&packed)
                .closest_points(&s.points, f32::INFINITY, &mut keys, &mut out)
                .unwrap_or_else(|e| panic!("{e}"));
            out.iter()
                .map(|c| c.map_or(0.0, |c| c.distance_squared))
                .sum::<f32>()
        })
    });
    group.bench_function("parry3d", |b| {
        b.iter(|| {
            s.points
                .iter()
                .map(|&p| parry_peer::closest_point(&parry, p))
                .sum::<f32>()
        })
    });
    group.finish();
}

criterion_group!(benches, build, raycast, closest_point);
criterion_main!(benches);
