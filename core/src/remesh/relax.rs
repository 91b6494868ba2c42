//! The last pass: moving single vertices to open up the smallest angles left after the
//! iterations.
//!
//! Smoothing moves every vertex toward a centroid that weighs areas, not angles, so a few
//! narrow triangles can survive it (often beside a vertex of valence 5 next to one of 7).
//! Here only the vertices of such triangles move, and only when the move raises the
//! smallest angle of their one-ring, measured after projecting onto the input.

use glam::Vec3;

use super::half_edges::HalfEdgeMesh;
use super::moves::{is_free, moves_safely};
use super::report::{RemeshObserver, RemeshStep};
use super::shape::smallest_angle_sine;
use super::surface::Input;
use crate::math::{cross, dot};
use crate::query::MeshQuery;

/// Sine of the angle under which a triangle's vertices are worth moving (about 40°).
const NARROW: f32 = 0.64;

/// Most sweeps over the vertices.
const RELAX_SWEEPS: usize = 4;

/// How far along the step to the one-ring's centroid a vertex is tried, farthest first.
const STEP_FRACTIONS: [f32; 2] = [1.0, 0.5];

/// Moves the vertices of triangles with an angle under about 40° (see [`NARROW`]) to where
/// the smallest angle of their one-ring is larger, then onto `reference`: a free vertex
/// within its tangent plane, a vertex inside a crease line along that line; boundary
/// vertices and crease corners stay. A move is kept only when it raises that smallest
/// angle, turns no triangle over (see [`moves_safely`]), and makes no edge shorter than
/// `low` (the collapse limit) unless one already was, and then none shorter than it: the
/// edge lengths stay as even as the iterations left them. Sweeps in vertex order until one
/// moves nothing (at most [`RELAX_SWEEPS`]). Returns the number of moves.
pub(super) fn relax_small_angles<Q: MeshQuery + ?Sized, O: RemeshObserver + ?Sized>(
    mesh: &mut HalfEdgeMesh<'_>,
    input: &Input<'_, Q>,
    low: f32,
    observer: &mut O,
) -> usize {
    let mut moves = 0usize;
    for _ in 0..RELAX_SWEEPS {
        let before_sweep = moves;
        for v in 0..mesh.vertex_count() as u32 {
            let Some(moves_along) = movable(mesh, v) else {
                continue;
            };
            let now = ring_smallest_sine(mesh, v, mesh.position(v));
            if now >= NARROW {
                continue;
            }
            if let Some(to) = better_place(mesh, input, v, moves_along, now, low) {
                mesh.set_position(v, to);
                moves += 1;
                observer.edited(RemeshStep::Relax, mesh);
            }
        }
        if moves == before_sweep {
            break;
        }
    }
    moves
}

/// How vertex `v` may move: freely within its tangent plane, along the crease line it lies
/// inside (see [`HalfEdgeMesh::crease_line_through`]), or not at all (`None`).
fn movable(mesh: &HalfEdgeMesh<'_>, v: u32) -> Option<Freedom> {
    if is_free(mesh, v) {
        Some(Freedom::Surface)
    } else {
        let (p, n) = mesh.crease_line_through(v)?;
        Some(Freedom::Crease(p, n))
    }
}

/// How a vertex may move.
#[derive(Clone, Copy)]
enum Freedom {
    /// Anywhere on the surface.
    Surface,
    /// Along its crease line, toward either of these crease neighbours.
    Crease(u32, u32),
}

/// How far toward a crease neighbour a crease vertex is tried, as a fraction of the edge.
const SLIDE_FRACTIONS: [f32; 2] = [0.25, 0.125];

