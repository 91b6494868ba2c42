//! [`HalfEdgeEdits`]: walking and editing a [`HalfEdgeMesh`] edge by edge, the operations the
//! remesher is made of, for tools and tests that check or drive them one at a time.

use glam::Vec3;

use super::half_edges::HalfEdgeMesh;
use crate::error::RemeshError;

/// The half-edge walk and the three edits of a [`HalfEdgeMesh`]. Half-edge `he` belongs to
/// triangle `he / 3`; the three half-edges of a triangle run around it in its winding order.
/// Ids out of range read as absent ([`None`], 0 or `u32::MAX`), never panic. Reach it through
/// [`meshq::advanced`](crate::advanced); remeshing itself needs none of it.
pub trait HalfEdgeEdits {
    /// Half-edges: three per triangle.
    fn half_edge_count(&self) -> usize;
    /// The vertex half-edge `he` starts at (`u32::MAX` out of range).
    fn origin(&self, he: u32) -> u32;
    /// The half-edge running the other way along the same edge; `None` on the boundary.
    fn twin(&self, he: u32) -> Option<u32>;
    /// The next half-edge around the same triangle.
    fn next(he: u32) -> u32;
    /// The previous half-edge around the same triangle.
    fn prev(he: u32) -> u32;
    /// Where half-edge `he` starts and ends.
    fn ends(&self, he: u32) -> (u32, u32);
    /// Vertex `v`'s outgoing half-edge (the boundary one for a boundary vertex); `None` for a
    /// vertex no triangle uses.
    fn vertex_half_edge(&self, v: u32) -> Option<u32>;
    /// Whether vertex `v` lies on the boundary.
    fn is_boundary_vertex(&self, v: u32) -> bool;
    /// The number of edges at vertex `v` (0 for a vertex no triangle uses).
    fn valence(&self, v: u32) -> u32;
    /// Edges, each counted once, interior or boundary.
    fn edge_count(&self) -> usize;
    /// Half-edges without a twin.
    fn boundary_half_edge_count(&self) -> usize;
    /// The number of closed boundary loops (holes and outer rims).
    fn boundary_loop_count(&self) -> usize;
    /// Used vertices − edges + triangles: `2 − 2g − b` for a connected surface of genus `g`
    /// with `b` boundary loops, summed over components.
    fn euler_characteristic(&self) -> i64;
    /// Splits the edge of `he` at `at` into two, joining the new vertex to the opposite corner
    /// of each of its one or two triangles; returns the new vertex. Creases stay creases.
    ///
    /// # Errors
    /// [`RemeshError::OutOfCapacity`] without room for one vertex and two triangles; the mesh
    /// is unchanged then.
    fn split_edge(&mut self, he: u32, at: Vec3) -> Result<u32, RemeshError>;
    /// Flips the edge of `he`: (a, b, c) and (b, a, d) become (a, d, c) and (d, b, c). Returns
    /// false and changes nothing unless the edge is interior, not a crease, `a` and `b` may
    /// each lose an edge and (c, d) is not already an edge.
    fn flip_edge(&mut self, he: u32) -> bool;
    /// Collapses the edge of `he` from `a` into `b`, which moves to `at`; the edge's triangles
    /// go. Returns false and changes nothing unless the link condition holds and `a` may be
    /// removed. The last vertex and triangles move into the freed slots, so other ids may
    /// change.
    fn collapse_edge(&mut self, he: u32, at: Vec3) -> bool;
}

// Each forwards to the crate's own method of the same name: inherent methods win inside the
// crate, so the remesher calls them directly and this impl is the only way in from outside.
impl HalfEdgeEdits for HalfEdgeMesh<'_> {
    fn half_edge_count(&self) -> usize {
        HalfEdgeMesh::half_edge_count(self)
    }
    fn origin(&self, he: u32) -> u32 {
        HalfEdgeMesh::origin(self, he)
    }
    fn twin(&self, he: u32) -> Option<u32> {
        HalfEdgeMesh::twin(self, he)
    }
    fn next(he: u32) -> u32 {
        HalfEdgeMesh::next(he)
    }
    fn prev(he: u32) -> u32 {
        HalfEdgeMesh::prev(he)
    }
    fn ends(&self, he: u32) -> (u32, u32) {
        HalfEdgeMesh::ends(self, he)
    }
    fn vertex_half_edge(&self, v: u32) -> Option<u32> {
        HalfEdgeMesh::vertex_half_edge(self, v)
    }
    fn is_boundary_vertex(&self, v: u32) -> bool {
        HalfEdgeMesh::is_boundary_vertex(self, v)
    }
    fn valence(&self, v: u32) -> u32 {
        HalfEdgeMesh::valence(self, v)
    }
    fn edge_count(&self) -> usize {
        HalfEdgeMesh::edge_count(self)
    }
    fn boundary_half_edge_count(&self) -> usize {
        HalfEdgeMesh::boundary_half_edge_count(self)
    }
    fn boundary_loop_count(&self) -> usize {
        HalfEdgeMesh::boundary_loop_count(self)
    }
    fn euler_characteristic(&self) -> i64 {
        HalfEdgeMesh::euler_characteristic(self)
    }
    fn split_edge(&mut self, he: u32, at: Vec3) -> Result<u32, RemeshError> {
        HalfEdgeMesh::split_edge(self, he, at)
    }
    fn flip_edge(&mut self, he: u32) -> bool {
        HalfEdgeMesh::flip_edge(self, he)
    }
    fn collapse_edge(&mut self, he: u32, at: Vec3) -> bool {
        HalfEdgeMesh::collapse_edge(self, he, at)
    }
}
