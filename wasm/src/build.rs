//! Building a [`Storage`] from JavaScript arrays or from a blob.

use js_sys::{Array, Uint16Array, Uint32Array};
use meshq::mesh::MeshRef;
use meshq::owned::{MeshIndex, StructureKind};
use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

use crate::args::{JsNumber, range_error, type_error, value_kind};
use crate::options::BuildChoice;
use crate::storage::Storage;

fn error(e: impl core::fmt::Display) -> JsError {
    JsError::new(&e.to_string())
}

/// Corner indices from a `Uint32Array`, a `Uint16Array` or an array of numbers; `None` for
/// `null` / `undefined` (non-indexed geometry: every three positions make a triangle).
pub fn read_indices(indices: &JsValue) -> Result<Option<Vec<u32>>, JsValue> {
    if indices.is_null() || indices.is_undefined() {
        return Ok(None);
    }
    if let Some(a) = indices.dyn_ref::<Uint32Array>() {
        return Ok(Some(a.to_vec()));
    }
    if let Some(a) = indices.dyn_ref::<Uint16Array>() {
        return Ok(Some(a.to_vec().into_iter().map(u32::from).collect()));
    }
    if let Some(a) = indices.dyn_ref::<Array>() {
        return a
            .iter()
            .enumerate()
            .map(|(i, v)| match v.as_f64() {
                Some(x) if x.fract() == 0.0 && (0.0..=f64::from(u32::MAX)).contains(&x) => {
                    Ok(x as u32)
                }
                Some(x) => Err(range_error(&format!(
                    "indices[{i}] must be a whole number in 0..2^32, got {}",
                    JsNumber(x)
                ))),
                None => Err(type_error(&format!(
                    "indices[{i}] must be a number, got {}",
                    value_kind(&v)
                ))),
            })
            .collect::<Result<Vec<u32>, _>>()
            .map(Some);
    }
    Err(type_error(&format!(
        "indices must be a Uint32Array, a Uint16Array, an array of numbers, or null, got {}",
        value_kind(indices)
    )))
}

/// Validates the mesh and builds its structure of `kind` (a BVH with `config`, the others with
/// their default configs) and the copies queries read, into owned buffers.
pub fn build(
    positions: Vec<f32>,
    indices: Option<Vec<u32>>,
    choice: &BuildChoice,
) -> Result<Storage, JsError> {
    if !positions.len().is_multiple_of(3) {
        return Err(JsError::new(&format!(
            "positions hold {} numbers, not a multiple of 3 (x, y, z per vertex)",
            positions.len()
        )));
    }
    let indices = match indices {
        Some(flat) => flat,
        None => {
            let n = u32::try_from(positions.len() / 3)
                .map_err(|_| JsError::new("too many vertices"))?;
            (0..n).collect()
        }
    };
    if !indices.len().is_multiple_of(3) {
        return Err(JsError::new(&format!(
            "{} corner indices is not a multiple of 3 (three per triangle)",
            indices.len()
        )));
    }
    // A build with spatial splits holds room for the extra references as well.
    let room = choice
        .spatial
        .map_or(1.0, |s| 1.0 + f64::from(s.extra_references));
    check_memory(positions.len() / 3, indices.len() / 3, room)?;
    let mesh = MeshRef::from_flat(&positions, &indices)
        .and_then(MeshRef::validate)
        .map_err(error)?;
    let config = &choice.config;
    let scene = match (choice.kind, &choice.spatial) {
        (StructureKind::Bvh, None) => {
            MeshIndex::Bvh(meshq::MeshBvh::build(&mesh, config).map_err(error)?)
        }
        (StructureKind::Bvh, Some(spatial)) => {
            MeshIndex::Bvh(meshq::MeshBvh::build_spatial(&mesh, config, spatial).map_err(error)?)
        }
        (other, _) => MeshIndex::build(&mesh, other).map_err(error)?,
    };
    Ok(Storage {
        scene,
        blob: None,
        winding: None,
        pseudo: None,
    })
}

/// A generous bound on what building takes per triangle and per vertex (structure, packed
/// copy, mesh copy and build scratch; a BVH build peaks near 200 bytes per triangle).
const BUILD_BYTES_PER_TRIANGLE: u64 = 256;
const BUILD_BYTES_PER_VERTEX: u64 = 32;
/// WebAssembly (32-bit) memory never grows past 4 GiB.
const WASM_MEMORY_LIMIT: u64 = 1 << 32;

/// Refuses a mesh whose build would need more memory than this module can still grow by: a
/// failed allocation would abort the module (a trap), so the limit is checked first.
fn check_memory(vertices: usize, triangles: usize, room: f64) -> Result<(), JsError> {
    // `room` (1 to 5) scales the per-triangle bound for builds with spatial splits.
    let per_triangle = (BUILD_BYTES_PER_TRIANGLE as f64 * room) as u64;
    let need = (triangles as u64)
        .saturating_mul(per_triangle)
        .saturating_add((vertices as u64).saturating_mul(BUILD_BYTES_PER_VERTEX));
    let left = WASM_MEMORY_LIMIT.saturating_sub(memory_in_use());
    if need > left {
        return Err(JsError::new(&format!(
            "mesh too large for WebAssembly: {triangles} triangles and {vertices} vertices need \
             about {} MB to build, and the module's memory can grow by only {} MB more (4 GiB \
             at most); build it natively (`meshq bake`) and load the blob, or split the mesh",
            need >> 20,
            left >> 20
        )));
    }
    Ok(())
}

/// Bytes of linear memory the module holds now.
#[cfg(target_arch = "wasm32")]
fn memory_in_use() -> u64 {
    core::arch::wasm32::memory_size(0) as u64 * 65_536
}

#[cfg(not(target_arch = "wasm32"))]
fn memory_in_use() -> u64 {
    0
}

/// Validates a blob of any structure once and decodes it into the buffers a build makes, so a loaded mesh is
/// queried exactly as fast as a built one (and answers the same, bit for bit); keeps the bytes
/// for `toBlob`.
pub fn from_blob(bytes: Vec<u8>) -> Result<Storage, JsError> {
    let scene = MeshIndex::from_blob(&bytes).map_err(error)?;
    Ok(Storage {
        scene,
        blob: Some(bytes),
        winding: None,
        pseudo: None,
    })
}
