//! What the demo draws: a BVH's node boxes at one depth, or the cells a k-d tree, octree or grid
//! cuts space into.

use meshq::math::Aabb;
use meshq::owned::MeshIndex;

use crate::storage::Storage;

fn push_box(out: &mut Vec<f32>, b: &Aabb) {
    out.extend_from_slice(&[b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z]);
}

impl Storage {
    /// Levels [`Storage::level_boxes`] can show: a BVH's depth; one more than a k-d tree's or
    /// octree's deepest leaf (the root is level 0); 1 for a grid.
    pub fn depth(&self) -> u32 {
        match &self.scene {
            MeshIndex::Bvh(s) => s.bvh().depth(),
            MeshIndex::Grid(_) => 1,
            other => other
                .cell_stats()
                .map_or(0, |c| u32::try_from(c.max_depth + 1).unwrap_or(u32::MAX)),
        }
    }

    /// Nodes of a tree; cells of a grid.
    pub fn node_count(&self) -> usize {
        match &self.scene {
            MeshIndex::Bvh(s) => s.bvh().nodes().len(),
            MeshIndex::Grid(s) => s.stats().cells,
            other => other.cell_stats().map_or(0, |c| c.nodes),
        }
    }

    /// Boxes, 6 numbers each: a BVH's nodes at depth `level`; the cells of a k-d tree or
    /// octree after `level` levels of splits (every node at that depth, and the non-empty
    /// leaves above it); a grid's non-empty cells.
    pub fn level_boxes(&self, level: u32) -> Vec<f32> {
        let mut out = Vec::new();
        let mut cell = |cell: meshq::advanced::Cell, _depth: u32, leaf: Option<(u32, u32)>| {
            if leaf.is_none_or(|(_, count)| count > 0) {
                push_box(&mut out, cell.aabb());
            }
        };
        match &self.scene {
            MeshIndex::Bvh(s) => {
                let nodes = s.bvh().nodes();
                let mut stack = vec![(0usize, 0u32)];
                while let Some((index, depth)) = stack.pop() {
                    let Some(node) = nodes.get(index) else {
                        continue;
                    };
                    if depth == level {
                        push_box(&mut out, &node.aabb());
                    } else if !node.is_leaf() {
                        let first = node.first as usize;
                        stack.push((first + 1, depth + 1));
                        stack.push((first, depth + 1));
                    }
                }
            }
            MeshIndex::KdTree(s) => s.structure().for_each_cell(level, &mut cell),
            MeshIndex::Octree(s) => s.structure().for_each_cell(level, &mut cell),
            MeshIndex::Grid(s) => {
                let grid = s.structure();
                let layout = grid.layout();
                let [nx, ny, nz] = layout.resolution;
                for k in 0..nz {
                    for j in 0..ny {
                        for i in 0..nx {
                            let c = [i, j, k];
                            if grid.cell_range(layout.index(c)).is_some_and(|(_, n)| n > 0) {
                                push_box(&mut out, layout.cell(c).aabb());
                            }
                        }
                    }
                }
            }
        }
        out
    }
}
