//! Arbitrary bytes as a blob: parsing must return `Err` or a view whose every query returns
//! without panicking. The first input byte picks the mode: odd means "recompute the checksum
//! first", so the fuzzer also explores the validation behind the checksum.
#![no_main]

use core::ops::ControlFlow;

use libfuzzer_sys::fuzz_target;
use meshq::advanced::BlobHeader;
use meshq::advanced::BvhNode;
use meshq::advanced::PackedTriangle;
use meshq::blob::BlobView;
use meshq::math::{Aabb, Ray, Vec3};
use meshq::{MeshBvh, MeshQuery, Traverse};

fuzz_target!(|data: &[u8]| {
    let Some((&mode, rest)) = data.split_first() else {
        return;
    };
    let mut bytes = rest.to_vec();
    if mode & 1 == 1 {
        let _ = meshq::advanced::reseal(&mut bytes);
    }
    let _ = BlobHeader::read(&bytes);
    let view = match BlobView::parse(&bytes) {
        Ok(view) => view,
        Err(err) => {
            // The owned loader checks boxes on its decoded copy: it refuses exactly what the
            // view refuses, with the same error.
            assert_eq!(MeshBvh::from_blob(&bytes).err(), Some(err));
            return;
        }
    };
    let b = view.bounds();
    let c = if b.is_empty() { Vec3::ZERO } else { b.center() };
    for k in 0..8u8 {
        let dir = Vec3::new(f32::from(k) - 3.5, 1.0, f32::from(mode) - 100.0);
        let ray = Ray::new(c - dir * 4.0, dir);
        let _ = view.raycast(&ray);
        let _ = view.raycast_any(&ray);
        let _ = view.closest_point(c + dir, f32::INFINITY);
    }
    let mut out = [0u32; 4];
    let _ = view.overlap_aabb_into(&Aabb::new(c - Vec3::ONE, c + Vec3::ONE), &mut out);
    view.overlap_sphere(c, 1.0, |_| ControlFlow::Continue(()));
    // Decoding into slices is exact and the in-memory tree agrees with the view.
    let h = view.header();
    let mut nodes = vec![BvhNode::EMPTY; h.node_count as usize];
    let mut order = vec![0u32; h.triangle_count as usize];
    let mut packed = vec![PackedTriangle::EMPTY; h.triangle_count as usize];
    if let (Ok(tree), Ok(tris)) = (
        view.decode_tree(&mut nodes, &mut order),
        view.decode_packed(&mut packed),
    ) {
        let ray = Ray::new(c + Vec3::new(0.3, 0.2, 5.0), -Vec3::Z);
        let a = tree
            .with(&tris)
            .raycast(&ray)
            .map(|h| (h.t.to_bits(), h.tri));
        let b = view.raycast(&ray).map(|h| (h.t.to_bits(), h.tri));
        assert_eq!(a, b);
    }
    // The owned decode of a valid blob answers as the view does.
    if let Ok(scene) = MeshBvh::from_blob(&bytes) {
        let ray = Ray::new(c + Vec3::new(-0.2, 0.1, 5.0), -Vec3::Z);
        let a = scene.raycast(&ray).map(|h| (h.t.to_bits(), h.tri));
        let b = view.raycast(&ray).map(|h| (h.t.to_bits(), h.tri));
        assert_eq!(a, b);
        let p = c + Vec3::new(0.1, -0.3, 0.2);
        let a = scene
            .closest_point(p, f32::INFINITY)
            .map(|h| (h.distance_squared.to_bits(), h.tri));
        let b = view
            .closest_point(p, f32::INFINITY)
            .map(|h| (h.distance_squared.to_bits(), h.tri));
        assert_eq!(a, b);
    }
});
