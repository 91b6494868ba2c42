//! Reading OBJ, PLY and STL files into one indexed triangle list, polygons fan-triangulated,
//! triangles in file order.

use std::path::Path;

use anyhow::{Context, Result, bail};
use ply_rs_bw::parser::{Parser, Reader};
use ply_rs_bw::ply::{Encoding, Property, PropertyAccess, PropertyAccessResult};

use crate::ply_limits::{check_header, payload_start};
use crate::stl_binary;

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
    let geometry = obj_geometry(bytes)?;
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
///
/// # Errors
/// Bytes that are not UTF-8 text (naming the first bad byte), a `v` line without three
/// numbers, or an `f` line with fewer than three vertex indices or one that is not a nonzero
/// integer (naming the line): a file cut off mid-line or not OBJ at all is never read as an
/// empty or smaller mesh.
fn obj_geometry(bytes: &[u8]) -> Result<String> {
    let text = std::str::from_utf8(bytes).map_err(|e| {
        anyhow::anyhow!(
            "byte {}: not UTF-8 text, so not an OBJ file",
            e.valid_up_to()
        )
    })?;
    let mut out = String::with_capacity(text.len());
    for (number, line) in (1usize..).zip(text.lines()) {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                let coordinates: Vec<&str> = words.take(3).collect();
                if coordinates.len() < 3 || coordinates.iter().any(|w| w.parse::<f32>().is_err()) {
                    bail!("line {number}: a vertex needs three numbers: {line:?}");
                }
                out.push('v');
                for w in coordinates {
                    out.push(' ');
                    out.push_str(w);
                }
            }
            Some("f") => {
                let indices: Vec<&str> = words.map(|w| w.split('/').next().unwrap_or(w)).collect();
                if indices.len() < 3 {
                    bail!("line {number}: a face needs at least three vertices: {line:?}");
                }
                if let Some(bad) = indices
                    .iter()
                    .find(|w| w.parse::<i64>().map_or(true, |i| i == 0))
                {
                    bail!("line {number}: {bad:?} is not a vertex index");
                }
                out.push('f');
                for w in indices {
                    out.push(' ');
                    out.push_str(w);
                }
            }
            _ => continue,
        }
        out.push('\n');
    }
    Ok(out)
}

/// A binary STL when its length is exactly what its triangle count needs (whatever its header
/// says: binary headers may start with `solid` too), else ASCII when it starts with `solid`,
/// else an error naming the mismatch.
fn read_stl(bytes: &[u8]) -> Result<MeshData> {
    if stl_binary::declared_count(bytes).is_some() {
        return stl_binary::read(bytes);
    }
    if !bytes.trim_ascii_start().starts_with(b"solid") {
        let Some(count) = bytes.get(80..84) else {
            bail!(
                "{} bytes: too short for a binary STL (84-byte header)",
                bytes.len()
            );
        };
        let count = u32::from_le_bytes([count[0], count[1], count[2], count[3]]);
        let expected = 84 + 50 * u64::from(count);
        bail!(
            "binary STL header says {count} triangles ({expected} bytes), but the file has {} bytes",
            bytes.len()
        );
    }
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
    let end = usize::try_from(reader.get_ref().position()).unwrap_or(usize::MAX);
    check_nothing_after(bytes, end, header.encoding == Encoding::Ascii)?;
    Ok(mesh)
}

/// A PLY file must end where its last declared element does (in ASCII, trailing white space
/// aside): more lines or bytes mean the header's counts are wrong, and reading by them would
/// drop data or take vertex lines for faces.
fn check_nothing_after(bytes: &[u8], end: usize, ascii: bool) -> Result<()> {
    let rest = bytes.get(end..).unwrap_or_default();
    if ascii {
        let Some(first) = rest.iter().position(|b| !b.is_ascii_whitespace()) else {
            return Ok(());
        };
        let at = end + first;
        let line = 1 + bytes
            .get(..at)
            .unwrap_or_default()
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        bail!("line {line}: data after the elements the header declares (its counts are wrong)");
    }
    if !rest.is_empty() {
        bail!(
            "byte {end}: {} bytes after the elements the header declares (its counts are wrong)",
            rest.len()
        );
    }
    Ok(())
}

/// Appends the fan `(p0, p_i, p_i+1)` of a polygon; fewer than three corners add nothing.
fn fan_triangulate(polygon: &[u32], out: &mut Vec<[u32; 3]>) {
    if let Some((&first, rest)) = polygon.split_first() {
        out.extend(rest.windows(2).map(|w| [first, w[0], w[1]]));
    }
}

#[cfg(test)]
mod tests {
    use super::{MeshFormat, fan_triangulate, parse_mesh};

    /// The error `parse_mesh` gives for `bytes`, as the command prints it.
    fn error(bytes: &[u8], format: MeshFormat) -> String {
        match parse_mesh(bytes, format) {
            Ok(mesh) => panic!("read as {} triangles", mesh.triangles.len()),
            Err(e) => format!("{e:#}"),
        }
    }

