//! The build quality presets on the command line.

use anyhow::{Result, bail};
use clap::{Args, ValueEnum};
use meshq::bvh::{BuildConfig, SpatialSplits, SplitStrategy};

/// How a BVH is built from a mesh: the options `bake` and the query commands share.
#[derive(Args, Debug, Clone, Copy)]
pub struct BuildChoice {
    /// Build quality (BVH only; the other structures use their default configs).
    #[arg(long, value_enum, default_value_t = Quality::Balanced)]
    pub quality: Quality,
    #[arg(long, value_name = "EXTRA", num_args = 0..=1, default_missing_value = "1",
          help = SPATIAL_SPLITS_HELP)]
    pub spatial_splits: Option<f32>,
    /// Split nodes by sweep SAH instead of binning: sort the triangles by centroid on each
    /// axis and weigh a cut every STEP triangles (default 32; 1 weighs every cut). Exact split
    /// positions for many times the build time; rays about as fast as the default's (see
    /// docs/benchmarks.md). Leaf size and costs come from --quality.
    #[arg(long, value_name = "STEP", num_args = 0..=1, conflicts_with = "spatial_splits",
          default_missing_value = "32",
          value_parser = clap::value_parser!(u32).range(1..))]
    pub sweep_sah: Option<u32>,
}

impl BuildChoice {
    /// The core's build config.
    pub fn config(&self) -> BuildConfig {
        let config = self.quality.config();
        match self.sweep_sah {
            Some(step) => BuildConfig {
                split: SplitStrategy::Sweep { step },
                ..config
            },
            None => config,
        }
    }

    /// The spatial-split settings, checked (`None` without `--spatial-splits`).
    pub fn spatial(&self) -> Result<Option<SpatialSplits>> {
        spatial_splits(self.spatial_splits)
    }
}

/// `--quality`: which [`BuildConfig`] preset to build with.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Quality {
    /// Centre splits, leaves up to 8: quickest build (about 4× quicker), somewhat slower rays.
    Fast,
    /// Binned SAH, 32 bins, leaves up to 4: the default.
    Balanced,
    /// Binned SAH, 64 bins, leaves up to 4, eager splits: best trees by the SAH (add
    /// --spatial-splits for scenes of long crossing triangles).
    High,
}

impl Quality {
    pub fn config(self) -> BuildConfig {
        match self {
            Self::Fast => BuildConfig::fast(),
            Self::Balanced => BuildConfig::balanced(),
            Self::High => BuildConfig::high_quality(),
        }
    }
}

/// The help of `--spatial-splits`, shared by `bake` and the query commands.
const SPATIAL_SPLITS_HELP: &str = "Build the BVH with spatial splits: a node may cut space \
and hold the triangles crossing the plane on both sides, each boxed by its part. Much faster \
rays on scenes of long crossing triangles (architecture, CAD, foliage), about the same on \
meshes of even triangles, several times the build time (on --threads threads, the same tree). \
EXTRA is the room for references beyond one per triangle, as a fraction of the triangle count \
(0 to 4, default 1)";

/// `--spatial-splits [EXTRA]` as the core's settings, checked.
fn spatial_splits(extra: Option<f32>) -> Result<Option<SpatialSplits>> {
    let Some(extra) = extra else {
        return Ok(None);
    };
    let spatial = SpatialSplits {
        extra_references: extra,
        ..SpatialSplits::DEFAULT
    };
    if spatial.check().is_err() {
        bail!(
            "--spatial-splits takes the extra room as a fraction of the triangle count, 0 to {}; got {extra}",
            SpatialSplits::MAX_EXTRA
        );
    }
    Ok(Some(spatial))
}
