//! One suite over every structure: the query layer gives each of them — the binary BVH, its
//! four-wide collapse, blob views and blob trees, the owned `MeshBvh`, and two structures written
//! here on the public `Traverse` trait alone — every query, single and batched, with exactly
//! the answers of a brute-force scan over all triangles (same `t` bits, same triangle under the
//! tie rule, same overlap sets).

use std::ops::ControlFlow;

use meshq::advanced::LeafTriangleIds;
use meshq::blob::{BlobTree, BlobView, MeshLayout};
use meshq::bvh::BuildConfig;
use meshq::geom::intersect_ray_aabb;
use meshq::math::Aabb;
use meshq::mesh::ValidMesh;
use meshq::query::{RayOptions, Visitor};
use meshq::{MeshBvh, MeshQuery, Traverse};
use meshq_tests::oracle::BruteForce;
use meshq_tests::suite::check_all;
use meshq_tests::{MESHES, checked_bvh, load_mesh, workload};

/// The smallest structure: one leaf holding every triangle, behind the mesh's bounds.
struct Scan<'a> {
    order: &'a [u32],
    bounds: Aabb,
}

impl Traverse for Scan<'_> {
    fn traverse<V: Visitor + ?Sized>(&self, visitor: &mut V) {
        if visitor.enter(&self.bounds).is_some() {
            let _ = visitor.leaf(LeafTriangleIds::new(0, self.order));
        }
    }
}

/// A structure that walks cells along the ray, as a grid or a k-d tree does: one cell per
/// triangle (its bounds), visited in order of the ray's entry `t`, stopping at the first cell
/// whose entry fails `revisit`. Without a ray it offers every cell through `enter`.
struct RayOrderedCells<'a> {
    mesh: ValidMesh<'a>,
    order: &'a [u32],
    visited: std::cell::Cell<usize>,
}

impl Traverse for RayOrderedCells<'_> {
    fn traverse<V: Visitor + ?Sized>(&self, visitor: &mut V) {
        let cell = |slot: usize| {
            let tri = self.order[slot];
            (tri, self.mesh.triangle(tri).unwrap().bounds().padded())
        };
        let Some(ray) = visitor.ray().copied() else {
            for slot in 0..self.order.len() {
                let (_, b) = cell(slot);
                if visitor.enter(&b).is_some()
                    && visitor
                        .leaf(LeafTriangleIds::new(slot, &self.order[slot..=slot]))
                        .is_break()
                {
                    return;
                }
            }
            return;
        };
        let mut entries: Vec<(f32, usize)> = (0..self.order.len())
            .filter_map(|slot| intersect_ray_aabb(&ray, &cell(slot).1).map(|(t, _)| (t, slot)))
            .collect();
        entries.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        for (t, slot) in entries {
            if !visitor.revisit(t) {
                return;
            }
            self.visited.set(self.visited.get() + 1);
            if visitor
                .leaf(LeafTriangleIds::new(slot, &self.order[slot..=slot]))
                .is_break()
            {
                return;
            }
        }
    }
}

