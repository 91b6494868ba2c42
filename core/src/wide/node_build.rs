//! Collapsing a binary tree into each node kind in one call, the bound of
//! [`WideBvh::build`](super::WideBvh::build).

use super::collapse::{collapse_into, collapse_to};
use super::plan::{CollapsePlan, PlanEntry};
use super::{CompactNode, WideNode, WideNode8};
use crate::bvh::Bvh;
use crate::error::{BufferKind, BuildError};

/// A node kind a binary tree collapses into by itself (public in a private module, so not
/// nameable outside): the four- and eight-wide nodes collapse at their width, the compact node
/// collapses four-wide and quantizes each node as it comes.
pub trait CollapsesFrom: Sized {
    /// Plans the collapse of `tree` in `entries` and writes its nodes into `out`; returns how
    /// many. Nothing is written when `out` is too small.
    fn collapse(
        tree: &Bvh<'_>,
        entries: &mut [PlanEntry],
        out: &mut [Self],
    ) -> Result<usize, BuildError>;
}

/// A full-width kind: planned and collapsed at its own width.
macro_rules! collapses_at_width {
    ($node:ty, $width:literal) => {
        impl CollapsesFrom for $node {
            fn collapse(
                tree: &Bvh<'_>,
                entries: &mut [PlanEntry],
                out: &mut [Self],
            ) -> Result<usize, BuildError> {
                collapse_into::<Self, $width>(&CollapsePlan::<$width>::new(tree, entries)?, out)
            }
        }
    };
}

collapses_at_width!(WideNode, 4);
collapses_at_width!(WideNode8, 8);

impl CollapsesFrom for CompactNode {
    fn collapse(
        tree: &Bvh<'_>,
        entries: &mut [PlanEntry],
        out: &mut [Self],
    ) -> Result<usize, BuildError> {
        let plan = CollapsePlan::<4>::new(tree, entries)?;
        if out.len() < plan.node_count() {
            return Err(BuildError::BufferTooSmall {
                buffer: BufferKind::WideNodes,
                needed: plan.node_count(),
                got: out.len(),
            });
        }
        // Quantizing fails only on a leaf of more than 255 triangles or a box that is not
        // finite, which no checked tree has; the first failure is kept and reported.
        let mut unquantizable = false;
        let count = collapse_to::<WideNode, 4>(&plan, |index, node| {
            match (out.get_mut(index), CompactNode::quantize(&node)) {
                (Some(slot), Some(compact)) => *slot = compact,
                _ => unquantizable = true,
            }
        })?;
        if unquantizable {
            return Err(BuildError::InvalidConfig {
                field: "max_leaf_size",
            });
        }
        Ok(count)
    }
}
