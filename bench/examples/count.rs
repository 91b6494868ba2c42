//! Profiling aid: boxes and triangles tested per random ray, meshq vs obvhs.
use meshq::bvh::{BuildConfig, BvhNode, BvhVisitor};
use meshq::geom::{CullMode, intersect_ray_aabb, intersect_ray_triangle_watertight};
use meshq::math::Ray;
use meshq::mesh::ValidMesh;
use meshq_tests::{OwnedBvh, load_mesh, workload};
use std::ops::ControlFlow;
struct C<'m> {
    mesh: &'m ValidMesh<'m>,
    ray: Ray,
    best: f32,
    boxes: usize,
    tris: usize,
}
impl BvhVisitor for C<'_> {
    fn enter(&mut self, n: &BvhNode) -> Option<f32> {
        self.boxes += 1;
        intersect_ray_aabb(&self.ray.with_range(0.0, self.best), &n.aabb()).map(|(e, _)| e)
    }
    fn revisit(&self, k: f32) -> bool {
        k <= self.best
    }
    fn leaf(&mut self, _: usize, tris: &[u32]) -> ControlFlow<()> {
        for &t in tris {
            self.tris += 1;
            if let Some(h) = intersect_ray_triangle_watertight(
                &self.ray.with_range(0.0, self.best),
                &self.mesh.triangle(t).unwrap(),
                CullMode::None,
            ) {
                self.best = h.t;
            }
        }
        ControlFlow::Continue(())
    }
}
fn main() {
    let l = load_mesh("stanford-bunny");
    let mesh = l.valid();
    let o = OwnedBvh::build(&mesh, &BuildConfig::default()).unwrap();
    let bvh = o.view(&mesh).unwrap();
    let rays = workload::random_rays(&l.positions, 100_000, 1);
    let (mut b, mut t) = (0, 0);
    for r in &rays {
        let mut v = C {
            mesh: &mesh,
            ray: *r,
            best: f32::INFINITY,
            boxes: 0,
            tris: 0,
        };
        bvh.traverse(&mut v);
        b += v.boxes;
        t += v.tris;
    }
    println!(
        "meshq: boxes/ray {:.1} tris/ray {:.1}",
        b as f64 / 1e5,
        t as f64 / 1e5
    );
    let otris: Vec<obvhs::triangle::Triangle> = l
        .triangles
        .iter()
        .map(|t| {
            let p = |i: u32| glam::Vec3A::from_array(l.positions[i as usize]);
            obvhs::triangle::Triangle {
                v0: p(t[0]),
                v1: p(t[1]),
                v2: p(t[2]),
            }
        })
        .collect();
    for (name, params) in [
        ("fast", obvhs::BvhBuildParams::fast_build()),
        ("medium", obvhs::BvhBuildParams::medium_build()),
    ] {
        let ob = obvhs::bvh2::builder::build_bvh2_from_tris(
            &otris,
            params,
            &mut std::time::Duration::default(),
        );
        let mut t = 0;
        for r in &rays {
            let mut hit = obvhs::ray::RayHit::none();
            ob.ray_traverse(
                obvhs::ray::Ray::new(r.origin.into(), r.dir.into(), 0.0, f32::INFINITY),
                &mut hit,
                |ray, id| {
                    t += 1;
                    otris[ob.primitive_indices[id] as usize].intersect(ray)
                },
            );
        }
        let leaves = ob.nodes.iter().filter(|n| n.is_leaf()).count();
        println!(
            "obvhs {name}: nodes {} tris/leaf {:.2} tris/ray {:.1}",
            ob.nodes.len(),
            l.triangles.len() as f64 / leaves as f64,
            t as f64 / 1e5
        );
    }
}
