//! The figures a remesh is judged by: valences, angles, edge-length spread.

use super::half_edges::HalfEdgeMesh;
use crate::math::dot;

/// Quality figures of a triangle mesh, as remeshing reports them before and after.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MeshQuality {
    /// Triangles.
    pub triangles: usize,
    /// Vertices used by a triangle.
    pub vertices: usize,
    /// Percentage of interior vertices with exactly six edges, `0..=100` (0 with none).
    pub valence_6_percent: f32,
    /// The smallest triangle angle, in degrees, over triangles with no boundary vertex (180
    /// with none).
    pub min_angle_off_boundary: f32,
    /// Percentage of triangles with an angle under 30°, `0..=100`.
    pub under_30_percent: f32,
    /// Mean edge length, in the mesh's units.
    pub mean_edge: f32,
    /// Standard deviation of the edge lengths divided by their mean (0 with no edges).
    pub edge_cv: f32,
}

/// The three angles of the triangle with corners `p`, in degrees (0 at a corner where an edge
/// has no length).
fn angles([p0, p1, p2]: [glam::Vec3; 3]) -> [f32; 3] {
    let mut out = [0.0f32; 3];
    for (angle, (a, b, c)) in out
        .iter_mut()
        .zip([(p0, p1, p2), (p1, p2, p0), (p2, p0, p1)])
    {
        let (u, v) = (b - a, c - a);
        let lengths = libm::sqrtf(dot(u, u) * dot(v, v));
        if lengths > 0.0 {
            let cos = (dot(u, v) / lengths).clamp(-1.0, 1.0);
            *angle = libm::acosf(cos).to_degrees();
        }
    }
    out
}

/// Sums over a mesh's edges, each counted once, in half-edge order.
pub(super) struct EdgeLengths {
    sum: f64,
    sum_sq: f64,
    count: usize,
}

impl EdgeLengths {
    pub(super) fn of(mesh: &HalfEdgeMesh<'_>) -> Self {
        let mut lengths = Self {
            sum: 0.0,
            sum_sq: 0.0,
            count: 0,
        };
        for he in 0..mesh.half_edge_count() as u32 {
            if mesh.twin(he).is_none_or(|g| he < g) {
                let (a, b) = mesh.ends(he);
                let d = mesh.position(b) - mesh.position(a);
                let len = f64::from(libm::sqrtf(dot(d, d)));
                lengths.sum += len;
                lengths.sum_sq += len * len;
                lengths.count += 1;
            }
        }
        lengths
    }

    /// The mean length (0 with no edges).
    pub(super) fn mean(&self) -> f64 {
        if self.count == 0 {
            0.0
        } else {
            self.sum / self.count as f64
        }
    }

    /// The standard deviation divided by the mean (0 with no edges or a zero mean).
    fn spread(&self) -> f64 {
        let mean = self.mean();
        if self.count == 0 || mean <= 0.0 {
            return 0.0;
        }
        let variance = (self.sum_sq / self.count as f64 - mean * mean).max(0.0);
        libm::sqrt(variance) / mean
    }
}

impl MeshQuality {
    /// The figures of `mesh`.
    #[must_use]
    pub fn of(mesh: &HalfEdgeMesh<'_>) -> Self {
        let (mut interior, mut six, mut used) = (0usize, 0usize, 0usize);
        for v in 0..mesh.vertex_count() as u32 {
            if mesh.vertex_half_edge(v).is_none() {
                continue;
            }
            used += 1;
            if !mesh.is_boundary_vertex(v) {
                interior += 1;
                six += usize::from(mesh.valence(v) == 6);
            }
        }
        let (mut min_angle, mut under_30) = (180.0f32, 0usize);
        for t in 0..mesh.triangle_count() as u32 {
            let corners = mesh.triangle(t);
            let a = angles(corners.map(|v| mesh.position(v)));
            let smallest = a.iter().copied().fold(180.0f32, f32::min);
            under_30 += usize::from(smallest < 30.0);
            if !corners.iter().any(|&v| mesh.is_boundary_vertex(v)) {
                min_angle = min_angle.min(smallest);
            }
        }
        let edges = EdgeLengths::of(mesh);
        let percent = |part: usize, whole: usize| {
            if whole == 0 {
                0.0
            } else {
                (100.0 * part as f64 / whole as f64) as f32
            }
        };
        Self {
            triangles: mesh.triangle_count(),
            vertices: used,
            valence_6_percent: percent(six, interior),
            min_angle_off_boundary: min_angle,
            under_30_percent: percent(under_30, mesh.triangle_count()),
            mean_edge: edges.mean() as f32,
            edge_cv: edges.spread() as f32,
        }
    }
}
