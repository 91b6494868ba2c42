//! The remeshing program (`--features remesh`): the small UV sphere's blob sits in flash; its
//! mesh is copied into RAM once, remeshed in fixed-capacity arrays on the stack while every
//! projection queries the blob's BVH in place, and the result's digest must equal the golden
//! remeshing file the native suite wrote.
//!
//! Exit status: 0 when the digest matches, 1 on a mismatch, 2 when the blob is refused, 3 when
//! the golden file has no usable line for the mesh, 4 when the blob holds another mesh, 5 when
//! the input does not fit the input arrays or remeshing fails (capacity, refused input).

use meshq::blob::{BlobMesh, BlobView};
use meshq::error::{MeshError, RemeshError};
use meshq::mesh::MeshRef;
use meshq::remesh::{HalfEdgeBuffers, HalfEdgeMesh, RemeshConfig, RemeshReport, remesh};
use meshq_workload::{MeshDigest, find_remesh_golden};

use crate::{report, stack};

/// The golden remeshing file shared with the native and WebAssembly tests.
static GOLDEN: &str = include_str!("../../tests/golden/remesh.txt");

/// Most input vertices and triangles (the sphere has 182 and 360).
const INPUT_VERTICES: usize = 192;
const INPUT_TRIANGLES: usize = 384;
/// Room while remeshing: the native run reports a peak of 262 vertices and 520 triangles
/// (`RemeshReport::peak_*`); about a tenth more.
const VERTICES: usize = 288;
const TRIANGLES: usize = 576;
const HALF_EDGES: usize = 3 * TRIANGLES;

/// The remeshing arrays, kept in `run`'s frame for the whole run.
struct Arrays {
    positions: [[f32; 3]; VERTICES],
    origins: [u32; HALF_EDGES],
    twins: [u32; HALF_EDGES],
    vertex_half_edges: [u32; VERTICES],
    creases: [bool; HALF_EDGES],
    smoothing: [[f32; 3]; VERTICES],
}

/// Bytes of the remeshing arrays.
pub const ARRAY_BYTES: usize = core::mem::size_of::<Arrays>();

/// Why a run stopped before a digest.
pub enum Failure {
    /// The blob's mesh has more vertices or triangles than the input arrays, or is not indexed.
    InputTooLarge,
    /// The blob's mesh failed validation as a mesh (the blob check makes this unreachable).
    Invalid(MeshError),
    /// The remesher refused the input or ran out of room.
    Remesh(RemeshError),
}

pub fn run(blob: &'static [u8], mesh_name: &str) -> i32 {
    report::start(mesh_name, blob.len());
    stack::repaint();
    let parsed = crate::validate(blob);
    let view = match &parsed {
        Ok(view) => view,
        Err(error) => {
            report::blob_refused(error);
            return 2;
        }
    };
    let golden = match find_remesh_golden(GOLDEN, mesh_name) {
        Ok(golden) => golden,
        Err(error) => {
            report::golden_unusable(&error);
            return 3;
        }
    };
    let header = view.header();
    if header.triangle_count != golden.triangles_in {
        report::wrong_mesh(header.triangle_count, golden.triangles_in);
        return 4;
    }
    report::blob_loaded(header);

    let config = RemeshConfig {
        iterations: golden.iterations,
        ..RemeshConfig::default()
    };
    let mut arrays = Arrays {
        positions: [[0.0; 3]; VERTICES],
        origins: [0; HALF_EDGES],
        twins: [0; HALF_EDGES],
        vertex_half_edges: [0; VERTICES],
        creases: [false; HALF_EDGES],
        smoothing: [[0.0; 3]; VERTICES],
    };
    let outcome = remeshed(view, &config, &mut arrays);
    let used = stack::high_water();
    match outcome {
        Ok((run, got)) => {
            report::remeshed(&run, &got, &golden.result);
            report::remesh_memory(ARRAY_BYTES, used);
            if got == golden.result { 0 } else { 1 }
        }
        Err(Failure::InputTooLarge) => {
            report::input_too_large(INPUT_VERTICES, INPUT_TRIANGLES);
            5
        }
        Err(Failure::Invalid(error)) => {
            report::mesh_refused(&error);
            5
        }
        Err(Failure::Remesh(error)) => {
            report::remesh_failed(&error);
            5
        }
    }
}

/// Builds the half-edge mesh from the blob's mesh, remeshes it against the blob, digests it.
#[inline(never)]
fn remeshed(
    view: &BlobView<'_>,
    config: &RemeshConfig,
    arrays: &mut Arrays,
) -> Result<(RemeshReport, MeshDigest), Failure> {
    let Arrays {
        positions,
        origins,
        twins,
        vertex_half_edges,
        creases,
        smoothing,
    } = arrays;
    let buffers = HalfEdgeBuffers {
        positions,
        origins,
        twins,
        vertex_half_edges,
        creases,
    };
    let mut mesh = half_edge_mesh(view, buffers)?;
    let run = remesh(&mut mesh, view, config, smoothing).map_err(Failure::Remesh)?;
    let digest = MeshDigest::of(
        (0..mesh.vertex_count() as u32).map(|v| mesh.position(v).to_array()),
        (0..mesh.triangle_count() as u32).map(|t| mesh.triangle(t)),
    );
    Ok((run, digest))
}

/// Copies the blob's mesh into RAM and pairs its half-edges. Out of line, so the copy and the
/// pairing scratch leave the stack before remeshing starts.
#[inline(never)]
fn half_edge_mesh<'a>(
    view: &BlobView<'_>,
    buffers: HalfEdgeBuffers<'a>,
) -> Result<HalfEdgeMesh<'a>, Failure> {
    let header = view.header();
    let (v, t) = (header.vertex_count as usize, header.triangle_count as usize);
    if v > INPUT_VERTICES || t > INPUT_TRIANGLES {
        return Err(Failure::InputTooLarge);
    }
    let BlobMesh::Indexed { .. } = view.mesh() else {
        return Err(Failure::InputTooLarge);
    };
    let mut positions = [[0.0f32; 3]; INPUT_VERTICES];
    let mut triangles = [[0u32; 3]; INPUT_TRIANGLES];
    for (i, slot) in (0u32..).zip(positions.iter_mut().take(v)) {
        *slot = view.mesh().position(i).ok_or(Failure::InputTooLarge)?;
    }
    for (i, slot) in (0u32..).zip(triangles.iter_mut().take(t)) {
        *slot = view
            .mesh()
            .triangle_indices(i)
            .ok_or(Failure::InputTooLarge)?;
    }
    let (positions, triangles) = (
        positions.get(..v).ok_or(Failure::InputTooLarge)?,
        triangles.get(..t).ok_or(Failure::InputTooLarge)?,
    );
    let mesh = MeshRef::new(positions, triangles)
        .validate()
        .map_err(Failure::Invalid)?;
    let mut pairing = [0u32; HALF_EDGES];
    HalfEdgeMesh::from_mesh(&mesh, buffers, &mut pairing).map_err(Failure::Remesh)
}
