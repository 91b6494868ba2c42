//! How a grid is built.

use crate::error::BuildError;

/// Settings of a uniform grid build.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridConfig {
    /// λ: cells per triangle. The grid gets about `λ · N` cells for `N` triangles, shaped to the
    /// mesh bounds (cubic cells where the bounds allow). More cells mean fewer triangles per
    /// cell and more references per triangle. Range `(0, 64]`; default
    /// [`GridConfig::DEFAULT_CELLS_PER_TRIANGLE`].
    pub cells_per_triangle: f32,
    /// The most cells along any axis, `1..=`[`GridConfig::MAX_RESOLUTION`]; default 512.
    pub max_resolution: u32,
}

impl GridConfig {
    /// The default λ, 2 cells per triangle: the middle of the range the uniform-grid
    /// literature recommends for ray casting (Cleary and Wyvill; Wald et al. use 1 to 8).
    pub const DEFAULT_CELLS_PER_TRIANGLE: f32 = 2.0;

    /// The largest `max_resolution` accepted: 1024 cells per axis.
    pub const MAX_RESOLUTION: u32 = 1024;

    /// Checks every field against its documented range.
    ///
    /// # Errors
    /// [`BuildError::InvalidConfig`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), BuildError> {
        if !(self.cells_per_triangle > 0.0 && self.cells_per_triangle <= 64.0) {
            return Err(BuildError::InvalidConfig {
                field: "cells_per_triangle",
            });
        }
        if !(1..=Self::MAX_RESOLUTION).contains(&self.max_resolution) {
            return Err(BuildError::InvalidConfig {
                field: "max_resolution",
            });
        }
        Ok(())
    }
}

impl Default for GridConfig {
    fn default() -> Self {
        Self {
            cells_per_triangle: Self::DEFAULT_CELLS_PER_TRIANGLE,
            max_resolution: 512,
        }
    }
}
