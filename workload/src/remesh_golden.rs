//! The golden remeshing file (`tests/golden/remesh.txt`): what remeshing a bundled mesh gives,
//! bit for bit, checked natively, in WebAssembly and on the firmware.
//!
//! A line is the mesh name followed by `key=value` fields in any order:
//!
//! ```text
//! uv-sphere triangles_in=360 iterations=10 vertices=145 triangles=286 digest=0x…
//! ```
//!
//! The run is `meshq::remesh` with the default target length (the input's mean edge length)
//! and `iterations` iterations, no feature angle, projecting onto a BVH of the input built
//! with the default build config. `triangles_in` checks that the right mesh was loaded;
//! `vertices`, `triangles` and `digest` ([`MeshDigest`]) are the result.
//!
//! Blank lines and lines starting with `#` are comments. Integers are decimal, or hexadecimal
//! with a `0x` prefix.

use core::fmt;

use crc::{CRC_64_XZ, Crc, NoTable};

use crate::golden::GoldenError;

/// Vertex count, triangle count and CRC-64/XZ digest of a mesh.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MeshDigest {
    /// Vertices.
    pub vertices: u32,
    /// Triangles.
    pub triangles: u32,
    /// CRC-64/XZ over the little-endian bytes of every position's `x, y, z` bit patterns in
    /// vertex order, then every triangle's three vertex indices in triangle order.
    pub digest: u64,
}

static CRC64: Crc<u64, NoTable> = Crc::<u64, NoTable>::new(&CRC_64_XZ);

impl MeshDigest {
    /// Digests a mesh given as its positions and its triangles (vertex-index triples).
    /// Counts past `u32::MAX` saturate.
    #[must_use]
    pub fn of(
        positions: impl IntoIterator<Item = [f32; 3]>,
        triangles: impl IntoIterator<Item = [u32; 3]>,
    ) -> Self {
        let mut digest = CRC64.digest();
        let (mut vertices, mut count) = (0u32, 0u32);
        for p in positions {
            for c in p {
                digest.update(&c.to_bits().to_le_bytes());
            }
            vertices = vertices.saturating_add(1);
        }
        for t in triangles {
            for i in t {
                digest.update(&i.to_le_bytes());
            }
            count = count.saturating_add(1);
        }
        Self {
            vertices,
            triangles: count,
            digest: digest.finalize(),
        }
    }
}

/// One mesh's golden remeshing entry.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RemeshGolden<'a> {
    /// The mesh name (the file stem of its asset, e.g. `uv-sphere`).
    pub mesh: &'a str,
    /// The input's triangle count.
    pub triangles_in: u32,
    /// Iterations run.
    pub iterations: u32,
    /// What the run must give.
    pub result: MeshDigest,
}

/// The remeshing entry for `mesh` in the golden file's `text`.
///
/// # Errors
/// [`GoldenError::MeshMissing`] when no line names it, [`GoldenError::Malformed`] when its line
/// lacks, repeats or cannot read a field.
// `#[inline]` makes it compiled only where it is used: compiled here, it shares core's line
// splitter with `find_golden`, which then stops being inlined into the firmware's query
// build and costs it flash.
#[inline]
pub fn find_remesh_golden<'a>(text: &'a str, mesh: &str) -> Result<RemeshGolden<'a>, GoldenError> {
    for (number, line) in crate::golden::numbered_lines(text) {
        let mut fields = line.split_ascii_whitespace();
        let Some(name) = fields.next() else { continue };
        if name.starts_with('#') || name != mesh {
            continue;
        }
        return parse(name, fields).ok_or(GoldenError::Malformed { line: number });
    }
    Err(GoldenError::MeshMissing)
}

/// A decimal or `0x` hexadecimal integer. (The parity file has its own copy: shared, it
/// stops being inlined there and the firmware's query build grows past its flash budget.)
#[inline]
fn number(text: &str) -> Option<u64> {
    match text.strip_prefix("0x") {
        Some(hex) => u64::from_str_radix(hex, 16).ok(),
        None => text.parse().ok(),
    }
}

#[inline]
fn parse<'a>(
    mesh: &'a str,
    fields: core::str::SplitAsciiWhitespace<'_>,
) -> Option<RemeshGolden<'a>> {
    const KEYS: [&str; 5] = [
        "triangles_in",
        "iterations",
        "vertices",
        "triangles",
        "digest",
    ];
    let mut slots: [Option<u64>; 5] = [None; 5];
    for field in fields {
        // A byte search, as in the parity file: no slice-index panic path for the firmware.
        let equals = field.bytes().position(|b| b == b'=')?;
        let key = field.get(..equals)?;
        let value = field.get(equals + 1..)?;
        let slot = slots.get_mut(KEYS.iter().position(|k| *k == key)?)?;
        if slot.is_some() {
            return None;
        }
        *slot = Some(number(value)?);
    }
    let [triangles_in, iterations, vertices, triangles, digest] = slots;
    let small = |v: Option<u64>| v.and_then(|v| u32::try_from(v).ok());
    Some(RemeshGolden {
        mesh,
        triangles_in: small(triangles_in)?,
        iterations: small(iterations)?,
        result: MeshDigest {
            vertices: small(vertices)?,
            triangles: small(triangles)?,
            digest: digest?,
        },
    })
}

/// Writes the entry as one golden-file line (without the newline), which
/// [`find_remesh_golden`] reads back.
impl fmt::Display for RemeshGolden<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} triangles_in={} iterations={} vertices={} triangles={} digest={:#018x}",
            self.mesh,
            self.triangles_in,
            self.iterations,
            self.result.vertices,
            self.result.triangles,
            self.result.digest
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_a_line_and_writes_it_back() {
        let text = "# c\nsphere digest=0xff triangles_in=8 iterations=10 vertices=6 triangles=8\n";
        let entry = find_remesh_golden(text, "sphere").expect("there");
        assert_eq!(entry.triangles_in, 8);
        assert_eq!(entry.result.digest, 255);
        let line = std::format!("{entry}");
        assert_eq!(find_remesh_golden(&line, "sphere"), Ok(entry));
        assert_eq!(
            find_remesh_golden(text, "cow"),
            Err(GoldenError::MeshMissing)
        );
        let repeated = "m triangles_in=1 iterations=1 vertices=1 triangles=1 digest=1 digest=1";
        assert_eq!(
            find_remesh_golden(repeated, "m"),
            Err(GoldenError::Malformed { line: 1 })
        );
        let missing = "m triangles_in=1 iterations=1 vertices=1 triangles=1";
        assert_eq!(
            find_remesh_golden(missing, "m"),
            Err(GoldenError::Malformed { line: 1 })
        );
    }

    #[test]
    fn the_digest_sees_every_bit_and_the_order() {
        let p = [[0.0f32, 1.0, 2.0], [3.0, 4.0, 5.0], [6.0, 7.0, 8.0]];
        let base = MeshDigest::of(p, [[0, 1, 2]]);
        assert_eq!((base.vertices, base.triangles), (3, 1));
        assert_ne!(base, MeshDigest::of(p, [[1, 2, 0]]));
        let mut q = p;
        q[2][1] = f32::from_bits(q[2][1].to_bits() ^ 1);
        assert_ne!(base.digest, MeshDigest::of(q, [[0, 1, 2]]).digest);
        // -0.0 and 0.0 differ in bits.
        q = p;
        q[0][0] = -0.0;
        assert_ne!(base.digest, MeshDigest::of(q, [[0, 1, 2]]).digest);
    }
}
