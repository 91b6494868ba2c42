//! Why a matrix could not be used as a mesh's placement.

use core::fmt;

/// Why a 4×4 matrix is not an [`Affine`](crate::collide::Affine) map.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TransformError {
    /// An element is NaN or infinite. Fix: compose the matrix from finite parts.
    NotFinite {
        /// The element's index in column-major order (0–15).
        index: usize,
    },
    /// The bottom row is not `0, 0, 0, 1`: a projective matrix moves points by a division
    /// that no placement of a mesh needs. Fix: pass the object's world matrix, not a camera's.
    NotAffine,
}

impl fmt::Display for TransformError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotFinite { index } => {
                write!(f, "transform element {index} is not a finite number")
            }
            Self::NotAffine => write!(
                f,
                "the transform's bottom row is not 0, 0, 0, 1 (not an affine map)"
            ),
        }
    }
}

impl core::error::Error for TransformError {}
