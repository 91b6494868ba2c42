//! How an octree is built.

use crate::error::BuildError;

/// Settings of an octree build.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OctreeConfig {
    /// The deepest a leaf may lie (the root cube is depth 0), `0..=`[`OctreeConfig::MAX_DEPTH`];
    /// default 10.
    pub max_depth: u32,
    /// A cell with at most this many references stays a leaf, `1..=1024`; default 8.
    pub max_items: u32,
}

impl OctreeConfig {
    /// The largest `max_depth`: cells down to 2⁻¹⁶ of the root cube.
    pub const MAX_DEPTH: u32 = 16;

    /// Checks every field against its documented range.
    ///
    /// # Errors
    /// [`BuildError::InvalidConfig`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), BuildError> {
        if self.max_depth > Self::MAX_DEPTH {
            return Err(BuildError::InvalidConfig { field: "max_depth" });
        }
        if !(1..=1024).contains(&self.max_items) {
            return Err(BuildError::InvalidConfig { field: "max_items" });
        }
        Ok(())
    }
}

impl Default for OctreeConfig {
    fn default() -> Self {
        Self {
            max_depth: 10,
            max_items: 8,
        }
    }
}
