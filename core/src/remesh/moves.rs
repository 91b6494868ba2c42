//! Moving one vertex: whether it may move at all, and whether a move is safe.

use glam::Vec3;

use super::half_edges::HalfEdgeMesh;
use super::shape::{flat_enough, flatness, normal_of};
use super::surface::Input;
use crate::math::dot;
use crate::query::MeshQuery;

/// Whether vertex `v` may move: not on the boundary, on no crease, used by a triangle.
pub(super) fn is_free(mesh: &HalfEdgeMesh<'_>, v: u32) -> bool {
    mesh.vertex_half_edge(v).is_some() && !mesh.is_boundary_vertex(v) && !mesh.touches_crease(v)
}

/// Whether moving vertex `v` to `to` keeps each of its triangles facing the same way, no
/// flatter than [`FLATTEST`](super::shape::FLATTEST) (unless it was flatter already and
/// gets no worse), and facing the way the input `reference` does under its centroid (see
/// [`faces_input`]).
pub(super) fn moves_safely<Q: MeshQuery + ?Sized>(
    mesh: &HalfEdgeMesh<'_>,
    input: &Input<'_, Q>,
    v: u32,
    to: Vec3,
) -> bool {
    // The cheap tests on every triangle first; the input is asked only when all pass.
    let mut safe = keeps_shape(mesh, v, to);
    mesh.for_each_outgoing(v, |he| {
        if safe {
            let corners = mesh.triangle(he / 3);
            safe = input.faces_input(corners.map(|x| if x == v { to } else { mesh.position(x) }));
        }
    });
    safe
}

/// Whether moving vertex `v` to `to` keeps each of its triangles facing the same way and no
/// flatter than [`FLATTEST`](super::shape::FLATTEST) (unless it was flatter already and
/// gets no worse): the tests of [`moves_safely`] that need no search.
pub(super) fn keeps_shape(mesh: &HalfEdgeMesh<'_>, v: u32, to: Vec3) -> bool {
    let mut kept = true;
    mesh.for_each_outgoing(v, |he| {
        if !kept {
            return;
        }
        let corners = mesh.triangle(he / 3);
        let before = corners.map(|x| mesh.position(x));
        let after = corners.map(|x| if x == v { to } else { mesh.position(x) });
        kept = dot(normal_of(before), normal_of(after)) > 0.0
            && flat_enough(flatness(after), || flatness(before));
    });
    kept
}