    const PLY_HEAD: &str = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n\
        property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n\
        end_header\n";

    #[test]
    fn a_ply_whose_counts_leave_data_unread_is_an_error_naming_the_line() {
        let good = format!("{PLY_HEAD}0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
        assert_eq!(
            parse_mesh(good.as_bytes(), MeshFormat::Ply)
                .unwrap()
                .triangles,
            [[0, 1, 2]]
        );
        // Two vertices declared, three given: the third would be read as the face.
        let short = good.replace("element vertex 3", "element vertex 2");
        let e = error(short.as_bytes(), MeshFormat::Ply);
        assert!(e.contains("line 13") && e.contains("counts"), "{e}");
        // A face more than declared.
        let extra = format!("{good}3 2 1 0\n");
        let e = error(extra.as_bytes(), MeshFormat::Ply);
        assert!(e.contains("line 14"), "{e}");
        // Binary: bytes past the last element.
        let mut binary = PLY_HEAD
            .replace("ascii", "binary_little_endian")
            .into_bytes();
        for v in [[0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
            for x in v {
                binary.extend_from_slice(&x.to_le_bytes());
            }
        }
        binary.push(3);
        for i in [0i32, 1, 2] {
            binary.extend_from_slice(&i.to_le_bytes());
        }
        assert_eq!(
            parse_mesh(&binary, MeshFormat::Ply)
                .unwrap()
                .triangles
                .len(),
            1
        );
        let end = binary.len();
        binary.extend_from_slice(&[0; 13]);
        let e = error(&binary, MeshFormat::Ply);
        assert!(
            e.contains(&format!("byte {end}")) && e.contains("13 bytes"),
            "{e}"
        );
    }

    /// A binary STL of `triangles` (each three corners), with `header` at its start.
    fn binary_stl(header: &[u8], triangles: &[[[f32; 3]; 3]]) -> Vec<u8> {
        let mut bytes = vec![0u8; 80];
        bytes[..header.len()].copy_from_slice(header);
        bytes.extend_from_slice(&(triangles.len() as u32).to_le_bytes());
        for t in triangles {
            bytes.extend_from_slice(&[0; 12]);
            for corner in t {
                for x in corner {
                    bytes.extend_from_slice(&x.to_le_bytes());
                }
            }
            bytes.extend_from_slice(&[0; 2]);
        }
        bytes
    }

    #[test]
    fn a_binary_stl_whose_header_starts_with_solid_is_read_whole() {
        let a = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let b = [[1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
        for header in [&b"solid made by a CAD tool"[..], b"binary"] {
            let mesh = parse_mesh(&binary_stl(header, &[a, b]), MeshFormat::Stl).unwrap();
            assert_eq!(mesh.triangles, [[0, 1, 2], [1, 3, 2]], "{header:?}");
            assert_eq!(mesh.positions, [a[0], a[1], a[2], b[1]]);
        }
        // A count the length does not match, without `solid`: refused.
        let mut cut = binary_stl(b"binary", &[a, b]);
        cut.truncate(cut.len() - 50);
        let e = error(&cut, MeshFormat::Stl);
        assert!(e.contains("2 triangles"), "{e}");
        // ASCII still reads.
        let ascii = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n\
            vertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
        assert_eq!(
            parse_mesh(ascii.as_bytes(), MeshFormat::Stl)
                .unwrap()
                .triangles
                .len(),
            1
        );
    }

    #[test]
    fn an_obj_cut_off_or_not_text_is_an_error_naming_where() {
        let good = "# a triangle\no t\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\nusemtl m\nf 1/1/1 2/1/1 3/1/1\n";
        assert_eq!(
            parse_mesh(good.as_bytes(), MeshFormat::Obj)
                .unwrap()
                .triangles,
            [[0, 1, 2]]
        );
        let cut = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n";
        let e = error(cut.as_bytes(), MeshFormat::Obj);
        assert!(e.contains("line 4"), "{e}");
        let cut_vertex = "v 0 0 0\nv 1 0\n";
        let e = error(cut_vertex.as_bytes(), MeshFormat::Obj);
        assert!(e.contains("line 2"), "{e}");
        let bad_index = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n";
        let e = error(bad_index.as_bytes(), MeshFormat::Obj);
        assert!(e.contains("line 4") && e.contains("\"x\""), "{e}");
        let mut garbage: Vec<u8> = (0..10_240u32)
            .map(|i| (i.wrapping_mul(2_654_435_761) >> 24) as u8)
            .collect();
        garbage[7] = 0xff;
        let e = error(&garbage, MeshFormat::Obj);
        assert!(e.contains("not UTF-8"), "{e}");
    }

    #[test]
    fn polygons_become_fans_in_order() {
        let mut out = Vec::new();
        fan_triangulate(&[4, 5, 6, 7, 8], &mut out);
        fan_triangulate(&[1, 2], &mut out);
        assert_eq!(out, vec![[4, 5, 6], [4, 6, 7], [4, 7, 8]]);
    }
}
