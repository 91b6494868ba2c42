//! The remeshing loop (Botsch and Kobbelt 2004): split long edges, collapse short ones, flip
//! toward valence 6, smooth tangentially, project back onto the input.

use glam::Vec3;

use super::config::RemeshConfig;
use super::flips::{flip_keeps_orientation, flip_toward_delaunay};
use super::half_edges::HalfEdgeMesh;
use super::relax::relax_small_angles;
use super::report::{Progress, RemeshObserver, RemeshReport, RemeshStep};
use super::shape::{FLATTEST, normal_of, smallest_angle_sine};
use super::smooth::smooth;
use super::surface::Input;
use crate::error::{RemeshBuffer, RemeshError};
use crate::math::{cross, dot};
use crate::query::MeshQuery;

/// The mean length of the mesh's edges (each counted once); 0 for a mesh without edges. The
/// same figure as [`MeshQuality::mean_edge`](super::MeshQuality::mean_edge).
#[must_use]
pub(crate) fn mean_edge_length(mesh: &HalfEdgeMesh<'_>) -> f32 {
    super::quality::EdgeLengths::of(mesh).mean() as f32
}

/// Remeshes `mesh` in place toward triangles of one edge length, keeping it on the surface
/// `reference` answers closest points for (build a BVH over the input mesh before editing and
/// pass it with the input: `bvh.with(&input)`).
///
/// Each iteration splits edges longer than `4/3·L`, always across the longest side of both
/// their triangles (longest-edge bisection), at the input's point nearest the midpoint
/// (the midpoint itself on boundaries and creases; a split of an edge longer than `8/3·L`,
/// a needle's side, is followed by flips toward Delaunay around the new vertex, so needles
/// refine in proportion to their area), collapses edges shorter than `4/5·L`
/// (to the input's point nearest their midpoint) unless that would make an edge longer
/// than `4/3·L`, turn a triangle over, or change the topology, flips edges that bring the
/// four vertices' valences nearer 6 (4 on the boundary), and moves every free vertex, one
/// after the other, to the input's point nearest the area-weighted centroid of its
/// one-ring (taken within its tangent plane, every centroid from the positions before the
/// pass) where the move is safe (see below). After the iterations, edges are flipped where that widens the pair's smallest
/// angle without worsening valences, and the vertices of triangles with an angle under
/// about 40° are moved, one at a time, where the angles around them are wider (see
/// [`RemeshReport::relaxed`]).
///
/// Every edit keeps two rules, and is refused (the edge stays, the vertex stays) where it
/// would break one: no triangle turns over against the triangles it replaces or flattens
/// below about 3° unless it was flatter already, and every triangle faces the way the input
/// triangle nearest its centroid does (their normals less than 90° apart). The input obeys
/// the second rule, so the result does too, even where the target is as long as the part
/// is thick. A vertex lies on the input, except the midpoint of a split whose point on the
/// input was refused, until a smoothing move puts it there. An edit is refused too where
/// the input is too crowded to search: where the leaves of `reference` whose boxes hold the
/// point it would be judged from list more input triangles than 1,024 plus four times the
/// input's highest vertex valence (slivers through one point, triangles spanning the whole
/// mesh), every search from there would visit them all; a run on such input stays linear
/// in its size, while a fan of many triangles around one vertex (a cylinder's cap) is
/// remeshed as usual.
///
/// Boundary vertices never move and are never removed, so boundaries keep their shape
/// (their edges are still split). Crease edges are never flipped; a vertex inside a nearly
/// straight crease line (turning by at most about 20°) may only be collapsed into its
/// crease neighbour or, in the final pass, slide along the line; corners where creases meet
/// and sharp bends stay. So creases keep their shape too. Vertices no triangle uses are
/// dropped first. `positions_scratch` holds the smoothing goals: at least one entry per
/// vertex the buffers can hold.
///
/// The result depends only on the inputs: every operation runs in a fixed order with plain
/// `f32` arithmetic, so it is the same on every target.
///
/// # Errors
/// - [`RemeshError::InvalidConfig`] for a config out of range, or a default target length
///   on a mesh whose edges all have zero length (a mesh with no triangles is returned empty);
/// - [`RemeshError::OutOfCapacity`] when a split finds no room: the mesh is left valid,
///   with the edits made so far;
/// - [`RemeshError::BufferTooSmall`] when `positions_scratch` is shorter than the vertex
///   capacity.
pub fn remesh<Q: MeshQuery + ?Sized>(
    mesh: &mut HalfEdgeMesh<'_>,
    reference: &Q,
    config: &RemeshConfig,
    positions_scratch: &mut [[f32; 3]],
) -> Result<RemeshReport, RemeshError> {
    remesh_with_progress(mesh, reference, config, positions_scratch, |_| {})
}

