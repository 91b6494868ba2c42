//! Writes the remeshing tests' hard-input corpus as OBJ files, so the remeshing benchmark
//! (`bench/peers/remesh.py --corpus DIR`) compares meshq with gpytoolbox on exactly the meshes
//! the tests remesh.
//!
//! `cargo run --release -p meshq-bench --example hard_corpus -- DIR`

use std::fmt::Write as _;
use std::path::PathBuf;

use meshq_tests::hard_inputs::{Mesh, capsule, cone, cuboid, range_scan, slivers, sphere, tube};

fn obj((positions, triangles): &Mesh) -> String {
    let mut text = String::new();
    for [x, y, z] in positions {
        let _ = writeln!(text, "v {x} {y} {z}");
    }
    for [a, b, c] in triangles {
        let _ = writeln!(text, "f {} {} {}", a + 1, b + 1, c + 1);
    }
    text
}

fn main() -> std::io::Result<()> {
    let dir = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "target/hard-corpus".into()),
    );
    std::fs::create_dir_all(&dir)?;
    let corpus = [
        ("capsule-16", capsule(16, 0.05, 1.0)),
        ("capsule-32", capsule(32, 0.05, 1.0)),
        ("capsule-64", capsule(64, 0.05, 1.0)),
        ("cone-1024", cone(1024, 0.5, 1.0)),
        ("tube-24", tube(24, 0.05, 1.0)),
        ("box-flat", cuboid(1.0, 0.3, 0.1)),
        ("box-cube", cuboid(1.0, 1.0, 1.0)),
        ("slivers-12", slivers(12)),
        ("sphere-stretched-6", sphere(2, [6.0, 1.0, 1.0])),
        ("sphere-stretched-10", sphere(3, [10.0, 1.0, 0.5])),
        // The 100k-triangle open scan the issue times (99,458 triangles).
        ("scan-224", range_scan(224)),
    ];
    for (name, mesh) in &corpus {
        let path = dir.join(format!("{name}.obj"));
        std::fs::write(&path, obj(mesh))?;
        println!("{} ({} triangles)", path.display(), mesh.1.len());
    }
    Ok(())
}
