//! A triangle mesh as half-edges in caller buffers: the topology remeshing edits.

use glam::Vec3;

use crate::error::{RemeshBuffer, RemeshError};
use crate::mesh::ValidMesh;

/// The twin of a half-edge on the boundary, and the half-edge of a vertex no triangle uses.
pub(crate) const NO_HALF_EDGE: u32 = u32::MAX;

/// The buffers a [`HalfEdgeMesh`] lives in, all owned by the caller. Each may be longer than
/// needed; the mesh uses their fronts.
#[derive(Debug)]
pub struct HalfEdgeBuffers<'a> {
    /// Vertex positions: at least one per vertex.
    pub positions: &'a mut [[f32; 3]],
    /// Each half-edge's origin vertex: at least three per triangle.
    pub origins: &'a mut [u32],
    /// Each half-edge's twin (`u32::MAX` on the boundary): as long as `origins`.
    pub twins: &'a mut [u32],
    /// One outgoing half-edge per vertex: at least one per vertex.
    pub vertex_half_edges: &'a mut [u32],
    /// Whether each half-edge lies on a kept crease: as long as `origins`. Written false by
    /// [`HalfEdgeMesh::from_mesh`]; a remesh marks them from its `feature_angle`.
    pub creases: &'a mut [bool],
}

/// A manifold, consistently oriented triangle mesh as half-edges.
///
/// Half-edges are implicit per triangle: triangle `t` owns half-edges `3t`, `3t + 1`, `3t + 2`,
/// running from its corner `k` to corner `k + 1`, so a half-edge's triangle, next and previous
/// are arithmetic and only its origin and twin are stored. The twin runs the other way along the
/// same edge in the neighbouring triangle; a boundary half-edge has none.
///
/// Each vertex keeps one outgoing half-edge: on the boundary, the one without a twin, so a walk
/// turning around the vertex from it covers the vertex's whole fan; a vertex no
/// triangle uses keeps `u32::MAX`.
#[derive(Debug)]
pub struct HalfEdgeMesh<'a> {
    pub(super) positions: &'a mut [[f32; 3]],
    pub(super) origins: &'a mut [u32],
    pub(super) twins: &'a mut [u32],
    pub(super) vertex_half_edges: &'a mut [u32],
    pub(super) creases: &'a mut [bool],
    /// Whether any half-edge may be a crease: false until one is marked, so meshes without
    /// creases skip looking for them.
    pub(super) has_creases: bool,
    pub(super) vertex_count: usize,
    pub(super) triangle_count: usize,
}

/// Checks that `buffer` has room for `needed` entries.
fn room(buffer: RemeshBuffer, got: usize, needed: usize) -> Result<(), RemeshError> {
    if got < needed {
        return Err(RemeshError::BufferTooSmall {
            buffer,
            needed,
            got,
        });
    }
    Ok(())
}

