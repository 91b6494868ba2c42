//! Build options passed from JavaScript, read strictly (see [`crate::fields`]).

use meshq::bvh::{BuildConfig, MAX_DEPTH, SpatialSplits, SplitStrategy};
use meshq::error::BuildError;
use meshq::owned::StructureKind;
use wasm_bindgen::prelude::*;

use crate::args::{JsNumber, range_error, type_error, value_kind};
use crate::fields::{field, omitted, optional_choice, optional_u32, options};

/// The keys `MeshBvh.build` accepts.
const BUILD_KEYS: &[&str] = &[
    "structure",
    "quality",
    "maxLeafSize",
    "bins",
    "maxDepth",
    "spatialSplits",
    "sweepSah",
];

/// What `MeshBvh.build`'s options ask for.
pub struct BuildChoice {
    pub config: BuildConfig,
    pub kind: StructureKind,
    /// Spatial splits for the BVH (`spatialSplits`), if asked for.
    pub spatial: Option<SpatialSplits>,
}

/// `spatialSplits`: omitted or `false` → none; `true` → the default room; a number → that
/// room (`extra_references`, `0..=4`).
fn spatial_option(value: &JsValue) -> Result<Option<SpatialSplits>, JsValue> {
    const WHAT: &str = "options.spatialSplits";
    if omitted(value) {
        return Ok(None);
    }
    if let Some(on) = value.as_bool() {
        return Ok(on.then_some(SpatialSplits::DEFAULT));
    }
    let Some(extra) = value.as_f64() else {
        return Err(type_error(&format!(
            "{WHAT} must be a boolean or a number, got {}",
            value_kind(value)
        )));
    };
    let spatial = SpatialSplits {
        extra_references: extra as f32,
        ..SpatialSplits::DEFAULT
    };
    if spatial.check().is_err() || !(0.0..=f64::from(SpatialSplits::MAX_EXTRA)).contains(&extra) {
        return Err(range_error(&format!(
            "{WHAT} must be true, false or a number in 0..={}, got {}",
            SpatialSplits::MAX_EXTRA,
            JsNumber(extra)
        )));
    }
    Ok(Some(spatial))
}

/// `sweepSah`: omitted or `false` → the quality's strategy; `true` → sweep SAH every
/// [`SplitStrategy::SWEEP_STEP`] triangles; a whole number `≥ 1` → every that many.
fn sweep_option(value: &JsValue) -> Result<Option<SplitStrategy>, JsValue> {
    const WHAT: &str = "options.sweepSah";
    if omitted(value) {
        return Ok(None);
    }
    if let Some(on) = value.as_bool() {
        return Ok(on.then_some(SplitStrategy::Sweep {
            step: SplitStrategy::SWEEP_STEP,
        }));
    }
    let Some(step) = value.as_f64() else {
        return Err(type_error(&format!(
            "{WHAT} must be a boolean or a number, got {}",
            value_kind(value)
        )));
    };
    if step.fract() != 0.0 || !(1.0..=f64::from(u32::MAX)).contains(&step) {
        return Err(range_error(&format!(
            "{WHAT} must be true, false or a whole number of triangles in 1..={}, got {}",
            u32::MAX,
            JsNumber(step)
        )));
    }
    Ok(Some(SplitStrategy::Sweep { step: step as u32 }))
}

/// Reads `{ structure?, quality?, maxLeafSize?, bins?, maxDepth?, spatialSplits?, sweepSah? }`: every
/// field optional (`undefined` or `null` means the default: a BVH, balanced, no spatial
/// splits). An unknown key, a value of the wrong kind or out of range throws, naming it.
pub fn build_options(value: &JsValue) -> Result<BuildChoice, JsValue> {
    let o = options(value, "options", BUILD_KEYS)?;
    let o = o.as_ref();
    let kind = match optional_choice(
        &field(o, "structure")?,
        "options.structure",
        &["bvh", "kdtree", "octree", "grid"],
    )? {
        None => StructureKind::Bvh,
        Some(name) => name
            .parse()
            .map_err(|e| JsValue::from(JsError::new(&format!("{e}"))))?,
    };
    let mut config = match optional_choice(
        &field(o, "quality")?,
        "options.quality",
        &["fast", "balanced", "high"],
    )? {
        Some("fast") => BuildConfig::fast(),
        Some("high") => BuildConfig::high_quality(),
        _ => BuildConfig::balanced(),
    };
    if let Some(n) = optional_u32(&field(o, "maxLeafSize")?, "options.maxLeafSize")? {
        config.max_leaf_size = n;
    }
    if let Some(n) = optional_u32(&field(o, "bins")?, "options.bins")? {
        config.bins = n;
    }
    if let Some(n) = optional_u32(&field(o, "maxDepth")?, "options.maxDepth")? {
        config.max_depth = n;
    }
    let sweep = sweep_option(&field(o, "sweepSah")?)?;
    if let Some(split) = sweep {
        config.split = split;
    }
    if let Err(e) = config.check() {
        let message = match e {
            BuildError::InvalidConfig {
                field: "max_leaf_size",
            } => format!(
                "options.maxLeafSize must be in 1..={}, got {}",
                BuildConfig::MAX_LEAF_SIZE,
                config.max_leaf_size
            ),
            BuildError::InvalidConfig { field: "bins" } => format!(
                "options.bins must be in 2..={}, got {}",
                BuildConfig::MAX_BINS,
                config.bins
            ),
            BuildError::InvalidConfig { field: "max_depth" } => format!(
                "options.maxDepth must be in 1..={MAX_DEPTH}, got {}",
                config.max_depth
            ),
            other => other.to_string(),
        };
        return Err(range_error(&message));
    }
    let spatial = spatial_option(&field(o, "spatialSplits")?)?;
    if spatial.is_some() && sweep.is_some() {
        return Err(type_error(
            "options.sweepSah and options.spatialSplits do not go together (spatial splits are weighed against the binned search)",
        ));
    }
    if (spatial.is_some() || sweep.is_some()) && kind != StructureKind::Bvh {
        let name = if spatial.is_some() {
            "spatialSplits"
        } else {
            "sweepSah"
        };
        return Err(type_error(&format!(
            "options.{name} applies to the BVH, not a {kind}"
        )));
    }
    Ok(BuildChoice {
        config,
        kind,
        spatial,
    })
}
