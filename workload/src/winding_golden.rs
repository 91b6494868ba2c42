//! The golden winding-number file (`tests/golden/winding.txt`): the generalized winding numbers
//! of a fixed point set around each bundled mesh, bit for bit, checked natively and in
//! WebAssembly.
//!
//! A line is the mesh name followed by `key=value` fields in any order:
//!
//! ```text
//! spot points=2000 inside=317 digest=0x…
//! ```
//!
//! The points are the first `points` of [`QueryPoints`](crate::QueryPoints) around the mesh's
//! bounds with seed [`WINDING_SEED`]; the numbers are those of
//! `meshq::inside::WindingTree::winding_numbers` at the default accuracy, over a BVH of the
//! mesh built with the default build config. `inside` counts the points with
//! `|w| ≥ 1/2`; `digest` ([`WindingDigest`]) covers every number's bits.
//!
//! Blank lines and lines starting with `#` are comments. Integers are decimal, or hexadecimal
//! with a `0x` prefix.

use core::fmt;

use crc::{CRC_64_XZ, Crc, NoTable};

use crate::golden::GoldenError;

/// The seed of the golden point set.
pub const WINDING_SEED: u64 = 0x5EED_0068;

/// Point count, inside count and CRC-64/XZ digest of a run of winding numbers.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct WindingDigest {
    /// Points.
    pub points: u32,
    /// Points with `|w| ≥ 1/2`.
    pub inside: u32,
    /// CRC-64/XZ over the little-endian bytes of every number's bit pattern, in point order.
    pub digest: u64,
}

static CRC64: Crc<u64, NoTable> = Crc::<u64, NoTable>::new(&CRC_64_XZ);

impl WindingDigest {
    /// Digests winding numbers in point order. Counts past `u32::MAX` saturate.
    #[must_use]
    pub fn of(numbers: &[f32]) -> Self {
        let mut digest = CRC64.digest();
        let mut inside = 0u32;
        for w in numbers {
            digest.update(&w.to_bits().to_le_bytes());
            inside = inside.saturating_add(u32::from(w.abs() >= 0.5));
        }
        Self {
            points: u32::try_from(numbers.len()).unwrap_or(u32::MAX),
            inside,
            digest: digest.finalize(),
        }
    }
}

impl fmt::Display for WindingDigest {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "points={} inside={} digest={:#018x}",
            self.points, self.inside, self.digest
        )
    }
}

/// The recorded digest of `mesh` in a golden file's `text`.
///
/// # Errors
/// [`GoldenError::MeshMissing`] when no line names `mesh`, [`GoldenError::Malformed`] for a
/// line that names it without all three fields.
pub fn find_winding_golden(text: &str, mesh: &str) -> Result<WindingDigest, GoldenError> {
    for (number, line) in text.lines().enumerate() {
        let mut fields = line.split_ascii_whitespace();
        let Some(name) = fields.next() else { continue };
        if name.starts_with('#') || name != mesh {
            continue;
        }
        return parse(fields).ok_or(GoldenError::Malformed { line: number + 1 });
    }
    Err(GoldenError::MeshMissing)
}

/// The three fields of a line, after its name.
fn parse<'a>(fields: impl Iterator<Item = &'a str>) -> Option<WindingDigest> {
    let (mut points, mut inside, mut digest) = (None, None, None);
    for field in fields {
        let (key, value) = field.split_once('=')?;
        let value = match value.strip_prefix("0x") {
            Some(hex) => u64::from_str_radix(hex, 16).ok()?,
            None => value.parse().ok()?,
        };
        match key {
            "points" => points = Some(u32::try_from(value).ok()?),
            "inside" => inside = Some(u32::try_from(value).ok()?),
            "digest" => digest = Some(value),
            _ => return None,
        }
    }
    Some(WindingDigest {
        points: points?,
        inside: inside?,
        digest: digest?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::format;

    #[test]
    fn a_digest_reads_back_from_its_line() {
        let d = WindingDigest::of(&[0.0, 1.0, 0.25, -0.75]);
        assert_eq!(d.inside, 2);
        let line = format!("# comment\nspot {d}\n");
        assert_eq!(find_winding_golden(&line, "spot"), Ok(d));
        assert_eq!(
            find_winding_golden(&line, "cow"),
            Err(GoldenError::MeshMissing)
        );
        assert!(find_winding_golden("spot points=1", "spot").is_err());
    }
}
