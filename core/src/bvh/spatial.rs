//! How much room a build with spatial splits may take, and the buffer sizes that follow.

use serde::{Deserialize, Serialize};

use crate::error::BuildError;

/// Spatial splits ([`Bvh::build_spatial`](super::Bvh::build_spatial)): where the best split by
/// centroid leaves two children whose boxes overlap, the builder may cut space instead, at a
/// plane, and put a triangle that crosses the plane in both children, each reference boxed by
/// the part of the triangle on its side (after Stich, Friedrich and Dietrich 2009, "Spatial
/// Splits in Bounding Volume Hierarchies"). Long thin triangles that cross each other get far
/// tighter boxes; the tree holds more references than triangles.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SpatialSplits {
    /// Room for references beyond one per triangle, as a fraction of the triangle count,
    /// `0.0..=`[`SpatialSplits::MAX_EXTRA`]: `1.0` lets the tree hold up to `2·n` references.
    /// The room is shared among the nodes in proportion to their references; a node splits
    /// in space only while its share holds every triangle the split would repeat. `0` builds
    /// the tree [`Bvh::build`](super::Bvh::build) builds.
    pub extra_references: f32,
    /// Smallest overlap of the two children of a node's best split by centroid, as a fraction
    /// of the root box's half area, for which the node also tries spatial splits (finite,
    /// `≥ 0`). Where children barely overlap a spatial split cannot do better, and trying
    /// costs build time.
    pub min_overlap: f32,
}

impl Default for SpatialSplits {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl SpatialSplits {
    /// Upper bound of [`SpatialSplits::extra_references`].
    pub const MAX_EXTRA: f32 = 4.0;

    /// Room for as many references again as triangles, tried where children overlap by more
    /// than 10⁻⁵ of the root's half area. Meshes of even triangles use little of the room
    /// (a few per cent); scenes of long crossing triangles most of it.
    pub const DEFAULT: Self = Self {
        extra_references: 1.0,
        min_overlap: 1e-5,
    };

    /// Checks both fields against their documented ranges.
    ///
    /// # Errors
    /// [`BuildError::InvalidConfig`] naming the bad field.
    pub fn check(&self) -> Result<(), BuildError> {
        if !(self.extra_references >= 0.0 && self.extra_references <= Self::MAX_EXTRA) {
            return Err(BuildError::InvalidConfig {
                field: "extra_references",
            });
        }
        if !(self.min_overlap.is_finite() && self.min_overlap >= 0.0) {
            return Err(BuildError::InvalidConfig {
                field: "min_overlap",
            });
        }
        Ok(())
    }

    /// Most references a tree over `tri_count` triangles may hold: `n + ⌊n·extra⌋`, the
    /// length the order and scratch buffers of [`Bvh::build_spatial`](super::Bvh::build_spatial)
    /// need (nodes: [`node_capacity`](super::node_capacity) of it). A range outside the
    /// documented one counts as `0` extra.
    #[must_use]
    pub(crate) fn reference_capacity(&self, tri_count: usize) -> usize {
        tri_count.saturating_add(self.extra_room(tri_count))
    }

    /// Most entries the split-reference buffer of
    /// [`Bvh::build_spatial`](super::Bvh::build_spatial) needs: two per extra reference (a
    /// triangle held `k > 1` times makes `k − 1` extra references and `k` entries).
    #[must_use]
    pub(crate) fn split_ref_capacity(&self, tri_count: usize) -> usize {
        self.extra_room(tri_count).saturating_mul(2)
    }

    /// `⌊n·extra⌋`, computed in `f64` so every target agrees (0 outside the range).
    fn extra_room(&self, tri_count: usize) -> usize {
        if self.check().is_err() {
            return 0;
        }
        let room = tri_count as f64 * f64::from(self.extra_references);
        // In range and non-negative, so the conversion saturates at worst.
        room as usize
    }
}
