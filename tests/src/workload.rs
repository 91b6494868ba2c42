//! The workloads of DESIGN.md as vectors, from the shared `meshq-workload` generators.

use glam::Vec3;
use meshq::math::Ray;
use meshq_workload::{CameraRays, QueryPoints, RandomRays};
pub use meshq_workload::{centre_radius, point_in_box, unit_sphere};

/// `count` random rays around the mesh with these positions.
#[must_use]
pub fn random_rays(positions: &[[f32; 3]], count: usize, seed: u64) -> Vec<Ray> {
    RandomRays::new(centre_radius(positions).2, seed)
        .take(count)
        .collect()
}

/// `width × height` camera rays, row-major.
#[must_use]
pub fn camera_rays(positions: &[[f32; 3]], width: usize, height: usize) -> Vec<Ray> {
    CameraRays::new(centre_radius(positions).2, width, height).collect()
}

/// `count` closest-point query points.
#[must_use]
pub fn closest_points(positions: &[[f32; 3]], count: usize, seed: u64) -> Vec<Vec3> {
    QueryPoints::new(centre_radius(positions).2, seed)
        .take(count)
        .collect()
}
