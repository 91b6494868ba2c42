use serde::de::{Deserializer, EnumAccess, Error as _, Unexpected, VariantAccess, Visitor};
use serde::{Deserialize, Serialize};

use super::MAX_DEPTH;
use crate::error::BuildError;

/// How the builder divides a node's triangles in two.
///
/// On the wire (blob header) a varint tag: 0 = [`SplitStrategy::Sah`], 1 =
/// [`SplitStrategy::Centre`], 2 = [`SplitStrategy::Sweep`] followed by its step as a varint.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize)]
#[non_exhaustive]
pub enum SplitStrategy {
    /// Binned surface area heuristic: at each node, triangle centroids are sorted into `bins`
    /// equal slices along each axis and the split with the lowest cost
    /// `C = traversal_cost + (A_L·B(N_L) + A_R·B(N_R))/A · triangle_cost` is taken, or a leaf
    /// is made when `B(N)·triangle_cost` is not more than that (and `N ≤ max_leaf_size`).
    /// `B(n) = ⌈n/4⌉` counts batches of up to four triangles: queries test a leaf's triangles
    /// four at a time, so a leaf of four costs what a leaf of one does. The best trees.
    #[default]
    Sah,
    /// The middle of the centroid bounds on their longest axis (the lowest axis on a tie):
    /// triangles whose centroid lies below it go left. Every node of more than `max_leaf_size`
    /// triangles is split; `bins` and the two costs are not used. Quicker to build than
    /// [`SplitStrategy::Sah`], for trees that answer rays more slowly (the README's benchmark
    /// table has the figures). The same rule as three-mesh-bvh's default (`CENTER`).
    Centre,
    /// Sweep SAH, the classic full-sort builder: at each node the triangles are sorted by
    /// centroid on each axis in turn (ties by triangle index) and the cost of
    /// [`SplitStrategy::Sah`] is evaluated between neighbours every `step` triangles along that
    /// order; the cheapest cut wins (ties: the lower axis, then fewer triangles on the left), and
    /// the leaf rule is the same. A node of `n` triangles is cut at most `⌈n/32⌉` apart, so
    /// small nodes still weigh 32 cuts (every cut when they have fewer). Split positions are
    /// exact rather than binned; each node costs a sort per axis (`O(n log² n)` in all;
    /// `docs/benchmarks.md` compares build times, SAH costs and ray speed with binned SAH).
    /// `bins` is not used. Not combined with spatial splits ([`BuildError::InvalidConfig`] naming
    /// `split`).
    Sweep {
        /// Triangles between evaluated cuts: 1 (or 0, which means the same) is a full sweep,
        /// every cut; [`SplitStrategy::SWEEP_STEP`] the usual choice.
        step: u32,
    },
}

/// Read by variant index only (the tag postcard writes), with the sweep's step as a plain
/// value: the same bytes the derived form reads, without its name-matching code (which would
/// cost the firmware flash).
impl<'de> Deserialize<'de> for SplitStrategy {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Tag;
        impl<'de> Visitor<'de> for Tag {
            type Value = SplitStrategy;
            fn expecting(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                f.write_str("a split strategy")
            }
            fn visit_enum<A: EnumAccess<'de>>(self, data: A) -> Result<Self::Value, A::Error> {
                let (tag, variant): (u32, _) = data.variant()?;
                match tag {
                    0 => variant.unit_variant().map(|()| SplitStrategy::Sah),
                    1 => variant.unit_variant().map(|()| SplitStrategy::Centre),
                    2 => variant
                        .newtype_variant()
                        .map(|step| SplitStrategy::Sweep { step }),
                    _ => Err(A::Error::invalid_value(
                        Unexpected::Unsigned(u64::from(tag)),
                        &"0, 1 or 2",
                    )),
                }
            }
        }
        d.deserialize_enum("SplitStrategy", &["Sah", "Centre", "Sweep"], Tag)
    }
}

impl SplitStrategy {
    /// The usual step of [`SplitStrategy::Sweep`]: a cut evaluated every 32 triangles.
    pub const SWEEP_STEP: u32 = 32;

    /// The strategy's name in lower case: `sah`, `centre` or `sweep` (what tools print).
    #[must_use]
    pub const fn name(&self) -> &'static str {
        match self {
            Self::Sah => "sah",
            Self::Centre => "centre",
            Self::Sweep { .. } => "sweep",
        }
    }
}

