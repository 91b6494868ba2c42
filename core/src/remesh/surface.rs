//! The input surface as the judge of the remeshed one: where it is, and which way it faces.
//!
//! Every edit (split, collapse, flip, move) keeps one rule: each triangle it makes faces the
//! way the input does under the triangle's centroid. The edit is refused otherwise. A
//! triangle no edit touches keeps its corners, so the rule holds for the whole mesh after
//! every edit if it held before: the input itself obeys it (each triangle's centroid lies on
//! it), so the result does too. The mesh's own normals cannot serve as the judge: on a
//! thin part (a capsule's tube, a stretched sphere's tip, the jump edge of a range scan) a
//! whole neighbourhood can lean over together and approve a triangle lying across the part.

use glam::Vec3;

use super::shape::normal_of;
use crate::math::{Triangle, dot};
use crate::query::{MeshQuery, closest_point_and_triangle};

/// The input's point nearest `p`, a point moved there from `was` on (or near) the surface.
/// The surface is then at most as far from `p` as the move, so the query first looks only
/// that far (a much smaller search) and only on finding nothing looks everywhere: the
/// closest point is the same either way. `None` only for an empty reference or a point it
/// cannot measure.
pub(super) fn closest_on<Q: MeshQuery + ?Sized>(reference: &Q, p: Vec3, was: Vec3) -> Option<Vec3> {
    let moved = p - was;
    nearest(reference, p, libm::sqrtf(dot(moved, moved))).map(|(point, _)| point)
}

/// Whether the triangle of corners `p` faces the way the input surface does under its
/// centroid: its normal and the normal of the input triangle nearest the centroid (the
/// lower index of equally near ones, as every closest-point query answers) make an angle
/// under 90°. A triangle without a normal (zero area, or corners not finite) faces no way,
/// and neither does one over an input triangle without a normal.
///
/// The centroid is `(p0 + p1 + p2) / 3`, so the answer is the one a check of the finished
/// mesh computes. The search first looks as far as the centroid's farthest corner (the
/// corners lie on or near the surface, so the nearest input point is almost always that
/// close).
pub(super) fn faces_input<Q: MeshQuery + ?Sized>(reference: &Q, p: [Vec3; 3]) -> bool {
    let Some(normal) = direction(p) else {
        return false;
    };
    let centroid = (p[0] + p[1] + p[2]) / 3.0;
    let reach = p
        .iter()
        .map(|&x| {
            let d = x - centroid;
            dot(d, d)
        })
        .fold(0.0f32, f32::max);
    nearest(reference, centroid, libm::sqrtf(reach)).is_some_and(|(_, under)| {
        direction([under.a, under.b, under.c]).is_some_and(|n| dot(normal, n) > 0.0)
    })
}

/// More input triangle references than this in the leaves of the reference whose boxes hold
/// a point, and the input is crowded there: no edit is judged by a search from that point.
/// Every exact search from the point visits those leaves, and on input no box separates
/// (thousands of slivers through one point, triangles spanning the whole mesh, copies of one
/// triangle) every search would visit most of the mesh, and a run would take the square of
/// its size. Real meshes stay far below (a cone's apex of 360 triangles is within it).
pub(super) const CROWDED: usize = 256;

/// The input's point nearest `p` and the triangle it lies on: first looked for within
/// `near` (with a little room), then everywhere. The same answer either way; only the work
/// differs. `None` where the input is crowded at `p` ([`CROWDED`]): the edit asking is
/// refused.
///
/// Each search is given [`CROWDED`] references to look at; only one that needs more asks
/// whether the leaves holding `p` have more than that (a search limited to distance 0 visits
/// exactly those), and goes on when not. So the verdict depends on that count alone, the
/// same whatever order a structure visits its leaves in: a search that looked at no more
/// than [`CROWDED`] references has looked at every leaf holding `p`.
#[cfg_attr(target_os = "none", inline(never))]
fn nearest<Q: MeshQuery + ?Sized>(reference: &Q, p: Vec3, near: f32) -> Option<(Vec3, Triangle)> {
    let search = |max, budget| closest_point_and_triangle(reference, reference, p, max, budget);
    for max in [near * 1.001, f32::INFINITY] {
        let found = match search(max, CROWDED) {
            Ok(found) => found,
            Err(_) if search(0.0, CROWDED).is_err() => return None,
            Err(_) => search(max, usize::MAX).ok().flatten(),
        };
        if found.is_some() {
            return found;
        }
    }
    None
}

/// The direction of the normal of corners `p`, from its two edges at `p0` divided by their
/// largest coordinate's magnitude first: the cross product and the dot product of two such
/// directions (between -4 and 4 in each coordinate) then neither overflow nor underflow to
/// zero, whatever the mesh's scale. `None` for corners in a line or not finite.
fn direction(p: [Vec3; 3]) -> Option<Vec3> {
    let (u, v) = (p[1] - p[0], p[2] - p[0]);
    let largest = u.abs().max_element().max(v.abs().max_element());
    if !(largest > 0.0 && largest.is_finite()) {
        return None;
    }
    let n = normal_of([Vec3::ZERO, u / largest, v / largest]);
    (n != Vec3::ZERO && n.is_finite()).then_some(n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bvh::{BuildConfig, BvhBuffers};
    use crate::mesh::MeshRef;
    use crate::query::traverse::Traverse;

    /// Two parallel squares facing away from each other, 0.1 apart (a slab's top and
    /// bottom): a triangle just above the top faces the input when it faces up and not when
    /// it faces down; one across the gap, nearer the bottom, must face down.
    #[test]
    fn judges_by_the_input_triangle_under_the_centroid() {
        let positions = [
            [0.0f32, 0.0, 0.1],
            [1.0, 0.0, 0.1],
            [1.0, 1.0, 0.1],
            [0.0, 1.0, 0.1],
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        // Top counter-clockwise seen from above (normal +z), bottom clockwise (normal -z).
        let triangles = [[0u32, 1, 2], [0, 2, 3], [4, 6, 5], [4, 7, 6]];
        let input = MeshRef::new(&positions, &triangles).validate().unwrap();
        let mut tree = BvhBuffers::<8>::new();
        let bvh = tree.build(&input, &BuildConfig::default()).unwrap();
        let reference = bvh.with(&input);
        let up = [
            Vec3::new(0.2, 0.2, 0.11),
            Vec3::new(0.6, 0.2, 0.11),
            Vec3::new(0.2, 0.6, 0.11),
        ];
        let down = [up[0], up[2], up[1]];
        assert!(faces_input(&reference, up));
        assert!(!faces_input(&reference, down));
        let low = [
            Vec3::new(0.2, 0.2, 0.02),
            Vec3::new(0.2, 0.6, 0.02),
            Vec3::new(0.6, 0.2, 0.02),
        ];
        assert!(faces_input(&reference, low));
        // No normal, no facing: three corners in a line.
        let line = [up[0], up[1], (up[0] + up[1]) * 0.5];
        assert!(!faces_input(&reference, line));
        // A triangle 1e-30 across just above the bottom square's corner at the origin, whose
        // normal underflows to zero in f32 unless its edges are scaled first, is judged: the
        // bottom (facing down) is nearest.
        let tiny =
            [[1.0f32, 1.0, 1.0], [3.0, 1.0, 1.0], [1.0, 3.0, 1.0]].map(|x| Vec3::from(x) * 1e-30);
        assert_eq!(normal_of(tiny), Vec3::ZERO);
        assert!(!faces_input(&reference, tiny));
        assert!(faces_input(&reference, [tiny[0], tiny[2], tiny[1]]));
    }
}
