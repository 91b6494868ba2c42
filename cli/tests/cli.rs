//! The `meshq` command end to end: files in, files out, compared with the library's answers
//! and with brute force; errors are one line and a non-zero status, never a panic.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use meshq::MeshBvh;
use meshq::bvh::BuildConfig;
use meshq::geom::{CullMode, closest_point_triangle, intersect_ray_triangle_watertight};
use meshq::math::{Ray, Vec3};
use meshq::mesh::MeshRef;
use meshq::query::{RayOptions, TriangleTest};
use meshq::{MeshQuery, Traverse};
use meshq_tests::oracle::BruteForce;
use meshq_tests::{checked_bvh, load_mesh, workload};

fn meshq(args: &[&dyn AsRef<std::ffi::OsStr>]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_meshq"))
        .args(args.iter().map(|a| a.as_ref()))
        .output()
        .expect("meshq runs")
}

fn ok(args: &[&dyn AsRef<std::ffi::OsStr>]) -> String {
    let out = meshq(args);
    assert!(
        out.status.success(),
        "meshq failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

fn asset(name: &str) -> PathBuf {
    meshq_tests::assets::assets_dir().join(name)
}

fn write_f32s(path: &Path, values: impl IntoIterator<Item = f32>) {
    let bytes: Vec<u8> = values.into_iter().flat_map(f32::to_le_bytes).collect();
    std::fs::write(path, bytes).unwrap();
}

fn read_records(path: &Path) -> Vec<(f32, u32)> {
    let bytes = std::fs::read(path).unwrap();
    let (records, rest) = bytes.as_chunks::<8>();
    assert!(rest.is_empty());
    records
        .iter()
        .map(|r| {
            let [a, b, c, d, e, f, g, h] = *r;
            (
                f32::from_le_bytes([a, b, c, d]),
                u32::from_le_bytes([e, f, g, h]),
            )
        })
        .collect()
}

fn ray_floats(rays: &[Ray]) -> Vec<f32> {
    rays.iter()
        .flat_map(|r| {
            [
                r.origin.x, r.origin.y, r.origin.z, r.dir.x, r.dir.y, r.dir.z,
            ]
        })
        .collect()
}

#[test]
fn bake_inspect_raycast_and_closest_agree_with_the_library_and_brute_force() {
    let dir = tempfile::tempdir().unwrap();
    let loaded = load_mesh("teapot");
    let mesh = loaded.valid();
    let obj = asset("teapot.obj");
    let blob = dir.path().join("teapot.meshq");
    let bake = ok(&[
        &"bake",
        &obj,
        &"-o",
        &blob,
        &"--quality",
        &"high",
        &"--json",
    ]);
    let bake: serde_json::Value = serde_json::from_str(&bake).unwrap();
    assert_eq!(bake["triangles"], mesh.triangle_count());
    assert_eq!(bake["bytes"], std::fs::metadata(&blob).unwrap().len());

    let inspect: serde_json::Value =
        serde_json::from_str(&ok(&[&"inspect", &blob, &"--json"])).unwrap();
    assert_eq!(inspect["triangles"], mesh.triangle_count());
    assert_eq!(inspect["vertices"], mesh.vertex_count());
    assert_eq!(inspect["mesh_layout"], "indexed");
    assert_eq!(inspect["config"]["bins"], 64);
    let leaves: u64 = inspect["leaf_sizes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p[1].as_u64().unwrap())
        .sum();
    assert_eq!(inspect["leaves"], leaves);
    assert!(inspect["sah_cost"].as_f64().unwrap() > 1.0);
    assert!(ok(&[&"inspect", &blob]).contains("leaf sizes"));

    // The library's answers on the same rays, built in-process.
    let rays = workload::random_rays(&loaded.positions, 5_000, 77);
    let ray_file = dir.path().join("rays.bin");
    write_f32s(&ray_file, ray_floats(&rays));
    let owned = MeshBvh::build(&mesh, &BuildConfig::high_quality()).unwrap();
    let bvh = checked_bvh(&owned, &mesh).unwrap();
    let expected: Vec<(f32, u32)> = rays
        .iter()
        .map(|r| {
            bvh.with(&mesh)
                .raycast(r)
                .map_or((f32::INFINITY, u32::MAX), |h| (h.t, h.tri))
        })
        .collect();
    for input in [&blob, &obj] {
        let hits = dir.path().join("hits.bin");
        let summary: serde_json::Value = serde_json::from_str(&ok(&[
            &"raycast", input, &"--rays", &ray_file, &"--out", &hits, &"--json",
        ]))
        .unwrap();
        assert_eq!(summary["rays"], 5_000);
        let got = read_records(&hits);
        let key = |v: &[(f32, u32)]| v.iter().map(|(t, i)| (t.to_bits(), *i)).collect::<Vec<_>>();
        assert_eq!(key(&got), key(&expected), "{}", input.display());
        assert_eq!(
            summary["hits"],
            got.iter().filter(|h| h.0.is_finite()).count()
        );
        // The preparation time is named for what it timed: a build, or a blob's load.
        let prepared = if input == &blob {
            "blob_load_seconds"
        } else {
            "build_seconds"
        };
        for key in [prepared, "query_seconds", "rays_per_second"] {
            assert!(summary[key].as_f64().unwrap() >= 0.0, "{key}");
        }
        let other = ["build_seconds", "blob_load_seconds"]
            .into_iter()
            .find(|k| *k != prepared)
            .unwrap();
        assert!(summary.get(other).is_none(), "{other} in {summary}");

        // Longer records: u, v and the hit point, as the library computes them.
        let full = dir.path().join("full.bin");
        ok(&[
            &"raycast",
            input,
            &"--rays",
            &ray_file,
            &"--out",
            &full,
            &"--format",
            &"full",
        ]);
        let bytes = std::fs::read(&full).unwrap();
        assert_eq!(bytes.len(), 28 * rays.len());
        for (r, record) in rays.iter().zip(bytes.chunks(28)).step_by(7) {
            let f = |k: usize| f32::from_le_bytes(record[4 * k..4 * k + 4].try_into().unwrap());
            let tri = u32::from_le_bytes(record[4..8].try_into().unwrap());
            match bvh.with(&mesh).raycast(r) {
                Some(h) => {
                    let p = r.at(h.t);
                    assert_eq!(
                        (f(0), tri, f(2), f(3), [f(4), f(5), f(6)]),
                        (h.t, h.tri, h.u, h.v, p.to_array())
                    );
                }
                None => {
                    assert_eq!((f(0), tri), (f32::INFINITY, u32::MAX));
                    assert!(f(2).is_nan() && f(6).is_nan());
                }
            }
        }
        let uv = dir.path().join("uv.bin");
        ok(&[
            &"raycast",
            input,
            &"--rays",
            &ray_file,
            &"--out",
            &uv,
            &"--format",
            &"t-tri-uv",
        ]);
        let uv_bytes = std::fs::read(&uv).unwrap();
        assert_eq!(uv_bytes.len(), 16 * rays.len());
        for (record, long) in uv_bytes.chunks(16).zip(bytes.chunks(28)) {
            assert_eq!(record, &long[..16]);
        }

        let any = dir.path().join("any.bin");
        ok(&[
            &"raycast", input, &"--rays", &ray_file, &"--out", &any, &"--any",
        ]);
        for (a, e) in read_records(&any).iter().zip(&expected) {
            // A hit names no triangle: 0xFFFFFFFE, which no mesh index can be confused with.
            let expect = if e.0.is_finite() {
                (0.0, 0xFFFF_FFFE)
            } else {
                (f32::INFINITY, u32::MAX)
            };
            assert_eq!(*a, expect);
        }

        // The nearest three hits of each ray, misses padding the rest, as brute force has them.
        let nearest = dir.path().join("nearest.bin");
        ok(&[
            &"raycast", input, &"--rays", &ray_file, &"--out", &nearest, &"--hits", &"3",
        ]);
        let got = read_records(&nearest);
        assert_eq!(got.len(), 3 * rays.len());
        let brute = BruteForce::new(&mesh);
        let mut several = 0;
        for (r, records) in rays.iter().zip(got.chunks(3)).step_by(10) {
            let mut want: Vec<(f32, u32)> = brute
                .raycast_all(r, &RayOptions::default())
                .iter()
                .take(3)
                .map(|h| (h.t, h.tri))
                .collect();
            several += usize::from(want.len() >= 2);
            want.resize(3, (f32::INFINITY, u32::MAX));
            assert_eq!(key(records), key(&want));
        }
        assert!(several > 20, "{several} sampled rays hit twice or more");
    }
    // Brute force on a sample: every triangle, watertight test, lower index on ties.
    for (r, e) in rays.iter().zip(&expected).step_by(25) {
        let mut best: Option<(f32, u32)> = None;
        for tri in 0..mesh.triangle_count() as u32 {
            let t = mesh.triangle(tri).unwrap();
            if t.is_degenerate() {
                continue;
            }
            if let Some(h) = intersect_ray_triangle_watertight(r, &t, CullMode::None)
                && best.is_none_or(|b| h.t < b.0)
            {
                best = Some((h.t, tri));
            }
        }
        assert_eq!(best.unwrap_or((f32::INFINITY, u32::MAX)), *e);
    }
    let _ = RayOptions::default();

    let points = workload::closest_points(&loaded.positions, 400, 78);
    let point_file = dir.path().join("points.bin");
    write_f32s(&point_file, points.iter().flat_map(|p| p.to_array()));
    let out = dir.path().join("closest.bin");
    let summary: serde_json::Value = serde_json::from_str(&ok(&[
        &"closest",
        &blob,
        &"--points",
        &point_file,
        &"--out",
        &out,
        &"--json",
    ]))
    .unwrap();
    assert_eq!(summary["points"], 400);
    for (p, (d, tri)) in points.iter().zip(read_records(&out)) {
        let best = (0..mesh.triangle_count() as u32)
            .filter_map(|i| {
                let t = mesh.triangle(i)?;
                (!t.is_degenerate()).then(|| (closest_point_triangle(*p, &t).distance_squared, i))
            })
            .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)))
            .unwrap();
        assert_eq!((d, tri), (best.0.sqrt(), best.1));
    }
    assert_eq!(summary["found"], 400);

    // With --max-distance only points that near count; the rest get the miss record.
    let limit = 0.01 * loaded_radius(&loaded.positions);
    let near = dir.path().join("near.bin");
    let summary: serde_json::Value = serde_json::from_str(&ok(&[
        &"closest",
        &blob,
        &"--points",
        &point_file,
        &"--out",
        &near,
        &"--max-distance",
        &limit.to_string(),
        &"--json",
    ]))
    .unwrap();
    let (mut within, mut beyond) = (0, 0);
    for ((d, tri), (all_d, all_tri)) in read_records(&near).into_iter().zip(read_records(&out)) {
        if all_d <= limit {
            assert_eq!((d, tri), (all_d, all_tri));
            within += 1;
        } else {
            assert_eq!((d, tri), (f32::INFINITY, u32::MAX));
            beyond += 1;
        }
    }
    assert!(within > 0 && beyond > 0, "{within} within, {beyond} beyond");
    assert_eq!(summary["found"], within);
    for bad in ["--max-distance=-1", "--max-distance=nan"] {
        fails(
            &[
                &"closest",
                &blob,
                &"--points",
                &point_file,
                &"--out",
                &near,
                &bad,
            ],
            2,
            "expected a distance",
        );
    }
}

