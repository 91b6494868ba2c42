//! Flips: whether one keeps the surface's orientation, and the flips toward Delaunay that
//! follow the split of a needle's side.

use glam::Vec3;

use super::half_edges::HalfEdgeMesh;
use super::report::{RemeshObserver, RemeshStep};
use super::shape::{flat_enough, flatness, normal_of};
use super::surface::Input;
use crate::math::{cross, dot};
use crate::query::MeshQuery;

/// Whether flipping the edge of `he` (twin `g`) gives two triangles facing the way the old
/// pair does (each new normal has a positive dot product with both old ones) and face the
/// input (see [`faces_input`]). Without the input's judgement, a flip
/// between two vertices of one cross-section of a thin tube passes: the old pair, already
/// leaning, agrees with a new pair lying across the tube.
#[cfg_attr(target_os = "none", inline(never))]
pub(super) fn flip_keeps_orientation<Q: MeshQuery + ?Sized>(
    mesh: &HalfEdgeMesh<'_>,
    input: &Input<'_, Q>,
    he: u32,
    g: u32,
) -> bool {
    let (a, b) = mesh.ends(he);
    let c = mesh.origin(HalfEdgeMesh::prev(he));
    let d = mesh.origin(HalfEdgeMesh::prev(g));
    let [pa, pb, pc, pd] = [a, b, c, d].map(|v| mesh.position(v));
    let (old0, old1) = (mesh.triangle_normal(he / 3), mesh.triangle_normal(g / 3));
    let new0 = cross(pd - pa, pc - pa);
    let new1 = cross(pb - pd, pc - pd);
    // Beside a crease, where vertices are fixed and a sliver once made stays, a flip may
    // not make one. (Elsewhere later passes mend slivers, and the guard costs quality.)
    let near_crease = [a, b, c, d].iter().any(|&v| mesh.touches_crease(v));
    let was = || flatness([pa, pb, pc]).min(flatness([pb, pa, pd]));
    let now = || flatness([pa, pd, pc]).min(flatness([pd, pb, pc]));
    (!near_crease || flat_enough(now(), was))
        && [new0, new1]
            .iter()
            .all(|&n| dot(n, old0) > 0.0 && dot(n, old1) > 0.0)
        && input.faces_input([pa, pd, pc])
        && input.faces_input([pd, pb, pc])
}

/// Most flips [`flip_toward_delaunay`] makes around one new vertex.
const DELAUNAY_FLIPS: usize = 16;

/// Flips the edges opposite vertex `m` (just made by a split) that are not locally Delaunay,
/// as point insertion does (Lawson's flips): an edge whose two opposite angles add up to
/// more than 180° is flipped to join `m` to the corner across it, where
/// [`flip_keeps_orientation`] allows, until every edge around `m` is Delaunay or refused (at
/// most [`DELAUNAY_FLIPS`] flips). Bisecting a needle (a triangle far longer than wide: a
/// scan's jump edge, a capsule's side strip) leaves `m` almost on the line of a long edge
/// beside it, in a flat triangle whose long edge, bisected in turn, does the same again:
/// without these flips the needles' count grows with the square of their length over the
/// target, with them like their area. Only a pair that stays nearly flat is flipped (see
/// [`is_delaunay`]), so no new edge cuts across a part as thin as the target.
pub(super) fn flip_toward_delaunay<Q: MeshQuery + ?Sized, O: RemeshObserver + ?Sized>(
    mesh: &mut HalfEdgeMesh<'_>,
    input: &Input<'_, Q>,
    m: u32,
    observer: &mut O,
) -> usize {
    let mut flips = 0usize;
    while flips < DELAUNAY_FLIPS {
        let mut flipped = false;
        let mut candidates = [0u32; DELAUNAY_FLIPS * 2];
        let mut count = 0usize;
        mesh.for_each_outgoing(m, |he| {
            // The edge opposite `m` in the triangle of its outgoing half-edge `he`.
            let far = HalfEdgeMesh::next(he);
            if let Some(slot) = candidates.get_mut(count)
                && !is_delaunay(mesh, far)
            {
                *slot = far;
                count += 1;
            }
        });
        for &far in candidates.iter().take(count) {
            let Some(g) = mesh.twin(far) else {
                continue;
            };
            if mesh.can_flip(far)
                && flip_keeps_orientation(mesh, input, far, g)
                && mesh.flip_edge(far)
            {
                flips += 1;
                observer.edited(RemeshStep::Flip, mesh);
                flipped = true;
                break;
            }
        }
        if !flipped {
            break;
        }
    }
    flips
}

/// Whether the edge of `he` counts as locally Delaunay for [`flip_toward_delaunay`]: on
/// the boundary, or its two opposite angles add up to at most 180° (their cotangents' sum is
/// not negative). An edge also counts as Delaunay where flipping it would not shorten it, or
/// where its two triangles, before or after the flip, bend more than 30° (normals' cosine
/// under √3/2), as a part as thin as the target does: there the flip could cut across it.
fn is_delaunay(mesh: &HalfEdgeMesh<'_>, he: u32) -> bool {
    let Some(g) = mesh.twin(he) else {
        return true;
    };
    let (a, b) = mesh.ends(he);
    let [pa, pb] = [a, b].map(|v| mesh.position(v));
    let [pc, pd] =
        [HalfEdgeMesh::prev(he), HalfEdgeMesh::prev(g)].map(|x| mesh.position(mesh.origin(x)));
    if dot(pd - pc, pd - pc) >= dot(pb - pa, pb - pa) {
        return true;
    }
    let bends = |n0: Vec3, n1: Vec3| {
        let d = dot(n0, n1);
        !(d > 0.0 && d * d > 0.75 * dot(n0, n0) * dot(n1, n1))
    };
    if bends(normal_of([pa, pb, pc]), normal_of([pb, pa, pd]))
        || bends(normal_of([pa, pd, pc]), normal_of([pd, pb, pc]))
    {
        return true;
    }
    // cot = cos / sin = dot / |cross|, so cot c + cot d < 0 is
    // dot_c·|cross_d| + dot_d·|cross_c| < 0 (both sines positive).
    let (ca, cb, da, db) = (pa - pc, pb - pc, pa - pd, pb - pd);
    let (cross_c, cross_d) = (cross(ca, cb), cross(da, db));
    let sin_c = libm::sqrtf(dot(cross_c, cross_c));
    let sin_d = libm::sqrtf(dot(cross_d, cross_d));
    dot(ca, cb) * sin_d + dot(da, db) * sin_c >= 0.0
}
