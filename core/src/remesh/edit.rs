//! The three topological edits of remeshing — split, flip, collapse — each keeping the mesh
//! manifold, oriented and compact (triangles `0..T`, vertices `0..V`, no holes in the arrays).

use glam::Vec3;

use super::half_edges::{HalfEdgeMesh, NO_HALF_EDGE};
use crate::error::{RemeshBuffer, RemeshError};
use crate::math::dot;

/// Cosine of the most a crease line may turn at a vertex that a collapse removes (20°).
const CREASE_TURN_COSINE: f32 = 0.94;

/// An outer half-edge of the triangles an edit rewrites: its twin and crease flag, saved
/// before the rewrite.
#[derive(Clone, Copy)]
struct Outer {
    twin: u32,
    crease: bool,
}

impl HalfEdgeMesh<'_> {
    fn set_origin(&mut self, he: u32, v: u32) {
        if let Some(slot) = self.origins.get_mut(he as usize) {
            *slot = v;
        }
    }

    fn set_crease(&mut self, he: u32, crease: bool) {
        self.has_creases |= crease;
        if let Some(slot) = self.creases.get_mut(he as usize) {
            *slot = crease;
        }
    }

    /// Makes `a` and `b` twins (`b` may be [`NO_HALF_EDGE`]: `a` is then on the boundary).
    fn link(&mut self, a: u32, b: u32) {
        if let Some(slot) = self.twins.get_mut(a as usize) {
            *slot = b;
        }
        if let Some(slot) = self.twins.get_mut(b as usize) {
            *slot = a;
        }
    }

    fn outer(&self, he: u32) -> Outer {
        Outer {
            twin: self.twin(he).unwrap_or(NO_HALF_EDGE),
            crease: self.is_crease(he),
        }
    }

    /// Gives half-edge `he` the saved outer half-edge's twin and crease flag.
    fn attach(&mut self, he: u32, outer: Outer) {
        self.link(he, outer.twin);
        self.set_crease(he, outer.crease);
    }

    fn set_vertex_half_edge(&mut self, v: u32, he: u32) {
        if let Some(slot) = self.vertex_half_edges.get_mut(v as usize) {
            *slot = he;
        }
    }

    /// Moves vertex `v` to `p`.
    pub(super) fn set_position(&mut self, v: u32, p: Vec3) {
        if let Some(slot) = self.positions.get_mut(v as usize) {
            *slot = p.to_array();
        }
    }

    /// Points vertex `v` at an outgoing half-edge found from `start` (which leaves `v`): the
    /// boundary one if `v` is on the boundary, so fan walks keep covering the whole fan.
    fn reset_vertex_half_edge(&mut self, v: u32, start: u32) {
        let mut he = start;
        for _ in 0..self.half_edge_count() {
            match self.twin(he) {
                None => break,
                Some(t) => {
                    let back = Self::next(t);
                    if back == start {
                        break;
                    }
                    he = back;
                }
            }
        }
        // A full turn found no boundary: any half-edge will do; keep the start.
        let chosen = if self.twin(he).is_none() { he } else { start };
        self.set_vertex_half_edge(v, chosen);
    }

    /// Calls `each` on every half-edge leaving vertex `v`, turning with
    /// [`rotate`](Self::rotate) from its own half-edge.
    pub(crate) fn for_each_outgoing(&self, v: u32, mut each: impl FnMut(u32)) {
        let Some(start) = self.vertex_half_edge(v) else {
            return;
        };
        let mut he = start;
        for _ in 0..self.half_edge_count() {
            each(he);
            match self.rotate(he) {
                Some(next) if next != start => he = next,
                _ => return,
            }
        }
    }

    /// Calls `each` on every neighbour of vertex `v` (each once, in fan order).
    pub(crate) fn for_each_neighbour(&self, v: u32, mut each: impl FnMut(u32)) {
        let mut last = NO_HALF_EDGE;
        self.for_each_outgoing(v, |he| {
            each(self.origin(Self::next(he)));
            last = he;
        });
        // On the boundary the fan's last edge has no half-edge leaving `v`.
        if last != NO_HALF_EDGE && self.rotate(last).is_none() {
            each(self.origin(Self::prev(last)));
        }
    }

    /// Whether vertices `a` and `b` share an edge.
    #[must_use]
    pub(crate) fn has_edge(&self, a: u32, b: u32) -> bool {
        let mut found = false;
        self.for_each_neighbour(a, |n| found |= n == b);
        found
    }

    /// Splits the edge of half-edge `he` at `at` (usually its midpoint): a new vertex there,
    /// joined to the corner opposite the edge in each of its one or two triangles. Returns the
    /// new vertex. A crease stays a crease on both halves.
    ///
    /// # Errors
    /// [`RemeshError::OutOfCapacity`] when the buffers have no room for one more vertex and
    /// two more triangles; the mesh is unchanged then.
    pub(crate) fn split_edge(&mut self, he: u32, at: Vec3) -> Result<u32, RemeshError> {
        let g = self.twin(he);
        let new_triangles = if g.is_some() { 2 } else { 1 };
        if self.vertex_count >= self.vertex_capacity() {
            return Err(RemeshError::OutOfCapacity {
                buffer: RemeshBuffer::Positions,
                capacity: self.vertex_capacity(),
            });
        }
        if self.triangle_count + new_triangles > self.triangle_capacity() {
            return Err(RemeshError::OutOfCapacity {
                buffer: RemeshBuffer::HalfEdges,
                capacity: self.triangle_capacity() * 3,
            });
        }
        let crease = self.is_crease(he);
        let m = self.vertex_count as u32;
        self.vertex_count += 1;
        self.set_position(m, at);
        // Triangle (a, b, c) becomes (a, m, c) in place plus a new (m, b, c).
        let t2 = self.split_side(he, m, crease);
        // m→b: on the boundary, the half-edge leaving m without a twin.
        self.set_vertex_half_edge(m, t2);
        match g {
            Some(g) => {
                // Its twin's triangle (b, a, d) becomes (b, m, d) plus a new (m, a, d).
                let t3 = self.split_side(g, m, crease);
                self.link(he, t3);
                self.link(g, t2);
            }
            None => {
                self.link(he, NO_HALF_EDGE);
                self.link(t2, NO_HALF_EDGE);
            }
        }
        Ok(m)
    }

    /// One side of a split: the triangle of `he` (from `x` to `y`, third corner `z`) becomes
    /// (x, m, z) in place plus a new triangle (m, y, z), whose first half-edge (m→y) is
    /// returned for the caller to pair across the edge. The new half-edge m→y keeps the split
    /// edge's crease flag; the inner edge m–z is no crease.
    fn split_side(&mut self, he: u32, m: u32, crease: bool) -> u32 {
        let y = self.origin(Self::next(he));
        let (n, p) = (Self::next(he), Self::prev(he));
        let z = self.origin(p);
        let old_yz = self.outer(n);
        let t = self.triangle_count as u32 * 3;
        self.triangle_count += 1;
        for (k, v) in [m, y, z].into_iter().enumerate() {
            self.set_origin(t + k as u32, v);
        }
        self.set_origin(n, m);
        self.attach(t + 1, old_yz);
        self.link(n, t + 2);
        self.set_crease(n, false);
        self.set_crease(t + 2, false);
        self.set_crease(t, crease);
        if self.vertex_half_edge(y) == Some(n) {
            self.set_vertex_half_edge(y, t + 1);
        }
        t
    }

    /// Whether the edge of `he` may be flipped: interior, not a crease, both ends keeping at
    /// least three edges, and the two opposite corners not already joined.
    #[must_use]
    pub(crate) fn can_flip(&self, he: u32) -> bool {
        let Some(g) = self.twin(he) else {
            return false;
        };
        if self.is_crease(he) {
            return false;
        }
        let (a, b) = self.ends(he);
        let c = self.origin(Self::prev(he));
        let d = self.origin(Self::prev(g));
        c != d && self.can_lose_edge(a) && self.can_lose_edge(b) && !self.has_edge(c, d)
    }

    /// Whether vertex `v` keeps a proper fan with one edge fewer: three edges inside, two on
    /// the boundary.
    fn can_lose_edge(&self, v: u32) -> bool {
        let least = if self.is_boundary_vertex(v) { 2 } else { 3 };
        self.valence(v) > least
    }

    /// Flips the edge of `he`: triangles (a, b, c) and (b, a, d) become (a, d, c) and
    /// (d, b, c). Does nothing and returns false unless the flip keeps the mesh manifold: the
    /// edge is interior and not a crease, `a` and `b` can each lose an edge, and (c, d) is not
    /// an edge already.
    pub(crate) fn flip_edge(&mut self, he: u32) -> bool {
        if !self.can_flip(he) {
            return false;
        }
        let Some(g) = self.twin(he) else {
            return false;
        };
        let (a, b) = self.ends(he);
        let (n0, p0, n1, p1) = (Self::next(he), Self::prev(he), Self::next(g), Self::prev(g));
        let (c, d) = (self.origin(p0), self.origin(p1));
        let (bc, ca, ad, db) = (
            self.outer(n0),
            self.outer(p0),
            self.outer(n1),
            self.outer(p1),
        );
        let (out_a, out_b, out_c, out_d) = (
            self.vertex_half_edge(a),
            self.vertex_half_edge(b),
            self.vertex_half_edge(c),
            self.vertex_half_edge(d),
        );
        let (t0, t1) = (he - he % 3, g - g % 3);
        for (k, v) in [a, d, c].into_iter().enumerate() {
            self.set_origin(t0 + k as u32, v);
        }
        for (k, v) in [d, b, c].into_iter().enumerate() {
            self.set_origin(t1 + k as u32, v);
        }
        self.attach(t0, ad);
        self.attach(t0 + 2, ca);
        self.attach(t1, db);
        self.attach(t1 + 1, bc);
        self.link(t0 + 1, t1 + 2);
        self.set_crease(t0 + 1, false);
        self.set_crease(t1 + 2, false);
        if out_a == Some(he) || out_a == Some(n1) {
            self.set_vertex_half_edge(a, t0);
        }
        if out_b == Some(g) || out_b == Some(n0) {
            self.set_vertex_half_edge(b, t1 + 1);
        }
        if out_c == Some(p0) {
            self.set_vertex_half_edge(c, t0 + 2);
        }
        if out_d == Some(p1) {
            self.set_vertex_half_edge(d, t1);
        }
        true
    }

    /// Whether the edge of `he` (from `a` to `b`) may be collapsed, moving `a` into `b`: `a`
    /// may be removed (see [`may_remove`](Self::may_remove)), and the edge passes the link
    /// condition (the only vertices both ends neighbour are the corners opposite the edge),
    /// so the result stays manifold with the same topology.
    #[must_use]
    pub(crate) fn can_collapse(&self, he: u32) -> bool {
        let (a, b) = self.ends(he);
        if !self.may_remove(he) {
            return false;
        }
        let Some(g) = self.twin(he) else {
            return false;
        };
        let c = self.origin(Self::prev(he));
        let d = self.origin(Self::prev(g));
        // The link condition: every common neighbour is c or d.
        let mut shared_ok = true;
        self.for_each_neighbour(a, |n| {
            if n != b && n != c && n != d && self.has_edge(n, b) {
                shared_ok = false;
            }
        });
        // Two triangles per side at least, so no vertex is left with two edges.
        shared_ok && self.can_lose_edge(c) && self.can_lose_edge(d) && self.triangle_count > 4
    }

    /// Whether the vertex `a` that half-edge `he` leaves may be removed by collapsing `he`'s
    /// edge, so that `a`'s edges then end at the other end `b`. Not on the boundary; and
    /// either on no crease, or inside a nearly straight crease line (see
    /// [`crease_line_through`](Self::crease_line_through)) of which `he`'s edge is part.
    /// The line then runs from `a`'s other crease neighbour straight to `b`, where it
    /// nearly ran already. A corner where creases meet, or a crease's end, is never removed.
    #[must_use]
    pub(crate) fn may_remove(&self, he: u32) -> bool {
        let (a, b) = self.ends(he);
        if self.is_boundary_vertex(a) {
            return false;
        }
        if !self.touches_crease(a) {
            return true;
        }
        self.is_crease(he)
            && self
                .crease_line_through(a)
                .is_some_and(|(p, n)| p == b || n == b)
    }

    /// The two crease neighbours of vertex `v` when `v` lies inside a crease line: off the
    /// boundary, with exactly two crease edges, turning there by at most about 20°.
    /// `None` for a vertex on no crease, a corner where creases meet, a crease's end or a
    /// sharp bend.
    #[must_use]
    pub(crate) fn crease_line_through(&self, v: u32) -> Option<(u32, u32)> {
        if self.is_boundary_vertex(v) {
            return None;
        }
        let (mut count, mut ends) = (0u32, [v; 2]);
        self.for_each_outgoing(v, |out| {
            if self.is_crease(out) {
                if let Some(slot) = ends.get_mut(count as usize) {
                    *slot = self.ends(out).1;
                }
                count += 1;
            }
        });
        let [p, n] = ends;
        let (pp, pv, pn) = (self.position(p), self.position(v), self.position(n));
        let (into, out) = (pv - pp, pn - pv);
        let lengths = libm::sqrtf(dot(into, into) * dot(out, out));
        (count == 2 && lengths > 0.0 && dot(into, out) >= CREASE_TURN_COSINE * lengths)
            .then_some((p, n))
    }

    /// Whether any edge at vertex `v` is a crease.
    #[must_use]
    pub(crate) fn touches_crease(&self, v: u32) -> bool {
        if !self.has_creases {
            return false;
        }
        let mut crease = false;
        self.for_each_outgoing(v, |he| {
            crease |= self.is_crease(he) || self.is_crease(Self::prev(he));
        });
        crease
    }

    /// Collapses the edge of `he` (from `a` to `b`): `a` is removed, `b` moves to `at`, and
    /// the two triangles on the edge disappear. Does nothing and returns false unless the
    /// collapse keeps the mesh manifold (the link condition) and `a` may be removed. The last vertex and triangles move into the
    /// freed slots, so indices of other elements may change.
    pub(crate) fn collapse_edge(&mut self, he: u32, at: Vec3) -> bool {
        if !self.can_collapse(he) {
            return false;
        }
        let Some(g) = self.twin(he) else {
            return false;
        };
        let (a, b) = self.ends(he);
        let (n0, p0, n1, p1) = (Self::next(he), Self::prev(he), Self::next(g), Self::prev(g));
        let (c, d) = (self.origin(p0), self.origin(p1));
        // Outer half-edges whose pairs merge: x (a→c) with y (c→b), z (d→a) with w (b→d).
        let (x, y, z, w) = (
            self.outer(p0),
            self.outer(n0),
            self.outer(n1),
            self.outer(p1),
        );
        // Every half-edge leaving a now leaves b (`a` is interior: its fan is closed).
        let mut out = self.vertex_half_edge(a).unwrap_or(NO_HALF_EDGE);
        for _ in 0..self.half_edge_count() {
            self.set_origin(out, b);
            match self.rotate(out) {
                Some(next) if Some(next) != self.vertex_half_edge(a) => out = next,
                _ => break,
            }
        }
        self.link(x.twin, y.twin);
        self.link(z.twin, w.twin);
        // A merged edge is a crease if either half was.
        let (xy, zw) = (x.crease || y.crease, z.crease || w.crease);
        self.set_crease(x.twin, xy);
        self.set_crease(y.twin, xy);
        self.set_crease(z.twin, zw);
        self.set_crease(w.twin, zw);
        self.set_position(b, at);
        self.reset_vertex_half_edge(b, x.twin);
        self.reset_vertex_half_edge(c, Self::next(x.twin));
        self.reset_vertex_half_edge(d, z.twin);
        let (t0, t1) = (he / 3, g / 3);
        self.remove_triangle(t0.max(t1));
        self.remove_triangle(t0.min(t1));
        self.remove_vertex(a);
        true
    }

    /// Removes every vertex no triangle uses, moving later vertices into the freed slots.
    pub(super) fn drop_unused_vertices(&mut self) {
        // From the top down, so a vertex moved into a freed slot was already kept.
        for v in (0..self.vertex_count as u32).rev() {
            if self.vertex_half_edge(v).is_none() {
                self.remove_vertex(v);
            }
        }
    }

    /// Removes triangle `t`, which nothing references any more, moving the last triangle into
    /// its slot.
    fn remove_triangle(&mut self, t: u32) {
        let Some(last) = (self.triangle_count as u32).checked_sub(1) else {
            return;
        };
        self.triangle_count -= 1;
        if t == last {
            return;
        }
        for k in 0..3 {
            let (from, to) = (last * 3 + k, t * 3 + k);
            let v = self.origin(from);
            let outer = self.outer(from);
            self.set_origin(to, v);
            self.attach(to, outer);
            if self.vertex_half_edge(v) == Some(from) {
                self.set_vertex_half_edge(v, to);
            }
        }
    }

    /// Removes vertex `v`, which no triangle uses any more, moving the last vertex into its
    /// slot.
    fn remove_vertex(&mut self, v: u32) {
        let Some(last) = (self.vertex_count as u32).checked_sub(1) else {
            return;
        };
        self.vertex_count -= 1;
        if v == last {
            return;
        }
        let moved = self.position(last);
        let he = self.vertex_half_edge(last).unwrap_or(NO_HALF_EDGE);
        self.set_position(v, moved);
        self.set_vertex_half_edge(v, he);
        let mut out = he;
        for _ in 0..self.half_edge_count() {
            if out == NO_HALF_EDGE {
                break;
            }
            self.set_origin(out, v);
            match self.rotate(out) {
                Some(next) if next != he => out = next,
                _ => break,
            }
        }
    }
}
