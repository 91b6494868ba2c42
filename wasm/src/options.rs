//! Options passed from JavaScript: build settings and three.js material sides.

use js_sys::Reflect;
use meshq::bvh::BuildConfig;
use meshq::owned::StructureKind;
use wasm_bindgen::prelude::*;

/// Reads `{ quality?: "fast" | "balanced" | "high", maxLeafSize?, bins?, maxDepth? }` (every field
/// optional; `undefined` or `null` means the balanced default).
pub fn build_config(options: &JsValue) -> Result<BuildConfig, JsError> {
    if options.is_undefined() || options.is_null() {
        return Ok(BuildConfig::default());
    }
    let field = |name: &str| Reflect::get(options, &JsValue::from_str(name)).ok();
    let mut config = match field("quality").and_then(|q| q.as_string()).as_deref() {
        None | Some("balanced") => BuildConfig::balanced(),
        Some("fast") => BuildConfig::fast(),
        Some("high") => BuildConfig::high_quality(),
        Some(other) => {
            return Err(JsError::new(&format!(
                "unknown quality {other:?}: use \"fast\", \"balanced\" or \"high\""
            )));
        }
    };
    let whole = |name: &str| -> Result<Option<u32>, JsError> {
        match field(name).and_then(|v| v.as_f64()) {
            None => Ok(None),
            Some(x) if x.fract() == 0.0 && (0.0..=f64::from(u32::MAX)).contains(&x) => {
                Ok(Some(x as u32))
            }
            Some(x) => Err(JsError::new(&format!(
                "{name} must be a whole number, got {x}"
            ))),
        }
    };
    if let Some(n) = whole("maxLeafSize")? {
        config.max_leaf_size = n;
    }
    if let Some(n) = whole("bins")? {
        config.bins = n;
    }
    if let Some(n) = whole("maxDepth")? {
        config.max_depth = n;
    }
    config.check().map_err(|e| JsError::new(&e.to_string()))?;
    Ok(config)
}

/// Reads `{ structure?: "bvh" | "kdtree" | "octree" | "grid" }` (`"bvh"` when absent).
pub fn structure_kind(options: &JsValue) -> Result<StructureKind, JsError> {
    if options.is_undefined() || options.is_null() {
        return Ok(StructureKind::Bvh);
    }
    match Reflect::get(options, &JsValue::from_str("structure"))
        .ok()
        .and_then(|v| v.as_string())
    {
        None => Ok(StructureKind::Bvh),
        Some(name) => name
            .parse()
            .map_err(|e| JsError::new(&format!("{e}, got {name:?}"))),
    }
}
