//! The build quality presets on the command line.

use anyhow::{Result, bail};
use clap::ValueEnum;
use meshq::bvh::{BuildConfig, SpatialSplits};

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
pub const SPATIAL_SPLITS_HELP: &str = "Build the BVH with spatial splits: a node may cut space \
and hold the triangles crossing the plane on both sides, each boxed by its part. Much faster \
rays on scenes of long crossing triangles (architecture, CAD, foliage), about the same on \
meshes of even triangles, several times the build time (on --threads threads, the same tree). \
EXTRA is the room for references beyond one per triangle, as a fraction of the triangle count \
(0 to 4, default 1)";

/// `--spatial-splits [EXTRA]` as the core's settings, checked.
pub fn spatial_splits(extra: Option<f32>) -> Result<Option<SpatialSplits>> {
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