impl<'a> HalfEdgeMesh<'a> {
    /// The half-edges of `mesh`, written into `buffers`, with `scratch` used to pair them.
    ///
    /// Needs, for `V` vertices and `T` triangles: `positions` and `vertex_half_edges` at least
    /// `V` long, `origins`, `twins` and `creases` at least `3T`, `scratch` at least
    /// `max(3T, V)`. Longer buffers are room for the edits to grow into. Vertices no triangle
    /// uses are kept (with no half-edge); no edge is a crease.
    ///
    /// # Errors
    /// - [`RemeshError::BufferTooSmall`] for a buffer shorter than that;
    /// - [`RemeshError::OutOfCapacity`] when `3T` half-edges cannot be indexed by `u32`;
    /// - [`RemeshError::RepeatedVertex`] for a triangle using a vertex twice;
    /// - [`RemeshError::NonManifoldEdge`] for an edge shared by more than two triangles;
    /// - [`RemeshError::InconsistentOrientation`] for two triangles running along an edge the
    ///   same way;
    /// - [`RemeshError::NonManifoldVertex`] for a vertex whose triangles form several fans.
    ///
    /// The first problem found is reported: triangles in order for repeated vertices, then
    /// edges in order of their lower vertex, then vertices in order.
    pub fn from_mesh(
        mesh: &ValidMesh<'_>,
        buffers: HalfEdgeBuffers<'a>,
        scratch: &mut [u32],
    ) -> Result<Self, RemeshError> {
        let (v, t) = (mesh.positions().len(), mesh.triangle_count());
        let h = t.checked_mul(3).ok_or(RemeshError::BufferTooSmall {
            buffer: RemeshBuffer::HalfEdges,
            needed: usize::MAX,
            got: buffers.origins.len(),
        })?;
        // Half-edges are indexed by `u32` below `NO_HALF_EDGE`.
        if h >= NO_HALF_EDGE as usize {
            return Err(RemeshError::OutOfCapacity {
                buffer: RemeshBuffer::HalfEdges,
                capacity: NO_HALF_EDGE as usize - 1,
            });
        }
        room(RemeshBuffer::Positions, buffers.positions.len(), v)?;
        room(RemeshBuffer::HalfEdges, buffers.origins.len(), h)?;
        room(RemeshBuffer::HalfEdges, buffers.twins.len(), h)?;
        room(RemeshBuffer::HalfEdges, buffers.creases.len(), h)?;
        room(
            RemeshBuffer::VertexHalfEdges,
            buffers.vertex_half_edges.len(),
            v,
        )?;
        room(RemeshBuffer::Scratch, scratch.len(), h.max(v))?;
        let mut this = Self {
            positions: buffers.positions,
            origins: buffers.origins,
            twins: buffers.twins,
            vertex_half_edges: buffers.vertex_half_edges,
            creases: buffers.creases,
            has_creases: false,
            vertex_count: v,
            triangle_count: t,
        };
        for (slot, p) in this.positions.iter_mut().zip(mesh.positions()) {
            *slot = *p;
        }
        for (tri, (corners, origins)) in (0u32..).zip(
            mesh.triangles()
                .iter()
                .zip(this.origins.chunks_exact_mut(3)),
        ) {
            let [a, b, c] = *corners;
            if a == b || a == c {
                return Err(RemeshError::RepeatedVertex {
                    triangle: tri,
                    vertex: a,
                });
            }
            if b == c {
                return Err(RemeshError::RepeatedVertex {
                    triangle: tri,
                    vertex: b,
                });
            }
            origins.copy_from_slice(corners);
        }
        for c in this.creases.iter_mut().take(h) {
            *c = false;
        }
        this.pair_twins(scratch.get_mut(..h).unwrap_or_default())?;
        this.pick_vertex_half_edges();
        this.check_fans(scratch.get_mut(..v).unwrap_or_default())?;
        Ok(this)
    }

    /// Pairs every half-edge with the one running the other way along its edge, by sorting
    /// the half-edges by edge in `order`.
    fn pair_twins(&mut self, order: &mut [u32]) -> Result<(), RemeshError> {
        self.sort_by_edge(order);
        let key = |this: &Self, he: u32| this.edge_key(he);
        let mut i = 0usize;
        while let Some(&first) = order.get(i) {
            let edge = key(self, first).0;
            let run = order
                .get(i..)
                .unwrap_or_default()
                .iter()
                .take_while(|&&he| key(self, he).0 == edge)
                .count();
            let (lo, hi) = ((edge >> 32) as u32, edge as u32);
            match *order.get(i..i + run).unwrap_or_default() {
                [he] => self.set_twin(he, NO_HALF_EDGE),
                [x, y] => {
                    let (a, b) = self.ends(x);
                    if key(self, x).1 == key(self, y).1 {
                        return Err(RemeshError::InconsistentOrientation { a, b });
                    }
                    self.set_twin(x, y);
                    self.set_twin(y, x);
                }
                _ => {
                    return Err(RemeshError::NonManifoldEdge {
                        a: lo,
                        b: hi,
                        triangles: run as u32,
                    });
                }
            }
            i += run.max(1);
        }
        Ok(())
    }