/// The radius the workloads use for `positions` (half the bounds' diagonal).
fn loaded_radius(positions: &[[f32; 3]]) -> f32 {
    workload::centre_radius(positions).1
}

/// A quad and a pentagon in the plane z = 0, as OBJ, ASCII PLY and (pre-triangulated) STL.
const QUAD_AND_PENTAGON_OBJ: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n\
v 2 0 0\nv 3 0 0\nv 3.5 1 0\nv 2.5 2 0\nv 2 1 0\n\
vt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 3/1/1 4/1/1\nf 5 6 7 8 9\n";

const QUAD_AND_PENTAGON_PLY: &str = "ply\nformat ascii 1.0\nelement vertex 9\n\
property float x\nproperty float y\nproperty float z\nproperty uchar red\n\
element face 2\nproperty list uchar int vertex_indices\nend_header\n\
0 0 0 1\n1 0 0 1\n1 1 0 1\n0 1 0 1\n2 0 0 1\n3 0 0 1\n3.5 1 0 1\n2.5 2 0 1\n2 1 0 1\n\
4 0 1 2 3\n5 4 5 6 7 8\n";

#[test]
fn triangle_indices_follow_the_file_after_fan_triangulation() {
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("shapes.obj");
    std::fs::write(&obj, QUAD_AND_PENTAGON_OBJ).unwrap();
    let ply = dir.path().join("shapes.ply");
    std::fs::write(&ply, QUAD_AND_PENTAGON_PLY).unwrap();
    // The fans: quad → 0:(1,2,3) 1:(1,3,4); pentagon → 2:(5,6,7) 3:(5,7,8) 4:(5,8,9).
    let corners: [[usize; 3]; 5] = [[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7], [4, 7, 8]];
    let p = [
        [0.0f32, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [2.0, 0.0, 0.0],
        [3.0, 0.0, 0.0],
        [3.5, 1.0, 0.0],
        [2.5, 2.0, 0.0],
        [2.0, 1.0, 0.0],
    ];
    let stl = dir.path().join("shapes.stl");
    let mut text = String::from("solid shapes\n");
    for c in corners {
        text.push_str("facet normal 0 0 1\nouter loop\n");
        for i in c {
            text.push_str(&format!("vertex {} {} {}\n", p[i][0], p[i][1], p[i][2]));
        }
        text.push_str("endloop\nendfacet\n");
    }
    text.push_str("endsolid shapes\n");
    std::fs::write(&stl, text).unwrap();

    // One ray straight down through each fan triangle's centroid.
    let rays: Vec<Ray> = corners
        .iter()
        .map(|c| {
            let centroid = c
                .iter()
                .fold(Vec3::ZERO, |s, &i| s + Vec3::from_array(p[i]))
                / 3.0;
            Ray::new(centroid + Vec3::Z, -Vec3::Z)
        })
        .collect();
    let ray_file = dir.path().join("rays.bin");
    write_f32s(&ray_file, ray_floats(&rays));
    for input in [&obj, &ply, &stl] {
        let hits = dir.path().join("hits.bin");
        ok(&[&"raycast", input, &"--rays", &ray_file, &"--out", &hits]);
        let got: Vec<(f32, u32)> = read_records(&hits);
        assert_eq!(
            got,
            (0..5).map(|i| (1.0, i)).collect::<Vec<_>>(),
            "{}",
            input.display()
        );
        // A blob baked from the file answers the same.
        let blob = dir.path().join("shapes.meshq");
        ok(&[&"bake", input, &"-o", &blob, &"--packed"]);
        ok(&[&"raycast", &blob, &"--rays", &ray_file, &"--out", &hits]);
        assert_eq!(read_records(&hits), got);
    }
    let _ = MeshRef::new(&p, &[]);
}

fn fails(args: &[&dyn AsRef<std::ffi::OsStr>], status: i32, needle: &str) {
    let out = meshq(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(status), "{stderr}");
    assert!(stderr.contains(needle), "{stderr:?} lacks {needle:?}");
    assert!(
        !stderr.contains("panicked") && !stderr.contains("backtrace"),
        "{stderr}"
    );
    if status == 1 {
        assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    }
}

#[test]
fn errors_are_one_line_and_a_status_never_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let obj = asset("teapot.obj");
    let blob = dir.path().join("t.meshq");
    ok(&[&"bake", &obj, &"-o", &blob]);
    let rays = dir.path().join("rays.bin");
    write_f32s(&rays, [0.0; 12]);
    let out = dir.path().join("out.bin");

    fails(
        &[&"bake", &"no/such/file.obj", &"-o", &blob],
        1,
        "no/such/file.obj",
    );
    fails(&[&"bake", &rays, &"-o", &blob], 1, "unknown mesh format");
    let broken = dir.path().join("broken.obj");
    std::fs::write(&broken, "v 0 0 0\nf 1 2 3\n").unwrap();
    fails(
        &[&"bake", &broken, &"-o", &blob.with_extension("x")],
        1,
        "broken.obj",
    );
    fails(&[&"inspect", &"missing.meshq"], 1, "missing.meshq");

    let mut bytes = std::fs::read(&blob).unwrap();
    let mid = bytes.len() / 2;
    bytes[mid] ^= 0x10;
    let corrupt = dir.path().join("corrupt.meshq");
    std::fs::write(&corrupt, &bytes).unwrap();
    fails(&[&"inspect", &corrupt], 1, "checksum mismatch");
    fails(
        &[&"raycast", &corrupt, &"--rays", &rays, &"--out", &out],
        1,
        "checksum",
    );
    std::fs::write(&corrupt, &bytes[..mid]).unwrap();
    fails(&[&"inspect", &corrupt], 1, "truncated");

    let odd = dir.path().join("odd.bin");
    std::fs::write(&odd, [0u8; 25]).unwrap();
    fails(
        &[&"raycast", &blob, &"--rays", &odd, &"--out", &out],
        1,
        "bad ray file length",
    );
    fails(
        &[&"closest", &blob, &"--points", &odd, &"--out", &out],
        1,
        "bad point file length",
    );

    let bare = dir.path().join("bare.meshq");
    ok(&[&"bake", &obj, &"-o", &bare, &"--no-mesh"]);
    fails(
        &[&"raycast", &bare, &"--rays", &rays, &"--out", &out],
        1,
        "--mesh",
    );
    ok(&[
        &"raycast", &bare, &"--mesh", &obj, &"--rays", &rays, &"--out", &out,
    ]);
    fails(
        &[
            &"raycast",
            &bare,
            &"--mesh",
            &asset("spot.obj"),
            &"--rays",
            &rays,
            &"--out",
            &out,
        ],
        1,
        "not the one the blob was baked from",
    );
    assert!(ok(&[&"inspect", &bare]).contains("omitted"));

    fails(&[&"raycast", &blob, &"--bogus"], 2, "--bogus");
    fails(
        &[&"bake", &obj, &"-o", &blob, &"--no-mesh", &"--packed"],
        2,
        "cannot be used",
    );
}

