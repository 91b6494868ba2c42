//! Angle-weighted pseudo-normals (Bærentzen and Aanæs, "Signed distance computation using the
//! angle weighted pseudonormal", 2005): the other way to sign a distance, for closed,
//! manifold, consistently oriented meshes.
//!
//! At the closest surface point `q` to `p`, the sign of `(p − q) · N` tells the side, where `N`
//! is the pseudo-normal of the feature `q` lies on: the face's normal inside a face, the sum of
//! the two faces' unit normals on an edge, and on a vertex the sum of its faces' unit normals,
//! each weighted by the face's angle at the vertex. Bærentzen and Aanæs prove that sign right
//! for every point off a closed manifold surface. It costs one closest-point search and no
//! winding number, but says nothing useful on open or non-manifold meshes, so building one
//! checks the mesh and refuses those.

use core::fmt;

use glam::Vec3;

use super::SignedDistance;
use crate::math::{ClosestPoint, TriangleFeature, cross, dot};
use crate::mesh::ValidMesh;
use crate::query::MeshQuery;

/// Why [`PseudoNormals::build`] refused a mesh or its buffers.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PseudoNormalError {
    /// A buffer is shorter than the mesh needs: `vertex_normals` one per vertex,
    /// `edge_normals` one per triangle, `scratch` three per triangle.
    BufferTooSmall,
    /// The edge from corner `corner` to the next of triangle `triangle` borders no other
    /// triangle: the mesh is open there. Fix: sign by winding number, which holds on open
    /// meshes.
    OpenEdge {
        /// The triangle.
        triangle: u32,
        /// Its corner where the edge starts (0, 1 or 2).
        corner: u8,
    },
    /// The edge borders more than two triangles: the mesh is not manifold there.
    NonManifoldEdge {
        /// A triangle on it.
        triangle: u32,
        /// Its corner where the edge starts.
        corner: u8,
    },
    /// The two triangles on the edge run it the same way: they face opposite sides, so the
    /// mesh has no consistent outside. Fix: orient the mesh (every edge run both ways).
    InconsistentOrientation {
        /// A triangle on it.
        triangle: u32,
        /// Its corner where the edge starts.
        corner: u8,
    },
}

impl fmt::Display for PseudoNormalError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::BufferTooSmall => write!(
                f,
                "a pseudo-normal buffer is too small (one vertex normal per vertex, one edge \
                 normal triple per triangle, three scratch entries per triangle)"
            ),
            Self::OpenEdge { triangle, corner } => write!(
                f,
                "pseudo-normals need a closed mesh: the edge at corner {corner} of triangle \
                 {triangle} borders no other triangle (sign by winding number instead)"
            ),
            Self::NonManifoldEdge { triangle, corner } => write!(
                f,
                "pseudo-normals need a manifold mesh: the edge at corner {corner} of triangle \
                 {triangle} borders more than two triangles (sign by winding number instead)"
            ),
            Self::InconsistentOrientation { triangle, corner } => write!(
                f,
                "pseudo-normals need a consistently oriented mesh: the triangles on the edge at \
                 corner {corner} of triangle {triangle} run it the same way"
            ),
        }
    }
}

impl core::error::Error for PseudoNormalError {}

/// One scratch entry of [`PseudoNormals::build`]: an edge's key (its two vertex indices, lower
/// first) and which triangle corner starts it.
pub type EdgeEntry = (u64, u32);

/// The pseudo-normals of a closed, manifold, consistently oriented mesh, in buffers you own.
/// Inside is the side the triangles' normals (`(b − a) × (c − a)`) point away from.
#[derive(Clone, Copy, Debug)]
pub struct PseudoNormals<'a> {
    vertices: &'a [Vec3],
    edges: &'a [[Vec3; 3]],
}