    /// Gives each vertex an outgoing half-edge: the first boundary one where there is one
    /// (a vertex with two sits where two fans meet, which [`Self::check_fans`] finds).
    fn pick_vertex_half_edges(&mut self) {
        for slot in self.vertex_half_edges.iter_mut().take(self.vertex_count) {
            *slot = NO_HALF_EDGE;
        }
        for he in 0..self.half_edge_count() as u32 {
            let v = self.origin(he);
            let held = self.vertex_half_edge(v);
            let take = match held {
                None => true,
                Some(h) => self.twin(he).is_none() && self.twin(h).is_some(),
            };
            if take && let Some(slot) = self.vertex_half_edges.get_mut(v as usize) {
                *slot = he;
            }
        }
    }

    /// Checks that turning around each vertex from its half-edge meets every half-edge leaving
    /// it (one fan), counting them first in `counts`.
    fn check_fans(&self, counts: &mut [u32]) -> Result<(), RemeshError> {
        counts.fill(0);
        for he in 0..self.half_edge_count() as u32 {
            if let Some(c) = counts.get_mut(self.origin(he) as usize) {
                *c += 1;
            }
        }
        for (v, &count) in (0u32..).zip(counts.iter()) {
            let Some(start) = self.vertex_half_edge(v) else {
                continue;
            };
            let mut seen = 1u32;
            let mut he = start;
            while let Some(next) = self.rotate(he) {
                if next == start || seen > count {
                    break;
                }
                seen += 1;
                he = next;
            }
            if seen != count {
                return Err(RemeshError::NonManifoldVertex { vertex: v });
            }
        }
        Ok(())
    }

    /// The sort key of half-edge `he`: its edge (lower vertex, higher vertex), then its
    /// direction.
    fn edge_key(&self, he: u32) -> (u64, bool) {
        let (a, b) = self.ends(he);
        ((u64::from(a.min(b)) << 32) | u64::from(a.max(b)), a > b)
    }

    /// Writes every half-edge into `order` sorted by edge (lower vertex, then higher vertex),
    /// half-edges of one edge in index order: two stable counting sorts, by the higher
    /// vertex into `twins` (free until pairing fills it) and then by the lower one into
    /// `order`, counting in `vertex_half_edges` (filled after pairing). Linear time, and no
    /// comparison sort whose panic paths the firmware's panic-free proof would refuse.
    fn sort_by_edge(&mut self, order: &mut [u32]) {
        let h = self.half_edge_count() as u32;
        let ends = |origins: &[u32], he: u32| {
            let next = HalfEdgeMesh::next(he);
            let a = origins.get(he as usize).copied().unwrap_or(0);
            let b = origins.get(next as usize).copied().unwrap_or(0);
            (a.min(b), a.max(b))
        };
        let origins = &*self.origins;
        let counts = &mut *self.vertex_half_edges;
        let vertices = self.vertex_count;
        // By the higher vertex, from index order into `twins`.
        counting_sort(counts, vertices, 0..h, &mut *self.twins, |he| {
            ends(origins, he).1
        });
        // By the lower vertex, stably, from `twins` into `order`.
        let by_higher = self.twins.get(..h as usize).unwrap_or_default();
        counting_sort(counts, vertices, by_higher.iter().copied(), order, |he| {
            ends(origins, he).0
        });
    }

    fn set_twin(&mut self, he: u32, twin: u32) {
        if let Some(slot) = self.twins.get_mut(he as usize) {
            *slot = twin;
        }
    }

    /// The most vertices the buffers hold (at most `u32::MAX − 1`: indices are `u32`).
    #[must_use]
    pub(crate) fn vertex_capacity(&self) -> usize {
        self.positions
            .len()
            .min(self.vertex_half_edges.len())
            .min(NO_HALF_EDGE as usize - 1)
    }

