//! What a remeshing run reports: its counts at the end, and each step to an observer.

use super::half_edges::HalfEdgeMesh;

/// What a [`remesh`](super::remesh) run did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RemeshReport {
    /// Iterations run.
    pub iterations: u32,
    /// Edges split.
    pub splits: usize,
    /// Edges collapsed.
    pub collapses: usize,
    /// Edges flipped: toward valence 6, toward wider angles, and toward Delaunay around the
    /// new vertex of each split of a needle's side (an edge over twice the split bound).
    pub flips: usize,
    /// Vertices moved one at a time after the iterations, to open up small angles (a
    /// vertex may move more than once).
    pub relaxed: usize,
    /// Crease edges marked at the start.
    pub creases: usize,
    /// The most vertices the mesh held at once (after a split pass): buffers of this many
    /// vertices and [`peak_triangles`](Self::peak_triangles) triangles are enough to repeat
    /// the run.
    pub peak_vertices: usize,
    /// The most triangles the mesh held at once.
    pub peak_triangles: usize,
}

/// One step of a remeshing run, as [`RemeshObserver::edited`] sees it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum RemeshStep {
    /// An edge was split at its midpoint.
    Split,
    /// An edge was collapsed (the last vertex and triangles moved into the freed slots).
    Collapse,
    /// An edge was flipped.
    Flip,
    /// The smoothing pass moved one free vertex toward its one-ring centroid and onto the
    /// reference surface.
    Smooth,
    /// After the iterations, one vertex of a narrow triangle moved (on the reference
    /// surface) to widen the smallest angle around it.
    Relax,
}

/// Watches a [`remesh_observed`](super::remesh_observed) run: called after every edit and
/// every iteration, with the mesh as it then is. It cannot change the run. Checking
/// invariants after every edit ([`HalfEdgeMesh::check`] and the topology) is what the
/// tests use it for; drawing the steps is another use.
pub trait RemeshObserver {
    /// After each split, collapse, flip and vertex move.
    fn edited(&mut self, step: RemeshStep, mesh: &HalfEdgeMesh<'_>) {
        let _ = (step, mesh);
    }

    /// After each iteration, with the report so far.
    fn iterated(&mut self, report: &RemeshReport) {
        let _ = report;
    }
}

/// A progress callback as an observer.
pub(super) struct Progress<F>(pub(super) F);

impl<F: FnMut(&RemeshReport)> RemeshObserver for Progress<F> {
    fn iterated(&mut self, report: &RemeshReport) {
        (self.0)(report);
    }
}
