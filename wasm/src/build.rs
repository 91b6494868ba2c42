//! Building a [`Storage`] from JavaScript arrays or from a blob.

use js_sys::{Array, Uint16Array, Uint32Array};
use meshq::blob::{BlobView, MeshLayout};
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
        let wide = widen(&bvh)?;
        let used = bvh.nodes().len();
        nodes.truncate(used);
        wide
    };
    let owner = Owner {
        positions,
        indices,
        nodes,
        order,
        packed,
        wide,
        blob: None,
    };
    Storage::try_new(owner, views)
}

/// The tree collapsed four-wide, in a buffer sized by the bound and then trimmed: one collapse
/// instead of a count and a collapse.
fn widen(bvh: &Bvh<'_>) -> Result<Vec<WideNode>, JsError> {
    let mut wide = vec![WideNode::EMPTY; Bvh::wide_node_bound(bvh.nodes().len())];
    let used = bvh.widen(&mut wide).map_err(error)?.nodes().len();
    wide.truncate(used);
    wide.shrink_to_fit();
    Ok(wide)
}

/// Validates a blob once and decodes it into the buffers a build makes, so a loaded mesh is
/// queried exactly as fast as a built one (and answers the same, bit for bit); keeps the bytes
/// for `toBlob`. A packed blob stores corners rather than an indexed mesh: its mesh becomes
/// three unshared vertices per triangle. Returns the build config the blob records too.
pub fn from_blob(bytes: Vec<u8>) -> Result<(Storage, BuildConfig), JsError> {
    let view = BlobView::parse(&bytes).map_err(error)?;
    let header = *view.header();
    let (n, v) = (header.triangle_count as usize, header.vertex_count as usize);
    let mut nodes = vec![BvhNode::EMPTY; header.node_count as usize];
    let mut order = vec![0u32; n];
    let mut packed = vec![PackedTriangle::EMPTY; n];
    let bvh = view.decode_tree(&mut nodes, &mut order).map_err(error)?;
    view.decode_packed(&mut packed).map_err(error)?;
    let wide = widen(&bvh)?;
    let (positions, indices) = if header.mesh == MeshLayout::Packed {
        unshared_mesh(&order, &packed)
    } else {
        let mut positions = vec![[0.0f32; 3]; v];
        let mut triangles = vec![[0u32; 3]; n];
        view.decode_mesh(&mut positions, &mut triangles)
            .map_err(error)?;
        (
            positions.into_iter().flatten().collect(),
            triangles.into_iter().flatten().collect(),
        )
    };
    let owner = Owner {
        positions,
        indices,
        nodes,
        order,
        packed,
        wide,
        blob: Some(bytes),
    };
    Ok((Storage::try_new(owner, views)?, header.config))
}

/// Flat positions and indices of triangles given in leaf order (`packed[slot]` is triangle
/// `order[slot]`): three vertices of their own per triangle, in triangle order.
fn unshared_mesh(order: &[u32], packed: &[PackedTriangle]) -> (Vec<f32>, Vec<u32>) {
    let mut positions = vec![0.0f32; 9 * packed.len()];
    for (&tri, corners) in order.iter().zip(packed) {
        let at = 9 * tri as usize;
        if let Some(out) = positions.get_mut(at..at + 9) {
            for (dst, src) in out
                .iter_mut()
                .zip(corners.a.iter().chain(&corners.b).chain(&corners.c))
            {
                *dst = *src;
            }
        }
    }
    let indices = (0..).take(3 * packed.len()).collect();
    (positions, indices)
}

fn views(owner: &Owner) -> Result<Views<'_>, JsError> {
    // The views must borrow from the owner, so the mesh is validated again (one vectorised
    // pass) and the tree re-borrowed with the topology check only: it was built from this very
    // mesh (or decoded from a blob validated against it) a moment ago.
    let mesh = MeshRef::from_flat(&owner.positions, &owner.indices)
        .and_then(MeshRef::validate)
        .map_err(error)?;
    let bvh = Bvh::from_built_parts(&owner.nodes, &owner.order, &mesh).map_err(error)?;
    if owner.packed.len() != owner.order.len() {
        return Err(JsError::new("packed triangles do not match the tree"));
    }
    // Checked against a fresh collapse of the tree (cheap next to the build).
    let wide = bvh.wide_view(&owner.wide).map_err(error)?;
    Ok(Views {
        mesh,
        bvh,
        wide,
        packed: LeafOrder(&owner.packed),
    })
}
