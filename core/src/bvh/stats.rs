//! Shape and cost figures of a built tree, for tools and tuning.

use super::{BuildConfig, TreeArrays};

/// Leaf sizes counted one by one up to this; larger leaves share the last histogram entry.
pub const LEAF_HISTOGRAM_LEN: usize = BuildConfig::MAX_LEAF_SIZE as usize + 1;

/// Figures of a tree: counts, leaf sizes and its surface-area-heuristic cost.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TreeStats {
    /// Nodes in all.
    pub nodes: usize,
    /// Leaves among them.
    pub leaves: usize,
    /// Triangles (order slots).
    pub triangles: usize,
    /// `leaf_sizes[k]` leaves hold `k` triangles; the last entry counts every leaf of
    /// [`LEAF_HISTOGRAM_LEN`]` − 1` triangles or more.
    pub leaf_sizes: [usize; LEAF_HISTOGRAM_LEN],
    /// The SAH cost `Σ_inner A/A_root · C_trav + Σ_leaf A/A_root · N · C_tri`, where `A` is a
    /// node's box surface area: the expected cost of one random ray through the tree, in units
    /// of the given costs (0 for an empty tree or a root without area).
    pub sah_cost: f64,
}

impl TreeStats {
    /// Measures `tree` in one pass over its nodes, with the costs of `config` in the SAH sum.
    #[must_use]
    pub fn of<A: TreeArrays + ?Sized>(tree: &A, config: &BuildConfig) -> Self {
        let mut stats = Self {
            nodes: tree.node_count(),
            leaves: 0,
            triangles: tree.slot_count(),
            leaf_sizes: [0; LEAF_HISTOGRAM_LEN],
            sah_cost: 0.0,
        };
        let root_area = tree
            .node(0)
            .map_or(0.0, |n| f64::from(n.aabb().half_area()));
        for index in 0..tree.node_count() {
            let Some(node) = tree.node(index) else {
                break;
            };
            let relative = if root_area > 0.0 {
                f64::from(node.aabb().half_area()) / root_area
            } else {
                0.0
            };
            if node.is_leaf() {
                stats.leaves += 1;
                let bucket = (node.count as usize).min(LEAF_HISTOGRAM_LEN - 1);
                if let Some(slot) = stats.leaf_sizes.get_mut(bucket) {
                    *slot += 1;
                }
                stats.sah_cost +=
                    relative * f64::from(node.count) * f64::from(config.triangle_cost);
            } else {
                stats.sah_cost += relative * f64::from(config.traversal_cost);
            }
        }
        stats
    }
}
