//! Moving one vertex: whether it may move at all, whether a move is safe, and where the
//! surface is.

use glam::Vec3;

use super::half_edges::HalfEdgeMesh;
use super::shape::{flat_enough, flatness, normal_of};
use crate::math::dot;
use crate::query::MeshQuery;

/// Whether vertex `v` may move: not on the boundary, on no crease, used by a triangle.
pub(super) fn is_free(mesh: &HalfEdgeMesh<'_>, v: u32) -> bool {
    mesh.vertex_half_edge(v).is_some() && !mesh.is_boundary_vertex(v) && !mesh.touches_crease(v)
}

/// Whether moving vertex `v` to `to` keeps each of its triangles facing the same way and no
/// flatter than [`FLATTEST`](super::shape::FLATTEST) (unless it was flatter already and
/// gets no worse).
pub(super) fn moves_safely(mesh: &HalfEdgeMesh<'_>, v: u32, to: Vec3) -> bool {
    let mut safe = true;
    mesh.for_each_outgoing(v, |he| {
        let corners = mesh.triangle(he / 3);
        let before = corners.map(|x| mesh.position(x));
        let after = corners.map(|x| if x == v { to } else { mesh.position(x) });
        let (was, now) = (flatness(before), flatness(after));
        let (before, after) = (normal_of(before), normal_of(after));
        safe &= dot(before, after) > 0.0 && flat_enough(now, was);
    });
    safe
}

/// The closest point of `reference` to `p`, a point moved there from `was` on (or near) the
/// surface. The surface is then at most as far from `p` as the move, so the query first
/// looks only that far (a much smaller search) and only on finding nothing looks
/// everywhere: the closest point is the same either way. `None` only for an empty
/// reference or a point it cannot measure.
pub(super) fn closest_on<Q: MeshQuery + ?Sized>(reference: &Q, p: Vec3, was: Vec3) -> Option<Vec3> {
    let moved = p - was;
    let near = libm::sqrtf(dot(moved, moved)) * 1.001;
    reference
        .closest_point(p, near)
        .or_else(|| reference.closest_point(p, f32::INFINITY))
        .map(|hit| hit.point)
}
