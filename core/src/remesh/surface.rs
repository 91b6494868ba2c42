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

use super::half_edges::HalfEdgeMesh;
use super::shape::normal_of;
use crate::math::{Triangle, dot};
use crate::query::{MeshQuery, closest_answer, nearest_triangle};

/// The input surface a run answers to: the query over it, and how crowded it may be at a
/// point before no edit is judged there.
pub(super) struct Input<'q, Q: ?Sized> {
    query: &'q Q,
    /// More triangle references than this in the leaves holding a point, and the input is
    /// crowded there (see [`Input::new`]).
    crowded: usize,
}

impl<'q, Q: MeshQuery + ?Sized> Input<'q, Q> {
    /// The surface `query` answers for, `mesh` being the input before any edit.
    ///
    /// Every exact search from a point visits the leaves whose boxes hold it. On input no
    /// box separates (thousands of slivers through one point, triangles spanning the whole
    /// mesh) every search would visit most of the mesh, and a run would take the square of
    /// its size; there the input counts as crowded, and no edit is judged by a search from
    /// such a point (the edit is refused). Triangles around one vertex of valence `v` all
    /// hold the points near it, and a vertex may sit in two such fans (a cone's base
    /// centre, under the fan of its apex), so crowded means more references than 1,024
    /// plus four times the input's highest valence: real meshes, fans of a thousand
    /// triangles included, stay below, and tangled input of many separate triangles
    /// (valence 1 or 2) is crowded from about a thousand triangles through a point.
    pub(super) fn new(query: &'q Q, mesh: &HalfEdgeMesh<'_>) -> Self {
        let mut highest = 0usize;
        for v in 0..mesh.vertex_count() as u32 {
            let mut valence = 0usize;
            mesh.for_each_outgoing(v, |_| valence += 1);
            highest = highest.max(valence);
        }
        Self {
            query,
            crowded: highest.saturating_mul(4).saturating_add(1024),
        }
    }

    /// The input's point nearest `p`, a point moved there from `was` on (or near) the
    /// surface. The surface is then at most as far from `p` as the move, so the query first
    /// looks only that far (a much smaller search) and only on finding nothing looks
    /// everywhere: the closest point is the same either way. `None` for an empty reference,
    /// a point it cannot measure, or a point where the input is crowded ([`Input::new`]).
    pub(super) fn closest_on(&self, p: Vec3, was: Vec3) -> Option<Vec3> {
        let moved = p - was;
        self.nearest(p, libm::sqrtf(dot(moved, moved)))
            .map(|found| closest_answer(p, found).point)
    }

    /// Whether the triangle of corners `p` faces the way the input surface does under its
    /// centroid: its normal and the normal of the input triangle nearest the centroid (the
    /// lower index of equally near ones, as every closest-point query answers) make an
    /// angle under 90°. A triangle without a normal (zero area, or corners not finite) faces
    /// no way, and neither does one over an input triangle without a normal, nor one whose
    /// centroid lies where the input is crowded ([`Input::new`]).
    ///
    /// The centroid is `(p0 + p1 + p2) / 3`, so the answer is the one a check of the
    /// finished mesh computes. The search first looks as far as the centroid's farthest
    /// corner (the corners lie on or near the surface, so the nearest input point is almost
    /// always that close).
    pub(super) fn faces_input(&self, p: [Vec3; 3]) -> bool {
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
        self.nearest(centroid, libm::sqrtf(reach))
            .is_some_and(|(_, under)| {
                direction([under.a, under.b, under.c]).is_some_and(|n| dot(normal, n) > 0.0)
            })
    }

    /// The input triangle nearest `p` (mesh index and corners): first looked for within
    /// `near` (with a little room), then everywhere. The same answer either way; only the
    /// work differs. `None` where the input is crowded at `p`.
    ///
    /// Each search may look at as many references as make the input crowded; only one that
    /// needs more asks whether the leaves holding `p` list more than that (a search limited
    /// to distance 0 visits exactly those), and goes on when not. So the verdict depends on
    /// that count alone, the same whatever order a structure visits its leaves in: a search
    /// that looked at no more has looked at every leaf holding `p`.
    #[cfg_attr(target_os = "none", inline(never))]
    fn nearest(&self, p: Vec3, near: f32) -> Option<(u32, Triangle)> {
        let search = |max, budget| nearest_triangle(self.query, self.query, p, max, budget);
        for max in [near * 1.001, f32::INFINITY] {
            let found = match search(max, self.crowded) {
                Ok(found) => found,
                Err(_) if search(0.0, self.crowded).is_err() => return None,
                Err(_) => search(max, usize::MAX).ok().flatten(),
            };
            if found.is_some() {
                return found;
            }
        }
        None
    }
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
        let surface = Input {
            query: &reference,
            crowded: 1024,
        };
        let up = [
            Vec3::new(0.2, 0.2, 0.11),
            Vec3::new(0.6, 0.2, 0.11),
            Vec3::new(0.2, 0.6, 0.11),
        ];
        let down = [up[0], up[2], up[1]];
        assert!(surface.faces_input(up));
        assert!(!surface.faces_input(down));
        let low = [
            Vec3::new(0.2, 0.2, 0.02),
            Vec3::new(0.2, 0.6, 0.02),
            Vec3::new(0.6, 0.2, 0.02),
        ];
        assert!(surface.faces_input(low));
        // No normal, no facing: three corners in a line.
        let line = [up[0], up[1], (up[0] + up[1]) * 0.5];
        assert!(!surface.faces_input(line));
        // A triangle 1e-30 across just above the bottom square's corner at the origin, whose
        // normal underflows to zero in f32 unless its edges are scaled first, is judged: the
        // bottom (facing down) is nearest.
        let tiny =
            [[1.0f32, 1.0, 1.0], [3.0, 1.0, 1.0], [1.0, 3.0, 1.0]].map(|x| Vec3::from(x) * 1e-30);
        assert_eq!(normal_of(tiny), Vec3::ZERO);
        assert!(!surface.faces_input(tiny));
        assert!(surface.faces_input([tiny[0], tiny[2], tiny[1]]));
    }
}
