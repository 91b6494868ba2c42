//! The WebAssembly leg of the parity check, run in Node by wasm-bindgen-test-runner
//! (`cargo test -p meshq-wasm --target wasm32-unknown-unknown --tests`): every bundled mesh is
//! built here, in WebAssembly, and must give the golden digest the native suite computed from
//! brute force, the same blob bytes as the native build, and the same answers again after a
//! blob round trip. On the host these tests compile to nothing.
#![cfg(target_arch = "wasm32")]

use glam::Vec3;
use js_sys::{Float32Array, Reflect, Uint32Array};
use meshq::math::{ClosestPoint, Ray, RayHit};
use meshq_wasm::MeshBvh;
use meshq_workload::{
    MeshDigest, ParitySpec, ParityTarget, find_golden, find_remesh_golden, run_parity,
};
use wasm_bindgen::JsValue;
use wasm_bindgen_test::wasm_bindgen_test;

const GOLDEN: &str = include_str!("../../tests/golden/parity.txt");
const BLOBS: &str = include_str!("../../tests/golden/blobs.txt");
const REMESH_GOLDEN: &str = include_str!("../../tests/golden/remesh.txt");

const MESHES: [(&str, &str); 5] = [
    (
        "stanford-bunny",
        include_str!("../../assets/stanford-bunny.obj"),
    ),
    ("fandisk", include_str!("../../assets/fandisk.obj")),
    ("spot", include_str!("../../assets/spot.obj")),
    ("cow", include_str!("../../assets/cow.obj")),
    ("teapot", include_str!("../../assets/teapot.obj")),
];

/// Flat positions and indices of an OBJ (polygons fan-triangulated, like the native loader).
fn load(obj: &str) -> (Vec<f32>, Vec<u32>) {
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, _) = tobj::load_obj_buf(&mut obj.as_bytes(), &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .unwrap();
    let (mut positions, mut indices) = (Vec::new(), Vec::new());
    for m in models {
        let base = u32::try_from(positions.len() / 3).unwrap();
        positions.extend_from_slice(&m.mesh.positions);
        indices.extend(m.mesh.indices.iter().map(|i| i + base));
    }
    (positions, indices)
}

/// Builds with `options` (`undefined` for the default).
fn build(obj: &str, options: &JsValue) -> MeshBvh {
    let (positions, indices) = load(obj);
    let indices = Uint32Array::from(&indices[..]);
    MeshBvh::build(
        &floats_js(&positions),
        Some(indices.into()),
        Some(options.clone()),
    )
    .unwrap()
}

/// `{ quality: "fast" }`.
fn fast() -> JsValue {
    option("quality", "fast")
}

/// `{ key: value }`.
fn option(key: &str, value: &str) -> JsValue {
    let options = js_sys::Object::new();
    Reflect::set(&options, &key.into(), &value.into()).unwrap();
    options.into()
}

struct Wasm<'a>(&'a MeshBvh);

impl ParityTarget for Wasm<'_> {
    fn raycast(&mut self, ray: &Ray) -> Option<RayHit> {
        self.0.raycast_ray(ray)
    }
    fn raycast_any(&mut self, ray: &Ray) -> bool {
        self.0.raycast_any_ray(ray)
    }
    fn closest_point(&mut self, point: Vec3) -> Option<ClosestPoint> {
        self.0.closest_point_at(point, f32::INFINITY)
    }
}

/// `bytes=… checksum=0x…` of a golden blob (`<mesh>` or `<mesh>-fast`), from the golden blob
/// file.
fn golden_blob(mesh: &str) -> (usize, u32) {
    let line = BLOBS
        .lines()
        .find(|l| l.split_whitespace().next() == Some(mesh))
        .unwrap_or_else(|| panic!("{mesh} missing from tests/golden/blobs.txt"));
    let field = |key: &str| {
        line.split_whitespace()
            .find_map(|f| f.strip_prefix(key))
            .unwrap_or_else(|| panic!("{mesh}: no {key}"))
    };
    let bytes = field("bytes=").parse().unwrap();
    let checksum = u32::from_str_radix(field("checksum=0x"), 16).unwrap();
    (bytes, checksum)
}

/// Bytes as the `Uint8Array` JavaScript passes.
fn bytes_js(bytes: &[u8]) -> JsValue {
    js_sys::Uint8Array::from(bytes).into()
}

/// Numbers as the `Float32Array` JavaScript passes.
fn floats_js(values: &[f32]) -> JsValue {
    Float32Array::from(values).into()
}

