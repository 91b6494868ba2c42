use super::check::{CheckLevel, Extent, check};
use super::{Bvh, BvhNode};
use crate::error::StructureError;
use crate::math::Aabb;
use crate::mesh::ValidMesh;

impl<'a> Bvh<'a> {
    /// Recomputes every box after the mesh's vertices moved (same triangles, same count), and
    /// returns the refreshed view. The tree's topology is kept, so its quality degrades as the
    /// motion grows; rebuild when it has changed a lot.
    ///
    /// One bottom-up pass: children always come after their parents, so visiting nodes from
    /// last to first sees both children before each parent.
    ///
    /// A tree built with spatial splits ([`Bvh::build_spatial`]) refits to leaf boxes that hold
    /// its split triangles whole, and the view returned has no split references: queries that
    /// report triangles may then report a split triangle once per leaf holding it. Rebuild such
    /// a tree instead.
    ///
    /// # Errors
    /// A [`StructureError`] if `nodes`/`order` are not a valid tree or name triangles `mesh`
    /// does not have; the nodes are then left untouched.
    pub fn refit(
        nodes: &'a mut [BvhNode],
        order: &'a [u32],
        mesh: &ValidMesh<'_>,
    ) -> Result<Self, StructureError> {
        let unchecked = Bvh {
            nodes: &*nodes,
            order,
            depth: 0,
            splits: crate::query::SplitRefs::NONE,
        };
        let shape = check(&unchecked, Some(mesh), CheckLevel::Topology, Extent::Prefix)?;
        let (nodes, order) = (
            nodes.get_mut(..shape.nodes).unwrap_or_default(),
            order.get(..shape.slots).unwrap_or_default(),
        );
        let depth = shape.depth;
        for i in (0..nodes.len()).rev() {
            let Some(&node) = nodes.get(i) else {
                continue;
            };
            let bounds = if node.is_leaf() {
                let first = node.first as usize;
                order
                    .get(first..first + node.count as usize)
                    .unwrap_or_default()
                    .iter()
                    .filter_map(|&tri| mesh.triangle(tri))
                    .fold(Aabb::EMPTY, |b, t| b.union(t.bounds()))
                    .padded()
            } else {
                let first = node.first as usize;
                let child = |k: usize| nodes.get(k).map_or(Aabb::EMPTY, BvhNode::aabb);
                child(first).union(child(first + 1))
            };
            if let Some(slot) = nodes.get_mut(i) {
                *slot = BvhNode::new(bounds, node.first, node.count);
            }
        }
        let nodes: &'a [BvhNode] = nodes;
        Ok(Self {
            nodes,
            order,
            depth,
            splits: crate::query::SplitRefs::NONE,
        })
    }
}
