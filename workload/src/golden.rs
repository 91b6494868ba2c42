//! The golden parity file (`tests/golden/parity.txt`): one line per mesh, written by the
//! native test suite from brute-force answers and read by every target.
//!
//! A line is the mesh name followed by `key=value` fields in any order:
//!
//! ```text
//! spot triangles=5856 seed=0x6d657368715061 rays=1024 any_rays=1024 points=256 min_x=0x… min_y=0x… min_z=0x… max_x=0x… max_y=0x… max_z=0x… hits=… any_hits=… points_found=… digest=0x…
//! ```
//!
//! `min_x` … `max_z` are the bit patterns of the box the queries are placed around (the
//! mesh's BVH root box when the line was written), so every target and every structure runs
//! the same queries whatever box its own structure records.
//!
//! Blank lines and lines starting with `#` are comments. Integers are decimal, or hexadecimal
//! with a `0x` prefix.

use core::fmt;

use glam::Vec3;
use meshq::math::Aabb;

use crate::parity::{ParityReport, ParitySpec};

/// One mesh's golden entry.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GoldenEntry<'a> {
    /// The mesh name (the file stem of its asset, e.g. `stanford-bunny`).
    pub mesh: &'a str,
    /// Its triangle count, a cheap check that the right mesh was baked.
    pub triangles: u32,
    /// The queries that were run.
    pub spec: ParitySpec,
    /// The bit patterns of the box they are placed around: min x, y, z, max x, y, z.
    pub bounds_bits: [u32; 6],
    /// What they must give.
    pub report: ParityReport,
}

impl GoldenEntry<'_> {
    /// The box the queries are placed around.
    #[must_use]
    pub fn bounds(&self) -> Aabb {
        let [a, b, c, d, e, f] = self.bounds_bits.map(f32::from_bits);
        Aabb::new(Vec3::new(a, b, c), Vec3::new(d, e, f))
    }

    /// The bit patterns of `bounds`, for a new entry.
    #[must_use]
    pub fn bits_of(bounds: &Aabb) -> [u32; 6] {
        let (min, max) = (bounds.min, bounds.max);
        [min.x, min.y, min.z, max.x, max.y, max.z].map(f32::to_bits)
    }
}

/// Why a golden entry could not be read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum GoldenError {
    /// No line names the mesh.
    MeshMissing,
    /// The mesh's line (1-based) lacks a field, repeats one, or has one that does not parse.
    Malformed {
        /// Line number, from 1.
        line: usize,
    },
}

impl fmt::Display for GoldenError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::MeshMissing => f.write_str("the golden file has no line for this mesh"),
            Self::Malformed { line } => write!(f, "golden file line {line} is malformed"),
        }
    }
}

impl core::error::Error for GoldenError {}

fn parse_u64(text: &str) -> Option<u64> {
    match text.strip_prefix("0x") {
        Some(hex) => u64::from_str_radix(hex, 16).ok(),
        None => text.parse().ok(),
    }
}

/// Reads the fields after the mesh name; `None` when one is missing, repeated or unreadable.
fn parse_fields<'a>(
    mesh: &'a str,
    fields: core::str::SplitAsciiWhitespace<'_>,
) -> Option<GoldenEntry<'a>> {
    // Each field once: a slot per key, filled at most once.
    let mut slots: [Option<u64>; 15] = [None; 15];
    const KEYS: [&str; 15] = [
        "triangles",
        "seed",
        "rays",
        "any_rays",
        "points",
        "min_x",
        "min_y",
        "min_z",
        "max_x",
        "max_y",
        "max_z",
        "hits",
        "any_hits",
        "points_found",
        "digest",
    ];
    for field in fields {
        // A byte search rather than `split_once`: core's char searcher keeps a slice-index
        // panic path when not inlined, which the firmware's panic-free proof would refuse.
        let equals = field.bytes().position(|b| b == b'=')?;
        let key = field.get(..equals)?;
        let value = field.get(equals + 1..)?;
        let index = KEYS.iter().position(|k| *k == key)?;
        let slot = slots.get_mut(index)?;
        if slot.is_some() {
            return None;
        }
        *slot = Some(parse_u64(value)?);
    }
    let [
        triangles,
        seed,
        rays,
        any_rays,
        points,
        min_x,
        min_y,
        min_z,
        max_x,
        max_y,
        max_z,
        hits,
        any_hits,
        points_found,
        digest,
    ] = slots;
    let small = |v: Option<u64>| v.and_then(|v| u32::try_from(v).ok());
    Some(GoldenEntry {
        mesh,
        triangles: small(triangles)?,
        spec: ParitySpec {
            seed: seed?,
            rays: small(rays)?,
            any_rays: small(any_rays)?,
            points: small(points)?,
        },
        bounds_bits: [
            small(min_x)?,
            small(min_y)?,
            small(min_z)?,
            small(max_x)?,
            small(max_y)?,
            small(max_z)?,
        ],
        report: ParityReport {
            digest: digest?,
            hits: small(hits)?,
            any_hits: small(any_hits)?,
            points_found: small(points_found)?,
        },
    })
}