    /// The most triangles the buffers hold (their half-edges indexed by `u32`, below
    /// [`NO_HALF_EDGE`]).
    #[must_use]
    pub(crate) fn triangle_capacity(&self) -> usize {
        self.origins
            .len()
            .min(self.twins.len())
            .min(self.creases.len())
            .min(NO_HALF_EDGE as usize - 1)
            / 3
    }

    /// Whether half-edge `he` lies on a kept crease.
    #[must_use]
    pub(crate) fn is_crease(&self, he: u32) -> bool {
        self.creases.get(he as usize).copied().unwrap_or(false)
    }

    /// The corners of triangle `t` (vertex indices, in order).
    #[must_use]
    pub fn triangle(&self, t: u32) -> [u32; 3] {
        let h = t.saturating_mul(3);
        [self.origin(h), self.origin(h + 1), self.origin(h + 2)]
    }

    /// The positions of vertices `0..vertex_count()` (the owned remesh's copy).
    #[cfg(feature = "alloc")]
    #[must_use]
    pub(crate) fn used_positions(&self) -> &[[f32; 3]] {
        self.positions.get(..self.vertex_count).unwrap_or_default()
    }

    /// Vertices (used by triangles or not).
    #[must_use]
    pub const fn vertex_count(&self) -> usize {
        self.vertex_count
    }

    /// Triangles.
    #[must_use]
    pub const fn triangle_count(&self) -> usize {
        self.triangle_count
    }

    /// Half-edges: three per triangle.
    #[must_use]
    pub(crate) const fn half_edge_count(&self) -> usize {
        self.triangle_count * 3
    }

    /// The position of vertex `v` (the origin for a vertex out of range).
    #[must_use]
    pub fn position(&self, v: u32) -> Vec3 {
        self.positions
            .get(v as usize)
            .map_or(Vec3::ZERO, |&p| Vec3::from_array(p))
    }

    /// The vertex half-edge `he` starts at ([`NO_HALF_EDGE`] out of range).
    #[must_use]
    pub(crate) fn origin(&self, he: u32) -> u32 {
        self.origins
            .get(he as usize)
            .copied()
            .unwrap_or(NO_HALF_EDGE)
    }

    /// The half-edge running the other way along the same edge; `None` on the boundary.
    #[must_use]
    pub(crate) fn twin(&self, he: u32) -> Option<u32> {
        self.twins
            .get(he as usize)
            .copied()
            .filter(|&t| t != NO_HALF_EDGE)
    }

    /// The next half-edge around the same triangle.
    #[must_use]
    pub(crate) const fn next(he: u32) -> u32 {
        if he % 3 == 2 { he - 2 } else { he + 1 }
    }

    /// The previous half-edge around the same triangle.
    #[must_use]
    pub(crate) const fn prev(he: u32) -> u32 {
        if he.is_multiple_of(3) { he + 2 } else { he - 1 }
    }

    /// Where half-edge `he` starts and ends.
    #[must_use]
    pub(crate) fn ends(&self, he: u32) -> (u32, u32) {
        (self.origin(he), self.origin(Self::next(he)))
    }

    /// The next half-edge leaving the same vertex, turning across the edge that ends there in
    /// `he`'s triangle; `None` where that edge is on the boundary.
    #[must_use]
    pub(crate) fn rotate(&self, he: u32) -> Option<u32> {
        self.twin(Self::prev(he))
    }

    /// Vertex `v`'s outgoing half-edge (the boundary one for a boundary vertex); `None` for a
    /// vertex no triangle uses.
    #[must_use]
    pub(crate) fn vertex_half_edge(&self, v: u32) -> Option<u32> {
        self.vertex_half_edges
            .get(v as usize)
            .copied()
            .filter(|&h| h != NO_HALF_EDGE)
    }

    /// Whether vertex `v` lies on the boundary.
    #[must_use]
    pub(crate) fn is_boundary_vertex(&self, v: u32) -> bool {
        self.vertex_half_edge(v)
            .is_some_and(|he| self.twin(he).is_none())
    }

