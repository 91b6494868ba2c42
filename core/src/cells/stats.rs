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
    /// Counts one leaf cell at `depth` holding `references`.
    pub(crate) fn add_cell(&mut self, depth: u32, references: usize) {
        self.cells += 1;
        self.empty_cells += usize::from(references == 0);
        self.max_depth = self.max_depth.max(depth as usize);
        self.max_cell_references = self.max_cell_references.max(references);
    }

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
