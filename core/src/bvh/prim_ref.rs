use glam::Vec3A;

use super::build_box::BuildBox;

/// Build scratch: one triangle's bounding box (32 bytes, 16-byte aligned so the builder can
/// work on whole boxes in SIMD registers). The builder fills and reorders a caller-provided
/// slice of these, one per triangle, and keeps the triangle indices alongside in the `order`
/// buffer; the scratch content afterwards is unspecified.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimRef {
    pub(crate) min: Vec3A,
    pub(crate) max: Vec3A,
}

impl PrimRef {
    /// A placeholder for initializing scratch buffers (an empty box).
    pub const EMPTY: Self = Self {
        min: Vec3A::INFINITY,
        max: Vec3A::NEG_INFINITY,
    };

    /// Twice the box centre, `min + max`. Binning and median splits only compare centroids,
    /// and the doubled one saves a multiplication per triangle and level.
    #[inline(always)]
    pub(super) fn centroid2(&self) -> Vec3A {
        self.min + self.max
    }

    #[inline(always)]
    pub(super) fn bounds(&self) -> BuildBox {
        BuildBox {
            min: self.min,
            max: self.max,
        }
    }
}

impl Default for PrimRef {
    fn default() -> Self {
        Self::EMPTY
    }
}
