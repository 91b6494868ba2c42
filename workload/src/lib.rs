//! The query workloads of meshq's DESIGN.md, generated from a seeded integer generator so every
//! harness — tests, benchmarks, the CLI, the browser and the firmware — uses the same inputs,
//! bit for bit, on every target. `no_std`, no allocation: every workload is an iterator.
//!
//! For a mesh with bounding-box centre `c` and half-diagonal `r`:
//! - [`RandomRays`]: origin uniform on the sphere of radius 1.5·r around `c`, direction
//!   normalized toward a point uniform in the box;
//! - [`CameraRays`]: pinhole rays from `c + (0, 0, 2.5·r)` looking at `c`, 45° vertical field of
//!   view, row-major;
//! - [`QueryPoints`]: points uniform in the box grown by 10 % of its size on each side.
//!
//! Only `+ − × ÷`, `sqrt` (correctly rounded everywhere) and `libm` are used, so the numbers do
//! not depend on the target.
//!
//! [`parity`] runs a fixed set of these queries on any target and digests every result bit;
//! [`golden`] reads and writes the golden file those digests are checked against, and
//! [`remesh_golden`] the golden file of remeshing results, [`winding_golden`] that of winding
//! numbers.
#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]

#[cfg(test)]
extern crate std;

pub mod distance_golden;
pub mod golden;
pub mod parity;
pub mod remesh_golden;
mod rng;
pub mod winding_golden;

use glam::Vec3;
use meshq::math::{Aabb, Ray};

pub use distance_golden::{
    DISTANCE_PLACEMENTS, DistanceDigest, find_distance_golden, golden_sweeps, placement_for,
};
pub use golden::{GoldenEntry, GoldenError, find_golden};
pub use parity::{ParityDigest, ParityReport, ParitySpec, ParityTarget, run_parity};
pub use remesh_golden::{MeshDigest, RemeshGolden, find_remesh_golden};
pub use rng::SplitMix64;
pub use winding_golden::{WINDING_SEED, WindingDigest, WindingDigester, find_winding_golden};

/// Bounding-box centre `c`, half-diagonal `r` and the box of a point set.
#[must_use]
pub fn centre_radius(positions: &[[f32; 3]]) -> (Vec3, f32, Aabb) {
    bounds_centre_radius(
        positions
            .iter()
            .fold(Aabb::EMPTY, |b, &p| b.grown(Vec3::from_array(p))),
    )
}

/// Centre and half-diagonal of a box, with the box.
#[must_use]
pub fn bounds_centre_radius(b: Aabb) -> (Vec3, f32, Aabb) {
    (b.center(), b.extent().length() * 0.5, b)
}

/// A direction uniform on the unit sphere (rejection sampling in the cube).
pub fn unit_sphere(rng: &mut SplitMix64) -> Vec3 {
    loop {
        let v = Vec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        let l2 = v.length_squared();
        if l2 > 1e-6 && l2 <= 1.0 {
            return v / libm::sqrtf(l2);
        }
    }
}

/// A point uniform in a box.
#[must_use]
pub fn point_in_box(rng: &mut SplitMix64, b: &Aabb) -> Vec3 {
    Vec3::new(
        rng.range(b.min.x, b.max.x),
        rng.range(b.min.y, b.max.y),
        rng.range(b.min.z, b.max.z),
    )
}

/// Endless random rays around a box (see the crate docs); take as many as needed.
#[derive(Clone, Debug)]
pub struct RandomRays {
    rng: SplitMix64,
    centre: Vec3,
    radius: f32,
    bounds: Aabb,
}

impl RandomRays {
    /// Random rays around the mesh bounds `bounds`, from `seed`.
    #[must_use]
    pub fn new(bounds: Aabb, seed: u64) -> Self {
        let (centre, radius, bounds) = bounds_centre_radius(bounds);
        Self {
            rng: SplitMix64::new(seed),
            centre,
            radius,
            bounds,
        }
    }
}

impl Iterator for RandomRays {
    type Item = Ray;

    fn next(&mut self) -> Option<Ray> {
        let origin = self.centre + unit_sphere(&mut self.rng) * (1.5 * self.radius);
        let target = point_in_box(&mut self.rng, &self.bounds);
        Some(Ray::new(origin, (target - origin).normalize_or(Vec3::X)))
    }
}

/// The camera rays of a `width × height` image, row-major (see the crate docs).
#[derive(Clone, Debug)]
pub struct CameraRays {
    eye: Vec3,
    half_w: f32,
    half_h: f32,
    width: usize,
    height: usize,
    next: usize,
}

impl CameraRays {
    /// The camera looking at the mesh bounds `bounds`.
    #[must_use]
    pub fn new(bounds: Aabb, width: usize, height: usize) -> Self {
        let (c, r, _) = bounds_centre_radius(bounds);
        let half_h = libm::tanf(22.5f32.to_radians());
        Self {
            eye: c + Vec3::new(0.0, 0.0, 2.5 * r),
            half_w: half_h * width as f32 / height.max(1) as f32,
            half_h,
            width,
            height,
            next: 0,
        }
    }
}

impl Iterator for CameraRays {
    type Item = Ray;

    fn next(&mut self) -> Option<Ray> {
        if self.width == 0 || self.next >= self.width.saturating_mul(self.height) {
            return None;
        }
        let (x, y) = (self.next % self.width, self.next / self.width);
        self.next += 1;
        let sx = ((x as f32 + 0.5) / self.width as f32 * 2.0 - 1.0) * self.half_w;
        let sy = (1.0 - (y as f32 + 0.5) / self.height as f32 * 2.0) * self.half_h;
        Some(Ray::new(self.eye, Vec3::new(sx, sy, -1.0).normalize()))
    }
}

/// Endless query points in the grown box (see the crate docs).
#[derive(Clone, Debug)]
pub struct QueryPoints {
    rng: SplitMix64,
    grown: Aabb,
}

impl QueryPoints {
    /// Query points around the mesh bounds `bounds`, from `seed`.
    #[must_use]
    pub fn new(bounds: Aabb, seed: u64) -> Self {
        let grow = bounds.extent() * 0.1;
        Self {
            rng: SplitMix64::new(seed),
            grown: Aabb::new(bounds.min - grow, bounds.max + grow),
        }
    }
}

impl Iterator for QueryPoints {
    type Item = Vec3;

    fn next(&mut self) -> Option<Vec3> {
        Some(point_in_box(&mut self.rng, &self.grown))
    }
}
