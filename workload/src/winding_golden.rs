//! The golden winding-number file (`tests/golden/winding.txt`): the generalized winding numbers
//! of a fixed point set around each bundled mesh, bit for bit, checked natively and in
//! WebAssembly.
//!
//! A line is the mesh name followed by `key=value` fields in any order:
//!
//! ```text
//! spot points=2000 inside=317 digest=0x… signed=0x…
//! ```
//!
//! The points are the first `points` of [`QueryPoints`](crate::QueryPoints) around the mesh's
//! bounds with seed [`WINDING_SEED`]; the numbers are those of
//! `meshq::inside::WindingTree::winding_numbers` at the default accuracy, over a BVH of the
//! mesh built with the default build config. `inside` counts the points with
//! `|w| ≥ 1/2`; `digest` ([`WindingDigest`]) covers every number's bits, `signed` every
//! point's signed distance (`WindingTree::signed_distance` with no maximum distance, at the
//! default accuracy).
//!
//! Blank lines and lines starting with `#` are comments. Integers are decimal, or hexadecimal
//! with a `0x` prefix.

use core::fmt;

use crc::{CRC_64_XZ, Crc, NoTable};

use crate::golden::GoldenError;

/// The seed of the golden point set.
pub const WINDING_SEED: u64 = 0x5EED_0068;

/// Point count, inside count and CRC-64/XZ digests of a run of winding numbers and of the
/// signed distances at the same points.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct WindingDigest {
    /// Points.
    pub points: u32,
    /// Points with `|w| ≥ 1/2`.
    pub inside: u32,
    /// CRC-64/XZ over the little-endian bytes of every number's bit pattern, in point order.
    pub digest: u64,
    /// The same over every signed distance.
    pub signed: u64,
}

static CRC64: Crc<u64, NoTable> = Crc::<u64, NoTable>::new(&CRC_64_XZ);

impl WindingDigest {
    /// Digests winding numbers and signed distances, pairs in point order (extra entries of
    /// the longer slice are left out). Counts past `u32::MAX` saturate.
    #[must_use]
    pub fn of(numbers: &[f32], signed: &[f32]) -> Self {
        let mut digester = WindingDigester::default();
        for (&w, &d) in numbers.iter().zip(signed) {
            digester.add(w, d);
        }
        digester.finish()
    }
}

/// [`WindingDigest::of`] one point at a time, for a caller with no room for the whole run
/// (firmware).
#[derive(Clone)]
pub struct WindingDigester {
    points: u32,
    inside: u32,
    numbers: crc::Digest<'static, u64, NoTable>,
    signed: crc::Digest<'static, u64, NoTable>,
}

impl Default for WindingDigester {
    fn default() -> Self {
        Self {
            points: 0,
            inside: 0,
            numbers: CRC64.digest(),
            signed: CRC64.digest(),
        }
    }
}

impl WindingDigester {
    /// Adds the next point's winding number `w` and signed distance `d`.
    pub fn add(&mut self, w: f32, d: f32) {
        self.numbers.update(&w.to_bits().to_le_bytes());
        self.signed.update(&d.to_bits().to_le_bytes());
        self.points = self.points.saturating_add(1);
        self.inside = self.inside.saturating_add(u32::from(w.abs() >= 0.5));
    }

    /// The digest of every point added.
    #[must_use]
    pub fn finish(self) -> WindingDigest {
        WindingDigest {
            points: self.points,
            inside: self.inside,
            digest: self.numbers.finalize(),
            signed: self.signed.finalize(),
        }
    }
}

impl fmt::Display for WindingDigest {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "points={} inside={} digest={:#018x} signed={:#018x}",
            self.points, self.inside, self.digest, self.signed
        )
    }
}

/// The recorded digest of `mesh` in a golden file's `text`.
///
/// # Errors
/// [`GoldenError::MeshMissing`] when no line names `mesh`, [`GoldenError::Malformed`] for a
/// line that names it without all four fields.
pub fn find_winding_golden(text: &str, mesh: &str) -> Result<WindingDigest, GoldenError> {
    for (number, line) in crate::golden::numbered_lines(text) {
        let mut fields = line.split_ascii_whitespace();
        let Some(name) = fields.next() else { continue };
        if name.starts_with('#') || name != mesh {
            continue;
        }
        return parse(fields).ok_or(GoldenError::Malformed { line: number });
    }
    Err(GoldenError::MeshMissing)
}

/// The four fields of a line, after its name.
fn parse<'a>(fields: impl Iterator<Item = &'a str>) -> Option<WindingDigest> {
    let (mut points, mut inside, mut digest, mut signed) = (None, None, None, None);
    for field in fields {
        // A byte search, as the parity file's reader makes it (panic-free on the firmware).
        let equals = field.bytes().position(|b| b == b'=')?;
        let (key, value) = (field.get(..equals)?, field.get(equals + 1..)?);
        let value = match value.strip_prefix("0x") {
            Some(hex) => u64::from_str_radix(hex, 16).ok()?,
            None => value.parse().ok()?,
        };
        match key {
            "points" => points = Some(u32::try_from(value).ok()?),
            "inside" => inside = Some(u32::try_from(value).ok()?),
            "digest" => digest = Some(value),
            "signed" => signed = Some(value),
            _ => return None,
        }
    }
    Some(WindingDigest {
        points: points?,
        inside: inside?,
        digest: digest?,
        signed: signed?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::format;

    #[test]
    fn a_digest_reads_back_from_its_line() {
        let d = WindingDigest::of(&[0.0, 1.0, 0.25, -0.75], &[0.5, -0.5, 1.0, -2.0]);
        assert_eq!(d.inside, 2);
        let line = format!("# comment\nspot {d}\n");
        assert_eq!(find_winding_golden(&line, "spot"), Ok(d));
        assert_eq!(
            find_winding_golden(&line, "cow"),
            Err(GoldenError::MeshMissing)
        );
        assert!(find_winding_golden("spot points=1", "spot").is_err());
        // Streamed, the same digest; another signed distance, another digest.
        let mut streamed = WindingDigester::default();
        for (w, s) in [(0.0, 0.5), (1.0, -0.5), (0.25, 1.0), (-0.75, -2.0)] {
            streamed.add(w, s);
        }
        assert_eq!(streamed.finish(), d);
        assert_ne!(
            WindingDigest::of(&[0.0], &[1.0]),
            WindingDigest::of(&[0.0], &[-1.0])
        );
    }
}
