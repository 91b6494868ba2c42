//! Writing a triangle mesh as OBJ (text) or PLY (binary little-endian), by extension.

use std::io::Write;
use std::path::Path;

use anyhow::{Context, Result, bail};

use crate::atomic::AtomicFile;

/// Writes `positions` and `triangles` to `path`: `.obj` or `.ply`, whole or not at all (see
/// [`AtomicFile`]); refused when `path` is one of `inputs`.
pub fn write_mesh(
    path: &Path,
    inputs: &[&Path],
    positions: &[[f32; 3]],
    triangles: &[[u32; 3]],
) -> Result<()> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .unwrap_or_default();
    if !matches!(ext.as_str(), "obj" | "ply") {
        bail!(
            "{}: unknown output format (expected .obj or .ply)",
            path.display()
        );
    }
    let mut out = AtomicFile::create(path, inputs)?;
    if ext == "obj" {
        write_obj(&mut out, positions, triangles)
    } else {
        write_ply(&mut out, positions, triangles)
    }
    .with_context(|| format!("cannot write {}", path.display()))?;
    out.commit()
}

fn write_obj(out: &mut impl Write, positions: &[[f32; 3]], triangles: &[[u32; 3]]) -> Result<()> {
    writeln!(
        out,
        "# meshq remesh: {} vertices, {} triangles",
        positions.len(),
        triangles.len()
    )?;
    // `{}` prints the shortest text that reads back as the same f32.
    for [x, y, z] in positions {
        writeln!(out, "v {x} {y} {z}")?;
    }
    for [a, b, c] in triangles {
        writeln!(out, "f {} {} {}", a + 1, b + 1, c + 1)?;
    }
    Ok(())
}

fn write_ply(out: &mut impl Write, positions: &[[f32; 3]], triangles: &[[u32; 3]]) -> Result<()> {
    write!(
        out,
        "ply\nformat binary_little_endian 1.0\ncomment meshq remesh\n\
         element vertex {}\nproperty float x\nproperty float y\nproperty float z\n\
         element face {}\nproperty list uchar uint vertex_indices\nend_header\n",
        positions.len(),
        triangles.len()
    )?;
    for p in positions {
        for c in p {
            out.write_all(&c.to_le_bytes())?;
        }
    }
    for t in triangles {
        out.write_all(&[3u8])?;
        for i in t {
            out.write_all(&i.to_le_bytes())?;
        }
    }
    Ok(())
}