/// The best place for `v` among a few tried ones. A free vertex tries the way to the
/// centroid (see [`STEP_FRACTIONS`]) and a short step (see [`PROBE`]) each way along two
/// perpendicular directions of its tangent plane; a crease vertex slides toward either
/// crease neighbour (see [`SLIDE_FRACTIONS`]). Best means the largest smallest-angle sine of the one-ring;
/// the places are compared before projecting (which moves them little, and costs a query
/// each). Only the best is projected onto `reference`, and returned when its sine there
/// still beats `now`.
fn better_place<Q: MeshQuery + ?Sized>(
    mesh: &HalfEdgeMesh<'_>,
    input: &Input<'_, Q>,
    v: u32,
    freedom: Freedom,
    now: f32,
    low: f32,
) -> Option<Vec3> {
    let p = mesh.position(v);
    // No edge may get shorter than the collapse limit, or than the shortest already is.
    let low = low.min(shortest_edge(mesh, v, p));
    let mut best: Option<(Vec3, f32)> = None;
    let mut consider = |goal: Vec3| {
        let sine = ring_smallest_sine(mesh, v, goal);
        if sine > best.map_or(now, |(_, s)| s) && shortest_edge(mesh, v, goal) >= low {
            best = Some((goal, sine));
        }
    };
    match freedom {
        Freedom::Surface => {
            let Tangent {
                step,
                across,
                along,
            } = tangent(mesh, v)?;
            for fraction in STEP_FRACTIONS {
                consider(p + step * fraction);
            }
            for probe in [across, along, -across, -along] {
                consider(p + probe);
            }
        }
        Freedom::Crease(previous, next) => {
            for n in [previous, next] {
                for fraction in SLIDE_FRACTIONS {
                    consider(p + (mesh.position(n) - p) * fraction);
                }
            }
        }
    }
    let (goal, _) = best?;
    let to = input.closest_on(goal, p)?;
    (ring_smallest_sine(mesh, v, to) > now && moves_safely(mesh, input, v, to)).then_some(to)
}

/// How far a directional try goes, as a fraction of the mean distance to the neighbours.
const PROBE: f32 = 0.05;

/// A vertex's tangent plane, as moves within it.
struct Tangent {
    /// To the plain mean of the neighbours, without its part along the normal.
    step: Vec3,
    /// Two perpendicular moves in the plane, [`PROBE`] times the mean distance to the
    /// neighbours long.
    across: Vec3,
    along: Vec3,
}

/// The tangent plane of `v` (normal to its one-ring's area-weighted normal); `None` when
/// that normal vanishes.
fn tangent(mesh: &HalfEdgeMesh<'_>, v: u32) -> Option<Tangent> {
    let p = mesh.position(v);
    let (mut sum, mut distance, mut count, mut normal) = (Vec3::ZERO, 0.0f32, 0u32, Vec3::ZERO);
    let mut first = None;
    mesh.for_each_outgoing(v, |he| {
        let (_, to) = mesh.ends(he);
        let q = mesh.position(to);
        first.get_or_insert(q - p);
        sum += q;
        distance += libm::sqrtf(dot(q - p, q - p));
        count += 1;
        normal += mesh.triangle_normal(he / 3);
    });
    let normal_len = dot(normal, normal);
    let first = first?;
    if !(normal_len > 0.0) {
        return None;
    }
    let flatten = |d: Vec3| d - normal * (dot(d, normal) / normal_len);
    let step = flatten(sum / count as f32 - p);
    let x = flatten(first);
    let x_len = libm::sqrtf(dot(x, x));
    if !(x_len > 0.0) {
        return None;
    }
    let probe = PROBE * distance / count as f32;
    let across = x * (probe / x_len);
    let along = cross(normal, across) * (1.0 / libm::sqrtf(normal_len));
    Some(Tangent {
        step,
        across,
        along,
    })
}

/// The length of the shortest edge at `v`, were `v` at `at`.
fn shortest_edge(mesh: &HalfEdgeMesh<'_>, v: u32, at: Vec3) -> f32 {
    let mut shortest = f32::INFINITY;
    mesh.for_each_neighbour(v, |n| {
        let d = mesh.position(n) - at;
        shortest = shortest.min(dot(d, d));
    });
    libm::sqrtf(shortest)
}

/// The smallest angle's sine over the triangles around `v`, were `v` at `at`.
fn ring_smallest_sine(mesh: &HalfEdgeMesh<'_>, v: u32, at: Vec3) -> f32 {
    let mut smallest = f32::INFINITY;
    mesh.for_each_outgoing(v, |he| {
        let corners = mesh
            .triangle(he / 3)
            .map(|x| if x == v { at } else { mesh.position(x) });
        smallest = smallest.min(smallest_angle_sine(corners));
    });
    smallest
}
