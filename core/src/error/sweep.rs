//! Why a sweep could not run.

use core::fmt;

/// Why [`MeshQuery::sweep`](crate::query::MeshQuery::sweep) refused its input.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SweepError {
    /// The shape has a NaN or infinite coordinate, a negative or NaN radius, or a box whose
    /// axes or half extents are not finite and `≥ 0` (see
    /// [`SweepShape::is_valid`](crate::query::SweepShape::is_valid)). Fix: build it from finite
    /// parts.
    InvalidShape,
    /// The motion has a NaN or infinite component. Fix: pass a finite displacement.
    InvalidMotion,
}

impl fmt::Display for SweepError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::InvalidShape => write!(
                f,
                "the swept shape is not valid (a coordinate is not finite, or a radius or half \
                 extent is negative)"
            ),
            Self::InvalidMotion => write!(f, "the sweep's motion is not a finite vector"),
        }
    }
}

impl core::error::Error for SweepError {}