#[wasm_bindgen_test]
fn every_mesh_matches_the_golden_digest_and_blob() {
    let spatial = js_sys::Object::new();
    Reflect::set(&spatial, &"spatialSplits".into(), &true.into()).unwrap();
    let sweep = js_sys::Object::new();
    Reflect::set(&sweep, &"sweepSah".into(), &true.into()).unwrap();
    let presets = [
        ("", JsValue::UNDEFINED),
        ("-fast", fast()),
        ("-spatial", spatial.into()),
        ("-sweep", sweep.into()),
    ];
    for ((name, obj), (suffix, options)) in MESHES
        .iter()
        .flat_map(|m| presets.iter().map(move |p| (m, p)))
    {
        let mut built = build(obj, options);
        let golden = find_golden(GOLDEN, name).unwrap();
        assert_eq!(built.triangle_count(), golden.triangles, "{name}");
        let report = run_parity(&golden.spec, golden.bounds(), &mut Wasm(&built));
        assert_eq!(report, golden.report, "{name}: built in WebAssembly");

        let blob = built.to_blob(None, None).unwrap();
        let (bytes, checksum) = golden_blob(&format!("{name}{suffix}"));
        let header = meshq::advanced::BlobHeader::read(&blob).unwrap();
        assert_eq!(
            (blob.len(), header.checksum),
            (bytes, checksum),
            "{name}{suffix}: blob bytes"
        );

        let mut loaded = MeshBvh::from_blob(&bytes_js(&blob)).unwrap();
        let report = run_parity(&golden.spec, golden.bounds(), &mut Wasm(&loaded));
        assert_eq!(report, golden.report, "{name}: loaded from the blob");

        // Four-wide nodes (built and loaded BVHs walk eight-wide ones here): the golden answers.
        let mut four = MeshBvh::from_blob(&bytes_js(&blob)).unwrap();
        let eight_bytes = four.query_node_bytes();
        assert_eq!(
            eight_bytes,
            built.query_node_bytes(),
            "{name}: built and loaded"
        );
        assert_eq!(
            eight_bytes % 256.0,
            0.0,
            "{name}: eight-wide nodes by default"
        );
        four.four_wide_nodes().unwrap();
        let four_bytes = four.query_node_bytes();
        // Exactly the core's four-wide collapse of the same tree (half the bytes per node, but
        // not always fewer bytes in all: the planned eight-wide tree can need fewer than half
        // as many nodes).
        let core_four = meshq::MeshBvh::from_blob(&blob)
            .unwrap()
            .with_four_wide_nodes()
            .unwrap()
            .query_node_bytes();
        assert!(
            four_bytes % 128.0 == 0.0 && four_bytes == core_four as f64,
            "{name}: four-wide node bytes {four_bytes}, the core's {core_four}"
        );
        let report = run_parity(&golden.spec, golden.bounds(), &mut Wasm(&four));
        assert_eq!(report, golden.report, "{name}: four-wide nodes");

        // Quantized nodes: half the bytes of four-wide nodes, the golden answers.
        let mut compact = MeshBvh::from_blob(&bytes_js(&blob)).unwrap();
        compact.compact_nodes().unwrap();
        assert_eq!(
            compact.query_node_bytes() * 2.0,
            four_bytes,
            "{name}: node bytes"
        );
        let report = run_parity(&golden.spec, golden.bounds(), &mut Wasm(&compact));
        assert_eq!(report, golden.report, "{name}: compact nodes");

        // Eight-wide nodes again after compact ones: the golden answers, the same blob.
        compact.eight_wide_nodes().unwrap();
        assert_eq!(
            compact.query_node_bytes(),
            eight_bytes,
            "{name}: eight-wide again"
        );
        let report = run_parity(&golden.spec, golden.bounds(), &mut Wasm(&compact));
        assert_eq!(report, golden.report, "{name}: eight-wide nodes");
        assert_eq!(
            compact.to_blob(None, None).unwrap(),
            blob,
            "{name}: eight-wide blob"
        );
        assert_eq!(loaded.to_blob(None, None).unwrap(), blob);

        // A packed blob (corners in leaf order, no indexed mesh) answers the same.
        let packed = built.to_blob(Some("packed".into()), None).unwrap();
        let loaded_packed = MeshBvh::from_blob(&bytes_js(&packed)).unwrap();
        let report = run_parity(&golden.spec, golden.bounds(), &mut Wasm(&loaded_packed));
        assert_eq!(report, golden.report, "{name}: loaded from the packed blob");
        // Both loads give back the built mesh's triangles and tree, for display.
        for (layout, other) in [("indexed", &loaded), ("packed", &loaded_packed)] {
            assert_eq!(
                other.triangle_positions(),
                built.triangle_positions(),
                "{name} {layout}: triangles"
            );
            assert_eq!(other.depth(), built.depth(), "{name} {layout}: depth");
            for level in [0, built.depth() / 2, built.depth() - 1] {
                assert_eq!(
                    other.level_boxes(level),
                    built.level_boxes(level),
                    "{name} {layout}: level {level}"
                );
            }
        }
        let omitted = built.to_blob(Some("omitted".into()), None).unwrap();
        assert!(
            MeshBvh::from_blob(&bytes_js(&omitted)).is_err(),
            "{name}: no mesh"
        );
    }
}

