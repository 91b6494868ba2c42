//! Marking the edges remeshing keeps: creases sharper than a feature angle.

use glam::Vec3;

use super::half_edges::HalfEdgeMesh;
use crate::math::{cross, dot};

impl HalfEdgeMesh<'_> {
    /// The unnormalised normal of triangle `t` (twice its area long), from its corners in
    /// order.
    #[must_use]
    pub(crate) fn triangle_normal(&self, t: u32) -> Vec3 {
        let [a, b, c] = self.triangle(t).map(|v| self.position(v));
        cross(b - a, c - a)
    }

    /// Marks as creases the interior edges whose two triangles' normals differ by more than
    /// `feature_angle` degrees, and clears every other edge's mark. Returns the number of
    /// crease edges. A triangle with no area has no normal: its edges are not marked.
    pub(crate) fn mark_creases(&mut self, feature_angle: f32) -> usize {
        let cos_limit = libm::cosf(feature_angle.to_radians());
        let mut creases = 0usize;
        for he in 0..self.half_edge_count() as u32 {
            let crease = self.twin(he).is_some_and(|g| {
                let (n1, n2) = (self.triangle_normal(he / 3), self.triangle_normal(g / 3));
                let (l1, l2) = (dot(n1, n1), dot(n2, n2));
                // cos θ = n1·n2 / (|n1||n2|) < cos limit, without dividing by a zero length.
                l1 > 0.0 && l2 > 0.0 && dot(n1, n2) < cos_limit * libm::sqrtf(l1 * l2)
            });
            if let Some(slot) = self.creases.get_mut(he as usize) {
                *slot = crease;
            }
            creases += usize::from(crease);
        }
        self.has_creases = creases > 0;
        creases / 2
    }
}
