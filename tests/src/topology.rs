//! Topology of a triangle list, counted from the triangles alone (no half-edges): the
//! independent reference the remeshing tests hold the half-edge mesh to.

use std::collections::HashMap;

/// What a triangle list is, topologically.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Topology {
    /// Used vertices − edges + triangles.
    pub euler: i64,
    /// Edges with one triangle.
    pub boundary_edges: usize,
    /// Closed loops of boundary edges (components of the boundary-edge graph).
    pub boundary_loops: usize,
    /// Every edge has at most two triangles, no directed edge appears twice (consistent
    /// orientation) and no triangle repeats a vertex.
    pub manifold_oriented: bool,
}

impl Topology {
    /// Counts `triangles` over `vertices` vertices.
    ///
    /// # Panics
    /// If a triangle names a vertex at or past `vertices`.
    #[must_use]
    pub fn of(vertices: usize, triangles: &[[u32; 3]]) -> Self {
        let mut directed: HashMap<(u32, u32), u32> = HashMap::with_capacity(3 * triangles.len());
        let mut used = vec![false; vertices];
        let mut manifold_oriented = true;
        for t in triangles {
            manifold_oriented &= t[0] != t[1] && t[1] != t[2] && t[2] != t[0];
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                used[a as usize] = true;
                *directed.entry((a, b)).or_default() += 1;
            }
        }
        let mut undirected: HashMap<(u32, u32), u32> = HashMap::with_capacity(directed.len());
        for (&(a, b), &n) in &directed {
            manifold_oriented &= n == 1;
            *undirected.entry((a.min(b), a.max(b))).or_default() += n;
        }
        manifold_oriented &= undirected.values().all(|&n| n <= 2);
        let boundary: Vec<(u32, u32)> = undirected
            .iter()
            .filter(|&(_, &n)| n == 1)
            .map(|(&e, _)| e)
            .collect();
        Self {
            euler: used.iter().filter(|&&u| u).count() as i64 - undirected.len() as i64
                + triangles.len() as i64,
            boundary_edges: boundary.len(),
            boundary_loops: components(vertices, &boundary),
            manifold_oriented,
        }
    }
}

/// Connected components of the graph of `edges` (vertices without edges not counted).
fn components(vertices: usize, edges: &[(u32, u32)]) -> usize {
    let mut parent: Vec<u32> = (0..vertices as u32).collect();
    fn root(parent: &mut [u32], mut v: u32) -> u32 {
        while parent[v as usize] != v {
            let up = parent[parent[v as usize] as usize];
            parent[v as usize] = up;
            v = up;
        }
        v
    }
    let mut on_edge = vec![false; vertices];
    for &(a, b) in edges {
        on_edge[a as usize] = true;
        on_edge[b as usize] = true;
        let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
        parent[ra as usize] = rb;
    }
    (0..vertices as u32)
        .filter(|&v| on_edge[v as usize] && root(&mut parent, v) == v)
        .count()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_a_square_a_tetrahedron_and_a_fold() {
        let square = Topology::of(4, &[[0, 1, 2], [0, 2, 3]]);
        assert_eq!(
            square,
            Topology {
                euler: 1,
                boundary_edges: 4,
                boundary_loops: 1,
                manifold_oriented: true
            }
        );
        let tetra = Topology::of(4, &[[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]]);
        assert_eq!(
            tetra,
            Topology {
                euler: 2,
                boundary_edges: 0,
                boundary_loops: 0,
                manifold_oriented: true
            }
        );
        // One triangle turned over: 0 → 2 twice.
        assert!(!Topology::of(4, &[[0, 1, 2], [0, 3, 2]]).manifold_oriented);
        // Three triangles on one edge.
        assert!(!Topology::of(5, &[[0, 1, 2], [1, 0, 3], [0, 1, 4]]).manifold_oriented);
    }
}
