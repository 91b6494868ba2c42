//! How an octree cell splits: into its eight octants, while it holds too many references.

use super::{OctreeConfig, OctreeNode};
use crate::cells::{Decision, MAX_ARITY, ReferencePad, Splitter};
use crate::math::Aabb;
use crate::mesh::ValidMesh;
use crate::query::Cell;

/// The eight octants of `cell`, child `k` above the middle on x for bit 0, y bit 1, z bit 2.
/// The middles are computed once per cell, so neighbouring octants share faces exactly.
#[inline(always)]
pub(super) fn octants(cell: &Cell) -> [Cell; 8] {
    let mid = cell.aabb().center();
    let (x0, x1) = cell.split(0, mid.x);
    let mut out = [*cell; 8];
    for (k, slot) in out.iter_mut().enumerate() {
        let x = if k & 1 == 0 { x0 } else { x1 };
        let (y0, y1) = x.split(1, mid.y);
        let y = if k & 2 == 0 { y0 } else { y1 };
        let (z0, z1) = y.split(2, mid.z);
        *slot = if k & 4 == 0 { z0 } else { z1 };
    }
    out
}

/// The cube an octree's root cell covers: centred on `bounds`, as wide as its largest extent
/// (grown by rounding where needed so it holds `bounds`).
#[must_use]
pub(super) fn root_cube(bounds: &Aabb) -> Aabb {
    if bounds.is_empty() || !bounds.is_finite() {
        return *bounds;
    }
    let c = bounds.center();
    let e = bounds.extent();
    let half = glam::Vec3::splat(e.x.max(e.y).max(e.z) * 0.5);
    Aabb::new((c - half).min(bounds.min), (c + half).max(bounds.max))
}

/// The octree's [`Splitter`].
pub(super) struct OctreeSplitter<'m> {
    pub(super) mesh: &'m ValidMesh<'m>,
    pub(super) config: OctreeConfig,
    pub(super) pad: ReferencePad,
}

impl Splitter for OctreeSplitter<'_> {
    const ARITY: usize = 8;
    type Node = OctreeNode;
    type Inner = ();

    fn split(&self, cell: &Cell, depth: u32, refs: &[u32], out: &mut [u32]) -> Decision<()> {
        if refs.len() <= self.config.max_items as usize || depth >= self.config.max_depth {
            return Decision::Leaf;
        }
        let children = octants(cell);
        let mut lens = [0u32; MAX_ARITY];
        let mut written = 0usize;
        for (child, len) in children.iter().zip(lens.iter_mut()) {
            for &tri in refs {
                let Some(t) = self.mesh.triangle(tri) else {
                    continue;
                };
                if self.pad.touches(&t, child.aabb()) {
                    if let Some(slot) = out.get_mut(written) {
                        *slot = tri;
                    }
                    written += 1;
                    *len += 1;
                }
            }
        }
        // Decided before the room, so the choice never depends on the buffer's length.
        if lens.iter().all(|&l| l as usize == refs.len()) {
            // Every triangle in every octant: splitting separates nothing.
            return Decision::Leaf;
        }
        if written > out.len() {
            return Decision::NoRoom;
        }
        Decision::Split {
            inner: (),
            cells: children,
            lens,
        }
    }

    fn inner((): (), first_child: u32) -> OctreeNode {
        OctreeNode::inner(first_child)
    }

    fn leaf(first: u32, count: u32) -> OctreeNode {
        OctreeNode::leaf(first, count)
    }
}
