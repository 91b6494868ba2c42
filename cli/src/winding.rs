//! What the winding-number commands share: the `--accuracy` option and the winding-number tree
//! of a prepared input.

use std::time::Instant;

use anyhow::Result;
use meshq::bvh::BuildConfig;
use meshq::inside::{WindingAccuracy, WindingTree};
use meshq::owned::{MeshBvh, MeshIndex};

use crate::structure::Prepared;

/// `--accuracy`: a far ratio ≥ 1, or `exact`.
pub fn accuracy_parser(text: &str) -> Result<WindingAccuracy, String> {
    if text == "exact" {
        return Ok(WindingAccuracy::EXACT);
    }
    text.parse::<f32>()
        .ok()
        .and_then(WindingAccuracy::new)
        .ok_or_else(|| format!("expected a ratio ≥ 1 or `exact`, got {text:?}"))
}

/// The help of `--accuracy`.
pub const ACCURACY_HELP: &str = "Winding-number accuracy: a group of triangles counts by its \
    expansion when the point is farther than RATIO times its radius (default 2: within 1e-2 of \
    the exact number, measured; larger is more exact and slower), or `exact`";

/// The BVH whose winding-number tree answers for `prepared`: its own BVH, prepared in place, or
/// (for a k-d tree, octree or grid) a BVH built over its mesh, returned. Adds the time taken
/// to the preparation time.
pub fn prepare(prepared: &mut Prepared) -> Result<Option<MeshBvh>> {
    let start = Instant::now();
    let built = match &mut prepared.scene {
        MeshIndex::Bvh(bvh) => {
            bvh.prepare_winding_numbers()?;
            None
        }
        other => {
            Some(MeshBvh::build(&other.mesh(), &BuildConfig::default())?.with_winding_numbers()?)
        }
    };
    prepared.prepare_seconds += start.elapsed().as_secs_f64();
    Ok(built)
}

/// The winding-number tree [`prepare`] made ready.
pub fn tree<'a>(prepared: &'a Prepared, built: &'a Option<MeshBvh>) -> Result<WindingTree<'a>> {
    let bvh = match (&prepared.scene, built) {
        (_, Some(bvh)) | (MeshIndex::Bvh(bvh), None) => bvh,
        (other, None) => anyhow::bail!("no winding-number tree for the {}", other.kind()),
    };
    bvh.winding()
        .ok_or_else(|| anyhow::anyhow!("the winding-number tree was not prepared"))
}