    /// The number of edges at vertex `v` (0 for a vertex no triangle uses).
    #[must_use]
    pub(crate) fn valence(&self, v: u32) -> u32 {
        let Some(start) = self.vertex_half_edge(v) else {
            return 0;
        };
        let mut edges = 1u32;
        let mut he = start;
        // At most one turn per half-edge: a bound even on a damaged mesh.
        for _ in 0..self.half_edge_count() {
            match self.rotate(he) {
                Some(next) if next != start => {
                    edges += 1;
                    he = next;
                }
                Some(_) => return edges,
                // The fan ends at the boundary: its last edge has no half-edge leaving `v`.
                None => return edges + 1,
            }
        }
        edges
    }

    /// Edges: interior ones once, boundary ones once.
    #[must_use]
    pub(crate) fn edge_count(&self) -> usize {
        let boundary = self.boundary_half_edge_count();
        (self.half_edge_count() - boundary) / 2 + boundary
    }

    /// Half-edges without a twin.
    #[must_use]
    pub(crate) fn boundary_half_edge_count(&self) -> usize {
        (0..self.half_edge_count() as u32)
            .filter(|&he| self.twin(he).is_none())
            .count()
    }

    /// The number of closed boundary loops (holes and outer rims).
    #[must_use]
    pub(crate) fn boundary_loop_count(&self) -> usize {
        // Each loop is counted at its boundary half-edge of lowest index: follow the loop from
        // every boundary half-edge and count those that meet no lower one.
        let mut loops = 0usize;
        for start in 0..self.half_edge_count() as u32 {
            if self.twin(start).is_some() {
                continue;
            }
            let mut he = start;
            let mut lowest = true;
            for _ in 0..self.half_edge_count() {
                he = self.next_on_boundary(he);
                if he == start {
                    break;
                }
                if he < start {
                    lowest = false;
                    break;
                }
            }
            loops += usize::from(lowest);
        }
        loops
    }

    /// The boundary half-edge that follows boundary half-edge `he` around its loop: the one
    /// leaving the vertex `he` ends at.
    #[must_use]
    pub(crate) fn next_on_boundary(&self, he: u32) -> u32 {
        // Turn around the end vertex until the fan's boundary half-edge.
        let mut out = Self::next(he);
        for _ in 0..self.half_edge_count() {
            match self.twin(out) {
                None => return out,
                Some(t) => out = Self::next(t),
            }
        }
        out
    }

    /// Vertices used by triangles, minus edges, plus triangles: `2 − 2g − b` for a connected
    /// surface of genus `g` with `b` boundary loops (summed over components).
    #[must_use]
    pub(crate) fn euler_characteristic(&self) -> i64 {
        let used = (0..self.vertex_count as u32)
            .filter(|&v| self.vertex_half_edge(v).is_some())
            .count();
        used as i64 - self.edge_count() as i64 + self.triangle_count as i64
    }
}

/// Stable counting sort of `items` by `key` (below `keys`) into `out`, with `counts` (at
/// least `keys` long) as the bucket offsets. Keys at or past `keys`, and items past the end
/// of `out`, are skipped (the callers' keys are vertex indices already checked in range).
fn counting_sort(
    counts: &mut [u32],
    keys: usize,
    items: impl Iterator<Item = u32> + Clone,
    out: &mut [u32],
    key: impl Fn(u32) -> u32,
) {
    let counts = counts.get_mut(..keys).unwrap_or_default();
    counts.fill(0);
    for item in items.clone() {
        if let Some(c) = counts.get_mut(key(item) as usize) {
            *c += 1;
        }
    }
    // Counts to first slots.
    let mut start = 0u32;
    for c in counts.iter_mut() {
        let n = *c;
        *c = start;
        start = start.saturating_add(n);
    }
    for item in items {
        if let Some(slot) = counts.get_mut(key(item) as usize) {
            if let Some(o) = out.get_mut(*slot as usize) {
                *o = item;
            }
            *slot += 1;
        }
    }
}