impl<'a> PseudoNormals<'a> {
    /// Computes the pseudo-normals of `mesh` into `vertex_normals` (one per vertex) and
    /// `edge_normals` (one triple per triangle, edge `i` from corner `i` to the next), sorting
    /// the edges in `scratch` (three entries per triangle; its contents afterwards are
    /// unspecified). Zero-area triangles add nothing; edges whose two corners are one vertex
    /// are skipped. No allocation.
    ///
    /// # Errors
    /// [`PseudoNormalError::BufferTooSmall`] for a short buffer, and
    /// [`OpenEdge`](PseudoNormalError::OpenEdge),
    /// [`NonManifoldEdge`](PseudoNormalError::NonManifoldEdge) or
    /// [`InconsistentOrientation`](PseudoNormalError::InconsistentOrientation) naming the
    /// first such edge (in sorted edge order) of a mesh whose inside they cannot tell.
    pub fn build(
        mesh: &ValidMesh<'_>,
        vertex_normals: &'a mut [Vec3],
        edge_normals: &'a mut [[Vec3; 3]],
        scratch: &mut [EdgeEntry],
    ) -> Result<Self, PseudoNormalError> {
        let (nv, nt) = (mesh.vertex_count(), mesh.triangle_count());
        let (Some(vertices), Some(edges), Some(scratch)) = (
            vertex_normals.get_mut(..nv),
            edge_normals.get_mut(..nt),
            scratch.get_mut(..nt.saturating_mul(3)),
        ) else {
            return Err(PseudoNormalError::BufferTooSmall);
        };
        vertices.fill(Vec3::ZERO);
        edges.fill([Vec3::ZERO; 3]);
        let tris = mesh.triangles();
        for (t, (corners, slot)) in tris.iter().zip(scratch.chunks_exact_mut(3)).enumerate() {
            let n = unit_face_normal(mesh, t as u32);
            let p = corners.map(|v| position(mesh, v));
            let around = [
                (0, p[0], p[1], p[2]),
                (1, p[1], p[2], p[0]),
                (2, p[2], p[0], p[1]),
            ];
            let runs = [
                (corners[0], corners[1]),
                (corners[1], corners[2]),
                (corners[2], corners[0]),
            ];
            for ((k, at, next, prev), (a, b)) in around.into_iter().zip(runs) {
                let angle = angle_between(next - at, prev - at);
                if let Some(v) = vertices.get_mut(a as usize) {
                    *v += n * angle;
                }
                if a != b {
                    let key = (u64::from(a.min(b)) << 32) | u64::from(a.max(b));
                    if let Some(entry) = slot.get_mut(k) {
                        *entry = (key, (t as u32) * 3 + k as u32);
                    }
                } else if let Some(entry) = slot.get_mut(k) {
                    *entry = (u64::MAX, u32::MAX);
                }
            }
        }
        scratch.sort_unstable();
        let mut at = 0usize;
        while let Some(&(key, first)) = scratch.get(at) {
            if key == u64::MAX {
                break;
            }
            let run = scratch
                .get(at..)
                .map_or(0, |rest| rest.iter().take_while(|e| e.0 == key).count());
            let name = |slot: u32| ((slot / 3), (slot % 3) as u8);
            let (triangle, corner) = name(first);
            match run {
                1 => return Err(PseudoNormalError::OpenEdge { triangle, corner }),
                2 => {}
                _ => return Err(PseudoNormalError::NonManifoldEdge { triangle, corner }),
            }
            let Some(&(_, second)) = scratch.get(at + 1) else {
                break;
            };
            let (other, other_corner) = name(second);
            let start = |t: u32, c: u8| {
                tris.get(t as usize)
                    .and_then(|v| v.get(c as usize))
                    .copied()
            };
            if start(triangle, corner) == start(other, other_corner) {
                return Err(PseudoNormalError::InconsistentOrientation { triangle, corner });
            }
            let sum = unit_face_normal(mesh, triangle) + unit_face_normal(mesh, other);
            for (t, c) in [(triangle, corner), (other, other_corner)] {
                if let Some(e) = edges
                    .get_mut(t as usize)
                    .and_then(|e| e.get_mut(c as usize))
                {
                    *e = sum;
                }
            }
            at += 2;
        }
        Ok(Self { vertices, edges })
    }

