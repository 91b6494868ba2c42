use glam::Vec3;

use crate::math::Aabb;

/// Build scratch: one triangle's bounds, centroid and index. The builder fills and reorders a
/// caller-provided slice of these (one per triangle); their content afterwards is unspecified.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimRef {
    pub(crate) bounds: Aabb,
    pub(crate) center: Vec3,
    pub(crate) tri: u32,
}

impl PrimRef {
    /// A placeholder for initializing scratch buffers.
    pub const EMPTY: Self = Self {
        bounds: Aabb::EMPTY,
        center: Vec3::ZERO,
        tri: 0,
    };
}

impl Default for PrimRef {
    fn default() -> Self {
        Self::EMPTY
    }
}
