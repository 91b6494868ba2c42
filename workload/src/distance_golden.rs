//! The golden mesh-distance file (`tests/golden/distance.txt`): the closest pairs of each
//! bundled mesh and copies of it in fixed placements, bit for bit, checked natively and in
//! WebAssembly.
//!
//! A line is the mesh name followed by `key=value` fields in any order:
//!
//! ```text
//! spot placements=4 digest=0x…
//! ```
//!
//! Each placement of [`DISTANCE_PLACEMENTS`] is scaled by the mesh's bounding radius `r` and
//! moved by its centre `c` (see [`placement_for`]); the pairs are those of
//! `meshq::collide::mesh_distance` with default limits, the mesh against itself so placed,
//! over BVHs built with the default build config. `digest` ([`DistanceDigest`]) covers every
//! pair's distance, points and triangles. A line `<mesh>-sweeps` digests the sweeps of
//! [`golden_sweeps`] by `MeshQuery::sweep` likewise, each hit as `(t, point, normal,
//! triangle, 0)` (its `placements` field counting the sweeps).

use core::fmt;

use crc::{CRC_64_XZ, Crc, NoTable};
use glam::Vec3;

use crate::golden::GoldenError;

/// Placements of the copy, as (quarter turns about z, offset along x in bounding radii):
/// crossing, just apart, turned inside itself, and far.
pub const DISTANCE_PLACEMENTS: [(u8, f32); 4] = [(1, 0.5), (0, 2.05), (2, 0.0), (3, 7.0)];

/// The column-major 4×4 matrix of placement `(quarter_turns, offset)` for a mesh of centre
/// `c` and bounding radius `r`: turned about the z axis through `c`, then moved `offset · r`
/// along x. Quarter turns have exact sines and cosines, and every other step is one IEEE
/// operation, so native and WebAssembly place the copy on the same bits.
#[must_use]
pub fn placement_for(c: [f32; 3], r: f32, (quarter_turns, offset): (u8, f32)) -> [f32; 16] {
    let (s, co) = match quarter_turns % 4 {
        0 => (0.0, 1.0),
        1 => (1.0, 0.0),
        2 => (0.0, -1.0),
        _ => (-1.0, 0.0),
    };
    // x' = co·(x − cx) − s·(y − cy) + cx + offset·r; y' = s·(x − cx) + co·(y − cy) + cy.
    let tx = c[0] - co * c[0] + s * c[1] + offset * r;
    let ty = c[1] - s * c[0] - co * c[1];
    [
        co, s, 0.0, 0.0, -s, co, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, tx, ty, 0.0, 1.0,
    ]
}

/// Sweeps of the golden file: `count` shapes (spheres, capsules and boxes in turn, sized by
/// `r`) starting on a ring of radius `2r` around `c`, each moved by `3.5r` through near the
/// centre. Directions come from a fixed table of small integers, so every coordinate is the
/// same bits on every target.
pub fn golden_sweeps(
    c: [f32; 3],
    r: f32,
) -> impl Iterator<Item = (meshq::query::SweepShape, Vec3)> {
    use meshq::math::Obb;
    use meshq::query::SweepShape;
    const DIRECTIONS: [[f32; 3]; 12] = [
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [-1.0, 0.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, -1.0],
        [0.6, 0.8, 0.0],
        [0.0, 0.6, -0.8],
        [-0.8, 0.0, 0.6],
        [0.48, -0.6, 0.64],
        [-0.6, -0.48, -0.64],
        [0.64, 0.48, -0.6],
    ];
    let centre = Vec3::from_array(c);
    DIRECTIONS.into_iter().enumerate().map(move |(k, d)| {
        let d = Vec3::from_array(d);
        let start = centre + d * (2.0 * r);
        // Aimed a little off the centre, so sweeps graze as well as hit square on.
        let aim = centre + Vec3::new(d.y, d.z, d.x) * (0.1 * r);
        let motion = (aim - start) * 1.75;
        let size = r * 0.08;
        let shape = match k % 3 {
            0 => SweepShape::Sphere {
                center: start,
                radius: size,
            },
            1 => SweepShape::Capsule {
                a: start - Vec3::new(d.z, d.x, d.y) * size,
                b: start + Vec3::new(d.z, d.x, d.y) * size,
                radius: size * 0.5,
            },
            _ => SweepShape::Box(Obb::new(
                start,
                [Vec3::X, Vec3::Y, Vec3::Z],
                Vec3::new(size, size * 0.5, size * 0.25),
            )),
        };
        (shape, motion)
    })
}