/// `--structure` builds each of the four structures over a mesh file, or bakes it into a blob;
/// raycast and closest write the same records for all of them, from the mesh and from the blob
/// (indexed and packed), `inspect` describes each, and a blob refuses another structure.
#[test]
fn every_structure_gives_the_same_records() {
    let dir = tempfile::tempdir().unwrap();
    let loaded = load_mesh("spot");
    let obj = asset("spot.obj");
    let rays = workload::random_rays(&loaded.positions, 500, 11);
    let ray_file = dir.path().join("rays.bin");
    write_f32s(&ray_file, ray_floats(&rays));
    let points = workload::closest_points(&loaded.positions, 200, 12);
    let point_file = dir.path().join("points.bin");
    write_f32s(&point_file, points.iter().flat_map(|p| p.to_array()));
    let mut outputs = Vec::new();
    for structure in ["bvh", "kdtree", "octree", "grid"] {
        let hits = dir.path().join(format!("hits-{structure}.bin"));
        ok(&[
            &"raycast",
            &obj,
            &"--structure",
            &structure,
            &"--rays",
            &ray_file,
            &"--out",
            &hits,
        ]);
        let closest = dir.path().join(format!("closest-{structure}.bin"));
        ok(&[
            &"closest",
            &obj,
            &"--structure",
            &structure,
            &"--points",
            &point_file,
            &"--out",
            &closest,
        ]);
        outputs.push((
            structure.to_owned(),
            std::fs::read(&hits).unwrap(),
            std::fs::read(&closest).unwrap(),
        ));
        let text = ok(&[&"inspect", &obj, &"--structure", &structure]);
        assert!(text.starts_with(structure), "{text}");
        assert!(text.contains("references"), "{text}");
        for packed in [false, true] {
            let blob = dir.path().join(format!("spot-{structure}-{packed}.meshq"));
            let mut bake: Vec<&dyn AsRef<std::ffi::OsStr>> =
                vec![&"bake", &obj, &"-o", &blob, &"--structure", &structure];
            if packed {
                bake.push(&"--packed");
            }
            ok(&bake);
            let text = ok(&[&"inspect", &blob]);
            assert!(text.contains(&format!(": {structure} with mesh")), "{text}");
            let name = format!("{structure} blob, packed {packed}");
            let hits = dir.path().join(format!("blob-hits-{structure}.bin"));
            ok(&[&"raycast", &blob, &"--rays", &ray_file, &"--out", &hits]);
            let closest = dir.path().join(format!("blob-closest-{structure}.bin"));
            ok(&[
                &"closest",
                &blob,
                &"--points",
                &point_file,
                &"--out",
                &closest,
            ]);
            outputs.push((
                name,
                std::fs::read(&hits).unwrap(),
                std::fs::read(&closest).unwrap(),
            ));
        }
    }
    let (_, bvh_hits, bvh_closest) = &outputs[0];
    assert!(
        read_records(&dir.path().join("hits-bvh.bin"))
            .iter()
            .any(|&(t, _)| t.is_finite())
    );
    for (structure, hits, closest) in &outputs[1..] {
        assert_eq!(hits, bvh_hits, "{structure}: raycast records");
        assert_eq!(closest, bvh_closest, "{structure}: closest records");
    }
    let blob = dir.path().join("spot-bvh-false.meshq");
    let out = dir.path().join("out.bin");
    fails(
        &[
            &"raycast",
            &blob,
            &"--structure",
            &"grid",
            &"--rays",
            &ray_file,
            &"--out",
            &out,
        ],
        1,
        "holding a bvh, not a grid",
    );
}

/// `meshq remesh` writes a mesh (OBJ and PLY) that reads back with the figures it printed,
/// better shaped than the input, and names the vertex of a mesh it refuses.
#[test]
fn remesh_writes_a_better_mesh_and_refuses_a_non_manifold_one() {
    let dir = tempfile::tempdir().unwrap();
    let spot = asset("spot.obj");
    for ext in ["obj", "ply"] {
        let out = dir.path().join(format!("spot.{ext}"));
        let json = ok(&[
            &"remesh",
            &spot,
            &"-o",
            &out,
            &"--iterations",
            &"4",
            &"--json",
        ]);
        let v: serde_json::Value = serde_json::from_str(&json).unwrap();
        // Read back by the command's own loader: a valid mesh of the printed size.
        let back: serde_json::Value =
            serde_json::from_str(&ok(&[&"inspect", &out, &"--json"])).unwrap();
        assert_eq!(back["triangles"], v["after"]["triangles"], "{ext}");
        let edge_cv = |side: &str| v[side]["edge_length_cv"].as_f64().unwrap();
        assert!(edge_cv("after") < edge_cv("before") / 2.0, "{json}");
        assert!(v["hausdorff_relative"].as_f64().unwrap() < 0.02, "{json}");
        assert_eq!(v["iterations"].as_u64(), Some(4));
        // The peak holds at least the input and the output.
        let count = |key: &str| v[key].as_u64().unwrap();
        let triangles = |side: &str| v[side]["triangles"].as_u64().unwrap();
        assert!(count("peak_triangles") >= triangles("before").max(triangles("after")));
        assert!(count("peak_vertices") > 0, "{json}");
    }
    // --target-ratio 2: about a quarter of the triangles.
    let coarse = dir.path().join("coarse.obj");
    let json = ok(&[
        &"remesh",
        &spot,
        &"-o",
        &coarse,
        &"--target-ratio",
        &"2",
        &"--json",
    ]);
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    let after = v["after"]["triangles"].as_f64().unwrap();
    let before = v["before"]["triangles"].as_f64().unwrap();
    assert!(after < before / 3.0 && after > before / 6.0, "{json}");
    fails(
        &[&"remesh", &asset("cow.obj"), &"-o", &coarse],
        1,
        "vertex 253 form more than one fan",
    );
    fails(
        &[&"remesh", &spot, &"-o", &dir.path().join("x.stl")],
        1,
        "unknown output format",
    );
}