/// The k-d tree, octree and grid, built here in WebAssembly, give the golden digest and the
/// golden blob bytes, in place of the BVH; so do their blobs once loaded (indexed and packed).
#[wasm_bindgen_test]
fn every_structure_matches_the_golden_digest_and_blob() {
    for (name, obj) in MESHES {
        let golden = find_golden(GOLDEN, name).unwrap();
        let bounds = golden.bounds();
        for kind in ["kdtree", "octree", "grid"] {
            let mut built = build(obj, &option("structure", kind));
            assert_eq!(built.structure(), kind);
            let report = run_parity(&golden.spec, bounds, &mut Wasm(&built));
            assert_eq!(report, golden.report, "{name}: {kind} built in WebAssembly");

            let blob = built.to_blob(None, None).unwrap();
            let header = meshq::advanced::BlobHeader::read(&blob).unwrap();
            assert_eq!(
                (blob.len(), header.checksum),
                golden_blob(&format!("{name}-{kind}")),
                "{name} {kind}: blob bytes"
            );
            for layout in [None, Some(JsValue::from("packed"))] {
                let bytes = match &layout {
                    None => blob.clone(),
                    Some(_) => built.to_blob(layout.clone(), None).unwrap(),
                };
                let loaded = MeshBvh::from_blob(&bytes_js(&bytes)).unwrap();
                assert_eq!(loaded.structure(), kind);
                let report = run_parity(&golden.spec, bounds, &mut Wasm(&loaded));
                assert_eq!(report, golden.report, "{name}: {kind} blob {layout:?}");
                assert_eq!(loaded.depth(), built.depth(), "{name} {kind}: depth");
                assert_eq!(
                    loaded.level_boxes(loaded.depth() / 2),
                    built.level_boxes(built.depth() / 2),
                    "{name} {kind}: cells"
                );
            }
        }
    }
    let positions = vec![0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0];
    assert!(
        MeshBvh::build(
            &floats_js(&positions),
            None,
            Some(option("structure", "quadtree"))
        )
        .is_err(),
        "unknown structure"
    );
}

/// `rays` as a batch takes them: 6 numbers per ray.
fn rays_js(rays: &[Ray]) -> Float32Array {
    let flat: Vec<f32> = rays
        .iter()
        .flat_map(|r| {
            [
                r.origin.x, r.origin.y, r.origin.z, r.dir.x, r.dir.y, r.dir.z,
            ]
        })
        .collect();
    Float32Array::from(flat.as_slice())
}

/// `raycastAnyBatch` over the `n` rays of `flat`: the count it returns and the flags.
fn any_hits(bvh: &MeshBvh, flat: &Float32Array, n: usize) -> (u32, Vec<u8>) {
    let hits = js_sys::Uint8Array::new_with_length(n as u32);
    let found = bvh
        .raycast_any_batch(flat, &JsValue::UNDEFINED, &JsValue::UNDEFINED, &hits, None)
        .unwrap();
    (found, hits.to_vec())
}

/// Ray batches are answered a chunk of `RAY_CHUNK` rays at a time: across chunk boundaries,
/// with a run of rays from one origin (a packet) straddling each, every ray's closest hit
/// (with its barycentric weights) and any-hit answer is the one single calls give, written to
/// its own place, and the counts returned are the hits.
#[wasm_bindgen_test]
fn ray_batches_answer_across_their_chunks_as_single_calls_do() {
    let bvh = build(MESHES[0].1, &JsValue::UNDEFINED);
    let bounds = bvh.root_bounds();
    let n = 2 * meshq_wasm::RAY_CHUNK + 500;
    let mut rays: Vec<Ray> = meshq_workload::RandomRays::new(bounds, 11)
        .take(n)
        .collect();
    // Rays from one corner toward points spread over the box, 24 around each boundary.
    let corner = bounds.max + (bounds.max - bounds.min);
    for boundary in [meshq_wasm::RAY_CHUNK, 2 * meshq_wasm::RAY_CHUNK] {
        for (k, ray) in rays[boundary - 12..boundary + 12].iter_mut().enumerate() {
            let f = k as f32 / 24.0;
            let target = bounds.min + (bounds.max - bounds.min) * Vec3::new(f, 0.5, 1.0 - f);
            *ray = Ray::new(corner, target - corner);
        }
    }
    let flat = rays_js(&rays);
    let t_js = Float32Array::new_with_length(n as u32);
    let triangles_js = Uint32Array::new_with_length(n as u32);
    let uv_js = Float32Array::new_with_length(2 * n as u32);
    let found = bvh
        .raycast_batch_barycentric(
            &flat,
            &JsValue::UNDEFINED,
            &JsValue::UNDEFINED,
            &t_js,
            &triangles_js,
            &uv_js,
            None,
        )
        .unwrap();
    let (any_found, any) = any_hits(&bvh, &flat, n);
    let (t, triangles, uv) = (t_js.to_vec(), triangles_js.to_vec(), uv_js.to_vec());
    let expected: Vec<_> = rays.iter().map(|r| bvh.raycast_ray(r)).collect();
    let hit_count = expected.iter().flatten().count();
    assert_eq!(found as usize, hit_count);
    assert_eq!(any_found as usize, hit_count);
    // Not vacuous: hits and misses on both sides of each boundary.
    for boundary in [meshq_wasm::RAY_CHUNK, 2 * meshq_wasm::RAY_CHUNK] {
        let near = &expected[boundary - 12..boundary + 12];
        assert!(near[..12].iter().any(Option::is_some) && near[12..].iter().any(Option::is_some));
    }
    assert!(hit_count > n / 10 && hit_count < n, "{hit_count} of {n}");
    for (i, e) in expected.iter().enumerate() {
        let got = (
            t[i].to_bits(),
            triangles[i],
            uv[2 * i].to_bits(),
            uv[2 * i + 1].to_bits(),
        );
        match e {
            Some(h) => assert_eq!(
                got,
                (h.t.to_bits(), h.tri, h.u.to_bits(), h.v.to_bits()),
                "ray {i}"
            ),
            None => {
                assert_eq!((t[i], triangles[i]), (f32::INFINITY, u32::MAX), "ray {i}");
                assert!(uv[2 * i].is_nan() && uv[2 * i + 1].is_nan(), "ray {i}");
            }
        }
        assert_eq!(any[i], u8::from(bvh.raycast_any_ray(&rays[i])), "ray {i}");
    }
}