/// How a BVH is built. Use a preset ([`BuildConfig::fast`], [`BuildConfig::balanced`] — the
/// default — or [`BuildConfig::high_quality`]) and adjust fields as needed.
///
/// Whatever the strategy, a split that would leave one side empty or exceed the depth limit
/// falls back to a median split (by centroid, then triangle index), so any mesh that fits
/// within `max_depth` builds.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct BuildConfig {
    /// How nodes are split.
    pub split: SplitStrategy,
    /// Bins per axis for [`SplitStrategy::Sah`], `2..=`[`BuildConfig::MAX_BINS`] (checked
    /// whatever the strategy). More bins find better splits and build a little more slowly.
    pub bins: u32,
    /// Most triangles in a leaf, `1..=`[`BuildConfig::MAX_LEAF_SIZE`]. Larger leaves give
    /// shallower, smaller trees and more triangle tests per ray.
    pub max_leaf_size: u32,
    /// Deepest level allowed, `1..=`[`MAX_DEPTH`] (the root is level 1). A build that cannot fit
    /// fails with [`BuildError::TooDeep`]; near the limit the builder switches to median splits
    /// so any mesh that can fit does fit. Lower it to bound traversal stacks further.
    pub max_depth: u32,
    /// Relative cost of visiting a node, finite and `≥ 0` (SAH only). At `1` or more (the
    /// presets), every node of at most `max_leaf_size ≤ 4` triangles is a leaf: splitting it
    /// costs a visit, and testing it one batch.
    pub traversal_cost: f32,
    /// Relative cost of testing one batch of up to four triangles against a query, finite and
    /// `> 0` (SAH only; see [`SplitStrategy::Sah`]).
    pub triangle_cost: f32,
}

impl Default for BuildConfig {
    fn default() -> Self {
        Self::balanced()
    }
}

impl BuildConfig {
    /// Upper bound of [`BuildConfig::bins`].
    pub const MAX_BINS: u32 = 64;
    /// Upper bound of [`BuildConfig::max_leaf_size`].
    pub const MAX_LEAF_SIZE: u32 = 64;

    /// Quickest build: centre splits ([`SplitStrategy::Centre`]), leaves of up to 8
    /// triangles.
    #[must_use]
    pub const fn fast() -> Self {
        Self {
            split: SplitStrategy::Centre,
            bins: 32,
            max_leaf_size: 8,
            max_depth: MAX_DEPTH,
            traversal_cost: 1.0,
            triangle_cost: 1.0,
        }
    }

    /// The default: binned SAH with 32 bins, leaves of up to 4 triangles (one batch), a node
    /// visit costed at three batch tests.
    #[must_use]
    pub const fn balanced() -> Self {
        Self {
            split: SplitStrategy::Sah,
            bins: 32,
            max_leaf_size: 4,
            max_depth: MAX_DEPTH,
            traversal_cost: 3.0,
            triangle_cost: 1.0,
        }
    }

    /// Best trees by the SAH: binned SAH with 64 bins (finer split positions than
    /// [`BuildConfig::balanced`]), leaves of up to 4 triangles, a node visit costed at two
    /// batch tests.
    #[must_use]
    pub const fn high_quality() -> Self {
        Self {
            split: SplitStrategy::Sah,
            bins: 64,
            max_leaf_size: 4,
            max_depth: MAX_DEPTH,
            traversal_cost: 2.0,
            triangle_cost: 1.0,
        }
    }

    /// Checks every field against its documented range.
    ///
    /// # Errors
    /// [`BuildError::InvalidConfig`] naming the first bad field.
    pub fn check(&self) -> Result<(), BuildError> {
        let bad = |field| Err(BuildError::InvalidConfig { field });
        if !(2..=Self::MAX_BINS).contains(&self.bins) {
            return bad("bins");
        }
        if !(1..=Self::MAX_LEAF_SIZE).contains(&self.max_leaf_size) {
            return bad("max_leaf_size");
        }
        if !(1..=MAX_DEPTH).contains(&self.max_depth) {
            return bad("max_depth");
        }
        if !(self.traversal_cost.is_finite() && self.traversal_cost >= 0.0) {
            return bad("traversal_cost");
        }
        if !(self.triangle_cost.is_finite() && self.triangle_cost > 0.0) {
            return bad("triangle_cost");
        }
        Ok(())
    }

    /// Most triangles a subtree whose root is at `level` can hold (saturating).
    /// 0 below the depth limit.
    pub(crate) fn subtree_capacity(&self, level: u32) -> usize {
        if level > self.max_depth {
            return 0;
        }
        let levels_below = self.max_depth - level;
        let leaf = self.max_leaf_size as usize;
        if levels_below >= usize::BITS - 8 {
            usize::MAX
        } else {
            leaf.saturating_mul(1usize << levels_below)
        }
    }
}
