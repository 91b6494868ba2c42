//! One suite over every structure: the query layer gives each of them — the binary BVH, its
//! four-wide collapse, blob views and blob trees, the owned `MeshBvh`, and two structures written
//! here on the public `Traverse` trait alone — every query, single and batched, with exactly
//! the answers of a brute-force scan over all triangles (same `t` bits, same triangle under the
//! tie rule, same overlap sets).

use std::ops::ControlFlow;

use meshq::blob::{BlobTree, BlobView, MeshLayout};
use meshq::bvh::BuildConfig;
use meshq::geom::{CullMode, intersect_ray_aabb};
use meshq::math::{Aabb, Vec3};
use meshq::mesh::ValidMesh;
use meshq::query::{LeafTriangleIds, RayOptions, TriangleTest, Visitor};
use meshq::{MeshBvh, MeshQuery, Traverse};
use meshq_tests::oracle::BruteForce;
use meshq_tests::{LoadedMesh, MESHES, checked_bvh, load_mesh, workload};

const RAYS: usize = 400;
const POINTS: usize = 150;
const OVERLAPS: usize = 12;

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

/// Every query of `q` against the brute-force scan.
fn check_all<Q: MeshQuery + ?Sized>(q: &Q, brute: &BruteForce, loaded: &LoadedMesh, what: &str) {
    let rays = workload::random_rays(&loaded.positions, RAYS, 5);
    let bits = |h: Option<meshq::math::RayHit>| {
        h.map(|h| (h.t.to_bits(), h.tri, h.u.to_bits(), h.v.to_bits()))
    };
    let options = [
        RayOptions::default(),
        RayOptions {
            test: TriangleTest::MollerTrumbore,
            cull: CullMode::Back,
        },
    ];
    for o in &options {
        for (i, ray) in rays.iter().enumerate() {
            let want = brute.raycast(ray, o);
            assert_eq!(
                bits(q.raycast_with(ray, o)),
                bits(want),
                "{what}: ray {i} {o:?}"
            );
            assert_eq!(
                q.raycast_any_with(ray, o),
                want.is_some(),
                "{what}: any {i}"
            );
        }
        let mut keys = vec![0u64; rays.len()];
        let mut hits = vec![None; rays.len()];
        q.raycast_batch(&rays, o, &mut keys, &mut hits).unwrap();
        let want: Vec<_> = rays.iter().map(|r| bits(brute.raycast(r, o))).collect();
        assert_eq!(
            hits.into_iter().map(bits).collect::<Vec<_>>(),
            want,
            "{what}: batch"
        );
        let mut any = vec![false; rays.len()];
        q.raycast_any_batch(&rays, o, &mut keys, &mut any).unwrap();
        let want: Vec<_> = want.iter().map(Option::is_some).collect();
        assert_eq!(any, want, "{what}: any batch");
    }
    for (i, r) in rays.iter().take(50).enumerate() {
        assert_eq!(
            bits(q.raycast(r)),
            bits(brute.raycast(r, &RayOptions::default()))
        );
        assert_eq!(
            q.raycast_any(r),
            brute.raycast(r, &RayOptions::default()).is_some(),
            "{i}"
        );
    }

    let (c, radius, _) = workload::centre_radius(&loaded.positions);
    let points = workload::closest_points(&loaded.positions, POINTS, 6);
    let key = |p: Option<meshq::math::ClosestPoint>| {
        p.map(|p| {
            (
                p.distance_squared.to_bits(),
                p.tri,
                p.point.to_array().map(f32::to_bits),
            )
        })
    };
    for max in [f32::INFINITY, 0.05 * radius] {
        let want: Vec<_> = points
            .iter()
            .map(|&p| key(brute.closest_point(p, max)))
            .collect();
        let got: Vec<_> = points
            .iter()
            .map(|&p| key(q.closest_point(p, max)))
            .collect();
        assert_eq!(got, want, "{what}: closest point, max {max}");
        let mut keys = vec![0u64; points.len()];
        let mut out = vec![None; points.len()];
        q.closest_points(&points, max, &mut keys, &mut out).unwrap();
        assert_eq!(
            out.into_iter().map(key).collect::<Vec<_>>(),
            want,
            "{what}: batch"
        );
    }

    for (i, p) in workload::closest_points(&loaded.positions, OVERLAPS, 7)
        .into_iter()
        .enumerate()
    {
        let half = Vec3::splat(radius * 0.02 * (1 + i % 4) as f32);
        let aabb = Aabb::new(p - half, p + half);
        let mut want = brute.overlap_aabb(&aabb);
        want.sort_unstable();
        let mut out = vec![0u32; want.len() + 3];
        let count = q.overlap_aabb_into(&aabb, &mut out);
        assert!(count.is_complete(), "{what}: box {i}");
        let mut got = out[..count.written].to_vec();
        got.sort_unstable();
        assert_eq!(got, want, "{what}: box {i}");

        let r = radius * 0.03 * (1 + i % 3) as f32;
        let mut want = brute.overlap_sphere(p, r);
        want.sort_unstable();
        let mut got = Vec::new();
        q.overlap_sphere(p, r, |t| {
            got.push(t);
            ControlFlow::Continue(())
        });
        got.sort_unstable();
        assert_eq!(got, want, "{what}: sphere {i}");
        // A report that breaks stops the query.
        let mut seen = 0;
        q.overlap_sphere(p, r, |_| {
            seen += 1;
            ControlFlow::Break(())
        });
        assert_eq!(seen, usize::from(!want.is_empty()), "{what}: break {i}");
    }
    let _ = c;
}

#[test]
fn every_structure_answers_every_query_as_brute_force() {
    for name in MESHES {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        let brute = BruteForce::new(&mesh);
        let scene = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
        let bvh = checked_bvh(&scene, &mesh).unwrap();
        let (wide, packed) = (scene.wide(), scene.packed());
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
    scene.wide().traverse(dynamic);
    runs.push(("wide, dyn visitor", v.0));
    for (what, mut seen) in runs {
        seen.sort_unstable();
        assert_eq!(seen, all, "{what}");
    }
}