/// [`remesh`], calling `progress` with the report so far after each iteration (to drive a
/// progress bar; it cannot change the result).
///
/// # Errors
/// As [`remesh`].
pub(crate) fn remesh_with_progress<Q: MeshQuery + ?Sized>(
    mesh: &mut HalfEdgeMesh<'_>,
    reference: &Q,
    config: &RemeshConfig,
    positions_scratch: &mut [[f32; 3]],
    progress: impl FnMut(&RemeshReport),
) -> Result<RemeshReport, RemeshError> {
    remesh_observed(
        mesh,
        reference,
        config,
        positions_scratch,
        &mut Progress(progress),
    )
}

/// [`remesh`], calling `observer` after every edit and every iteration (it cannot change
/// the result).
///
/// # Errors
/// As [`remesh`].
pub fn remesh_observed<Q: MeshQuery + ?Sized, O: RemeshObserver + ?Sized>(
    mesh: &mut HalfEdgeMesh<'_>,
    reference: &Q,
    config: &RemeshConfig,
    positions_scratch: &mut [[f32; 3]],
    observer: &mut O,
) -> Result<RemeshReport, RemeshError> {
    config.validate()?;
    if positions_scratch.len() < mesh.vertex_capacity() {
        return Err(RemeshError::BufferTooSmall {
            buffer: RemeshBuffer::Scratch,
            needed: mesh.vertex_capacity(),
            got: positions_scratch.len(),
        });
    }
    if mesh.triangle_count() == 0 {
        // Nothing to remesh: the result is the empty mesh.
        mesh.drop_unused_vertices();
        return Ok(RemeshReport::default());
    }
    let length = config.target.length(mean_edge_length(mesh));
    if !(length > 0.0 && length.is_finite()) {
        return Err(RemeshError::InvalidConfig { field: "target" });
    }
    mesh.drop_unused_vertices();
    let input = &Input::new(reference, mesh);
    let mut report = RemeshReport {
        creases: config.feature_angle.map_or(0, |a| mesh.mark_creases(a)),
        peak_vertices: mesh.vertex_count(),
        peak_triangles: mesh.triangle_count(),
        ..RemeshReport::default()
    };
    let (high, low) = (length * 4.0 / 3.0, length * 4.0 / 5.0);
    for _ in 0..config.iterations {
        let (splits, flips) = split_long_edges(mesh, input, high, observer)?;
        report.splits += splits;
        report.flips += flips;
        // Only splits add: the counts peak here.
        report.peak_vertices = report.peak_vertices.max(mesh.vertex_count());
        report.peak_triangles = report.peak_triangles.max(mesh.triangle_count());
        report.collapses += collapse_short_edges(mesh, input, low, high, observer);
        report.flips += equalize_valences(mesh, input, observer);
        smooth(mesh, input, positions_scratch, observer);
        report.iterations += 1;
        observer.iterated(&report);
    }
    if config.iterations > 0 {
        report.flips += improve_angles(mesh, input, observer);
        report.relaxed = relax_small_angles(mesh, input, low, observer);
    }
    Ok(report)
}

fn squared_length(mesh: &HalfEdgeMesh<'_>, he: u32) -> f32 {
    let (a, b) = mesh.ends(he);
    let d = mesh.position(b) - mesh.position(a);
    dot(d, d)
}