/// Placement count and CRC-64/XZ digest of a run of closest pairs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DistanceDigest {
    /// Placements digested.
    pub placements: u32,
    /// CRC-64/XZ over, per pair in order, the little-endian bits of the distance, the six
    /// point coordinates and the two triangle indices (a missing pair digests nothing but
    /// counts).
    pub digest: u64,
}

static CRC64: Crc<u64, NoTable> = Crc::<u64, NoTable>::new(&CRC_64_XZ);

/// One closest pair as the digest reads it: distance, point on the first mesh, point on the
/// second, triangle of the first, triangle of the second.
pub type DigestedPair = (f32, [f32; 3], [f32; 3], u32, u32);

impl DistanceDigest {
    /// Digests closest pairs in placement order.
    #[must_use]
    pub fn of(pairs: &[Option<DigestedPair>]) -> Self {
        let mut digest = CRC64.digest();
        for (d, a, b, ta, tb) in pairs.iter().flatten() {
            digest.update(&d.to_bits().to_le_bytes());
            for x in a.iter().chain(b) {
                digest.update(&x.to_bits().to_le_bytes());
            }
            digest.update(&ta.to_le_bytes());
            digest.update(&tb.to_le_bytes());
        }
        Self {
            placements: u32::try_from(pairs.len()).unwrap_or(u32::MAX),
            digest: digest.finalize(),
        }
    }
}

impl fmt::Display for DistanceDigest {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "placements={} digest={:#018x}",
            self.placements, self.digest
        )
    }
}

/// The recorded digest of `mesh` in a golden file's `text`.
///
/// # Errors
/// [`GoldenError::MeshMissing`] when no line names `mesh`, [`GoldenError::Malformed`] for a
/// line that names it without both fields.
pub fn find_distance_golden(text: &str, mesh: &str) -> Result<DistanceDigest, GoldenError> {
    for (number, line) in crate::golden::numbered_lines(text) {
        let mut fields = line.split_ascii_whitespace();
        let Some(name) = fields.next() else { continue };
        if name.starts_with('#') || name != mesh {
            continue;
        }
        let (mut placements, mut digest) = (None, None);
        for field in fields {
            let parsed = field.split_once('=').and_then(|(key, value)| {
                let value = match value.strip_prefix("0x") {
                    Some(hex) => u64::from_str_radix(hex, 16).ok()?,
                    None => value.parse().ok()?,
                };
                Some((key, value))
            });
            match parsed {
                Some(("placements", v)) => placements = u32::try_from(v).ok(),
                Some(("digest", v)) => digest = Some(v),
                _ => return Err(GoldenError::Malformed { line: number }),
            }
        }
        return match (placements, digest) {
            (Some(placements), Some(digest)) => Ok(DistanceDigest { placements, digest }),
            _ => Err(GoldenError::Malformed { line: number }),
        };
    }
    Err(GoldenError::MeshMissing)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::format;

    #[test]
    fn a_line_round_trips_and_bad_lines_are_named() {
        let d = DistanceDigest::of(&[Some((1.5, [0.0; 3], [1.0; 3], 3, 4)), None]);
        let line = format!("spot {d}");
        assert_eq!(find_distance_golden(&line, "spot"), Ok(d));
        assert_eq!(
            find_distance_golden(&line, "cow"),
            Err(GoldenError::MeshMissing)
        );
        assert!(find_distance_golden("spot placements=1", "spot").is_err());
        assert!(find_distance_golden("spot placements=1 digest=0x1 extra=2", "spot").is_err());
        // The pair's bits change the digest.
        let other = DistanceDigest::of(&[Some((1.5, [0.0; 3], [1.0; 3], 3, 5)), None]);
        assert_ne!(d, other);
    }
}