#[test]
fn every_structure_answers_every_query_as_brute_force() {
    for name in MESHES {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        let brute = BruteForce::new(&mesh);
        let scene = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
        let bvh = checked_bvh(&scene, &mesh).unwrap();
        let four = scene.clone().with_four_wide_nodes().unwrap();
        let (wide, packed) = (four.wide().unwrap(), scene.packed());
        check_all(&scene, &brute, &loaded, &format!("{name} MeshBvh"));
        check_all(
            &bvh.with(&mesh),
            &brute,
            &loaded,
            &format!("{name} bvh+mesh"),
        );
        check_all(
            &wide.with(&packed),
            &brute,
            &loaded,
            &format!("{name} wide+packed"),
        );
        check_all(
            &wide.with(&mesh),
            &brute,
            &loaded,
            &format!("{name} wide+mesh"),
        );
        for layout in [MeshLayout::Indexed, MeshLayout::Packed] {
            let bytes = scene.to_blob(layout).unwrap();
            let view = BlobView::parse(&bytes).unwrap();
            check_all(&view, &brute, &loaded, &format!("{name} blob {layout:?}"));
            let loaded_back = MeshBvh::from_blob(&bytes).unwrap();
            check_all(
                &loaded_back,
                &brute,
                &loaded,
                &format!("{name} from_blob {layout:?}"),
            );
        }
        let bytes = scene.to_blob(MeshLayout::Omitted).unwrap();
        let (_, tree) = BlobTree::parse(&bytes).unwrap();
        check_all(
            &tree.with(&mesh),
            &brute,
            &loaded,
            &format!("{name} blob tree"),
        );
        let scan = Scan {
            order: bvh.order(),
            bounds: mesh.bounds(),
        };
        check_all(&scan.with(&mesh), &brute, &loaded, &format!("{name} scan"));
    }
}

/// A structure that walks cells along the ray and stops where `revisit` says: the layer's ray
/// keys are ray parameters, so stopping there loses no hit, and it does stop early.
#[test]
fn ray_ordered_structures_stop_early_and_lose_nothing() {
    let loaded = load_mesh("spot");
    let mesh = loaded.valid();
    let brute = BruteForce::new(&mesh);
    let order: Vec<u32> = (0..mesh.triangle_count() as u32).collect();
    let cells = RayOrderedCells {
        mesh,
        order: &order,
        visited: std::cell::Cell::new(0),
    };
    let rays = workload::random_rays(&loaded.positions, 300, 9);
    let mut possible = 0;
    for ray in &rays {
        let want = brute.raycast(ray, &RayOptions::default());
        assert_eq!(cells.with(&mesh).raycast(ray), want);
        possible += order
            .iter()
            .filter(|&&t| {
                let b = mesh.triangle(t).unwrap().bounds().padded();
                intersect_ray_aabb(ray, &b).is_some()
            })
            .count();
    }
    let visited = cells.visited.get();
    assert!(
        visited * 2 < possible,
        "visited {visited} of {possible} cells on the rays"
    );
    check_all(&cells.with(&mesh), &brute, &loaded, "ray-ordered cells");
}

/// A custom visitor reaches every triangle of every structure exactly once when it enters
/// every box.
#[test]
fn custom_visitors_see_every_triangle_once() {
    struct Everything(Vec<u32>);
    impl Visitor for Everything {
        fn enter(&mut self, _: &Aabb) -> Option<f32> {
            Some(0.0)
        }
        fn leaf(&mut self, tris: LeafTriangleIds<'_>) -> ControlFlow<()> {
            self.0.extend(tris.map(|(_, t)| t));
            ControlFlow::Continue(())
        }
    }
    let loaded = load_mesh("cow");
    let mesh = loaded.valid();
    let scene = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
    let bytes = scene.to_blob(MeshLayout::Indexed).unwrap();
    let view = BlobView::parse(&bytes).unwrap();
    let all: Vec<u32> = (0..mesh.triangle_count() as u32).collect();
    let mut runs: Vec<(&str, Vec<u32>)> = Vec::new();
    let mut v = Everything(Vec::new());
    scene.traverse(&mut v);
    runs.push(("MeshBvh", v.0));
    let mut v = Everything(Vec::new());
    scene.bvh().traverse(&mut v);
    runs.push(("bvh", v.0));
    let mut v = Everything(Vec::new());
    view.traverse(&mut v);
    runs.push(("blob view", v.0));
    let mut v = Everything(Vec::new());
    let dynamic: &mut dyn Visitor = &mut v;
    let four = scene.clone().with_four_wide_nodes().unwrap();
    four.wide().unwrap().traverse(dynamic);
    runs.push(("wide, dyn visitor", v.0));
    for (what, mut seen) in runs {
        seen.sort_unstable();
        assert_eq!(seen, all, "{what}");
    }
}
