//! Reading OBJ, PLY and STL files into one indexed triangle list, polygons fan-triangulated,
//! triangles in file order.

use std::path::Path;

use anyhow::{Context, Result, bail};
use ply_rs_bw::parser::{Parser, Reader};
use ply_rs_bw::ply::{Property, PropertyAccess, PropertyAccessResult};

use crate::ply_limits::{check_header, payload_start};

/// An indexed triangle mesh as read from a file.
#[derive(Clone, Debug, Default)]
pub struct MeshData {
    pub positions: Vec<[f32; 3]>,
    pub triangles: Vec<[u32; 3]>,
}

/// The mesh file formats read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshFormat {
    Obj,
    Ply,
    Stl,
}

impl MeshFormat {
    /// The format an extension names (`.obj`, `.ply`, `.stl`, any case).
    pub fn of(path: &Path) -> Option<Self> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "obj" => Some(Self::Obj),
            "ply" => Some(Self::Ply),
            "stl" => Some(Self::Stl),
            _ => None,
        }
    }
}

/// Reads the mesh at `path`; the format comes from the extension (`.obj`, `.ply`, `.stl`).
/// Only regular files are read (a pipe or a device could hang or never end), whole, so what
/// reading allocates is bounded by the file's size.
pub fn read_mesh(path: &Path) -> Result<MeshData> {
    let Some(format) = MeshFormat::of(path) else {
        bail!(
            "{}: unknown mesh format (expected .obj, .ply or .stl)",
            path.display()
        );
    };
    let meta =
        std::fs::metadata(path).with_context(|| format!("cannot read mesh {}", path.display()))?;
    if !meta.is_file() {
        bail!("{}: not a regular file", path.display());
    }
    let bytes =
        std::fs::read(path).with_context(|| format!("cannot read mesh {}", path.display()))?;
    parse_mesh(&bytes, format).with_context(|| format!("cannot read mesh {}", path.display()))
}

/// Parses a whole mesh file held in memory. Every count a file declares is checked against
/// its bytes before anything is allocated for it; materials (`mtllib`) are never read.
pub fn parse_mesh(bytes: &[u8], format: MeshFormat) -> Result<MeshData> {
    match format {
        MeshFormat::Obj => read_obj(bytes),
        MeshFormat::Ply => read_ply(bytes),
        MeshFormat::Stl => read_stl(bytes),
    }
}

fn read_obj(bytes: &[u8]) -> Result<MeshData> {
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
    };
    // Materials are never read: an `mtllib` line could name any file (a device, a pipe).
    let geometry = obj_geometry(bytes);
    let mut reader = std::io::Cursor::new(geometry.as_bytes());
    let (models, _) = tobj::load_obj_buf(&mut reader, &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })?;
    let mut mesh = MeshData::default();
    for m in models {
        let base = u32::try_from(mesh.positions.len()).context("too many vertices")?;
        let (positions, _) = m.mesh.positions.as_chunks::<3>();
        mesh.positions.extend_from_slice(positions);
        let (triangles, _) = m.mesh.indices.as_chunks::<3>();
        for t in triangles {
            mesh.triangles.push(t.map(|i| i.saturating_add(base)));
        }
    }
    Ok(mesh)
}

/// The lines of an OBJ file that carry geometry, reduced to what meshq reads: `v` with its
/// first three coordinates (vertex colours dropped) and `f` with its vertex indices (texture
/// and normal indices dropped). Texture coordinates, normals, materials and everything else
/// go: tobj's code for them overflows on hostile indices (found by the `mesh_load` fuzz
/// target), and meshq uses none of it. The result is never longer than the input.
fn obj_geometry(bytes: &[u8]) -> String {
    let text = String::from_utf8_lossy(bytes);
    let mut out = String::with_capacity(text.len());
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                out.push('v');
                for w in words.take(3) {
                    out.push(' ');
                    out.push_str(w);
                }
            }
            Some("f") => {
                out.push('f');
                for w in words {
                    out.push(' ');
                    out.push_str(w.split('/').next().unwrap_or(w));
                }
            }
            _ => continue,
        }
        out.push('\n');
    }
    out
}

fn read_stl(bytes: &[u8]) -> Result<MeshData> {
    check_binary_stl_count(bytes)?;
    let stl = stl_io::read_stl(&mut std::io::Cursor::new(bytes))?;
    let positions = stl.vertices.iter().map(|v| v.0).collect();
    let triangles = stl
        .faces
        .iter()
        .map(|f| {
            let [a, b, c] = f.vertices;
            Ok([u32::try_from(a)?, u32::try_from(b)?, u32::try_from(c)?])
        })
        .collect::<Result<_>>()?;
    Ok(MeshData {
        positions,
        triangles,
    })
}