/// The entry for `mesh` in the golden file's `text`.
///
/// # Errors
/// [`GoldenError::MeshMissing`] when no line names it, [`GoldenError::Malformed`] when its line
/// does not parse.
pub fn find_golden<'a>(text: &'a str, mesh: &str) -> Result<GoldenEntry<'a>, GoldenError> {
    for (number, line) in numbered_lines(text) {
        let mut fields = line.split_ascii_whitespace();
        let Some(name) = fields.next() else { continue };
        if name.starts_with('#') || name != mesh {
            continue;
        }
        return parse_fields(name, fields).ok_or(GoldenError::Malformed { line: number });
    }
    Err(GoldenError::MeshMissing)
}

/// The lines of `text` with their numbers from 1, without the `\n` or `\r\n` that ends them
/// (as `str::lines`, which, shared by two callers and so not inlined, keeps a slice-index panic
/// path the firmware's panic-free proof refuses; this finds line ends byte by byte).
pub(crate) fn numbered_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    let mut rest = text;
    let mut number = 0;
    core::iter::from_fn(move || {
        if rest.is_empty() {
            return None;
        }
        let end = rest.bytes().position(|b| b == b'\n').unwrap_or(rest.len());
        let line = rest.get(..end).unwrap_or_default();
        rest = rest.get(end + 1..).unwrap_or_default();
        number += 1;
        let line = match line.as_bytes().last() {
            Some(b'\r') => line.get(..line.len() - 1).unwrap_or_default(),
            _ => line,
        };
        Some((number, line))
    })
}

/// Writes the entry as one golden-file line (without the newline), which [`find_golden`]
/// reads back.
impl fmt::Display for GoldenEntry<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (s, r) = (&self.spec, &self.report);
        write!(
            f,
            "{} triangles={} seed={:#x} rays={} any_rays={} points={} min_x={:#010x} \
             min_y={:#010x} min_z={:#010x} max_x={:#010x} max_y={:#010x} max_z={:#010x} hits={} \
             any_hits={} points_found={} digest={:#018x}",
            self.mesh,
            self.triangles,
            s.seed,
            s.rays,
            s.any_rays,
            s.points,
            self.bounds_bits[0],
            self.bounds_bits[1],
            self.bounds_bits[2],
            self.bounds_bits[3],
            self.bounds_bits[4],
            self.bounds_bits[5],
            r.hits,
            r.any_hits,
            r.points_found,
            r.digest
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = "# comment\n\nspot triangles=5856 seed=0x10 rays=3 any_rays=4 points=5 \
        min_x=0xbf800000 min_y=0 min_z=0 max_x=0x3f800000 max_y=0x40000000 max_z=0x3f000000 \
        hits=1 any_hits=2 points_found=5 digest=0x00000000000000ff\n\
        bad triangles=1 seed=1\n";

    #[test]
    fn reads_a_line_and_writes_it_back() {
        let entry = find_golden(TEXT, "spot").expect("spot is there");
        assert_eq!(entry.triangles, 5856);
        assert_eq!(entry.spec.seed, 16);
        assert_eq!(entry.spec.points, 5);
        assert_eq!(entry.report.digest, 255);
        assert_eq!(
            entry.bounds(),
            Aabb::new(Vec3::new(-1.0, 0.0, 0.0), Vec3::new(1.0, 2.0, 0.5))
        );
        let line = std::format!("{entry}");
        assert_eq!(find_golden(&line, "spot"), Ok(entry));
    }

    #[test]
    fn reports_missing_and_malformed_lines() {
        assert_eq!(find_golden(TEXT, "cow"), Err(GoldenError::MeshMissing));
        assert_eq!(
            find_golden(TEXT, "bad"),
            Err(GoldenError::Malformed { line: 4 })
        );
        let repeated = "m triangles=1 triangles=1 seed=1 rays=1 any_rays=1 points=1 min_x=0 \
            min_y=0 min_z=0 max_x=0 max_y=0 max_z=0 hits=1 any_hits=1 points_found=1 digest=1";
        assert_eq!(
            find_golden(repeated, "m"),
            Err(GoldenError::Malformed { line: 1 })
        );
        let too_big = "m triangles=0x100000000 seed=1 rays=1 any_rays=1 points=1 min_x=0 \
            min_y=0 min_z=0 max_x=0 max_y=0 max_z=0 hits=1 any_hits=1 points_found=1 digest=1";
        assert_eq!(
            find_golden(too_big, "m"),
            Err(GoldenError::Malformed { line: 1 })
        );
    }
}
