//! Quantized wide nodes (`CompactNode`, `WideBvh<CompactNode>`, `MeshBvh::with_compact_nodes`): each
//! decoded box holds the box it was made from and is the tightest the 8-bit grid allows, the
//! tree keeps the wide tree's shape, and every query answers as a brute-force scan does.

use std::ops::ControlFlow;

use meshq::MeshBvh;
use meshq::advanced::Aabb4;
use meshq::advanced::{CompactNode, WideNode};
use meshq::bvh::BuildConfig;
use meshq::math::{Aabb, Vec3};
use meshq::query::{MeshQuery, RayOptions, Traverse};
use meshq::wide::WideBvh;
use meshq_tests::oracle::BruteForce;
use meshq_tests::{MESHES, load_mesh, workload};

/// Lane `lane` of `boxes` as an `Aabb`.
fn lane(boxes: &Aabb4, lane: usize) -> Aabb {
    boxes.lane(lane)
}

/// Checks one quantized node against the wide node it came from.
fn check_node(wide: &WideNode, compact: &CompactNode, what: &str) {
    let decoded = compact.boxes();
    let used = wide.lanes();
    for l in 0..4 {
        assert_eq!(compact.child(l), wide.child[l], "{what}: lane {l} child");
        assert_eq!(compact.count(l), wide.count[l], "{what}: lane {l} count");
        let (exact, got) = (lane(&wide.bounds, l), lane(&decoded, l));
        if l >= used {
            assert!(
                got.min.x > got.max.x,
                "{what}: unused lane {l} decodes {got:?}"
            );
            continue;
        }
        assert!(
            got.contains_aabb(&exact),
            "{what}: lane {l}: {got:?} misses {exact:?}"
        );
        // Tight: one step less on any side would cut into the exact box (or leave the
        // node's origin).
        for axis in 0..3 {
            let step = f32::from_bits(((i32::from(compact.exponent[axis]) + 127) as u32) << 23);
            let origin = f32::from_bits(compact.origin[axis]);
            let lo = compact.lo[axis][l];
            let hi = compact.hi[axis][l];
            if lo < u8::MAX {
                let next = origin + f32::from(lo + 1) * step;
                assert!(
                    next > exact.min[axis],
                    "{what}: lane {l} axis {axis} min not tight"
                );
            }
            if hi > 0 {
                let prev = origin + f32::from(hi - 1) * step;
                assert!(
                    prev < exact.max[axis],
                    "{what}: lane {l} axis {axis} max not tight"
                );
            }
        }
    }
}

#[test]
fn every_node_holds_its_boxes_tightly_on_every_mesh() {
    for name in MESHES {
        let loaded = load_mesh(name);
        let owned = MeshBvh::build(&loaded.valid(), &BuildConfig::default())
            .unwrap()
            .with_four_wide_nodes()
            .unwrap();
        let wide = owned.wide().unwrap();
        let mut storage = vec![CompactNode::EMPTY; wide.nodes().len()];
        let compact = WideBvh::quantize(&wide, &mut storage).unwrap();
        assert_eq!(compact.nodes().len(), wide.nodes().len());
        for (i, (w, c)) in wide.nodes().iter().zip(compact.nodes()).enumerate() {
            check_node(w, c, &format!("{name} node {i}"));
        }
        assert!(compact.bounds().contains_aabb(&wide.bounds()));
        // The quantized option's budget: at most 12 bytes of nodes per triangle.
        let per_triangle = compact.node_bytes() as f64 / loaded.triangles.len() as f64;
        assert!(
            per_triangle <= 12.0,
            "{name}: {per_triangle:.2} bytes per triangle"
        );
        let owned_compact = owned.clone().with_compact_nodes().unwrap();
        assert_eq!(owned_compact.query_node_bytes(), compact.node_bytes());
        assert!(owned_compact.wide().is_none());
        assert_eq!(owned_compact.compact().unwrap().nodes(), compact.nodes());
    }
}

