//! The smoothing pass: every free vertex toward the area-weighted centroid of its one-ring,
//! within its tangent plane, and onto the input, one vertex at a time, each move judged as
//! it is made.

use glam::Vec3;

use super::half_edges::HalfEdgeMesh;
use super::moves::{is_free, moves_safely};
use super::report::{RemeshObserver, RemeshStep};
use super::surface::Input;
use crate::math::{cross, dot};
use crate::query::MeshQuery;

/// Moves each free vertex, in order, to the point of `reference` nearest its
/// [`tangential_goal`] (every goal from the positions before the pass), where
/// [`moves_safely`] allows (no triangle turned over, flattened or facing against the
/// input); a vertex whose goal is refused and that lies off the input (a split's midpoint)
/// tries its own nearest point of the input instead; otherwise it stays. Each move is
/// judged against the mesh as the moves before it left it, so the mesh is sound after every
/// one (`observer` sees each); the order changes which moves are refused, not where a
/// vertex aims. `goals` holds the goals: at least one entry per vertex.
pub(super) fn smooth<Q: MeshQuery + ?Sized, O: RemeshObserver + ?Sized>(
    mesh: &mut HalfEdgeMesh<'_>,
    input: &Input<'_, Q>,
    goals: &mut [[f32; 3]],
    observer: &mut O,
) {
    let count = mesh.vertex_count();
    for (v, slot) in (0u32..).zip(goals.iter_mut().take(count)) {
        let goal = is_free(mesh, v).then(|| tangential_goal(mesh, v)).flatten();
        *slot = goal.unwrap_or_else(|| mesh.position(v)).to_array();
    }
    for (v, goal) in (0u32..).zip(goals.iter().take(count)) {
        let (goal, p) = (Vec3::from_array(*goal), mesh.position(v));
        if goal == p {
            continue;
        }
        let safe = |to: &Vec3| *to != p && moves_safely(mesh, input, v, *to);
        let to = input
            .closest_on(goal, p)
            .filter(safe)
            .or_else(|| input.closest_on(p, goal).filter(safe));
        if let Some(to) = to {
            mesh.set_position(v, to);
            observer.edited(RemeshStep::Smooth, mesh);
        }
    }
}

/// Where tangential smoothing takes free vertex `v`: toward the area-weighted centroid of its
/// one-ring's triangles, within its tangent plane (the plane of their area-weighted normal).
/// `None` where the one-ring has no area or no normal.
fn tangential_goal(mesh: &HalfEdgeMesh<'_>, v: u32) -> Option<Vec3> {
    let p = mesh.position(v);
    let (mut weighted, mut area, mut normal) = (Vec3::ZERO, 0.0f32, Vec3::ZERO);
    mesh.for_each_outgoing(v, |he| {
        let [a, b, c] = mesh.triangle(he / 3).map(|x| mesh.position(x));
        let n = cross(b - a, c - a);
        let double_area = libm::sqrtf(dot(n, n));
        weighted += (a + b + c) * (double_area / 3.0);
        area += double_area;
        normal += n;
    });
    let normal_len = dot(normal, normal);
    if !(area > 0.0 && normal_len > 0.0) {
        return None;
    }
    let step = weighted / area - p;
    // Remove the step's part along the normal: the move stays on the tangent plane.
    Some(p + (step - normal * (dot(step, normal) / normal_len)))
}
