//! A full structural check of a [`HalfEdgeMesh`]: what every edit must preserve.

use core::fmt;

use super::half_edges::HalfEdgeMesh;

/// A broken rule of the half-edge structure, found by [`HalfEdgeMesh::check`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum HalfEdgeDefect {
    /// The triangle repeats a vertex or names a vertex past the vertex count.
    Corner {
        /// The triangle.
        triangle: u32,
    },
    /// The half-edge's twin is out of range, is not paired back, or does not run the other
    /// way along the same edge.
    Twin {
        /// The half-edge.
        half_edge: u32,
    },
    /// Two half-edges run from `a` to `b`: an edge with more than two triangles, or two
    /// triangles on it facing opposite ways.
    RepeatedEdge {
        /// Where they start.
        a: u32,
        /// Where they end.
        b: u32,
    },
    /// The vertex's half-edge does not leave it, is missing while triangles use the vertex,
    /// is not its boundary half-edge on the boundary, or turning from it misses some of the
    /// vertex's half-edges (two fans meet there).
    Vertex {
        /// The vertex.
        vertex: u32,
    },
}

impl fmt::Display for HalfEdgeDefect {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Corner { triangle } => write!(f, "triangle {triangle} has a bad corner"),
            Self::Twin { half_edge } => write!(f, "half-edge {half_edge} has a bad twin"),
            Self::RepeatedEdge { a, b } => {
                write!(f, "two half-edges run from vertex {a} to vertex {b}")
            }
            Self::Vertex { vertex } => write!(f, "vertex {vertex} has a bad fan"),
        }
    }
}

impl core::error::Error for HalfEdgeDefect {}

impl HalfEdgeMesh<'_> {
    /// Checks every rule the edits keep: corners distinct and in range, twins paired both
    /// ways along the same edge in opposite directions, no directed edge twice (so the mesh
    /// is manifold and consistently oriented), and each used vertex's half-edge leaving it,
    /// on the boundary where the vertex is, with one fan around it that meets every half-edge
    /// leaving it. Takes time proportional to the half-edges times the largest valence: a
    /// debugging aid (the tests run it after every edit), not something the remesher needs.
    ///
    /// # Errors
    /// The first defect found, in half-edge then vertex order.
    pub fn check(&self) -> Result<(), HalfEdgeDefect> {
        let (h, v) = (self.half_edge_count() as u32, self.vertex_count() as u32);
        for t in 0..self.triangle_count() as u32 {
            let [a, b, c] = self.triangle(t);
            if a == b || b == c || c == a || a.max(b).max(c) >= v {
                return Err(HalfEdgeDefect::Corner { triangle: t });
            }
        }
        for he in 0..h {
            let (a, b) = self.ends(he);
            if let Some(g) = self.twin(he)
                && (g >= h || self.twin(g) != Some(he) || self.ends(g) != (b, a))
            {
                return Err(HalfEdgeDefect::Twin { half_edge: he });
            }
            // Every half-edge leaving `a` is met once turning around `a`, and no other one
            // there ends at `b`.
            let (mut met, mut same_way) = (0u32, 0u32);
            self.for_each_outgoing(a, |o| {
                met += u32::from(o == he);
                same_way += u32::from(self.origin(Self::next(o)) == b);
            });
            if same_way > 1 {
                return Err(HalfEdgeDefect::RepeatedEdge { a, b });
            }
            if met != 1 {
                return Err(HalfEdgeDefect::Vertex { vertex: a });
            }
            if self.twin(he).is_none() && !self.is_boundary_vertex(a) {
                return Err(HalfEdgeDefect::Vertex { vertex: a });
            }
        }
        for vertex in 0..v {
            if let Some(he) = self.vertex_half_edge(vertex)
                && (he >= h || self.origin(he) != vertex)
            {
                return Err(HalfEdgeDefect::Vertex { vertex });
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::MeshRef;
    use crate::remesh::HalfEdgeBuffers;

    /// A square of two triangles passes; a second copy of one triangle does not, and neither
    /// does a twin pointing the wrong way.
    #[test]
    fn finds_broken_links() {
        let positions = [
            [0.0f32, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let triangles = [[0u32, 1, 2], [0, 2, 3]];
        let input = MeshRef::new(&positions, &triangles).validate().unwrap();
        let mut p = [[0.0f32; 3]; 4];
        let (mut o, mut t, mut c) = ([0u32; 6], [0u32; 6], [false; 6]);
        let mut out = [0u32; 4];
        let mut scratch = [0u32; 6];
        let buffers = HalfEdgeBuffers {
            positions: &mut p,
            origins: &mut o,
            twins: &mut t,
            vertex_half_edges: &mut out,
            creases: &mut c,
        };
        let mesh = HalfEdgeMesh::from_mesh(&input, buffers, &mut scratch).unwrap();
        assert_eq!(mesh.check(), Ok(()));
        // Half-edges 2 (2 → 0) and 3 (0 → 2) are twins; point 2 at 0 instead.
        assert_eq!((mesh.twins[2], mesh.twins[3]), (3, 2));
        mesh.twins[2] = 0;
        assert_eq!(mesh.check(), Err(HalfEdgeDefect::Twin { half_edge: 2 }));
        mesh.twins[2] = 3;
        // The second triangle turned over: 0 → 2 twice.
        mesh.origins[3..6].copy_from_slice(&[0, 3, 2]);
        mesh.twins[3..6].copy_from_slice(&[super::super::half_edges::NO_HALF_EDGE; 3]);
        mesh.twins[2] = super::super::half_edges::NO_HALF_EDGE;
        assert!(mesh.check().is_err());
    }
}