/// The longest of triangle `t`'s three half-edges (the first of equal ones).
fn longest_half_edge(mesh: &HalfEdgeMesh<'_>, t: u32) -> u32 {
    let first = 3 * t;
    let mut best = (first, squared_length(mesh, first));
    for he in [first + 1, first + 2] {
        let length = squared_length(mesh, he);
        if length > best.1 {
            best = (he, length);
        }
    }
    best.0
}

/// Most steps of a longest-edge propagation path. Edges grow strictly along a path, so one
/// never repeats; the bound only caps the walk on meshes whose lengths are not finite.
const PATH_STEPS: usize = 64;

/// The end of the longest-edge propagation path (Rivara) from half-edge `he`: while the
/// triangle across the edge has a strictly longer edge, step to that edge. The edge found is
/// the longest of both its triangles (or lies on the boundary), so splitting it bisects each
/// of them across its longest side.
fn terminal_edge(mesh: &HalfEdgeMesh<'_>, he: u32) -> u32 {
    let mut edge = he;
    for _ in 0..PATH_STEPS {
        let Some(twin) = mesh.twin(edge) else {
            return edge;
        };
        let longest = longest_half_edge(mesh, twin / 3);
        if squared_length(mesh, longest) <= squared_length(mesh, edge) {
            return edge;
        }
        edge = longest;
    }
    edge
}

/// Splits until no edge is longer than `high`, always across the longest side of both
/// triangles of the edge split (longest-edge bisection along the propagation path, Rivara
/// 1997): each triangle whose longest edge is too long is bisected, through the neighbours
/// its longest edge leads to, until it is short enough. Triangles made by splits are visited
/// in turn.
///
/// Bisecting across the longest side keeps every new angle at least half the smallest angle
/// it cut and never fans new edges out of one corner. Splitting any long edge at its
/// midpoint instead joins the midpoint to the opposite corner, which on a skinny triangle is
/// another long edge from that same corner, and the count runs away. Bisection alone still
/// keeps a needle's shape, though, so a needle `n` targets long would become about `n²`
/// triangles: a split of an edge over twice `high` is followed by
/// [`flip_toward_delaunay`], and skinny input (a capsule's side strip, a scan's jump edge, a
/// cone's sides) refines into about as many triangles as its area needs.
fn split_long_edges<Q: MeshQuery + ?Sized, O: RemeshObserver + ?Sized>(
    mesh: &mut HalfEdgeMesh<'_>,
    input: &Input<'_, Q>,
    high: f32,
    observer: &mut O,
) -> Result<(usize, usize), RemeshError> {
    let limit = high * high;
    let (mut splits, mut flips) = (0usize, 0usize);
    let mut t = 0u32;
    // Triangles made by splits are visited in turn, so every edge ends short enough.
    while (t as usize) < mesh.triangle_count() {
        let he = longest_half_edge(mesh, t);
        // Not `<=`: a NaN length is never split.
        if !(squared_length(mesh, he) > limit) {
            t += 1;
            continue;
        }
        let edge = terminal_edge(mesh, he);
        let Some(mid) = split_point(mesh, input, edge) else {
            // Refused: triangle `t` keeps its long edge (it is not visited again in this pass).
            t += 1;
            continue;
        };
        let long = squared_length(mesh, edge) > 4.0 * limit;
        let m = mesh.split_edge(edge, mid)?;
        splits += 1;
        observer.edited(RemeshStep::Split, mesh);
        if long {
            flips += flip_toward_delaunay(mesh, input, m, observer);
        }
        // Triangle `t` may still be too long (a neighbour's edge was split first): look again.
    }
    Ok((splits, flips))
}

