//! Building a [`Storage`] from JavaScript arrays or from a blob.

use js_sys::{Array, Uint16Array, Uint32Array};
use meshq::blob::BlobView;
use meshq::bvh::{self, BuildConfig, Bvh, BvhNode, PackedTriangle, PrimRef, WideNode};
use meshq::mesh::MeshRef;
use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

use crate::storage::{LeafOrder, Owner, Storage, Views};

fn error(e: impl core::fmt::Display) -> JsError {
    JsError::new(&e.to_string())
}

/// Corner indices from a `Uint32Array`, a `Uint16Array` or an array of numbers; `None` for
/// `null` / `undefined` (non-indexed geometry: every three positions make a triangle).
pub fn read_indices(indices: &JsValue) -> Result<Option<Vec<u32>>, JsError> {
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
            .map(|v| match v.as_f64() {
                Some(x) if x.fract() == 0.0 && (0.0..=f64::from(u32::MAX)).contains(&x) => {
                    Ok(x as u32)
                }
                _ => Err(JsError::new("indices must be whole numbers in 0..2^32")),
            })
            .collect::<Result<Vec<u32>, _>>()
            .map(Some);
    }
    Err(JsError::new(
        "indices must be a Uint32Array, a Uint16Array, an array of numbers, or null",
    ))
}

/// Validates the mesh, builds its BVH into exactly sized buffers and keeps both. The flat
/// arrays are kept as they came from JavaScript (copied once, by wasm-bindgen) and viewed as
/// triples in place.
pub fn build(
    positions: Vec<f32>,
    indices: Option<Vec<u32>>,
    config: &BuildConfig,
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
    let n = indices.len() / 3;
    let mut nodes = vec![BvhNode::EMPTY; bvh::node_capacity(n)];
    let mut order = vec![0u32; n];
    let mut packed = vec![PackedTriangle::EMPTY; n];
    let wide = {
        let mesh = MeshRef::from_flat(&positions, &indices)
            .and_then(MeshRef::validate)
            .map_err(error)?;
        let mut scratch = vec![PrimRef::EMPTY; n];
        let bvh = Bvh::build(&mesh, config, &mut nodes, &mut order, &mut scratch).map_err(error)?;
        bvh.pack_triangles(&mesh, &mut packed).map_err(error)?;
        // Sized by the bound, then trimmed: one collapse instead of a count and a collapse.
        let mut wide = vec![WideNode::EMPTY; Bvh::wide_node_bound(bvh.nodes().len())];
        let used = bvh.widen(&mut wide).map_err(error)?.nodes().len();
        wide.truncate(used);
        wide.shrink_to_fit();
        let used = bvh.nodes().len();
        nodes.truncate(used);
        wide
    };
    let owner = Owner::Built {
        positions,
        indices,
        nodes,
        order,
        packed,
        wide,
    };
    Storage::try_new(owner, views)
}

/// Validates a blob once and keeps its bytes.
pub fn from_blob(bytes: Vec<u8>) -> Result<Storage, JsError> {
    Storage::try_new(Owner::Blob(bytes), views)
}

fn views(owner: &Owner) -> Result<Views<'_>, JsError> {
    match owner {
        Owner::Built {
            positions,
            indices,
            nodes,
            order,
            packed,
            wide,
        } => {
            // The views must borrow from the owner, so the mesh is validated again (one
            // vectorised pass) and the tree re-borrowed with the topology check only: it was
            // built from this very mesh a moment ago.
            let mesh = MeshRef::from_flat(positions, indices)
                .and_then(MeshRef::validate)
                .map_err(error)?;
            let bvh = Bvh::from_built_parts(nodes, order, &mesh).map_err(error)?;
            if packed.len() != order.len() {
                return Err(JsError::new("packed triangles do not match the tree"));
            }
            // Checked against a fresh collapse of the tree (cheap next to the build).
            let wide = bvh.wide_view(wide).map_err(error)?;
            Ok(Views::Built {
                mesh,
                bvh,
                wide,
                packed: LeafOrder(packed),
            })
        }
        Owner::Blob(bytes) => BlobView::parse(bytes).map(Views::Blob).map_err(error),
    }
}
