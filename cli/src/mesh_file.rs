//! Reading OBJ, PLY and STL files into one indexed triangle list, polygons fan-triangulated,
//! triangles in file order.

use std::fs::File;
use std::io::BufReader;
use std::path::Path;

use anyhow::{Context, Result, bail};
use ply_rs_bw::parser::{Parser, Reader};
use ply_rs_bw::ply::{Property, PropertyAccess, PropertyAccessResult};

/// An indexed triangle mesh as read from a file.
#[derive(Clone, Debug, Default)]
pub struct MeshData {
    pub positions: Vec<[f32; 3]>,
    pub triangles: Vec<[u32; 3]>,
}

/// Reads the mesh at `path`; the format comes from the extension (`.obj`, `.ply`, `.stl`).
pub fn read_mesh(path: &Path) -> Result<MeshData> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .unwrap_or_default();
    let mesh = match ext.as_str() {
        "obj" => read_obj(path),
        "ply" => read_ply(path),
        "stl" => read_stl(path),
        _ => bail!(
            "{}: unknown mesh format (expected .obj, .ply or .stl)",
            path.display()
        ),
    }
    .with_context(|| format!("cannot read mesh {}", path.display()))?;
    Ok(mesh)
}

fn read_obj(path: &Path) -> Result<MeshData> {
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, _) = tobj::load_obj(path, &options)?;
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

fn read_stl(path: &Path) -> Result<MeshData> {
    let mut file = BufReader::new(File::open(path)?);
    let stl = stl_io::read_stl(&mut file)?;
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

fn read_ply(path: &Path) -> Result<MeshData> {
    let mut reader = Reader::new(BufReader::new(File::open(path)?));
    let vertex_parser = Parser::<PlyVertex>::new();
    let face_parser = Parser::<PlyFace>::new();
    let header = vertex_parser.read_header(&mut reader)?;
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
