use glam::Vec3;

use crate::math::{Aabb, Triangle};

/// A mesh that passed [`MeshRef::validate`](super::MeshRef::validate): every index is in range,
/// every coordinate finite and bounded, and both counts fit in `u32`.
///
/// Only `validate` creates one, so holding a `ValidMesh` is the proof.
#[derive(Clone, Copy, Debug)]
pub struct ValidMesh<'a> {
    positions: &'a [[f32; 3]],
    triangles: &'a [[u32; 3]],
}

impl<'a> ValidMesh<'a> {
    /// Only for `MeshRef::validate`, after its checks, and for copies of a validated mesh.
    pub(crate) const fn new_unchecked_by_validate(
        positions: &'a [[f32; 3]],
        triangles: &'a [[u32; 3]],
    ) -> Self {
        Self {
            positions,
            triangles,
        }
    }

    /// The positions.
    #[must_use]
    pub const fn positions(&self) -> &'a [[f32; 3]] {
        self.positions
    }

    /// The triangles (vertex-index triples).
    #[must_use]
    pub const fn triangles(&self) -> &'a [[u32; 3]] {
        self.triangles
    }

    /// Number of vertices.
    #[must_use]
    pub const fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of triangles (fits in `u32`).
    #[must_use]
    pub const fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Triangle `index` by value, or `None` past the end.
    #[inline(always)]
    #[must_use]
    pub fn triangle(&self, index: u32) -> Option<Triangle> {
        let [i, j, k] = *self.triangles.get(index as usize)?;
        let a = *self.positions.get(i as usize)?;
        let b = *self.positions.get(j as usize)?;
        let c = *self.positions.get(k as usize)?;
        Some(Triangle::new(
            Vec3::from_array(a),
            Vec3::from_array(b),
            Vec3::from_array(c),
        ))
    }

    /// The bounds of every vertex used or not ([`Aabb::EMPTY`] for no vertices).
    #[must_use]
    pub fn bounds(&self) -> Aabb {
        self.positions
            .iter()
            .fold(Aabb::EMPTY, |b, &p| b.grown(Vec3::from_array(p)))
    }
}
