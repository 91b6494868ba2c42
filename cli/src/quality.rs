//! The build quality presets on the command line.

use clap::ValueEnum;
use meshq::bvh::BuildConfig;

/// `--quality`: which [`BuildConfig`] preset to build with.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Quality {
    /// Centre splits, leaves up to 8: quickest build (about 4× quicker), somewhat slower rays.
    Fast,
    /// Binned SAH, 32 bins, leaves up to 4: the default.
    Balanced,
    /// Binned SAH, 64 bins, leaves up to 4, eager splits: best trees.
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
