//! Fuzzes the `meshq` command's mesh loaders (OBJ, PLY, STL) with the bytes of a file: the first
//! byte picks the format, the rest is the file. Whatever the bytes, loading returns a mesh or
//! an error, never panics, and allocates in proportion to the input (run with
//! `-malloc_limit_mb`, so an allocation sized by a declared count is a finding). A file that
//! loads is read whole: a binary STL whose length fits its count gives that many triangles,
//! and a PLY that declares one vertex element gives that many vertices (a loader that stopped
//! early, or read vertex lines as faces, is a finding).
#![no_main]

use libfuzzer_sys::fuzz_target;
use meshq::mesh::MeshRef;
use meshq_cli::mesh_file::{MeshFormat, parse_mesh};

fuzz_target!(|data: &[u8]| {
    let Some((&pick, file)) = data.split_first() else {
        return;
    };
    let format = match pick % 3 {
        0 => MeshFormat::Obj,
        1 => MeshFormat::Ply,
        _ => MeshFormat::Stl,
    };
    if let Ok(mesh) = parse_mesh(file, format) {
        match format {
            MeshFormat::Stl => {
                if let Some(count) = binary_stl_count(file) {
                    assert_eq!(
                        mesh.triangles.len() as u64,
                        count,
                        "a binary STL read whole"
                    );
                }
            }
            MeshFormat::Ply => {
                if let Some(vertices) = declared_ply_vertices(file) {
                    assert_eq!(
                        mesh.positions.len() as u64,
                        vertices,
                        "every PLY vertex read"
                    );
                }
            }
            MeshFormat::Obj => {}
        }
        // What the command does next: validation refuses bad indices and coordinates.
        let _ = MeshRef::new(&mesh.positions, &mesh.triangles).validate();
    }
});

/// The triangle count of a binary STL whose length is exactly what its count says (84 bytes of
/// header and count, 50 per triangle), which the loader reads as binary.
fn binary_stl_count(file: &[u8]) -> Option<u64> {
    let count = u64::from(u32::from_le_bytes(file.get(80..84)?.try_into().ok()?));
    (file.len() as u64 == 84 + 50 * count).then_some(count)
}

/// The vertex count of a PLY header (read here on its own, line by line up to the line
/// `end_header`) that declares exactly one `vertex` element.
fn declared_ply_vertices(file: &[u8]) -> Option<u64> {
    let mut counts = Vec::new();
    for line in file.split(|&b| b == b'\n') {
        let line = std::str::from_utf8(line).ok()?;
        if line.trim() == "end_header" {
            return match counts.as_slice() {
                [n] => *n,
                _ => None,
            };
        }
        let words: Vec<&str> = line.split_ascii_whitespace().collect();
        if let ["element", "vertex", n] = words.as_slice() {
            counts.push(n.parse::<u64>().ok());
        }
    }
    None
}