/// Where to split the edge of `he`, or `None` to leave it whole. An edge inside the surface
/// is split at the input's point nearest its midpoint, so the new vertex lies on the input
/// as every other one does, when [`splits_safely`] there; otherwise, and on a boundary or
/// crease edge (whose midpoint stays on its line), at its midpoint when that is safe (a
/// later smoothing pass puts such a vertex on the input).
fn split_point<Q: MeshQuery + ?Sized>(
    mesh: &HalfEdgeMesh<'_>,
    input: &Input<'_, Q>,
    he: u32,
) -> Option<Vec3> {
    let (a, b) = mesh.ends(he);
    let middle = (mesh.position(a) + mesh.position(b)) * 0.5;
    let on_line = mesh.twin(he).is_none() || mesh.is_crease(he);
    let on_input = if on_line {
        None
    } else {
        input
            .closest_on(middle, mesh.position(a))
            .filter(|&p| p != middle)
    };
    [on_input, Some(middle)]
        .into_iter()
        .flatten()
        .find(|&at| splits_safely(mesh, input, he, at))
}

/// Whether splitting the edge of `he` at `at` makes four (two on the boundary) triangles
/// that each face the way the triangle they halve does and face the input (see
/// [`faces_input`]). A half lies in or near the triangle it halves, but its centroid does
/// not lie over the same input: across a thin part, the input nearest it can be the far
/// side.
fn splits_safely<Q: MeshQuery + ?Sized>(
    mesh: &HalfEdgeMesh<'_>,
    input: &Input<'_, Q>,
    he: u32,
    at: Vec3,
) -> bool {
    let (a, b) = mesh.ends(he);
    [Some(he), mesh.twin(he)].into_iter().flatten().all(|side| {
        let corners = mesh.triangle(side / 3);
        let whole = normal_of(corners.map(|x| mesh.position(x)));
        [a, b].into_iter().all(|end| {
            let half = corners.map(|x| if x == end { at } else { mesh.position(x) });
            dot(normal_of(half), whole) > 0.0 && input.faces_input(half)
        })
    })
}

/// Collapses edges shorter than `low` where [`stays_short`] and [`keeps_orientation`]
/// allow, each in a direction that removes a vertex [`HalfEdgeMesh::may_remove`] allows.
fn collapse_short_edges<Q: MeshQuery + ?Sized, O: RemeshObserver + ?Sized>(
    mesh: &mut HalfEdgeMesh<'_>,
    input: &Input<'_, Q>,
    low: f32,
    high: f32,
    observer: &mut O,
) -> usize {
    let limit = low * low;
    let mut collapses = 0usize;
    let mut he = 0u32;
    while (he as usize) < mesh.half_edge_count() {
        if squared_length(mesh, he) < limit && try_collapse(mesh, input, he, high) {
            collapses += 1;
            observer.edited(RemeshStep::Collapse, mesh);
            // Slots were refilled from the end: look at this one again.
            continue;
        }
        he += 1;
    }
    collapses
}

/// Collapses the edge of `he` one way or the other if allowed; true when it did.
fn try_collapse<Q: MeshQuery + ?Sized>(
    mesh: &mut HalfEdgeMesh<'_>,
    input: &Input<'_, Q>,
    he: u32,
    high: f32,
) -> bool {
    for w in [Some(he), mesh.twin(he)].into_iter().flatten() {
        let (a, b) = mesh.ends(w);
        // The refusals that do not depend on where the ends meet first (`can_collapse`
        // repeats `may_remove` with the link condition): the place costs a query.
        if !mesh.may_remove(w) || !mesh.can_collapse(w) {
            continue;
        }
        // A vertex that stays keeps its place; two free ones meet at the input's point
        // nearest their midpoint, on the input like every vertex. That point is no farther
        // from the midpoint than `a` is (when `a` lies on the input, as almost every vertex
        // does), so an edge longer than
        // `high` plus that from the midpoint is too long from the point too: most refusals
        // come before the query the point costs.
        let (pa, pb) = (mesh.position(a), mesh.position(b));
        let stays = mesh.is_boundary_vertex(b) || mesh.touches_crease(b);
        let middle = if stays { pb } else { (pa + pb) * 0.5 };
        let slack = libm::sqrtf(dot(pa - middle, pa - middle)) * 1.001;
        if !stays_short(mesh, a, b, middle, high + slack) {
            continue;
        }
        let target = if stays {
            pb
        } else {
            let Some(on_input) = input.closest_on(middle, pa) else {
                continue;
            };
            on_input
        };
        if stays_short(mesh, a, b, target, high)
            && keeps_orientation(mesh, a, b, target)
            && collapse_faces_input(mesh, input, a, b, target)
        {
            return mesh.collapse_edge(w, target);
        }
    }
    false
}