#[test]
fn extreme_boxes_quantize_outward() {
    let boxes = [
        Aabb::new(Vec3::splat(-1e30), Vec3::splat(3e30)),
        Aabb::new(Vec3::new(1e-30, -2e-30, 0.0), Vec3::new(3e-30, -1e-30, 0.0)),
        Aabb::new(Vec3::splat(16_777_215.0), Vec3::splat(16_777_217.0)),
        Aabb::new(Vec3::new(0.1, 0.2, 0.3), Vec3::new(0.1, 0.2, 0.3)),
        Aabb::new(Vec3::splat(-3.0e38), Vec3::splat(3.0e38)),
        Aabb::new(
            Vec3::new(-7.0, 1.0, 2.0),
            Vec3::new(-6.999_999, 1.000_001, 1e20),
        ),
    ];
    for (i, a) in boxes.iter().enumerate() {
        for (j, b) in boxes.iter().enumerate() {
            let mut node = WideNode::EMPTY;
            node.bounds.set_lane(0, a);
            node.bounds.set_lane(1, b);
            node.child = [1, 2, 0, 0];
            node.count = [0, 3, 0, 0];
            let compact = CompactNode::quantize(&node).unwrap();
            check_node(&node, &compact, &format!("boxes {i} and {j}"));
        }
    }
    let mut too_big = WideNode::EMPTY;
    too_big.bounds.set_lane(0, &boxes[0]);
    too_big.count[0] = 256;
    assert!(CompactNode::quantize(&too_big).is_none());
}

#[test]
fn compact_queries_match_brute_force() {
    for name in ["spot", "fandisk", "stanford-bunny"] {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        let brute = BruteForce::new(&mesh);
        let owned = MeshBvh::build(&mesh, &BuildConfig::default())
            .unwrap()
            .with_compact_nodes()
            .unwrap();
        let view = owned.compact().unwrap();
        let packed = owned.packed();
        let options = RayOptions::default();
        let bits = |h: Option<meshq::math::RayHit>| {
            h.map(|h| (h.t.to_bits(), h.tri, h.u.to_bits(), h.v.to_bits()))
        };
        let mut rays = workload::random_rays(&loaded.positions, 20_000, 41);
        rays.extend(workload::camera_rays(&loaded.positions, 64, 48));
        for (i, ray) in rays.iter().enumerate() {
            let want = brute.raycast(ray, &options);
            assert_eq!(bits(owned.raycast(ray)), bits(want), "{name} ray {i}");
            assert_eq!(
                bits(view.with(&packed).raycast(ray)),
                bits(want),
                "{name} ray {i}"
            );
            assert_eq!(owned.raycast_any(ray), want.is_some(), "{name} any {i}");
        }
        let mut keys = vec![0u64; rays.len()];
        let mut out = vec![None; rays.len()];
        owned
            .raycast_batch(&rays, &options, &mut keys, &mut out)
            .unwrap();
        for (i, (ray, got)) in rays.iter().zip(&out).enumerate() {
            assert_eq!(
                bits(*got),
                bits(brute.raycast(ray, &options)),
                "{name} batch {i}"
            );
        }
        for (i, p) in workload::closest_points(&loaded.positions, 3_000, 42)
            .into_iter()
            .enumerate()
        {
            let want = brute.closest_point(p, f32::INFINITY);
            let got = owned.closest_point(p, f32::INFINITY);
            assert_eq!(
                got.map(|c| (c.distance_squared.to_bits(), c.tri)),
                want.map(|c| (c.distance_squared.to_bits(), c.tri)),
                "{name} point {i}"
            );
        }
        let (c, r, _) = workload::centre_radius(&loaded.positions);
        let query = Aabb::new(c - Vec3::splat(0.3 * r), c + Vec3::splat(0.2 * r));
        let mut found = Vec::new();
        owned.overlap_aabb(&query, |t| {
            found.push(t);
            ControlFlow::Continue(())
        });
        found.sort_unstable();
        assert_eq!(found, brute.overlap_aabb(&query), "{name} box overlap");
    }
}
