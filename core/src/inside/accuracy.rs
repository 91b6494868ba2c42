//! How close a group of triangles may be before its expansion no longer stands for it.

/// The accuracy of a fast winding number: a node of the tree is summarised by its expansion
/// when the query point lies farther than `far_ratio` times the node's radius from the node's
/// centre, and summed triangle by triangle (exactly) otherwise.
///
/// Barill et al.'s β. The expansion is taken to second order, so its error falls about as the
/// fourth power of the ratio; the largest error measured against an `f64` brute-force sum, at
/// points anywhere off the surface of the bundled meshes, open and crossing ones included, is
/// 3.3·10⁻² at 1.5, 8.8·10⁻³ at 2, 3.0·10⁻³ at 2.5, 1.3·10⁻³ at 3 and 1.1·10⁻⁴ at 5
/// (`docs/inside.md`).
/// [`WindingAccuracy::EXACT`] never uses an expansion: the exact sum of every triangle's solid
/// angle, through the tree only for its order.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WindingAccuracy {
    far_ratio: f32,
}

impl WindingAccuracy {
    /// A ratio of 2, Barill et al.'s default (largest error measured: 8.8·10⁻³).
    pub const DEFAULT: Self = Self { far_ratio: 2.0 };

    /// No expansions: the exact sum of the solid angles, up to `f32` rounding (largest error
    /// measured: 2.5·10⁻⁵). Its cost grows with the triangle count.
    pub const EXACT: Self = Self {
        far_ratio: f32::INFINITY,
    };

    /// An accuracy with `far_ratio` (≥ 1; `+∞` is [`WindingAccuracy::EXACT`]); `None` below 1 or
    /// NaN, where the expansion would be used inside its own ball and mean nothing.
    #[must_use]
    pub fn new(far_ratio: f32) -> Option<Self> {
        (far_ratio >= 1.0).then_some(Self { far_ratio })
    }

    /// The ratio.
    #[must_use]
    pub const fn far_ratio(&self) -> f32 {
        self.far_ratio
    }
}

impl Default for WindingAccuracy {
    fn default() -> Self {
        Self::DEFAULT
    }
}