#[test]
fn check_reports_self_intersections_and_contacts_as_brute_force_finds_them() {
    use meshq::geom::{TriangleTriangle, intersect_triangle_triangle, triangles_meet};
    let spot = asset("spot.obj");
    let parse = |s: String| serde_json::from_str::<serde_json::Value>(&s).unwrap();
    let clean = parse(ok(&[&"check", &spot, &"--json"]));
    assert_eq!(clean["self_intersecting_pairs"], 0, "{clean}");
    assert!(clean.get("against").is_none());
    // The same cow moved along x by a quarter of its width: count the meeting pairs by brute
    // force over every pair of triangles.
    let loaded = load_mesh("spot");
    let mesh = loaded.valid();
    let tris: Vec<_> = (0..mesh.triangle_count() as u32)
        .map(|t| mesh.triangle(t).unwrap())
        .collect();
    let (lo, hi) = loaded
        .positions
        .iter()
        .fold((f32::MAX, f32::MIN), |(l, h), p| (l.min(p[0]), h.max(p[0])));
    let shift = (hi - lo) / 4.0;
    let moved: Vec<_> = tris
        .iter()
        .map(|t| {
            let d = Vec3::new(shift, 0.0, 0.0);
            meshq::math::Triangle::new(t.a + d, t.b + d, t.c + d)
        })
        .collect();
    let (mut meeting, mut crossing) = (0usize, 0usize);
    for a in &tris {
        for b in &moved {
            // Meeting decided exactly; crossing where the tolerant test places a segment.
            if triangles_meet(a, b) {
                meeting += 1;
                if let TriangleTriangle::Segment { .. } = intersect_triangle_triangle(a, b) {
                    crossing += 1;
                }
            }
        }
    }
    assert!(meeting > 0);
    let transform = format!("1,0,0,0, 0,1,0,0, 0,0,1,0, {shift},0,0,1");
    let both = parse(ok(&[
        &"check",
        &spot,
        &"--against",
        &spot,
        &"--transform",
        &transform,
        &"--json",
        &"--first",
        &"3",
    ]));
    assert_eq!(both["against"]["intersecting_pairs"], meeting, "{both}");
    assert_eq!(both["against"]["crossing_pairs"], crossing, "{both}");
    assert_eq!(both["against"]["first_pairs"].as_array().unwrap().len(), 3);
    let text = ok(&[
        &"check",
        &spot,
        &"--against",
        &spot,
        &"--transform",
        &transform,
    ]);
    assert!(
        text.contains(&format!("{meeting} intersecting triangle pairs")),
        "{text}"
    );
    // A huge --first allocates no more than the pairs found.
    let huge = parse(ok(&[
        &"check",
        &spot,
        &"--against",
        &spot,
        &"--transform",
        &transform,
        &"--json",
        &"--first",
        &"100000000000",
    ]));
    let listed = huge["against"]["first_pairs"].as_array().unwrap().len();
    assert_eq!(listed, meeting, "{huge}");
    fails(
        &[
            &"check",
            &spot,
            &"--against",
            &spot,
            &"--transform",
            &"1,2,3",
        ],
        1,
        "16 numbers",
    );
    fails(
        &[
            &"check",
            &spot,
            &"--against",
            &spot,
            &"--transform",
            &"1,0,0,1,0,1,0,0,0,0,1,0,0,0,0,1",
        ],
        1,
        "not an affine map",
    );
    fails(&[&"check", &spot, &"--transform", &"1"], 2, "--against");
}

/// `--threads` changes who answers, never the answer: raycast (closest hit, any hit, every
/// hit) and closest records on 2 threads and on one per core equal a brute-force scan and the
/// one-thread records byte for byte; the JSON says how many threads answered.
/// Camera rays share an origin, so batches walk them in packets: the records are those of one
/// ray per call (`--per-ray`) and of a brute-force scan, for closest and any hit.
#[test]
fn batched_camera_rays_give_the_records_of_one_ray_per_call() {
    let dir = tempfile::tempdir().unwrap();
    let loaded = load_mesh("spot");
    let mesh = loaded.valid();
    let brute = BruteForce::new(&mesh);
    let obj = asset("spot.obj");
    // More rays than one batch call takes (16,384), the last batch short.
    let rays = workload::camera_rays(&loaded.positions, 160, 121);
    let ray_file = dir.path().join("camera.bin");
    write_f32s(&ray_file, ray_floats(&rays));
    let options = RayOptions::default();
    for any in [false, true] {
        let mut outputs = Vec::new();
        for (name, extra) in [("batch", &[][..]), ("per-ray", &["--per-ray"][..])] {
            let out = dir.path().join(format!("{name}-{any}.bin"));
            let mut args: Vec<&dyn AsRef<std::ffi::OsStr>> =
                vec![&"raycast", &obj, &"--rays", &ray_file, &"--out", &out];
            if any {
                args.push(&"--any");
            }
            args.extend(extra.iter().map(|f| f as &dyn AsRef<std::ffi::OsStr>));
            ok(&args);
            outputs.push(std::fs::read(&out).unwrap());
        }
        assert_eq!(outputs[0], outputs[1], "any: {any}");
        let records = read_records(&dir.path().join(format!("batch-{any}.bin")));
        assert_eq!(records.len(), rays.len());
        let mut hits = 0;
        for (i, (ray, &(t, tri))) in rays.iter().zip(&records).enumerate() {
            let want = brute.raycast(ray, &options);
            hits += usize::from(want.is_some());
            let want = match (want, any) {
                (None, _) => (f32::INFINITY.to_bits(), u32::MAX),
                (Some(_), true) => (0f32.to_bits(), 0xFFFF_FFFE),
                (Some(h), false) => (h.t.to_bits(), h.tri),
            };
            assert_eq!((t.to_bits(), tri), want, "any: {any}, ray {i}");
        }
        assert!(hits > rays.len() / 10, "{hits} hits");
    }
}