    /// Pseudo-normals over buffers filled earlier by [`build`](Self::build) for the same
    /// mesh (kept, or stored with it).
    #[must_use]
    pub const fn from_parts(vertex_normals: &'a [Vec3], edge_normals: &'a [[Vec3; 3]]) -> Self {
        Self {
            vertices: vertex_normals,
            edges: edge_normals,
        }
    }

    /// The pseudo-normal at `closest` (a closest point of `mesh`, with its feature): the
    /// face's normal, the edge's or the vertex's pseudo-normal. Not unit length; `None` for a
    /// triangle or vertex out of range.
    #[must_use]
    pub fn normal_at(&self, mesh: &ValidMesh<'_>, closest: &ClosestPoint) -> Option<Vec3> {
        match closest.feature {
            TriangleFeature::Face => Some(unit_face_normal(mesh, closest.tri)),
            TriangleFeature::Edge(i) => self
                .edges
                .get(closest.tri as usize)?
                .get(i as usize)
                .copied(),
            TriangleFeature::Vertex(i) => {
                let v = *mesh
                    .triangles()
                    .get(closest.tri as usize)?
                    .get(i as usize)?;
                self.vertices.get(v as usize).copied()
            }
        }
    }

    /// The distance from `point` to the mesh, negative inside: the closest point within
    /// `max_distance` by `surface` (any structure over `mesh`: the same point and bits as
    /// [`MeshQuery::closest_point`]), signed by the pseudo-normal there. Its
    /// [`winding_number`](SignedDistance::winding_number) is the one a closed outward mesh has:
    /// 1 inside, 0 outside. `None` when nothing lies within `max_distance` or `point` is not
    /// finite. A point on the surface is outside (`+0.0`).
    #[must_use]
    pub fn signed_distance<Q: MeshQuery + ?Sized>(
        &self,
        surface: &Q,
        mesh: &ValidMesh<'_>,
        point: Vec3,
        max_distance: f32,
    ) -> Option<SignedDistance> {
        let closest = surface.closest_point(point, max_distance)?;
        let inside = self.inside_at(mesh, point, &closest)?;
        Some(SignedDistance::new(
            point,
            closest,
            if inside { 1.0 } else { 0.0 },
        ))
    }

    /// Whether `point` is inside, given `closest`, its closest point on `mesh` (with the
    /// feature): `(point − closest) · N < 0` for the pseudo-normal `N` there. `None` for a
    /// triangle or vertex out of range.
    #[must_use]
    pub fn inside_at(
        &self,
        mesh: &ValidMesh<'_>,
        point: Vec3,
        closest: &ClosestPoint,
    ) -> Option<bool> {
        let n = self.normal_at(mesh, closest)?;
        Some(dot(point - closest.point, n) < 0.0)
    }
}

/// Vertex `v`'s position (zero when out of range, which a valid mesh rules out).
fn position(mesh: &ValidMesh<'_>, v: u32) -> Vec3 {
    mesh.positions()
        .get(v as usize)
        .map_or(Vec3::ZERO, |&p| Vec3::from_array(p))
}

/// Triangle `t`'s unit normal, zero for a zero-area triangle.
fn unit_face_normal(mesh: &ValidMesh<'_>, t: u32) -> Vec3 {
    mesh.triangle(t)
        .and_then(|tri| tri.unit_normal())
        .unwrap_or(Vec3::ZERO)
}

/// The angle between `u` and `v` in radians (0 when either is zero), by `atan2` of the cross
/// and dot products: accurate for small and near-straight angles alike.
fn angle_between(u: Vec3, v: Vec3) -> f32 {
    let c = cross(u, v);
    libm::atan2f(libm::sqrtf(dot(c, c)), dot(u, v))
}
