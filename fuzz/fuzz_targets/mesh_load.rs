//! Fuzzes the `meshq` command's mesh loaders (OBJ, PLY, STL) with the bytes of a file: the first
//! byte picks the format, the rest is the file. Whatever the bytes, loading returns a mesh or
//! an error, never panics, and allocates in proportion to the input (run with
//! `-malloc_limit_mb`, so an allocation sized by a declared count is a finding).
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
        // What the command does next: validation refuses bad indices and coordinates.
        let _ = MeshRef::new(&mesh.positions, &mesh.triangles).validate();
    }
});