/// A large batch from many origins on a large mesh (the bunny with each triangle split in
/// four: 277,804 triangles) goes in passes of `SORTED_PASS` rays, each answered sorted: across
/// the pass boundary, with a camera's run and an invalid ray inside, every ray's closest hit
/// and any-hit answer is the one single calls give, written to its own place.
#[wasm_bindgen_test]
fn large_batches_on_large_meshes_answer_in_sorted_passes_as_single_calls_do() {
    let (positions, indices) = load(MESHES[0].1);
    // Each triangle into four through its edges' midpoints (corners repeated per triangle).
    let (mut split, mut split_indices) = (Vec::new(), Vec::new());
    for t in indices.chunks_exact(3) {
        let p = |i: u32| Vec3::from_slice(&positions[3 * i as usize..3 * i as usize + 3]);
        let (a, b, c) = (p(t[0]), p(t[1]), p(t[2]));
        let base = u32::try_from(split.len() / 3).unwrap();
        for v in [a, b, c, (a + b) * 0.5, (b + c) * 0.5, (c + a) * 0.5] {
            split.extend_from_slice(&v.to_array());
        }
        split_indices.extend([0, 3, 5, 3, 1, 4, 5, 4, 2, 3, 4, 5].map(|k| base + k));
    }
    assert!(split_indices.len() / 3 >= 131_072);
    let bvh = MeshBvh::build(
        &floats_js(&split),
        Some(Uint32Array::from(&split_indices[..]).into()),
        None,
    )
    .unwrap();
    let bounds = bvh.root_bounds();
    let n = meshq_wasm::SORTED_PASS + 3_000;
    let mut rays: Vec<Ray> = meshq_workload::RandomRays::new(bounds, 5).take(n).collect();
    let boundary = meshq_wasm::SORTED_PASS;
    let corner = bounds.max + (bounds.max - bounds.min);
    for (k, ray) in rays[boundary - 12..boundary + 12].iter_mut().enumerate() {
        let f = k as f32 / 24.0;
        let target = bounds.min + (bounds.max - bounds.min) * Vec3::new(f, 0.5, 1.0 - f);
        *ray = Ray::new(corner, target - corner);
    }
    rays[boundary + 100] = Ray::new(Vec3::new(f32::NAN, 0.0, 0.0), Vec3::X);
    let flat = rays_js(&rays);
    let t_js = Float32Array::new_with_length(n as u32);
    let triangles_js = Uint32Array::new_with_length(n as u32);
    let found = bvh
        .raycast_batch(
            &flat,
            &JsValue::UNDEFINED,
            &JsValue::UNDEFINED,
            &t_js,
            &triangles_js,
            None,
        )
        .unwrap();
    let (any_found, any) = any_hits(&bvh, &flat, n);
    let (t, triangles) = (t_js.to_vec(), triangles_js.to_vec());
    let expected: Vec<_> = rays.iter().map(|r| bvh.raycast_ray(r)).collect();
    let hit_count = expected.iter().flatten().count();
    assert_eq!(found as usize, hit_count);
    assert_eq!(any_found as usize, hit_count);
    assert!(hit_count > n / 10 && hit_count < n, "{hit_count} of {n}");
    for (i, e) in expected.iter().enumerate() {
        let want = e.map_or((f32::INFINITY.to_bits(), u32::MAX), |h| {
            (h.t.to_bits(), h.tri)
        });
        assert_eq!((t[i].to_bits(), triangles[i]), want, "ray {i}");
        assert_eq!(any[i], u8::from(e.is_some()), "ray {i}");
    }
}

fn number(object: &JsValue, path: &[&str]) -> f64 {
    let mut v = object.clone();
    for key in path {
        v = Reflect::get(&v, &JsValue::from_str(key)).unwrap();
    }
    v.as_f64().unwrap()
}

