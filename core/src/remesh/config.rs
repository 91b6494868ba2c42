//! What a remeshing run aims at.

use crate::error::RemeshError;

/// Settings of [`remesh`](super::remesh).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RemeshConfig {
    /// The target edge length `L`, in the mesh's units: finite and positive, or 0 (the
    /// default) for the input's mean edge length. Edges longer than `4/3·L` are split, edges
    /// shorter than `4/5·L` collapsed.
    pub target_length: f32,
    /// Rounds of split, collapse, flip, smooth and project; default 10, at most
    /// [`RemeshConfig::MAX_ITERATIONS`].
    pub iterations: u32,
    /// Edges whose two triangles' normals differ by more than this angle, in degrees, are
    /// creases and kept: never flipped, split along the crease, and their vertices moved or
    /// removed only along a nearly straight crease line (see [`remesh`](super::remesh)).
    /// `None` (the default) keeps none; otherwise in `(0, 180)`.
    pub feature_angle: Option<f32>,
}

impl RemeshConfig {
    /// The most iterations a run accepts.
    pub const MAX_ITERATIONS: u32 = 1000;

    /// Checks every field against its documented range.
    ///
    /// # Errors
    /// [`RemeshError::InvalidConfig`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), RemeshError> {
        let bad = |field| Err(RemeshError::InvalidConfig { field });
        if !(self.target_length >= 0.0 && self.target_length.is_finite()) {
            return bad("target_length");
        }
        if self.iterations > Self::MAX_ITERATIONS {
            return bad("iterations");
        }
        if let Some(angle) = self.feature_angle
            && !(angle > 0.0 && angle < 180.0)
        {
            return bad("feature_angle");
        }
        Ok(())
    }
}

impl Default for RemeshConfig {
    fn default() -> Self {
        Self {
            target_length: 0.0,
            iterations: 10,
            feature_angle: None,
        }
    }
}
