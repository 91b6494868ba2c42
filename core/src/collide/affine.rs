//! The map that places one mesh in another's frame.

use glam::Vec3;

use crate::error::TransformError;
use crate::math::{Aabb, Triangle};

/// An affine map `x ↦ M·x + t` (rotation, translation, and any scale or shear), in `f32`.
///
/// The mesh–mesh queries apply it to the second mesh to place it in the first mesh's frame;
/// every point they report is in that frame. Each coordinate is computed in one fixed order,
/// `((m₀·x + m₁·y) + m₂·z) + t`, so the same map gives the same bits on every target.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Affine {
    /// The columns of `M`: the images of the x, y and z unit vectors.
    pub columns: [[f32; 3]; 3],
    /// The translation `t`.
    pub translation: [f32; 3],
}

impl Affine {
    /// The map that leaves every point where it is.
    pub const IDENTITY: Self = Self {
        columns: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        translation: [0.0; 3],
    };

    /// A pure translation by `t`.
    #[must_use]
    pub const fn translation(t: [f32; 3]) -> Self {
        Self {
            translation: t,
            ..Self::IDENTITY
        }
    }

    /// The map of a 4×4 matrix in column-major order (three.js `Matrix4.elements`, glam's
    /// `Mat4::to_cols_array`): elements 0–2, 4–6 and 8–10 are the columns of `M`, 12–14 the
    /// translation.
    ///
    /// # Errors
    /// [`TransformError::NotFinite`] when an element is NaN or infinite, and
    /// [`TransformError::NotAffine`] when the bottom row (elements 3, 7, 11, 15) is not
    /// `0, 0, 0, 1`: a projective matrix has no affine meaning here.
    pub fn from_cols_4x4(m: &[f32; 16]) -> Result<Self, TransformError> {
        if let Some(index) = m.iter().position(|x| !x.is_finite()) {
            return Err(TransformError::NotFinite { index });
        }
        let [a, b, c, w0, d, e, f, w1, g, h, i, w2, x, y, z, w3] = *m;
        if [w0, w1, w2, w3] != [0.0, 0.0, 0.0, 1.0] {
            return Err(TransformError::NotAffine);
        }
        Ok(Self {
            columns: [[a, b, c], [d, e, f], [g, h, i]],
            translation: [x, y, z],
        })
    }

    /// The image of point `p`.
    #[inline]
    #[must_use]
    pub fn apply(&self, p: Vec3) -> Vec3 {
        let [c0, c1, c2] = self.columns.map(Vec3::from_array);
        c0 * p.x + c1 * p.y + c2 * p.z + Vec3::from_array(self.translation)
    }

    /// The image of triangle `t`, corner by corner.
    #[inline]
    #[must_use]
    pub fn apply_triangle(&self, t: &Triangle) -> Triangle {
        Triangle::new(self.apply(t.a), self.apply(t.b), self.apply(t.c))
    }

    /// A box holding the image of every point of `b`, including [`apply`](Self::apply)'s
    /// rounding: the exact image box (each output axis the sum of the extreme products,
    /// after Arvo 1990), grown on each axis by eight `f32` epsilons of the largest magnitude
    /// a term of that coordinate can have. An empty box stays empty.
    #[must_use]
    pub(crate) fn apply_box(&self, b: &Aabb) -> Aabb {
        if b.is_empty() {
            return *b;
        }
        let (mut min, mut max) = (self.translation, self.translation);
        let mut magnitude = self.translation.map(f32::abs);
        let ends = b.min.to_array().into_iter().zip(b.max.to_array());
        for (column, (l, h)) in self.columns.iter().zip(ends) {
            let reach = l.abs().max(h.abs());
            let outputs = min.iter_mut().zip(max.iter_mut()).zip(magnitude.iter_mut());
            for (&m, ((lo, hi), size)) in column.iter().zip(outputs) {
                let (x, y) = (m * l, m * h);
                *lo += x.min(y);
                *hi += x.max(y);
                *size += m.abs() * reach;
            }
        }
        let slack = magnitude.map(|m| m * (8.0 * f32::EPSILON));
        Aabb::new(
            Vec3::from_array(min) - Vec3::from_array(slack),
            Vec3::from_array(max) + Vec3::from_array(slack),
        )
    }
}