#[wasm_bindgen_test]
fn javascript_results_carry_the_core_answers() {
    let bvh = build(MESHES[2].1, &JsValue::UNDEFINED);
    let bounds = bvh.root_bounds();
    let spec = ParitySpec::DEFAULT;
    let (mut hits, mut misses) = (0, 0);
    for ray in spec.rays(bounds).take(200) {
        let (o, d) = (ray.origin, ray.dir);
        let js = bvh
            .raycast_xyz(
                f64::from(o.x),
                f64::from(o.y),
                f64::from(o.z),
                f64::from(d.x),
                f64::from(d.y),
                f64::from(d.z),
                Some(0.0),
                None,
                None,
            )
            .unwrap();
        match bvh.raycast_ray(&ray) {
            None => {
                assert!(js.is_null());
                misses += 1;
            }
            Some(hit) => {
                hits += 1;
                // f32 → f64 is exact, so the JavaScript numbers carry the same bits.
                assert_eq!(number(&js, &["t"]) as f32, hit.t);
                // The Euclidean distance: t times the direction's length, in doubles.
                let length = d.to_array().map(f64::from);
                let length = length.iter().map(|c| c * c).sum::<f64>().sqrt();
                assert_eq!(number(&js, &["distance"]), f64::from(hit.t) * length);
                assert_eq!(number(&js, &["triangle"]) as u32, hit.tri);
                assert_eq!(number(&js, &["u"]) as f32, hit.u);
                let p = o + d * hit.t;
                assert_eq!(number(&js, &["point", "x"]) as f32, p.x);
                let n = Vec3::new(
                    number(&js, &["normal", "x"]) as f32,
                    number(&js, &["normal", "y"]) as f32,
                    number(&js, &["normal", "z"]) as f32,
                );
                assert!((n.length() - 1.0).abs() < 1e-5);
            }
        }
    }
    assert!(hits > 50 && misses > 10, "{hits} hits, {misses} misses");

    // The batch gives the same answers as single calls.
    let rays: Vec<Ray> = spec.rays(bounds).take(500).collect();
    let flat: Vec<f32> = rays
        .iter()
        .flat_map(|r| {
            [
                r.origin.x, r.origin.y, r.origin.z, r.dir.x, r.dir.y, r.dir.z,
            ]
        })
        .collect();
    let distances_js = Float32Array::new_with_length(rays.len() as u32);
    let triangles_js = Uint32Array::new_with_length(rays.len() as u32);
    let n = bvh
        .raycast_batch(
            &Float32Array::from(flat.as_slice()),
            &JsValue::UNDEFINED,
            &JsValue::UNDEFINED,
            &distances_js,
            &triangles_js,
            None,
        )
        .unwrap();
    let (distances, triangles) = (distances_js.to_vec(), triangles_js.to_vec());
    let expected: Vec<_> = rays.iter().map(|r| bvh.raycast_ray(r)).collect();
    assert_eq!(n as usize, expected.iter().flatten().count());
    for (i, e) in expected.iter().enumerate() {
        match e {
            Some(h) => assert_eq!(
                (distances[i].to_bits(), triangles[i]),
                (h.t.to_bits(), h.tri)
            ),
            None => assert_eq!((distances[i], triangles[i]), (f32::INFINITY, u32::MAX)),
        }
    }

    // So does the closest-point batch (answered in Morton order inside), with and without a
    // maximum distance, a non-finite point included.
    let mut points: Vec<Vec3> = spec.points(bounds).take(2_000).collect();
    points[7] = Vec3::NAN;
    let flat: Vec<f32> = points.iter().flat_map(|p| p.to_array()).collect();
    let radius = (bounds.max - bounds.min).length() * 0.5;
    for max in [f32::INFINITY, 0.05 * radius] {
        let closest_js = Float32Array::new_with_length(flat.len() as u32);
        let triangles_js = Uint32Array::new_with_length(points.len() as u32);
        let distances_js = Float32Array::new_with_length(points.len() as u32);
        let found = bvh
            .closest_point_batch(
                &Float32Array::from(flat.as_slice()),
                &max.into(),
                &closest_js,
                &triangles_js,
                &distances_js,
            )
            .unwrap();
        let (closest, triangles, distances) = (
            closest_js.to_vec(),
            triangles_js.to_vec(),
            distances_js.to_vec(),
        );
        let expected: Vec<_> = points
            .iter()
            .map(|&p| bvh.closest_point_at(p, max))
            .collect();
        assert_eq!(found as usize, expected.iter().flatten().count());
        assert!(found > 0 && (max.is_infinite() || (found as usize) < points.len()));
        for (i, e) in expected.iter().enumerate() {
            let got = (
                triangles[i],
                distances[i].to_bits(),
                [closest[3 * i], closest[3 * i + 1], closest[3 * i + 2]].map(f32::to_bits),
            );
            match e {
                Some(c) => assert_eq!(
                    got,
                    (
                        c.tri,
                        c.distance_squared.sqrt().to_bits(),
                        c.point.to_array().map(f32::to_bits)
                    ),
                    "point {i}, max {max}"
                ),
                None => assert_eq!((got.0, distances[i]), (u32::MAX, f32::INFINITY)),
            }
        }
    }
}

#[wasm_bindgen_test]
fn bad_input_throws_with_the_core_message() {
    let positions = [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0];
    let bad = Uint32Array::from(&[0u32, 1, 7][..]);
    let error = MeshBvh::build(&floats_js(&positions), Some(bad.into()), None)
        .err()
        .unwrap();
    let message = js_sys::Error::from(error).message();
    assert!(
        String::from(message).contains('7'),
        "message names the index"
    );
    assert!(MeshBvh::from_blob(&bytes_js(&[1, 2, 3])).is_err());
    let ok = MeshBvh::build(&floats_js(&positions), None, None).unwrap();
    assert_eq!(ok.triangle_count(), 1);
}

/// The `remesh` binding, with its default options, gives the golden remeshing file's bits:
/// the small sphere the firmware remeshes and two bundled meshes.
#[wasm_bindgen_test]
fn remeshing_matches_the_golden_remesh_file() {
    let sphere = ("uv-sphere", include_str!("../../assets/uv-sphere.obj"));
    for (name, obj) in [sphere, MESHES[1], MESHES[2]] {
        let golden = find_remesh_golden(REMESH_GOLDEN, name).unwrap();
        let (positions, indices) = load(obj);
        assert_eq!(indices.len() / 3, golden.triangles_in as usize, "{name}");
        let indices = Uint32Array::from(&indices[..]);
        let out = meshq_wasm::remesh(&floats_js(&positions), Some(indices.into()), None).unwrap();
        let array = |key: &str| Reflect::get(&out, &key.into()).unwrap();
        let positions = js_sys::Float32Array::from(array("positions")).to_vec();
        let indices = Uint32Array::from(array("indices")).to_vec();
        let got = MeshDigest::of(
            positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]),
            indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]),
        );
        assert_eq!(got, golden.result, "{name}: remeshed in WebAssembly");
    }
}