/// Whether moving `a` and `b` to `target` keeps every edge around them at most `high` long.
fn stays_short(mesh: &HalfEdgeMesh<'_>, a: u32, b: u32, target: Vec3, high: f32) -> bool {
    let limit = high * high;
    let mut short = true;
    for v in [a, b] {
        mesh.for_each_neighbour(v, |n| {
            if n != a && n != b {
                let d = mesh.position(n) - target;
                short &= dot(d, d) <= limit;
            }
        });
    }
    short
}

/// Whether moving `a` and `b` to `target` leaves no triangle around them turned over or flat
/// (the triangles on edge `a`–`b` itself vanish). "Over" is judged against the
/// area-weighted normal of all their triangles before, so a triangle that was already flat
/// does not block the collapse that removes it.
fn keeps_orientation(mesh: &HalfEdgeMesh<'_>, a: u32, b: u32, target: Vec3) -> bool {
    let mut reference = Vec3::ZERO;
    for v in [a, b] {
        mesh.for_each_outgoing(v, |he| reference += mesh.triangle_normal(he / 3));
    }
    let mut kept = true;
    for v in [a, b] {
        mesh.for_each_outgoing(v, |he| {
            let t = mesh.triangle(he / 3);
            if t.contains(&a) && t.contains(&b) {
                return;
            }
            let [p, q, r] = t.map(|x| {
                if x == a || x == b {
                    target
                } else {
                    mesh.position(x)
                }
            });
            let after = cross(q - p, r - p);
            kept &= dot(reference, after) > 0.0 && dot(after, after) > 0.0;
        });
    }
    kept
}

/// Whether every triangle around `a` and `b` moved to `target` (but those on edge `a`–`b`,
/// which vanish) faces the input (see [`faces_input`]). [`keeps_orientation`] judges by the
/// neighbourhood's own normals, which can all lean far from the surface together on a thin
/// part (a collapse across a capsule's tube, a sphere's sharp tip): the input does not
/// drift.
fn collapse_faces_input<Q: MeshQuery + ?Sized>(
    mesh: &HalfEdgeMesh<'_>,
    input: &Input<'_, Q>,
    a: u32,
    b: u32,
    target: Vec3,
) -> bool {
    let mut faces = true;
    for v in [a, b] {
        mesh.for_each_outgoing(v, |he| {
            let t = mesh.triangle(he / 3);
            if !faces || (t.contains(&a) && t.contains(&b)) {
                return;
            }
            let corners = t.map(|x| {
                if x == a || x == b {
                    target
                } else {
                    mesh.position(x)
                }
            });
            faces = input.faces_input(corners);
        });
    }
    faces
}

/// The valence a vertex aims at: 6 inside, 4 on the boundary.
fn target_valence(mesh: &HalfEdgeMesh<'_>, v: u32) -> i64 {
    if mesh.is_boundary_vertex(v) { 4 } else { 6 }
}

/// An interior edge seen from its lower half-edge, with what flipping it does to valences.
struct FlipCandidate {
    /// The twin half-edge.
    g: u32,
    /// The edge's ends `a`, `b` and the opposite corners `c` (in `he`'s triangle) and `d`.
    corners: [u32; 4],
    /// The four vertices' total distance from their target valences now,
    before: i64,
    /// and after the flip (`a`, `b` lose an edge, `c`, `d` gain one).
    after: i64,
}