/// A binary STL's triangle count (bytes 80..84) must match its length exactly: a count larger
/// than the data would read past the end, a smaller one would drop triangles silently. Files
/// that start with `solid` are left to the ASCII reader.
fn check_binary_stl_count(bytes: &[u8]) -> Result<()> {
    if bytes.trim_ascii_start().starts_with(b"solid") {
        return Ok(());
    }
    let Some(count) = bytes.get(80..84) else {
        bail!(
            "{} bytes: too short for a binary STL (84-byte header)",
            bytes.len()
        );
    };
    let count = u32::from_le_bytes([count[0], count[1], count[2], count[3]]);
    let expected = 84 + 50 * u64::from(count);
    if expected != bytes.len() as u64 {
        bail!(
            "binary STL header says {count} triangles ({expected} bytes), but the file has {} bytes",
            bytes.len()
        );
    }
    Ok(())
}

/// A PLY vertex: x, y, z of any numeric type, other properties ignored.
#[derive(Default)]
struct PlyVertex([f32; 3]);

impl PropertyAccess for PlyVertex {
    fn new() -> Self {
        Self::default()
    }

    fn set_property(&mut self, key: &str, property: Property) -> PropertyAccessResult {
        let axis = match key {
            "x" => 0,
            "y" => 1,
            "z" => 2,
            _ => return PropertyAccessResult::Ignored,
        };
        match (self.0.get_mut(axis), property.to_f32_lossy()) {
            (Some(slot), Some(v)) => {
                *slot = v;
                PropertyAccessResult::Set
            }
            _ => PropertyAccessResult::UnsupportedType,
        }
    }
}

/// A PLY face: its vertex index list (`vertex_indices` or `vertex_index`).
#[derive(Default)]
struct PlyFace(Vec<u32>);

impl PropertyAccess for PlyFace {
    fn new() -> Self {
        Self::default()
    }

    fn set_property(&mut self, key: &str, property: Property) -> PropertyAccessResult {
        if key != "vertex_indices" && key != "vertex_index" {
            return PropertyAccessResult::Ignored;
        }
        match property.to_u32_list() {
            Some(list) => {
                self.0 = list;
                PropertyAccessResult::Set
            }
            None => PropertyAccessResult::UnsupportedType,
        }
    }
}

fn read_ply(bytes: &[u8]) -> Result<MeshData> {
    let payload = bytes.len() - payload_start(bytes)?.min(bytes.len());
    let mut reader = Reader::new(std::io::Cursor::new(bytes));
    let vertex_parser = Parser::<PlyVertex>::new();
    let face_parser = Parser::<PlyFace>::new();
    let header = vertex_parser.read_header(&mut reader)?;
    check_header(&header, payload as u64)?;
    let mut mesh = MeshData::default();
    for element in header.elements.values() {
        match element.name.as_str() {
            "vertex" => {
                let vertices =
                    vertex_parser.read_payload_for_element(&mut reader, element, &header)?;
                mesh.positions = vertices.into_iter().map(|v| v.0).collect();
            }
            "face" => {
                let faces = face_parser.read_payload_for_element(&mut reader, element, &header)?;
                for face in faces {
                    fan_triangulate(&face.0, &mut mesh.triangles);
                }
            }
            // Elements after the ones we need still have to be read past in binary files;
            // the face parser ignores every property it does not know.
            _ => {
                face_parser.read_payload_for_element(&mut reader, element, &header)?;
            }
        }
    }
    Ok(mesh)
}

/// Appends the fan `(p0, p_i, p_i+1)` of a polygon; fewer than three corners add nothing.
fn fan_triangulate(polygon: &[u32], out: &mut Vec<[u32; 3]>) {
    if let Some((&first, rest)) = polygon.split_first() {
        out.extend(rest.windows(2).map(|w| [first, w[0], w[1]]));
    }
}

#[cfg(test)]
mod tests {
    use super::fan_triangulate;

    #[test]
    fn polygons_become_fans_in_order() {
        let mut out = Vec::new();
        fan_triangulate(&[4, 5, 6, 7, 8], &mut out);
        fan_triangulate(&[1, 2], &mut out);
        assert_eq!(out, vec![[4, 5, 6], [4, 6, 7], [4, 7, 8]]);
    }
}