/// `--compact-nodes` quantizes the BVH's wide nodes, `--eight-wide` and `--four-wide` collapse
/// it eight- or four-wide: the records of ray and closest-point queries are byte for byte those
/// of the default nodes, from a mesh file and from a blob; other structures refuse all three,
/// and they exclude each other.
#[test]
fn compact_and_eight_wide_nodes_give_the_same_records() {
    let dir = tempfile::tempdir().unwrap();
    let loaded = load_mesh("spot");
    let obj = asset("spot.obj");
    let mut rays = workload::random_rays(&loaded.positions, 3_000, 31);
    rays.extend(workload::camera_rays(&loaded.positions, 40, 30));
    let ray_file = dir.path().join("rays.bin");
    write_f32s(&ray_file, ray_floats(&rays));
    let points = workload::closest_points(&loaded.positions, 2_000, 32);
    let point_file = dir.path().join("points.bin");
    write_f32s(&point_file, points.iter().flat_map(|p| p.to_array()));
    let blob = dir.path().join("spot.meshq");
    ok(&[&"bake", &obj, &"-o", &blob]);
    let layouts = [
        None,
        Some("--compact-nodes"),
        Some("--eight-wide"),
        Some("--four-wide"),
    ];
    for input in [&obj, &blob] {
        for any in [false, true] {
            let mut outputs = Vec::new();
            for (i, layout) in layouts.iter().enumerate() {
                let out = dir.path().join(format!("hits-{i}.bin"));
                let mut args: Vec<&dyn AsRef<std::ffi::OsStr>> =
                    vec![&"raycast", input, &"--rays", &ray_file, &"--out", &out];
                if any {
                    args.push(&"--any");
                }
                if let Some(flag) = layout {
                    args.push(flag);
                }
                ok(&args);
                outputs.push(std::fs::read(&out).unwrap());
            }
            for (layout, output) in layouts.iter().zip(&outputs) {
                assert_eq!(&outputs[0], output, "{input:?} any: {any} {layout:?}");
            }
        }
        let mut outputs = Vec::new();
        for (i, layout) in layouts.iter().enumerate() {
            let out = dir.path().join(format!("closest-{i}.bin"));
            let mut args: Vec<&dyn AsRef<std::ffi::OsStr>> =
                vec![&"closest", input, &"--points", &point_file, &"--out", &out];
            if let Some(flag) = layout {
                args.push(flag);
            }
            ok(&args);
            outputs.push(std::fs::read(&out).unwrap());
        }
        for (layout, output) in layouts.iter().zip(&outputs) {
            assert_eq!(&outputs[0], output, "{input:?} closest {layout:?}");
        }
    }
    let out = dir.path().join("kd.bin");
    for flag in ["--compact-nodes", "--eight-wide", "--four-wide"] {
        fails(
            &[
                &"raycast",
                &obj,
                &"--structure",
                &"kdtree",
                &flag,
                &"--rays",
                &ray_file,
                &"--out",
                &out,
            ],
            1,
            &format!("{flag} applies to a BVH"),
        );
    }
    for (a, b) in [
        ("--compact-nodes", "--eight-wide"),
        ("--four-wide", "--eight-wide"),
        ("--compact-nodes", "--four-wide"),
    ] {
        fails(
            &[
                &"raycast", &obj, &a, &b, &"--rays", &ray_file, &"--out", &out,
            ],
            2,
            "cannot be used with",
        );
    }
}

#[test]
fn threads_give_the_same_records() {
    let dir = tempfile::tempdir().unwrap();
    let loaded = load_mesh("spot");
    let mesh = loaded.valid();
    let brute = BruteForce::new(&mesh);
    let obj = asset("spot.obj");
    // More than one run of meshq::parallel, so several threads share the work.
    let rays = workload::random_rays(&loaded.positions, 9_000, 21);
    let ray_file = dir.path().join("rays.bin");
    write_f32s(&ray_file, ray_floats(&rays));
    let points = workload::closest_points(&loaded.positions, 9_000, 22);
    let point_file = dir.path().join("points.bin");
    write_f32s(&point_file, points.iter().flat_map(|p| p.to_array()));
    let options = RayOptions::default();
    for flags in [&[][..], &["--any"][..], &["--hits", "3"][..]] {
        let mut outputs = Vec::new();
        for threads in ["1", "2", "0"] {
            let out = dir.path().join(format!("hits-{threads}.bin"));
            let mut args: Vec<&dyn AsRef<std::ffi::OsStr>> = vec![
                &"raycast",
                &obj,
                &"--rays",
                &ray_file,
                &"--out",
                &out,
                &"--threads",
                &threads,
                &"--json",
            ];
            args.extend(flags.iter().map(|f| f as &dyn AsRef<std::ffi::OsStr>));
            let json = ok(&args);
            let want = if threads == "2" {
                "\"threads\":2"
            } else {
                "\"threads\":"
            };
            assert!(json.contains(want), "{json}");
            outputs.push(std::fs::read(&out).unwrap());
        }
        assert_eq!(outputs[1], outputs[0], "{flags:?}: 2 threads");
        assert_eq!(outputs[2], outputs[0], "{flags:?}: a thread per core");
        if flags.is_empty() {
            let records = read_records(&dir.path().join("hits-2.bin"));
            for (i, (ray, &(t, tri))) in rays.iter().zip(&records).enumerate() {
                let want = brute.raycast(ray, &options);
                assert_eq!(
                    (t.to_bits(), tri),
                    want.map_or((f32::INFINITY.to_bits(), u32::MAX), |h| (
                        h.t.to_bits(),
                        h.tri
                    )),
                    "ray {i}"
                );
            }
        }
    }
    let mut outputs = Vec::new();
    for threads in ["1", "2"] {
        let out = dir.path().join(format!("closest-{threads}.bin"));
        ok(&[
            &"closest",
            &obj,
            &"--points",
            &point_file,
            &"--out",
            &out,
            &"--threads",
            &threads,
        ]);
        outputs.push(std::fs::read(&out).unwrap());
    }
    assert_eq!(outputs[1], outputs[0], "closest on 2 threads");
    // A bake on threads (the bunny is large enough to be split in parallel): the same bytes.
    let bunny = asset("stanford-bunny.obj");
    let blobs: Vec<Vec<u8>> = ["1", "2"]
        .iter()
        .map(|threads| {
            let blob = dir.path().join(format!("bunny-{threads}.meshq"));
            ok(&[&"bake", &bunny, &"-o", &blob, &"--threads", threads]);
            std::fs::read(&blob).unwrap()
        })
        .collect();
    assert_eq!(blobs[1], blobs[0], "bake on 2 threads");
    // A thread count past the limit is a usage error, not a crash while the threads start.
    let out = dir.path().join("never.bin");
    fails(
        &[
            &"raycast",
            &obj,
            &"--rays",
            &ray_file,
            &"--out",
            &out,
            &"--threads",
            &"100000",
        ],
        2,
        "not in 0..=1024",
    );
    assert!(!out.exists());
    let records = read_records(&dir.path().join("closest-2.bin"));
    for (i, (&p, &(d, tri))) in points.iter().zip(&records).enumerate() {
        let want = brute
            .closest_point(p, f32::INFINITY)
            .expect("a nearest point");
        assert_eq!(
            (d.to_bits(), tri),
            (want.distance_squared.sqrt().to_bits(), want.tri),
            "point {i}"
        );
    }
}

/// Casts 3,000 random rays at each input (`raycast INPUT-ARGS --rays … --out …`) and checks
/// every record against brute force on `loaded`.
fn assert_raycast_records_are_brute_force(
    dir: &std::path::Path,
    loaded: &meshq_tests::LoadedMesh,
    seed: u64,
    inputs: &[Vec<&dyn AsRef<std::ffi::OsStr>>],
) {
    assert_records_with_test_are_brute_force(dir, loaded, seed, inputs, TriangleTest::Watertight);
}

/// [`assert_raycast_records_are_brute_force`] with `--triangle-test` naming `test`, checked
/// against the brute-force scan with that test.
fn assert_records_with_test_are_brute_force(
    dir: &std::path::Path,
    loaded: &meshq_tests::LoadedMesh,
    seed: u64,
    inputs: &[Vec<&dyn AsRef<std::ffi::OsStr>>],
    test: TriangleTest,
) {
    let options = RayOptions {
        test,
        ..RayOptions::default()
    };
    let mesh = loaded.valid();
    let rays = workload::random_rays(&loaded.positions, 3_000, seed);
    let ray_file = dir.join("rays.bin");
    write_f32s(&ray_file, ray_floats(&rays));
    let brute = BruteForce::new(&mesh);
    let expected: Vec<(u32, u32)> = rays
        .iter()
        .map(|r| {
            brute
                .raycast(r, &options)
                .map_or((f32::INFINITY.to_bits(), u32::MAX), |h| {
                    (h.t.to_bits(), h.tri)
                })
        })
        .collect();
    let hits = dir.join("hits.bin");
    let test_name = test.name();
    for args in inputs {
        let mut all: Vec<&dyn AsRef<std::ffi::OsStr>> = vec![&"raycast"];
        all.extend(args.iter().copied());
        all.extend([
            &"--rays" as &dyn AsRef<std::ffi::OsStr>,
            &ray_file,
            &"--out",
            &hits,
            &"--triangle-test",
            &test_name,
        ]);
        ok(&all);
        let got: Vec<(u32, u32)> = read_records(&hits)
            .into_iter()
            .map(|(t, i)| (t.to_bits(), i))
            .collect();
        assert_eq!(got, expected);
    }
}