/// The flip candidate of half-edge `he`: `None` on the boundary and for the higher
/// half-edge of a pair, so each edge is seen once.
fn flip_candidate(mesh: &HalfEdgeMesh<'_>, he: u32) -> Option<FlipCandidate> {
    let g = mesh.twin(he).filter(|&g| g > he)?;
    let (a, b) = mesh.ends(he);
    let c = mesh.origin(HalfEdgeMesh::prev(he));
    let d = mesh.origin(HalfEdgeMesh::prev(g));
    let [da, db, dc, dd] =
        [a, b, c, d].map(|v| i64::from(mesh.valence(v)) - target_valence(mesh, v));
    Some(FlipCandidate {
        g,
        corners: [a, b, c, d],
        before: da.abs() + db.abs() + dc.abs() + dd.abs(),
        after: (da - 1).abs() + (db - 1).abs() + (dc + 1).abs() + (dd + 1).abs(),
    })
}

/// Flips every interior edge whose flip lowers the four vertices' total distance from their
/// target valences, unless it would fold the two triangles over or, beside a crease, make
/// one flatter than [`FLATTEST`] and than the pair was.
fn equalize_valences<Q: MeshQuery + ?Sized, O: RemeshObserver + ?Sized>(
    mesh: &mut HalfEdgeMesh<'_>,
    input: &Input<'_, Q>,
    observer: &mut O,
) -> usize {
    let mut flips = 0usize;
    for he in 0..mesh.half_edge_count() as u32 {
        if !an_end_has_edges_to_spare(mesh, he) {
            continue;
        }
        let Some(FlipCandidate {
            g, before, after, ..
        }) = flip_candidate(mesh, he)
        else {
            continue;
        };
        // `flip_edge` checks `can_flip` itself: the cheaper tests go first.
        if after < before && flip_keeps_orientation(mesh, input, he, g) && mesh.flip_edge(he) {
            flips += 1;
            observer.edited(RemeshStep::Flip, mesh);
        }
    }
    flips
}

/// Whether an end of `he`'s edge has more edges than its target valence. A flip takes an
/// edge from both ends and gives one to both opposite corners, each moving one step nearer
/// or farther from its target: the total falls only when three of the four move nearer, so
/// never when both ends are at or under their targets. Cheaper than [`flip_candidate`],
/// which also counts the corners.
fn an_end_has_edges_to_spare(mesh: &HalfEdgeMesh<'_>, he: u32) -> bool {
    let (a, b) = mesh.ends(he);
    // Each interior edge once, from its lower half-edge, as `flip_candidate` sees it.
    mesh.twin(he).is_some_and(|g| g > he)
        && [a, b]
            .iter()
            .any(|&v| i64::from(mesh.valence(v)) > target_valence(mesh, v))
}

/// Most sweeps of [`improve_angles`].
const ANGLE_SWEEPS: usize = 3;

