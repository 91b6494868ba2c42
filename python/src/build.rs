//! Build options from keyword arguments: the structure, the BVH's quality and tuning, spatial
//! splits.

use meshq::bvh::{BuildConfig, MAX_DEPTH, SpatialSplits, SplitStrategy};
use meshq::error::BuildError;
use meshq::owned::StructureKind;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use crate::arrays::setting;

/// The nodes a BVH's queries walk (`nodes`): every layout gives the same answers.
#[derive(Clone, Copy)]
pub enum Nodes {
    /// The default: eight-wide where the CPU has 128-bit SIMD (every x86-64 and AArch64).
    Default,
    EightWide,
    FourWide,
    /// Four-wide nodes with 8-bit child boxes: half the node memory.
    Compact,
}

/// What to build: the structure's kind, the BVH's config and, for a BVH, spatial splits and
/// the node layout.
pub struct BuildChoice {
    pub kind: StructureKind,
    pub config: BuildConfig,
    pub spatial: Option<SpatialSplits>,
    pub nodes: Nodes,
}

/// The choice of `structure` (`"bvh"`, `"kdtree"`, `"octree"`, `"grid"`), `quality` (`"fast"`,
/// `"balanced"`, `"high"`), the BVH's `max_leaf_size`, `bins`, `max_depth`, `spatial_splits`
/// (`False`/`None`, `True`, or the extra room `0..=4`) and `sweep_sah` (`False`/`None`,
/// `True`, or the triangles between weighed cuts, `≥ 1`) and `nodes` (`None`, `"eight-wide"`,
/// `"four-wide"`, `"compact"`), each checked and named when wrong.
#[allow(clippy::too_many_arguments)] // One per keyword argument of `Mesh(...)`.
pub fn build_choice(
    structure: &str,
    quality: &str,
    max_leaf_size: Option<&Bound<'_, PyAny>>,
    bins: Option<&Bound<'_, PyAny>>,
    max_depth: Option<&Bound<'_, PyAny>>,
    spatial_splits: Option<&Bound<'_, PyAny>>,
    sweep_sah: Option<&Bound<'_, PyAny>>,
    nodes: Option<&str>,
) -> PyResult<BuildChoice> {
    let kind: StructureKind = structure.parse().map_err(|_| {
        PyValueError::new_err(format!(
            "structure must be 'bvh', 'kdtree', 'octree' or 'grid', got {structure:?}"
        ))
    })?;
    let mut config = match quality {
        "fast" => BuildConfig::fast(),
        "balanced" => BuildConfig::balanced(),
        "high" => BuildConfig::high_quality(),
        other => {
            return Err(PyValueError::new_err(format!(
                "quality must be 'fast', 'balanced' or 'high', got {other:?}"
            )));
        }
    };
    if let Some(n) = setting(max_leaf_size, "max_leaf_size")? {
        config.max_leaf_size = n;
    }
    if let Some(n) = setting(bins, "bins")? {
        config.bins = n;
    }
    if let Some(n) = setting(max_depth, "max_depth")? {
        config.max_depth = n;
    }
    let sweep = sweep_option(sweep_sah)?;
    if let Some(split) = sweep {
        config.split = split;
    }
    if let Err(e) = config.check() {
        let message = match e {
            BuildError::InvalidConfig {
                field: "max_leaf_size",
            } => format!(
                "max_leaf_size must be in 1..={}, got {}",
                BuildConfig::MAX_LEAF_SIZE,
                config.max_leaf_size
            ),
            BuildError::InvalidConfig { field: "bins" } => format!(
                "bins must be in 2..={}, got {}",
                BuildConfig::MAX_BINS,
                config.bins
            ),
            BuildError::InvalidConfig { field: "max_depth" } => format!(
                "max_depth must be in 1..={MAX_DEPTH}, got {}",
                config.max_depth
            ),
            other => other.to_string(),
        };
        return Err(PyValueError::new_err(message));
    }
    let spatial = spatial_option(spatial_splits)?;
    if spatial.is_some() && sweep.is_some() {
        return Err(PyValueError::new_err(
            "sweep_sah and spatial_splits do not go together (spatial splits are weighed against the binned search)",
        ));
    }
    if (spatial.is_some() || sweep.is_some()) && kind != StructureKind::Bvh {
        let name = if spatial.is_some() {
            "spatial_splits"
        } else {
            "sweep_sah"
        };
        return Err(PyValueError::new_err(format!(
            "{name} applies to the BVH, not a {kind}"
        )));
    }
    let nodes = match nodes {
        None => Nodes::Default,
        Some("eight-wide") => Nodes::EightWide,
        Some("four-wide") => Nodes::FourWide,
        Some("compact") => Nodes::Compact,
        Some(other) => {
            return Err(PyValueError::new_err(format!(
                "nodes must be 'eight-wide', 'four-wide', 'compact' or None, got {other:?}"
            )));
        }
    };
    if !matches!(nodes, Nodes::Default) && kind != StructureKind::Bvh {
        return Err(PyValueError::new_err(format!(
            "nodes applies to the BVH, not a {kind}"
        )));
    }
    Ok(BuildChoice {
        kind,
        config,
        spatial,
        nodes,
    })
}

/// `sweep_sah`: `None` or `False` → the quality's strategy; `True` → sweep SAH every
/// [`SplitStrategy::SWEEP_STEP`] triangles; a whole number `≥ 1` → every that many.
fn sweep_option(value: Option<&Bound<'_, PyAny>>) -> PyResult<Option<SplitStrategy>> {
    let Some(value) = value.filter(|v| !v.is_none()) else {
        return Ok(None);
    };
    if let Ok(on) = value.extract::<bool>() {
        return Ok(on.then_some(SplitStrategy::Sweep {
            step: SplitStrategy::SWEEP_STEP,
        }));
    }
    match setting(Some(value), "sweep_sah")? {
        Some(step) if step >= 1 => Ok(Some(SplitStrategy::Sweep { step })),
        _ => Err(PyValueError::new_err(
            "sweep_sah must be True, False, None or a whole number of triangles ≥ 1, got 0",
        )),
    }
}

/// `spatial_splits`: `None` or `False` → none; `True` → the default room; a number → that room.
fn spatial_option(value: Option<&Bound<'_, PyAny>>) -> PyResult<Option<SpatialSplits>> {
    let Some(value) = value.filter(|v| !v.is_none()) else {
        return Ok(None);
    };
    if let Ok(on) = value.extract::<bool>() {
        return Ok(on.then_some(SpatialSplits::DEFAULT));
    }
    let extra: f64 = value.extract().map_err(|_| {
        PyValueError::new_err("spatial_splits must be True, False, None or a number")
    })?;
    let spatial = SpatialSplits {
        extra_references: extra as f32,
        ..SpatialSplits::DEFAULT
    };
    if spatial.check().is_err() || !(0.0..=f64::from(SpatialSplits::MAX_EXTRA)).contains(&extra) {
        return Err(PyValueError::new_err(format!(
            "spatial_splits must be True, False or a number in 0..={}, got {extra}",
            SpatialSplits::MAX_EXTRA
        )));
    }
    Ok(Some(spatial))
}