#[test]
fn every_triangle_test_answers_as_brute_force_with_that_test() {
    let dir = tempfile::tempdir().unwrap();
    let loaded = load_mesh("spot");
    let obj = asset("spot.obj");
    for test in TriangleTest::ALL {
        assert_records_with_test_are_brute_force(
            dir.path(),
            &loaded,
            80,
            &[
                vec![&obj as &dyn AsRef<std::ffi::OsStr>],
                vec![&obj, &"--per-ray"],
                vec![&obj, &"--structure", &"kdtree"],
            ],
            test,
        );
    }
}

#[test]
fn spatial_splits_bake_a_version_5_blob_that_answers_as_brute_force() {
    let dir = tempfile::tempdir().unwrap();
    let loaded = load_mesh("fandisk");
    let mesh = loaded.valid();
    let obj = asset("fandisk.obj");
    let blob = dir.path().join("fandisk.meshq");
    let bake: serde_json::Value = serde_json::from_str(&ok(&[
        &"bake",
        &obj,
        &"-o",
        &blob,
        &"--spatial-splits",
        &"--json",
    ]))
    .unwrap();
    let references = bake["references"].as_u64().unwrap();
    assert!(references > mesh.triangle_count() as u64, "{bake}");
    // On two threads: the same blob, byte for byte.
    let threaded = dir.path().join("fandisk-2.meshq");
    ok(&[
        &"bake",
        &obj,
        &"-o",
        &threaded,
        &"--spatial-splits",
        &"--threads",
        &"2",
    ]);
    assert_eq!(
        std::fs::read(&threaded).unwrap(),
        std::fs::read(&blob).unwrap()
    );
    let inspect: serde_json::Value =
        serde_json::from_str(&ok(&[&"inspect", &blob, &"--json"])).unwrap();
    assert_eq!(inspect["format_version"], 5);
    assert_eq!(inspect["references"], references);
    assert!(inspect["split_refs"].as_u64().unwrap() > 0);
    assert!(ok(&[&"inspect", &blob]).contains("spatial splits"));

    assert_raycast_records_are_brute_force(
        dir.path(),
        &loaded,
        78,
        &[
            vec![&blob as &dyn AsRef<std::ffi::OsStr>],
            vec![&obj, &"--spatial-splits", &"0.5"],
        ],
    );
    // Out of range, or for another structure: one line, non-zero status.
    for bad in [
        vec![
            &"bake" as &dyn AsRef<std::ffi::OsStr>,
            &obj,
            &"-o",
            &blob,
            &"--spatial-splits",
            &"5",
        ],
        vec![
            &"bake",
            &obj,
            &"-o",
            &blob,
            &"--spatial-splits",
            &"--structure",
            &"grid",
        ],
    ] {
        let out = meshq(&bad);
        assert!(!out.status.success());
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("--spatial-splits"), "{err}");
    }
}

#[test]
fn sweep_builds_bake_the_library_tree_and_answer_as_brute_force() {
    let dir = tempfile::tempdir().unwrap();
    let loaded = load_mesh("fandisk");
    let mesh = loaded.valid();
    let obj = asset("fandisk.obj");
    let blob = dir.path().join("fandisk.meshq");
    ok(&[&"bake", &obj, &"-o", &blob, &"--sweep-sah"]);
    // On two threads: the same blob, byte for byte.
    let threaded = dir.path().join("fandisk-2.meshq");
    ok(&[
        &"bake",
        &obj,
        &"-o",
        &threaded,
        &"--sweep-sah",
        &"--threads",
        &"2",
    ]);
    assert_eq!(
        std::fs::read(&threaded).unwrap(),
        std::fs::read(&blob).unwrap()
    );
    // The library's sweep tree, node for node (its SAH cost and node count).
    let config = meshq::bvh::BuildConfig {
        split: meshq::bvh::SplitStrategy::Sweep { step: 32 },
        ..meshq::bvh::BuildConfig::default()
    };
    let library = meshq::MeshBvh::build(&mesh, &config).unwrap();
    let inspect: serde_json::Value =
        serde_json::from_str(&ok(&[&"inspect", &blob, &"--json"])).unwrap();
    assert_eq!(inspect["config"]["split"], "sweep", "{inspect}");
    assert_eq!(inspect["config"]["sweep_step"], 32, "{inspect}");
    assert_eq!(inspect["nodes"], library.bvh().nodes().len());
    assert!(ok(&[&"inspect", &blob]).contains("sweep SAH"));

    assert_raycast_records_are_brute_force(
        dir.path(),
        &loaded,
        79,
        &[
            vec![&blob as &dyn AsRef<std::ffi::OsStr>],
            vec![&obj, &"--sweep-sah", &"1"],
        ],
    );
    // A step of 0, or with spatial splits: one message naming the option, non-zero status.
    for bad in [
        vec![
            &"bake" as &dyn AsRef<std::ffi::OsStr>,
            &obj,
            &"-o",
            &blob,
            &"--sweep-sah",
            &"0",
        ],
        vec![
            &"bake",
            &obj,
            &"-o",
            &blob,
            &"--sweep-sah",
            &"--spatial-splits",
        ],
    ] {
        let out = meshq(&bad);
        assert!(!out.status.success());
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("--sweep-sah"), "{err}");
    }
}