/// Flips interior edges whose flip raises the smaller of the pair's smallest angles without
/// taking the four vertices farther from their target valences in total (or at any valence
/// cost when the pair holds a sliver, an angle under about 3°), sweep after sweep
/// until one flips nothing (at most [`ANGLE_SWEEPS`]). Vertices stay where they are.
fn improve_angles<Q: MeshQuery + ?Sized, O: RemeshObserver + ?Sized>(
    mesh: &mut HalfEdgeMesh<'_>,
    input: &Input<'_, Q>,
    observer: &mut O,
) -> usize {
    let mut flips = 0usize;
    for _ in 0..ANGLE_SWEEPS {
        let before_sweep = flips;
        for he in 0..mesh.half_edge_count() as u32 {
            let Some(FlipCandidate {
                g,
                corners,
                before,
                after,
            }) = flip_candidate(mesh, he)
            else {
                continue;
            };
            let [pa, pb, pc, pd] = corners.map(|v| mesh.position(v));
            let old = smallest_angle_sine([pa, pb, pc]).min(smallest_angle_sine([pb, pa, pd]));
            // A sliver is worth a valence step; a fair pair is not.
            if after > before && old >= FLATTEST {
                continue;
            }
            let new = smallest_angle_sine([pa, pd, pc]).min(smallest_angle_sine([pd, pb, pc]));
            if new > old && flip_keeps_orientation(mesh, input, he, g) && mesh.flip_edge(he) {
                flips += 1;
                observer.edited(RemeshStep::Flip, mesh);
            }
        }
        if flips == before_sweep {
            break;
        }
    }
    flips
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::MeshRef;
    use crate::query::traverse::Traverse;
    use crate::remesh::HalfEdgeBuffers;

    /// The longest edge of `mesh`.
    fn longest(mesh: &HalfEdgeMesh<'_>) -> f32 {
        (0..mesh.half_edge_count() as u32)
            .map(|he| libm::sqrtf(squared_length(mesh, he)))
            .fold(0.0, f32::max)
    }

    /// A flat patch: `a` at the origin and `b` 0.1 beside it (a short edge for L = 1), a ring
    /// of six vertices 1.3 from `a`. Collapsing `a`–`b` to its midpoint would stretch the
    /// edge to the ring vertex opposite `b` to 1.35, past 4/3: the guard must refuse it, and
    /// without the guard the pass makes that long edge.
    #[test]
    fn a_collapse_that_would_make_a_long_edge_is_refused() {
        let ring: Vec<[f32; 3]> = (0..6)
            .map(|k| {
                let angle = core::f32::consts::PI / 3.0 * k as f32;
                [1.3 * libm::cosf(angle), 1.3 * libm::sinf(angle), 0.0]
            })
            .collect();
        let mut positions = vec![[0.0, 0.0, 0.0], [0.1, 0.0, 0.0]];
        positions.extend(ring);
        let (a, b) = (0u32, 1u32);
        let r = |k: u32| 2 + k;
        let triangles = [
            [b, r(0), r(1)],
            [b, r(1), a],
            [a, r(1), r(2)],
            [a, r(2), r(3)],
            [a, r(3), r(4)],
            [a, r(4), r(5)],
            [a, r(5), b],
            [b, r(5), r(0)],
        ];
        let input = MeshRef::new(&positions, &triangles).validate().unwrap();
        let (high, low) = (4.0 / 3.0, 0.8);
        for guard in [true, false] {
            let mut p = vec![[0.0f32; 3]; 8];
            let (mut o, mut t, mut c) = (vec![0u32; 24], vec![0u32; 24], vec![false; 24]);
            let mut out = vec![0u32; 8];
            let mut scratch = vec![0u32; 24];
            let buffers = HalfEdgeBuffers {
                positions: &mut p,
                origins: &mut o,
                twins: &mut t,
                vertex_half_edges: &mut out,
                creases: &mut c,
            };
            let mut mesh = HalfEdgeMesh::from_mesh(&input, buffers, &mut scratch).unwrap();
            assert!(longest(&mesh) <= high);
            if guard {
                let mut tree = crate::bvh::BvhBuffers::<8>::new();
                let bvh = tree
                    .build(&input, &crate::bvh::BuildConfig::default())
                    .unwrap();
                let reference = bvh.with(&input);
                let surface = Input::new(&reference, &mesh);
                let collapses =
                    collapse_short_edges(&mut mesh, &surface, low, high, &mut Progress(|_: &_| {}));
                assert_eq!(collapses, 0);
                assert!(longest(&mesh) <= high);
            } else {
                // Every other rule allows a collapse of the short edge: made here by hand,
                // past the long-edge rule, it stretches an edge, so that rule is what refused.
                let short = (0..mesh.half_edge_count() as u32)
                    .find(|&he| squared_length(&mesh, he) < low * low)
                    .expect("a short edge");
                let (a, b) = mesh.ends(short);
                let target = (mesh.position(a) + mesh.position(b)) * 0.5;
                assert!(mesh.may_remove(short) && mesh.can_collapse(short));
                assert!(keeps_orientation(&mesh, a, b, target));
                assert!(mesh.collapse_edge(short, target));
                assert!(longest(&mesh) > high, "without the rule an edge stretches");
            }
        }
    }
}
