//! The cross-target parity run: one fixed set of closest-hit rays, any-hit rays and
//! closest-point queries, folded into a 64-bit digest of every result bit. Native tests, the
//! WebAssembly tests and the firmware all run it and compare the digest with the golden file
//! (see [`crate::golden`]), so "bit-identical on every target" is checked, not assumed.
//!
//! The queries come from [`RandomRays`] and [`QueryPoints`] around the structure's root bounds
//! (the box a blob header records), so every target derives the same inputs from the blob alone.

use crc::{CRC_64_XZ, Crc, Digest, NoTable};
use glam::Vec3;
use meshq::math::{Aabb, ClosestPoint, Ray, RayHit};

use crate::{QueryPoints, RandomRays};

/// How many queries of each kind a parity run makes, and from which seed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ParitySpec {
    /// Seed of the closest-hit rays; the any-hit rays use `seed + 1`, the points `seed + 2`.
    pub seed: u64,
    /// Number of closest-hit rays (`raycast`).
    pub rays: u32,
    /// Number of any-hit rays (`raycast_any`).
    pub any_rays: u32,
    /// Number of closest-point queries (unbounded distance).
    pub points: u32,
}

impl ParitySpec {
    /// The run every target makes: small enough for an emulated Cortex-M4 to finish the
    /// 69k-triangle bunny in seconds, large enough that every result kind appears many times.
    pub const DEFAULT: Self = Self {
        seed: 0x6d65_7368_7150_6172,
        rays: 1024,
        any_rays: 1024,
        points: 256,
    };

    /// The closest-hit rays around `bounds`.
    pub fn rays(&self, bounds: Aabb) -> impl Iterator<Item = Ray> {
        RandomRays::new(bounds, self.seed).take(self.rays as usize)
    }

    /// The any-hit rays around `bounds`.
    pub fn any_rays(&self, bounds: Aabb) -> impl Iterator<Item = Ray> {
        RandomRays::new(bounds, self.seed.wrapping_add(1)).take(self.any_rays as usize)
    }

    /// The closest-point queries around `bounds`.
    pub fn points(&self, bounds: Aabb) -> impl Iterator<Item = Vec3> {
        QueryPoints::new(bounds, self.seed.wrapping_add(2)).take(self.points as usize)
    }
}

/// What a parity run found: the digest of every result bit and counts that make a mismatch
/// easier to read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ParityReport {
    /// CRC-64/XZ over every result in query order (see [`ParityDigest`]).
    pub digest: u64,
    /// Closest-hit rays that hit.
    pub hits: u32,
    /// Any-hit rays that hit.
    pub any_hits: u32,
    /// Closest-point queries that found a point.
    pub points_found: u32,
}

static CRC64: Crc<u64, NoTable> = Crc::<u64, NoTable>::new(&CRC_64_XZ);

/// Folds query results into a CRC-64/XZ digest. Each result is written as little-endian bytes:
/// a miss as one `0` byte; a ray hit as `1`, then `t`, `tri`, `u`, `v` (f32 as raw bits); an
/// any-hit answer as one byte `0`/`1`; a closest point as `1`, then the point's `x, y, z`,
/// `tri`, `u`, `v` and `distance_squared`. No table, so the firmware pays no flash for one.
pub struct ParityDigest {
    digest: Digest<'static, u64, NoTable>,
    hits: u32,
    any_hits: u32,
    points_found: u32,
}

impl Default for ParityDigest {
    fn default() -> Self {
        Self::new()
    }
}

impl core::fmt::Debug for ParityDigest {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("ParityDigest")
            .field("hits", &self.hits)
            .field("any_hits", &self.any_hits)
            .field("points_found", &self.points_found)
            .finish_non_exhaustive()
    }
}

impl ParityDigest {
    /// An empty digest.
    #[must_use]
    pub fn new() -> Self {
        Self {
            digest: CRC64.digest(),
            hits: 0,
            any_hits: 0,
            points_found: 0,
        }
    }

    fn words(&mut self, words: &[u32]) {
        for w in words {
            self.digest.update(&w.to_le_bytes());
        }
    }

    /// Adds a closest-hit answer.
    pub fn ray(&mut self, hit: Option<RayHit>) {
        match hit {
            None => self.digest.update(&[0]),
            Some(h) => {
                self.hits += 1;
                self.digest.update(&[1]);
                self.words(&[h.t.to_bits(), h.tri, h.u.to_bits(), h.v.to_bits()]);
            }
        }
    }

    /// Adds an any-hit answer.
    pub fn any(&mut self, hit: bool) {
        self.any_hits += u32::from(hit);
        self.digest.update(&[u8::from(hit)]);
    }

    /// Adds a closest-point answer.
    pub fn closest(&mut self, found: Option<ClosestPoint>) {
        match found {
            None => self.digest.update(&[0]),
            Some(c) => {
                self.points_found += 1;
                self.digest.update(&[1]);
                self.words(&[
                    c.point.x.to_bits(),
                    c.point.y.to_bits(),
                    c.point.z.to_bits(),
                    c.tri,
                    c.u.to_bits(),
                    c.v.to_bits(),
                    c.distance_squared.to_bits(),
                ]);
            }
        }
    }

    /// The digest and counts so far.
    #[must_use]
    pub fn report(&self) -> ParityReport {
        ParityReport {
            digest: self.digest.clone().finalize(),
            hits: self.hits,
            any_hits: self.any_hits,
            points_found: self.points_found,
        }
    }
}

/// The three queries a parity run needs from a structure (or from a brute-force scan).
pub trait ParityTarget {
    /// The closest hit in `[ray.t_min, ray.t_max]`, lower triangle index on equal `t`.
    fn raycast(&mut self, ray: &Ray) -> Option<RayHit>;
    /// Whether anything is hit in `[ray.t_min, ray.t_max]`.
    fn raycast_any(&mut self, ray: &Ray) -> bool;
    /// The closest surface point at any distance, lower triangle index on equal distance.
    fn closest_point(&mut self, point: Vec3) -> Option<ClosestPoint>;
}

/// Runs `spec` against `target` around `bounds` and returns the digest of every answer.
pub fn run_parity<T: ParityTarget + ?Sized>(
    spec: &ParitySpec,
    bounds: Aabb,
    target: &mut T,
) -> ParityReport {
    let mut digest = ParityDigest::new();
    for ray in spec.rays(bounds) {
        digest.ray(target.raycast(&ray));
    }
    for ray in spec.any_rays(bounds) {
        digest.any(target.raycast_any(&ray));
    }
    for point in spec.points(bounds) {
        digest.closest(target.closest_point(point));
    }
    digest.report()
}