#[test]
fn inside_and_signed_closest_give_the_library_answers_on_every_input() {
    use meshq::inside::WindingAccuracy;
    let dir = tempfile::tempdir().unwrap();
    let mesh_path = asset("spot.obj");
    let loaded = load_mesh("spot");
    let mesh = MeshRef::new(&loaded.positions, &loaded.triangles)
        .validate()
        .unwrap();
    let scene = MeshBvh::build(&mesh, &BuildConfig::default())
        .unwrap()
        .with_winding_numbers()
        .unwrap();
    let tree = scene.winding().unwrap();
    let mut points = workload::closest_points(&loaded.positions, 3000, 5);
    points.push(Vec3::new(f32::NAN, 0.0, 0.0));
    let points_path = dir.path().join("points.bin");
    write_f32s(&points_path, points.iter().flat_map(|p| p.to_array()));
    let blob = dir.path().join("spot.meshq");
    ok(&[&"bake", &mesh_path, &"-o", &blob]);
    // With the expansions stored: format version 6, 112 bytes per node, the same answers.
    let stored = dir.path().join("spot-winding.meshq");
    ok(&[
        &"bake",
        &mesh_path,
        &"-o",
        &stored,
        &"--winding",
        &"--packed",
    ]);
    let report: serde_json::Value =
        serde_json::from_str(&ok(&[&"inspect", &stored, &"--json"])).unwrap();
    assert_eq!(report["format_version"], 6, "{report}");
    assert_eq!(
        report["bytes"]["winding"],
        112 * report["nodes"].as_u64().unwrap(),
        "{report}"
    );
    fails(
        &[
            &"bake",
            &mesh_path,
            &"-o",
            &stored,
            &"--winding",
            &"--structure",
            &"octree",
        ],
        1,
        "--winding applies to a BVH",
    );
    for accuracy in ["2", "3", "exact"] {
        let wanted = match accuracy {
            "exact" => WindingAccuracy::EXACT,
            ratio => WindingAccuracy::new(ratio.parse().unwrap()).unwrap(),
        };
        let out = dir.path().join(format!("inside-{accuracy}.bin"));
        ok(&[
            &"inside",
            &mesh_path,
            &"--points",
            &points_path,
            &"--out",
            &out,
            &"--accuracy",
            &accuracy,
        ]);
        let records = read_records(&out);
        assert_eq!(records.len(), points.len());
        for (&(w, inside), &p) in records.iter().zip(&points) {
            let want = tree.winding_number(p, wanted);
            assert_eq!(w.to_bits(), want.to_bits(), "{accuracy} at {p}");
            assert_eq!(inside, u32::from(want.abs() >= 0.5), "{accuracy} at {p}");
        }
        // A blob, an octree, two threads: the same records, byte for byte.
        for extra in [
            vec![blob.as_os_str()],
            vec![stored.as_os_str()],
            vec![
                mesh_path.as_os_str(),
                "--structure".as_ref(),
                "octree".as_ref(),
            ],
            vec![mesh_path.as_os_str(), "--threads".as_ref(), "2".as_ref()],
        ] {
            let again = dir.path().join("again.bin");
            let mut args: Vec<&dyn AsRef<std::ffi::OsStr>> = vec![&"inside"];
            for a in &extra {
                args.push(a);
            }
            args.extend([
                &"--points" as &dyn AsRef<std::ffi::OsStr>,
                &points_path,
                &"--out",
                &again,
            ]);
            args.extend([&"--accuracy" as &dyn AsRef<std::ffi::OsStr>, &accuracy]);
            ok(&args);
            assert_eq!(
                std::fs::read(&again).unwrap(),
                std::fs::read(&out).unwrap(),
                "{extra:?}"
            );
        }
    }
    let signed = dir.path().join("signed.bin");
    ok(&[
        &"closest",
        &mesh_path,
        &"--points",
        &points_path,
        &"--out",
        &signed,
        &"--signed",
        &"--max-distance",
        &"0.02",
    ]);
    let records = read_records(&signed);
    let (mut negative, mut found) = (0, 0);
    for (&(d, tri), &p) in records.iter().zip(&points) {
        match tree.signed_distance(p, 0.02, WindingAccuracy::DEFAULT) {
            Some(s) => {
                assert_eq!(
                    (d.to_bits(), tri),
                    (s.distance.to_bits(), s.closest.tri),
                    "{p}"
                );
                negative += usize::from(d < 0.0);
                found += 1;
            }
            None => assert_eq!((d, tri), (f32::INFINITY, u32::MAX), "{p}"),
        }
    }
    assert!(
        negative > 10 && found > negative,
        "{negative} inside of {found}"
    );
    fails(
        &[
            &"inside",
            &mesh_path,
            &"--points",
            &points_path,
            &"--out",
            &signed,
            &"--accuracy",
            &"0.5",
        ],
        2,
        "ratio ≥ 1",
    );
    fails(
        &[
            &"closest",
            &mesh_path,
            &"--points",
            &points_path,
            &"--out",
            &signed,
            &"--accuracy",
            &"2",
        ],
        2,
        "--signed",
    );
}

#[test]
fn sdf_writes_the_library_volume_as_nrrd() {
    use meshq::inside::{SampleGrid, WindingAccuracy};
    let dir = tempfile::tempdir().unwrap();
    let mesh_path = asset("spot.obj");
    let loaded = load_mesh("spot");
    let mesh = MeshRef::new(&loaded.positions, &loaded.triangles)
        .validate()
        .unwrap();
    let scene = MeshBvh::build(&mesh, &BuildConfig::default())
        .unwrap()
        .with_winding_numbers()
        .unwrap();
    let tree = scene.winding().unwrap();
    let grid = SampleGrid::cubic(mesh.bounds(), 20, 0.1).unwrap();
    let mut want = vec![0.0f32; grid.len()];
    tree.signed_distance_grid(&scene, &grid, 0.05, WindingAccuracy::DEFAULT, 0, &mut want)
        .unwrap();
    let one = dir.path().join("one.nrrd");
    let two = dir.path().join("two.nrrd");
    ok(&[
        &"sdf",
        &mesh_path,
        &"-o",
        &one,
        &"--resolution",
        &"20",
        &"--band",
        &"0.05",
    ]);
    ok(&[
        &"sdf",
        &mesh_path,
        &"-o",
        &two,
        &"--resolution",
        &"20",
        &"--band",
        &"0.05",
        &"--threads",
        &"2",
    ]);
    let bytes = std::fs::read(&one).unwrap();
    assert_eq!(bytes, std::fs::read(&two).unwrap());
    let end = bytes.windows(2).position(|w| w == b"\n\n").unwrap() + 2;
    let header = std::str::from_utf8(&bytes[..end]).unwrap();
    let [nx, ny, nz] = grid.counts();
    assert!(header.starts_with("NRRD0004\n"), "{header}");
    assert!(
        header.contains(&format!("sizes: {nx} {ny} {nz}\n")),
        "{header}"
    );
    assert!(header.contains("type: float\n") && header.contains("endian: little\n"));
    let values: Vec<f32> = bytes[end..]
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes(b.try_into().unwrap()))
        .collect();
    assert_eq!(values.len(), grid.len());
    assert!(
        values
            .iter()
            .zip(&want)
            .all(|(a, b)| a.to_bits() == b.to_bits())
    );
    assert!(values.iter().any(|&v| v < 0.0) && values.contains(&0.05));
    fails(
        &[&"sdf", &mesh_path, &"-o", &one, &"--resolution", &"1"],
        2,
        "resolution",
    );
    fails(
        &[&"sdf", &mesh_path, &"-o", &one, &"--band=0"],
        2,
        "distance > 0",
    );
}

#[test]
fn distance_reports_the_brute_force_closest_pair() {
    use meshq_tests::distance_oracle::{self, Tri64, point_triangle_squared, widen};
    let spot = asset("spot.obj");
    let parse = |s: String| serde_json::from_str::<serde_json::Value>(&s).unwrap();
    let loaded = load_mesh("spot");
    let mesh = loaded.valid();
    let tris: Vec<Tri64> = (0..mesh.triangle_count() as u32)
        .map(|t| widen(&mesh.triangle(t).unwrap()))
        .collect();
    let width = loaded
        .positions
        .iter()
        .fold((f32::MAX, f32::MIN), |(l, h), p| (l.min(p[0]), h.max(p[0])));
    let size = (width.1 - width.0) as f64;
    // Apart (a little more than its width along x) and crossing (a quarter of it).
    for (shift, meets) in [
        (1.1 * (width.1 - width.0), false),
        (0.25 * (width.1 - width.0), true),
    ] {
        let transform = format!("1,0,0,0,0,1,0,0,0,0,1,0,{shift},0,0,1");
        let report = parse(ok(&[
            &"distance",
            &spot,
            &spot,
            &"--transform",
            &transform,
            &"--json",
        ]));
        let moved: Vec<Tri64> = (0..mesh.triangle_count() as u32)
            .map(|t| {
                let d = Vec3::new(shift, 0.0, 0.0);
                let t = mesh.triangle(t).unwrap();
                widen(&meshq::math::Triangle::new(t.a + d, t.b + d, t.c + d))
            })
            .collect();
        let expected = distance_oracle::mesh_mesh(&tris, &moved);
        let c = &report["closest"];
        let got = c["distance"].as_f64().unwrap();
        assert!(
            (got - expected).abs() <= size * 1e-6,
            "{report}: brute force {expected}"
        );
        assert_eq!(report["meets"], meets, "{report}");
        let point = |v: &serde_json::Value| {
            Vec3::new(
                v[0].as_f64().unwrap() as f32,
                v[1].as_f64().unwrap() as f32,
                v[2].as_f64().unwrap() as f32,
            )
            .as_dvec3()
        };
        let ta = &tris[c["triangle_a"].as_u64().unwrap() as usize];
        let tb = &moved[c["triangle_b"].as_u64().unwrap() as usize];
        assert!(point_triangle_squared(point(&c["point_a"]), ta).sqrt() <= size * 1e-6);
        assert!(point_triangle_squared(point(&c["point_b"]), tb).sqrt() <= size * 1e-6);
        // Below the distance, nothing is found; the text says so.
        if !meets {
            let limit = format!("{}", expected * 0.5);
            let far = parse(ok(&[
                &"distance",
                &spot,
                &spot,
                &"--transform",
                &transform,
                &"--max-distance",
                &limit,
                &"--json",
            ]));
            assert!(far["closest"].is_null(), "{far}");
            let text = ok(&[
                &"distance",
                &spot,
                &spot,
                &"--transform",
                &transform,
                &"--max-distance",
                &limit,
            ]);
            assert!(text.contains("farther apart than"), "{text}");
        }
    }
    fails(
        &[&"distance", &spot, &spot, &"--max-distance=-1"],
        1,
        "--max-distance",
    );
    fails(
        &[&"distance", &spot, &spot, &"--transform", &"1,2"],
        1,
        "16 numbers",
    );
    fails(&[&"distance", &spot], 2, "<OTHER>");
    fails(
        &[
            &"distance",
            &spot,
            &spot,
            &"--max-pair-tests",
            &"1",
            &"--transform",
            &"1,0,0,0,0,1,0,0,0,0,1,0,2,0,0,1",
        ],
        1,
        "--max-pair-tests",
    );
}