#[wasm_bindgen_test]
fn mesh_mesh_checks_match_brute_force_here_too() {
    use meshq::collide::Affine;
    use meshq::geom::{TriangleTriangle, intersect_triangle_triangle, triangles_meet};
    use meshq::math::Triangle;
    let obj = include_str!("../../assets/uv-sphere.obj");
    let (positions, indices) = load(obj);
    let tris: Vec<Triangle> = indices
        .chunks_exact(3)
        .map(|t| {
            let p = |i: u32| Vec3::from_slice(&positions[3 * i as usize..3 * i as usize + 3]);
            Triangle::new(p(t[0]), p(t[1]), p(t[2]))
        })
        .collect();
    // The second sphere moved by half its radius along x and turned a little about z.
    let (s, c) = 0.3f32.sin_cos();
    let matrix = [
        c, s, 0.0, 0.0, -s, c, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.5, 0.0, 0.0, 1.0,
    ];
    let place = Affine::from_cols_4x4(&matrix).unwrap();
    let (mut pairs, mut crossing) = (Vec::new(), 0usize);
    for (i, a) in tris.iter().enumerate() {
        for (j, b) in tris.iter().enumerate() {
            // Meeting decided exactly; crossing where the tolerant test places a segment.
            let placed = place.apply_triangle(b);
            if triangles_meet(a, &placed) {
                pairs.push((i as u32, j as u32));
                let how = intersect_triangle_triangle(a, &placed);
                crossing += usize::from(matches!(how, TriangleTriangle::Segment { .. }));
            }
        }
    }
    pairs.sort_unstable();
    assert!(!pairs.is_empty());
    for options in [JsValue::UNDEFINED, option("structure", "octree")] {
        let one = build(obj, &options);
        let other = build(obj, &JsValue::UNDEFINED);
        assert!(
            one.intersects_mesh(&other, Some(Float32Array::from(&matrix[..]).into()), None)
                .unwrap()
        );
        let found = one
            .intersecting_pairs(
                &other,
                Some(Float32Array::from(&matrix[..]).into()),
                None,
                None,
            )
            .unwrap();
        assert_eq!(number(&found, &["total"]) as usize, pairs.len());
        let flat = Uint32Array::from(Reflect::get(&found, &"pairs".into()).unwrap()).to_vec();
        let mut got: Vec<(u32, u32)> = flat.chunks_exact(2).map(|p| (p[0], p[1])).collect();
        got.sort_unstable();
        assert_eq!(got, pairs);
        let capped = one
            .intersecting_pairs(
                &other,
                Some(Float32Array::from(&matrix[..]).into()),
                Some(JsValue::from(3)),
                None,
            )
            .unwrap();
        assert_eq!(number(&capped, &["total"]) as usize, pairs.len());
        // The largest cap allocates no more than the pairs found.
        let all = one
            .intersecting_pairs(
                &other,
                Some(Float32Array::from(&matrix[..]).into()),
                Some(JsValue::from(u32::MAX)),
                None,
            )
            .unwrap();
        let listed = Uint32Array::from(Reflect::get(&all, &"pairs".into()).unwrap()).length();
        assert_eq!(listed as usize, 2 * pairs.len());
        assert_eq!(
            Reflect::get(&capped, &"overflowed".into()).unwrap(),
            JsValue::TRUE
        );
        let segments = one
            .intersection_segments(&other, Some(Float32Array::from(&matrix[..]).into()), None)
            .unwrap();
        assert_eq!(segments.length() as usize, 6 * crossing);
        let apart = one.intersects_mesh(
            &other,
            Some({
                let mut m = matrix;
                m[12] = 5.0;
                Float32Array::from(&m[..]).into()
            }),
            None,
        );
        assert!(!apart.unwrap());
        let itself = one.self_intersections(None, None).unwrap();
        assert_eq!(number(&itself, &["total"]), 0.0);
        assert!(
            one.intersects_mesh(
                &other,
                Some(Float32Array::from(&[1.0f32; 3][..]).into()),
                None
            )
            .is_err()
        );
    }
}

const WINDING_GOLDEN: &str = include_str!("../../tests/golden/winding.txt");

