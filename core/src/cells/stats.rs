//! Figures of a cell structure, for tools and tuning.

/// Shape figures of a k-d tree, octree or grid.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CellStats {
    /// Nodes (the grid has none: 0).
    pub nodes: usize,
    /// Leaf cells.
    pub cells: usize,
    /// Leaf cells that reference no triangle.
    pub empty_cells: usize,
    /// References in all (one per triangle and cell it touches).
    pub references: usize,
    /// Triangles of the mesh.
    pub triangles: usize,
    /// The deepest leaf's depth (the root is depth 0; a grid is depth 0).
    pub max_depth: usize,
    /// The most references one cell holds.
    pub max_cell_references: usize,
}

impl CellStats {
    /// References per triangle (0 without triangles).
    #[must_use]
    pub fn references_per_triangle(&self) -> f64 {
        if self.triangles == 0 {
            0.0
        } else {
            self.references as f64 / self.triangles as f64
        }
    }
}
