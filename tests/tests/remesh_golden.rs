//! The golden remeshing file `tests/golden/remesh.txt`, which the WebAssembly tests and the
//! firmware check too: remeshing is deterministic, so every target must give these bits.
//!
//! Natively, three routes must agree before the file is compared: the owned
//! [`Remeshed::of`], the core [`remesh`] over tight caller buffers projecting onto an
//! in-memory BVH, and the same projecting onto a blob view of the input (what the firmware
//! does from flash). After an intended change of results, rewrite the file with
//! `MESHQ_BLESS_GOLDEN=1 cargo test -p meshq-tests --test integration remesh_golden::`.

use std::fmt::Write as _;
use std::path::PathBuf;

use meshq::MeshBvh;
use meshq::blob::{BlobView, MeshLayout};
use meshq::bvh::BuildConfig;
use meshq::error::RemeshError;
use meshq::mesh::ValidMesh;
use meshq::owned::Remeshed;
use meshq::query::MeshQuery;
use meshq::remesh::{
    EdgeTarget, HalfEdgeBuffers, HalfEdgeMesh, RemeshCapacity, RemeshConfig, remesh,
};
use meshq_tests::{bake, load_mesh};
use meshq_workload::{MeshDigest, RemeshGolden, find_remesh_golden};

/// The meshes in the file: the firmware's small sphere and two bundled scans.
const MESHES: [&str; 3] = ["uv-sphere", "spot", "fandisk"];

fn golden_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("golden/remesh.txt")
}

/// Remeshes through the core API into buffers of `capacity`, projecting onto `reference`.
fn core_route<Q: MeshQuery + ?Sized>(
    mesh: &ValidMesh<'_>,
    reference: &Q,
    config: &RemeshConfig,
    capacity: RemeshCapacity,
) -> Result<MeshDigest, RemeshError> {
    let (v, h) = (capacity.vertices, capacity.half_edges());
    let mut positions = vec![[0.0f32; 3]; v];
    let mut origins = vec![0u32; h];
    let mut twins = vec![0u32; h];
    let mut vertex_half_edges = vec![0u32; v];
    let mut creases = vec![false; h];
    let mut pairing = vec![0u32; capacity.pairing_scratch()];
    let mut he = HalfEdgeMesh::from_mesh(
        mesh,
        HalfEdgeBuffers {
            positions: &mut positions,
            origins: &mut origins,
            twins: &mut twins,
            vertex_half_edges: &mut vertex_half_edges,
            creases: &mut creases,
        },
        &mut pairing,
    )
    .unwrap();
    let mut smoothing = vec![[0.0f32; 3]; v];
    remesh(&mut he, reference, config, &mut smoothing)?;
    Ok(MeshDigest::of(
        (0..he.vertex_count() as u32).map(|i| he.position(i).to_array()),
        (0..he.triangle_count() as u32).map(|t| he.triangle(t)),
    ))
}

fn computed_line(name: &str) -> String {
    let loaded = load_mesh(name);
    let mesh = loaded.valid();
    let config = RemeshConfig::default();

    let owned = Remeshed::of(&mesh, &config).unwrap();
    let expected = MeshDigest::of(
        owned.positions.iter().copied(),
        owned.triangles.iter().copied(),
    );

    // Tight buffers: three times the output, far below the sizing estimate, so the
    // result cannot depend on how much room there is.
    let estimate = RemeshCapacity::for_mesh(&mesh, EdgeTarget::default());
    let tight = RemeshCapacity {
        vertices: (expected.vertices as usize * 3).max(mesh.vertex_count()) + 16,
        triangles: (expected.triangles as usize * 3).max(mesh.triangle_count()) + 32,
    };
    assert!(tight.triangles < estimate.triangles, "{name}: {tight:?}");
    let bvh = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
    assert_eq!(
        core_route(&mesh, &bvh, &config, tight),
        Ok(expected),
        "{name}: core route, in-memory BVH"
    );
    // The reported peak is exactly the room the run needs: one triangle or one vertex less
    // stops it with a capacity error.
    let peak = RemeshCapacity {
        vertices: owned.report.peak_vertices,
        triangles: owned.report.peak_triangles,
    };
    assert_eq!(
        core_route(&mesh, &bvh, &config, peak),
        Ok(expected),
        "{name}: peak"
    );
    for short in [
        RemeshCapacity {
            vertices: peak.vertices - 1,
            ..peak
        },
        RemeshCapacity {
            triangles: peak.triangles - 1,
            ..peak
        },
    ] {
        assert!(
            matches!(
                core_route(&mesh, &bvh, &config, short),
                Err(RemeshError::OutOfCapacity { .. })
            ),
            "{name}: {short:?} is below the peak"
        );
    }
    let blob = bake(&mesh, &BuildConfig::default(), MeshLayout::Indexed).unwrap();
    let view = BlobView::parse(&blob).unwrap();
    assert_eq!(
        core_route(&mesh, &view, &config, estimate),
        Ok(expected),
        "{name}: core route, blob view"
    );

    RemeshGolden {
        mesh: name,
        triangles_in: u32::try_from(mesh.triangle_count()).unwrap(),
        iterations: config.iterations,
        result: expected,
    }
    .to_string()
}

const HEADER: &str = "\
# meshq remeshing golden file: one line per mesh, remeshed with the default config (target
# length = mean edge length, 10 iterations, no feature angle) onto a default BVH of the input.
# Checked by the native tests (tests/tests/remesh_golden.rs: owned, core and blob-view routes
# agree), the WebAssembly tests and the firmware under QEMU (uv-sphere). digest = CRC-64/XZ
# over every position bit and triangle index (meshq_workload::MeshDigest). Rewrite with
# MESHQ_BLESS_GOLDEN=1 only after an intended change.
";

#[test]
fn every_route_gives_the_golden_remesh() {
    let lines: Vec<String> = MESHES.iter().map(|name| computed_line(name)).collect();
    if std::env::var_os("MESHQ_BLESS_GOLDEN").is_some() {
        let mut file = String::from(HEADER);
        for line in &lines {
            writeln!(file, "{line}").unwrap();
        }
        std::fs::write(golden_path(), &file).unwrap();
        return;
    }
    let recorded = std::fs::read_to_string(golden_path()).unwrap();
    for (name, line) in MESHES.iter().zip(&lines) {
        let recorded_entry = find_remesh_golden(&recorded, name)
            .unwrap_or_else(|e| panic!("{name}: {e} (bless with MESHQ_BLESS_GOLDEN=1)"));
        assert_eq!(
            recorded_entry,
            find_remesh_golden(line, name).unwrap(),
            "{name}: remeshing gives other bits than the golden file; if results changed on \
             purpose, rewrite it with MESHQ_BLESS_GOLDEN=1"
        );
    }
}
