//! Which cells reference a triangle: every cell its triangle touches, padded for rounding.

use crate::geom::overlap_triangle_aabb;
use crate::math::{Aabb, Triangle, max_f32};

/// The slack added around every cell before testing which triangles touch it.
///
/// A query meets a triangle in a cell only if the cell references it. Where a hit point, a
/// closest point or an overlap's witness lies within rounding of a cell face, the traversal may
/// find it on either side, so a triangle within that distance of a cell is referenced by it
/// too. The pad is 2⁻²⁰ of the scene's largest extent plus its largest coordinate: sixteen
/// times the rounding of a point computed within the scene, and small enough that a plane cut
/// close beside a triangle (as a k-d tree cuts off empty space) does not pick it up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ReferencePad(f32);

impl ReferencePad {
    /// The pad for a scene with bounds `bounds`.
    pub(crate) fn of(bounds: &Aabb) -> Self {
        if bounds.is_empty() || !bounds.is_finite() {
            return Self(0.0);
        }
        let e = bounds.extent();
        let m = bounds.min.abs().max(bounds.max.abs());
        Self((max_f32(max_f32(e.x, e.y), e.z) + max_f32(max_f32(m.x, m.y), m.z)) / 1_048_576.0)
    }

    /// Whether triangle `tri` is referenced by the cell with box `cell`.
    #[inline]
    pub(crate) fn touches(self, tri: &Triangle, cell: &Aabb) -> bool {
        let padded = self.grow(cell);
        // A corner inside the padded box settles it without the separating-axis test (most
        // small triangles have one in each cell they touch).
        let corner_inside = padded.is_finite()
            && [tri.a, tri.b, tri.c]
                .iter()
                .any(|&p| padded.contains_point(p));
        corner_inside || overlap_triangle_aabb(tri, &padded)
    }

    /// Whether a triangle with bounds `bounds` may touch the side of the plane `axis = at`
    /// (above it when `above`, else below) once that side's cell is padded: false when its
    /// bounds end more than the pad short of the plane, so no overlap test is needed.
    #[inline]
    pub(crate) fn reaches_side(self, bounds: &Aabb, axis: usize, at: f32, above: bool) -> bool {
        if above {
            !(bounds.max[axis] < at - self.0)
        } else {
            !(bounds.min[axis] > at + self.0)
        }
    }

    /// `aabb` grown by the pad.
    #[inline]
    pub(crate) fn grow(self, aabb: &Aabb) -> Aabb {
        let pad = glam::Vec3::splat(self.0);
        Aabb::new(aabb.min - pad, aabb.max + pad)
    }
}
