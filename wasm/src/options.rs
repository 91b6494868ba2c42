//! Build options passed from JavaScript, read strictly (see [`crate::fields`]).

use meshq::bvh::{BuildConfig, MAX_DEPTH};
use meshq::error::BuildError;
use meshq::owned::StructureKind;
use wasm_bindgen::prelude::*;

use crate::fields::{field, optional_choice, optional_u32, options};

/// The keys `MeshBvh.build` accepts.
const BUILD_KEYS: &[&str] = &["structure", "quality", "maxLeafSize", "bins", "maxDepth"];

/// Reads `{ structure?, quality?, maxLeafSize?, bins?, maxDepth? }`: every field optional
/// (`undefined` or `null` means the default: a BVH, balanced). An unknown key, a value of the
/// wrong kind or out of range throws, naming it.
pub fn build_options(value: &JsValue) -> Result<(BuildConfig, StructureKind), JsValue> {
    let o = options(value, "options", BUILD_KEYS)?;
    let o = o.as_ref();
    let kind = match optional_choice(
        &field(o, "structure"),
        "options.structure",
        &["bvh", "kdtree", "octree", "grid"],
    )? {
        None => StructureKind::Bvh,
        Some(name) => name
            .parse()
            .map_err(|e| JsValue::from(JsError::new(&format!("{e}"))))?,
    };
    let mut config = match optional_choice(
        &field(o, "quality"),
        "options.quality",
        &["fast", "balanced", "high"],
    )? {
        Some("fast") => BuildConfig::fast(),
        Some("high") => BuildConfig::high_quality(),
        _ => BuildConfig::balanced(),
    };
    if let Some(n) = optional_u32(&field(o, "maxLeafSize"), "options.maxLeafSize")? {
        config.max_leaf_size = n;
    }
    if let Some(n) = optional_u32(&field(o, "bins"), "options.bins")? {
        config.bins = n;
    }
    if let Some(n) = optional_u32(&field(o, "maxDepth"), "options.maxDepth")? {
        config.max_depth = n;
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
        return Err(crate::args::range_error(&message));
    }
    Ok((config, kind))
}
