//! Sizes of the four structures on each mesh and its stadium: bytes per triangle of the
//! structure's own arrays and of the packed triangles queries read, references per triangle,
//! cells, empty cells, depth. Deterministic (no timing).
//!
//! `cargo run --release -p meshq-bench --example structures [mesh names or .obj paths]`
//! (default: every bundled mesh).

use meshq::owned::{MeshIndex, StructureKind};
use meshq_tests::{MESHES, in_stadium, load_mesh, load_obj};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let names: Vec<String> = if args.is_empty() {
        MESHES.iter().map(|s| (*s).to_string()).collect()
    } else {
        args
    };
    println!(
        "| scene | structure | structure B/tri | packed B/tri | refs/tri | cells | empty cells | depth |"
    );
    println!("|---|---|---:|---:|---:|---:|---:|---:|");
    for name in names {
        let mesh = if name.ends_with(".obj") {
            load_obj(std::path::Path::new(&name))
        } else {
            load_mesh(&name)
        };
        for scene in [mesh.clone(), in_stadium(&mesh)] {
            let valid = scene.valid();
            let n = valid.triangle_count() as f64;
            for kind in StructureKind::ALL {
                let index = MeshIndex::build(&valid, kind).expect("builds");
                let (structure, packed) = match &index {
                    MeshIndex::Bvh(s) => (
                        size_of_val(s.bvh().nodes())
                            + size_of_val(s.bvh().order())
                            + s.query_node_bytes(),
                        size_of_val(s.packed().as_slice()),
                    ),
                    MeshIndex::KdTree(s) => (s.structure_bytes(), s.packed_bytes()),
                    MeshIndex::Octree(s) => (s.structure_bytes(), s.packed_bytes()),
                    MeshIndex::Grid(s) => (s.structure_bytes(), s.packed_bytes()),
                };
                let (refs, cells, empty, depth) = index.cell_stats().map_or(
                    (
                        "1.00".to_string(),
                        "–".to_string(),
                        "–".to_string(),
                        "–".to_string(),
                    ),
                    |s| {
                        (
                            format!("{:.2}", s.references_per_triangle()),
                            s.cells.to_string(),
                            s.empty_cells.to_string(),
                            s.max_depth.to_string(),
                        )
                    },
                );
                println!(
                    "| {} | {kind} | {:.1} | {:.1} | {refs} | {cells} | {empty} | {depth} |",
                    scene.name,
                    structure as f64 / n,
                    packed as f64 / n,
                );
            }
        }
    }
}