#[wasm_bindgen_test]
fn winding_numbers_match_the_golden_digest() {
    for (name, obj) in MESHES {
        let (positions, _) = load(obj);
        let corners: Vec<[f32; 3]> = positions
            .chunks_exact(3)
            .map(|p| [p[0], p[1], p[2]])
            .collect();
        let bounds = meshq_workload::centre_radius(&corners).2;
        let points: Vec<Vec3> =
            meshq_workload::QueryPoints::new(bounds, meshq_workload::WINDING_SEED)
                .take(2000)
                .collect();
        let flat: Vec<f32> = points.iter().flat_map(|p| p.to_array()).collect();
        // A k-d tree too: its winding numbers come from a BVH of the same mesh, the same bits.
        for options in [JsValue::UNDEFINED, option("structure", "kdtree")] {
            let mut built = build(obj, &options);
            let numbers = Float32Array::new_with_length(points.len() as u32);
            let inside = built
                .winding_number_batch(&floats_js(&flat), &numbers.clone().into(), None)
                .unwrap();
            let numbers = numbers.to_vec();
            let distances = Float32Array::new_with_length(points.len() as u32);
            let triangles = Uint32Array::new_with_length(points.len() as u32);
            built
                .signed_distance_batch(
                    &floats_js(&flat),
                    &JsValue::UNDEFINED,
                    &distances.clone().into(),
                    &triangles.into(),
                    None,
                )
                .unwrap();
            let digest = meshq_workload::WindingDigest::of(&numbers, &distances.to_vec());
            let golden = meshq_workload::find_winding_golden(WINDING_GOLDEN, name).unwrap();
            assert_eq!(digest, golden, "{name}: winding numbers in WebAssembly");
            assert_eq!(inside, golden.inside, "{name}");
            // Stored in a blob (a BVH only) and loaded again: the same numbers, no build.
            if options.is_undefined() {
                let blob = built.to_blob(None, Some(JsValue::TRUE)).unwrap();
                assert_eq!(meshq::advanced::BlobHeader::read(&blob).unwrap().version, 6);
                let mut loaded = MeshBvh::from_blob(&bytes_js(&blob)).unwrap();
                let again = Float32Array::new_with_length(points.len() as u32);
                loaded
                    .winding_number_batch(&floats_js(&flat), &again.clone().into(), None)
                    .unwrap();
                assert!(
                    again
                        .to_vec()
                        .iter()
                        .map(|w| w.to_bits())
                        .eq(numbers.iter().map(|w| w.to_bits())),
                    "{name}: from a blob"
                );
                assert_eq!(
                    loaded.to_blob(None, Some(JsValue::TRUE)).unwrap(),
                    blob,
                    "{name}: kept as loaded"
                );
            }
            for (k, p) in points.iter().enumerate().step_by(97) {
                let one = built
                    .winding_number(&floats_js(&p.to_array()), None)
                    .unwrap();
                assert_eq!(one.to_bits(), numbers[k].to_bits(), "{name} point {k}");
                let holds = built.contains(&floats_js(&p.to_array()), None).unwrap();
                assert_eq!(holds, numbers[k].abs() >= 0.5, "{name} point {k}");
            }
        }
    }
}

#[wasm_bindgen_test]
fn a_signed_distance_grid_holds_the_single_signed_distances() {
    let mut built = build(MESHES[2].1, &JsValue::UNDEFINED);
    let volume = built
        .signed_distance_grid(&JsValue::from(12), None, None, None)
        .unwrap();
    let field = |k: &str| Reflect::get(&volume, &k.into()).unwrap();
    let values = Float32Array::from(field("values")).to_vec();
    let counts = Uint32Array::from(field("counts")).to_vec();
    let origin = Float32Array::from(field("origin")).to_vec();
    let spacing = field("spacing").as_f64().unwrap() as f32;
    assert_eq!(values.len(), counts.iter().product::<u32>() as usize);
    let (nx, ny) = (counts[0] as usize, counts[1] as usize);
    for (i, &v) in values.iter().enumerate().step_by(7) {
        let p = Vec3::from_array([origin[0], origin[1], origin[2]])
            + Vec3::new(
                (i % nx) as f32,
                ((i / nx) % ny) as f32,
                (i / (nx * ny)) as f32,
            ) * spacing;
        let single = built
            .signed_distance(&floats_js(&p.to_array()), None, None)
            .unwrap();
        let d = Reflect::get(&single, &"distance".into())
            .unwrap()
            .as_f64()
            .unwrap() as f32;
        assert_eq!(d.to_bits(), v.to_bits(), "sample {i}");
    }
    assert!(values.iter().any(|&v| v < 0.0));
}

const DISTANCE_GOLDEN: &str = include_str!("../../tests/golden/distance.txt");

#[wasm_bindgen_test]
fn mesh_distances_match_the_golden_digest() {
    for (name, obj) in MESHES {
        let Ok(golden) = meshq_workload::find_distance_golden(DISTANCE_GOLDEN, name) else {
            continue;
        };
        let (positions, _) = load(obj);
        let corners: Vec<[f32; 3]> = positions
            .chunks_exact(3)
            .map(|p| [p[0], p[1], p[2]])
            .collect();
        let (c, r, _) = meshq_workload::centre_radius(&corners);
        let built = build(obj, &JsValue::UNDEFINED);
        let field = |o: &JsValue, k: &str| Reflect::get(o, &k.into()).unwrap();
        let xyz = |o: &JsValue| ["x", "y", "z"].map(|k| field(o, k).as_f64().unwrap() as f32);
        let pairs: Vec<_> = meshq_workload::DISTANCE_PLACEMENTS
            .iter()
            .map(|&placement| {
                let matrix = meshq_workload::placement_for(c.to_array(), r, placement);
                let found = built
                    .distance_to_mesh(&built, Some(floats_js(&matrix)), None, None, None)
                    .unwrap();
                (!found.is_null()).then(|| {
                    (
                        field(&found, "distance").as_f64().unwrap() as f32,
                        xyz(&field(&found, "pointA")),
                        xyz(&field(&found, "pointB")),
                        field(&found, "triangleA").as_f64().unwrap() as u32,
                        field(&found, "triangleB").as_f64().unwrap() as u32,
                    )
                })
            })
            .collect();
        let digest = meshq_workload::DistanceDigest::of(&pairs);
        assert_eq!(digest, golden, "{name}: mesh distances in WebAssembly");
    }
}

