//! How a k-d tree is built.

use crate::error::BuildError;

/// Settings of a k-d tree build (surface-area heuristic over binned, clipped triangle bounds).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KdConfig {
    /// The deepest a leaf may lie (the root is depth 0), `0..=`[`KdConfig::MAX_DEPTH`]; 0 (the
    /// default) picks `8 + 1.3 · log₂ N` for `N` triangles (Havran's rule), capped at the
    /// maximum.
    pub max_depth: u32,
    /// A cell with at most this many references stays a leaf, `1..=1024`; default 2.
    pub leaf_size: u32,
    /// Cost of one traversal step relative to `triangle_cost`, finite and positive; default 1.
    pub traversal_cost: f32,
    /// Cost of one ray–triangle test, finite and positive; default 1.5.
    pub triangle_cost: f32,
    /// Discount on a split that leaves one side empty (cutting off empty space), `[0, 1)`;
    /// default 0.8 (the split's cost is multiplied by `1 − empty_bonus`).
    pub empty_bonus: f32,
}

impl KdConfig {
    /// The largest `max_depth`.
    pub const MAX_DEPTH: u32 = 40;

    /// The depth limit for `triangles` triangles: `max_depth`, or the automatic one when 0.
    #[must_use]
    pub(crate) fn depth_limit(&self, triangles: usize) -> u32 {
        if self.max_depth != 0 {
            return self.max_depth.min(Self::MAX_DEPTH);
        }
        let log2 = f64::from(usize::BITS - triangles.max(1).leading_zeros() - 1);
        ((8.0 + 1.3 * log2) as u32).min(Self::MAX_DEPTH)
    }

    /// Checks every field against its documented range.
    ///
    /// # Errors
    /// [`BuildError::InvalidConfig`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), BuildError> {
        let bad = |field| Err(BuildError::InvalidConfig { field });
        if self.max_depth > Self::MAX_DEPTH {
            return bad("max_depth");
        }
        if !(1..=1024).contains(&self.leaf_size) {
            return bad("leaf_size");
        }
        if !(self.traversal_cost > 0.0 && self.traversal_cost.is_finite()) {
            return bad("traversal_cost");
        }
        if !(self.triangle_cost > 0.0 && self.triangle_cost.is_finite()) {
            return bad("triangle_cost");
        }
        if !(0.0..1.0).contains(&self.empty_bonus) {
            return bad("empty_bonus");
        }
        Ok(())
    }
}

impl Default for KdConfig {
    fn default() -> Self {
        Self {
            max_depth: 0,
            leaf_size: 2,
            traversal_cost: 1.0,
            triangle_cost: 1.5,
            empty_bonus: 0.8,
        }
    }
}