#[test]
fn sweep_records_are_the_library_answers_on_any_thread_count() {
    use meshq::math::Obb;
    use meshq::query::{MeshQuery, SweepShape};
    let spot = asset("spot.obj");
    let loaded = load_mesh("spot");
    let mesh = loaded.valid();
    let bvh = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
    let dir = tempfile::tempdir().unwrap();
    // Shapes starting around the cow, moved through its middle.
    let mut spheres = Vec::new();
    let mut boxes = Vec::new();
    let mut expected_spheres = Vec::new();
    let mut expected_boxes = Vec::new();
    for k in 0..40 {
        let a = k as f32 * 0.7;
        let start = Vec3::new(a.cos() * 1.5, 0.3 * (a * 1.3).sin(), a.sin() * 1.5);
        let motion = -start * 2.0 + Vec3::new(0.0, 0.1, 0.0);
        let r = 0.02 + 0.01 * (k % 5) as f32;
        spheres.extend([start.x, start.y, start.z, r, motion.x, motion.y, motion.z]);
        expected_spheres.push(
            bvh.sweep(
                &SweepShape::Sphere {
                    center: start,
                    radius: r,
                },
                motion,
            )
            .unwrap(),
        );
        let obb = Obb::new(start, [Vec3::X, Vec3::Y, Vec3::Z], Vec3::new(r, 2.0 * r, r));
        boxes.extend(start.to_array());
        boxes.extend([1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]);
        boxes.extend([r, 2.0 * r, r]);
        boxes.extend(motion.to_array());
        expected_boxes.push(bvh.sweep(&SweepShape::Box(obb), motion).unwrap());
    }
    let read = |path: &Path| {
        let bytes = std::fs::read(path).unwrap();
        bytes
            .chunks_exact(32)
            .map(|r| {
                let f = |i: usize| f32::from_le_bytes(r[i..i + 4].try_into().unwrap());
                let tri = u32::from_le_bytes(r[4..8].try_into().unwrap());
                (f(0), tri, [f(8), f(12), f(16)], [f(20), f(24), f(28)])
            })
            .collect::<Vec<_>>()
    };
    for (shape, floats, expected) in [
        ("sphere", &spheres, &expected_spheres),
        ("box", &boxes, &expected_boxes),
    ] {
        let input = dir.path().join(format!("{shape}.bin"));
        write_f32s(&input, floats.iter().copied());
        let mut outputs = Vec::new();
        for threads in ["1", "2"] {
            let out = dir.path().join(format!("{shape}-{threads}.out"));
            let json = ok(&[
                &"sweep",
                &spot,
                &"--shape",
                &shape,
                &"--sweeps",
                &input,
                &"--out",
                &out,
                &"--threads",
                &threads,
                &"--json",
            ]);
            let summary: serde_json::Value = serde_json::from_str(&json).unwrap();
            assert_eq!(summary["sweeps"], 40, "{summary}");
            let hits = expected.iter().filter(|h| h.is_some()).count();
            assert_eq!(summary["hits"], hits as u64, "{summary}");
            assert!(hits >= 20, "{shape}: {hits} hits");
            let records = read(&out);
            for (k, (r, e)) in records.iter().zip(expected.iter()).enumerate() {
                match e {
                    Some(h) => {
                        assert_eq!((r.0.to_bits(), r.1), (h.t.to_bits(), h.tri), "{shape} {k}");
                        assert_eq!(
                            (r.2, r.3),
                            (h.point.to_array(), h.normal.to_array()),
                            "{shape} {k}"
                        );
                    }
                    None => {
                        assert_eq!((r.0, r.1), (f32::INFINITY, u32::MAX), "{shape} {k}");
                        assert!(r.2.iter().chain(&r.3).all(|x| x.is_nan()));
                    }
                }
            }
            outputs.push(std::fs::read(&out).unwrap());
        }
        assert_eq!(
            outputs[0], outputs[1],
            "{shape}: threads change the records"
        );
    }
    // A bad record is an error naming it, and no output is left.
    let bad = dir.path().join("bad.bin");
    let mut floats = spheres.clone();
    floats[7 * 3 + 3] = -1.0;
    write_f32s(&bad, floats);
    let out = dir.path().join("bad.out");
    fails(
        &[
            &"sweep",
            &spot,
            &"--shape",
            &"sphere",
            &"--sweeps",
            &bad,
            &"--out",
            &out,
        ],
        1,
        "sweep 3",
    );
    assert!(!out.exists());
    let short = dir.path().join("short.bin");
    write_f32s(&short, spheres[..10].iter().copied());
    fails(
        &[
            &"sweep",
            &spot,
            &"--shape",
            &"sphere",
            &"--sweeps",
            &short,
            &"--out",
            &out,
        ],
        1,
        "sweep",
    );
}

#[test]
fn pseudo_normal_signs_are_the_library_answers_and_refuse_open_meshes() {
    use meshq::owned::MeshPseudoNormals;
    let dir = tempfile::tempdir().unwrap();
    let spot = asset("spot.obj");
    let loaded = load_mesh("spot");
    let mesh = loaded.valid();
    let scene = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
    let normals = MeshPseudoNormals::of(&mesh).unwrap();
    let points = workload::closest_points(&loaded.positions, 2000, 9);
    let points_path = dir.path().join("points.bin");
    write_f32s(&points_path, points.iter().flat_map(|p| p.to_array()));
    let out = dir.path().join("signed.bin");
    let json = ok(&[
        &"closest",
        &spot,
        &"--points",
        &points_path,
        &"--out",
        &out,
        &"--signed",
        &"--sign",
        &"pseudo-normal",
        &"--json",
    ]);
    let summary: serde_json::Value = serde_json::from_str(&json).unwrap();
    let records = read_records(&out);
    let mut inside = 0;
    for (&(d, tri), &p) in records.iter().zip(&points) {
        let want = normals
            .view()
            .signed_distance(&scene, &mesh, p, f32::INFINITY)
            .unwrap();
        assert_eq!(
            (d.to_bits(), tri),
            (want.distance.to_bits(), want.closest.tri),
            "at {p}"
        );
        inside += u64::from(d < 0.0);
    }
    assert!(inside > 100, "{inside} inside");
    assert_eq!(summary["inside"], inside, "{summary}");
    // The bunny has holes: refused naming the edge; --sign needs --signed.
    let bunny = asset("stanford-bunny.obj");
    fails(
        &[
            &"closest",
            &bunny,
            &"--points",
            &points_path,
            &"--out",
            &out,
            &"--signed",
            &"--sign",
            &"pseudo-normal",
        ],
        1,
        "borders no other triangle",
    );
    fails(
        &[
            &"closest",
            &spot,
            &"--points",
            &points_path,
            &"--out",
            &out,
            &"--sign",
            &"pseudo-normal",
        ],
        2,
        "--signed",
    );
}