#[wasm_bindgen_test]
fn sweeps_match_the_golden_digest() {
    use meshq::query::SweepShape;
    for (name, obj) in MESHES {
        let Ok(golden) =
            meshq_workload::find_distance_golden(DISTANCE_GOLDEN, &format!("{name}-sweeps"))
        else {
            continue;
        };
        let (positions, _) = load(obj);
        let corners: Vec<[f32; 3]> = positions
            .chunks_exact(3)
            .map(|p| [p[0], p[1], p[2]])
            .collect();
        let (c, r, _) = meshq_workload::centre_radius(&corners);
        let built = build(obj, &JsValue::UNDEFINED);
        let field = |o: &JsValue, k: &str| Reflect::get(o, &k.into()).unwrap();
        let xyz = |o: &JsValue| ["x", "y", "z"].map(|k| field(o, k).as_f64().unwrap() as f32);
        let js = |v: Vec3| floats_js(&v.to_array());
        let hits: Vec<_> = meshq_workload::golden_sweeps(c.to_array(), r)
            .map(|(shape, motion)| {
                let found = match shape {
                    SweepShape::Sphere { center, radius } => {
                        built.sweep_sphere(&js(center), &JsValue::from(radius), &js(motion))
                    }
                    SweepShape::Capsule { a, b, radius } => {
                        built.sweep_capsule(&js(a), &js(b), &JsValue::from(radius), &js(motion))
                    }
                    SweepShape::Box(obb) => {
                        let axes: Vec<f32> = obb.axes.iter().flat_map(|a| a.to_array()).collect();
                        built.sweep_box(
                            &js(obb.center),
                            &floats_js(&axes),
                            &js(obb.half_extents),
                            &js(motion),
                        )
                    }
                }
                .unwrap();
                (!found.is_null()).then(|| {
                    (
                        field(&found, "t").as_f64().unwrap() as f32,
                        xyz(&field(&found, "point")),
                        xyz(&field(&found, "normal")),
                        field(&found, "triangle").as_f64().unwrap() as u32,
                        0,
                    )
                })
            })
            .collect();
        let digest = meshq_workload::DistanceDigest::of(&hits);
        assert_eq!(digest, golden, "{name}: sweeps in WebAssembly");
    }
}

#[wasm_bindgen_test]
fn pseudo_normal_signs_match_the_winding_sign_away_from_the_surface() {
    let spot = MESHES.iter().find(|(n, _)| *n == "spot").unwrap().1;
    let mut built = build(spot, &JsValue::UNDEFINED);
    let (positions, _) = load(spot);
    let corners: Vec<[f32; 3]> = positions
        .chunks_exact(3)
        .map(|p| [p[0], p[1], p[2]])
        .collect();
    let bounds = meshq_workload::centre_radius(&corners).2;
    let points: Vec<Vec3> = meshq_workload::QueryPoints::new(bounds, 17)
        .take(400)
        .collect();
    let flat: Vec<f32> = points.iter().flat_map(|p| p.to_array()).collect();
    let pseudo = JsValue::from_str("pseudo-normal");
    let n = points.len() as u32;
    let (d, t) = (
        Float32Array::new_with_length(n),
        Uint32Array::new_with_length(n),
    );
    built
        .signed_distance_batch(
            &floats_js(&flat),
            &JsValue::NULL,
            &d.clone().into(),
            &t.clone().into(),
            Some(pseudo.clone()),
        )
        .unwrap();
    let (d, t) = (d.to_vec(), t.to_vec());
    let mut checked = 0;
    for (k, p) in points.iter().enumerate() {
        let one = built
            .signed_distance(&floats_js(&p.to_array()), None, Some(pseudo.clone()))
            .unwrap();
        let get = |o: &JsValue, f: &str| Reflect::get(o, &f.into()).unwrap().as_f64().unwrap();
        assert_eq!(get(&one, "distance") as f32, d[k], "point {k}");
        assert_eq!(get(&one, "triangle") as u32, t[k], "point {k}");
        let by_winding = built
            .signed_distance(&floats_js(&p.to_array()), None, None)
            .unwrap();
        let w = get(&by_winding, "distance") as f32;
        // Away from the surface both signs are right, so they agree.
        if w.abs() > 1e-3 {
            checked += 1;
            assert_eq!(d[k] < 0.0, w < 0.0, "point {k}: {} vs {w}", d[k]);
            assert_eq!(d[k].abs(), w.abs(), "point {k}");
        }
    }
    assert!(checked > 300, "{checked}");
    // The bunny has holes: refused.
    let bunny = MESHES
        .iter()
        .find(|(n, _)| *n == "stanford-bunny")
        .unwrap()
        .1;
    let mut open = build(bunny, &JsValue::UNDEFINED);
    assert!(
        open.signed_distance(&floats_js(&[0.0, 0.0, 0.0]), None, Some(pseudo.clone()))
            .is_err()
    );
    assert!(
        built
            .signed_distance(
                &floats_js(&[0.0, 0.0, 0.0]),
                None,
                Some(JsValue::from_str("pseudo"))
            )
            .is_err()
    );
}
