//! What a remeshing run aims at.

use crate::error::RemeshError;

/// The edge length a remesh aims at.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum EdgeTarget {
    /// This length `L`, in the mesh's units: finite and positive.
    Length(f32),
    /// This multiple of the input's mean edge length (each edge counted once, as
    /// [`MeshQuality::mean_edge`](super::MeshQuality::mean_edge) gives it): finite and positive. `1.0`
    /// (the default) keeps the input's scale; `0.5` asks for edges half as long, about four
    /// times as many triangles.
    MeanEdgeTimes(f32),
}

impl EdgeTarget {
    /// The target length for a mesh whose mean edge length is `mean_edge`.
    #[must_use]
    pub fn length(self, mean_edge: f32) -> f32 {
        match self {
            Self::Length(length) => length,
            Self::MeanEdgeTimes(ratio) => ratio * mean_edge,
        }
    }
}

impl Default for EdgeTarget {
    fn default() -> Self {
        Self::MeanEdgeTimes(1.0)
    }
}

/// Settings of [`remesh`](super::remesh).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RemeshConfig {
    /// The target edge length `L` ([`EdgeTarget`]; by default the input's mean edge length).
    /// Edges longer than `4/3·L` are split, edges shorter than `4/5·L` collapsed.
    pub target: EdgeTarget,
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
        let (EdgeTarget::Length(value) | EdgeTarget::MeanEdgeTimes(value)) = self.target;
        if !(value > 0.0 && value.is_finite()) {
            return bad("target");
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
            target: EdgeTarget::default(),
            iterations: 10,
            feature_angle: None,
        }
    }
}
