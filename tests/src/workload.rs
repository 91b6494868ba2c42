//! The workloads of DESIGN.md, so tests and benchmarks use identical inputs.

use glam::Vec3;
use meshq::math::{Aabb, Ray};

use crate::SplitMix64;

/// Bounding-box centre `c` and half-diagonal `r` of a point set.
#[must_use]
pub fn centre_radius(positions: &[[f32; 3]]) -> (Vec3, f32, Aabb) {
    let b = positions
        .iter()
        .fold(Aabb::EMPTY, |b, &p| b.grown(Vec3::from_array(p)));
    (b.center(), b.extent().length() * 0.5, b)
}

/// A direction uniform on the unit sphere.
pub fn unit_sphere(rng: &mut SplitMix64) -> Vec3 {
    loop {
        let v = Vec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        let l2 = v.length_squared();
        if l2 > 1e-6 && l2 <= 1.0 {
            return v / l2.sqrt();
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

/// `count` random rays: origin uniform on the sphere of radius 1.5·r around `c`, direction
/// normalized toward a point uniform in the bounding box.
#[must_use]
pub fn random_rays(positions: &[[f32; 3]], count: usize, seed: u64) -> Vec<Ray> {
    let (c, r, b) = centre_radius(positions);
    let mut rng = SplitMix64::new(seed);
    (0..count)
        .map(|_| {
            let origin = c + unit_sphere(&mut rng) * (1.5 * r);
            let target = point_in_box(&mut rng, &b);
            Ray::new(origin, (target - origin).normalize_or(Vec3::X))
        })
        .collect()
}

/// `width × height` pinhole camera rays, row-major, from `c + (0, 0, 2.5·r)` looking at `c`
/// with a 45° vertical field of view.
#[must_use]
pub fn camera_rays(positions: &[[f32; 3]], width: usize, height: usize) -> Vec<Ray> {
    let (c, r, _) = centre_radius(positions);
    let eye = c + Vec3::new(0.0, 0.0, 2.5 * r);
    let half_h = (22.5f32).to_radians().tan();
    let half_w = half_h * width as f32 / height as f32;
    let mut rays = Vec::with_capacity(width * height);
    for y in 0..height {
        for x in 0..width {
            let sx = ((x as f32 + 0.5) / width as f32 * 2.0 - 1.0) * half_w;
            let sy = (1.0 - (y as f32 + 0.5) / height as f32 * 2.0) * half_h;
            rays.push(Ray::new(eye, Vec3::new(sx, sy, -1.0).normalize()));
        }
    }
    rays
}

/// `count` query points uniform in the bounding box grown by 10 % of its size on each side.
#[must_use]
pub fn closest_points(positions: &[[f32; 3]], count: usize, seed: u64) -> Vec<Vec3> {
    let (_, _, b) = centre_radius(positions);
    let grow = b.extent() * 0.1;
    let grown = Aabb::new(b.min - grow, b.max + grow);
    let mut rng = SplitMix64::new(seed);
    (0..count).map(|_| point_in_box(&mut rng, &grown)).collect()
}
