//! The structure a query command runs on: built from a mesh file, or loaded from a blob. Either
//! way queries run on an in-memory BVH with packed triangles, the fastest path.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context, Result, anyhow, bail};
use clap::Args;
use meshq::blob::{BlobView, MAGIC};
use meshq::bvh::{self, BuildConfig, Bvh, BvhNode, PackedTriangle, PackedTriangles, PrimRef};
use meshq::error::BlobError;
use meshq::mesh::MeshRef;

use crate::mesh_file::{MeshData, read_mesh};
use crate::quality::Quality;

/// What a query command gets: the tree, its triangles in leaf order, and how long preparing
/// them took (building from a mesh, or validating and decoding a blob; file reading excluded).
pub struct Prepared<'a> {
    pub tree: Bvh<'a>,
    pub triangles: PackedTriangles<'a>,
    pub prepare_seconds: f64,
}

/// The input of a query command: what to query and how to prepare it.
#[derive(Args, Debug)]
pub struct QueryInput {
    /// A mesh file (OBJ, PLY, STL; built first) or a blob.
    pub input: PathBuf,
    /// The mesh of a blob baked with --no-mesh.
    #[arg(long)]
    pub mesh: Option<PathBuf>,
    /// Build quality when INPUT is a mesh.
    #[arg(long, value_enum, default_value_t = Quality::Balanced)]
    pub quality: Quality,
}

/// Loads the input — a blob when the file starts with the blob magic, otherwise a mesh file
/// built with the chosen quality — and runs `query` on it.
pub fn with_structure<R>(
    args: &QueryInput,
    query: impl FnOnce(Prepared<'_>) -> Result<R>,
) -> Result<R> {
    let (input, mesh, config) = (
        args.input.as_path(),
        args.mesh.as_deref(),
        &args.quality.config(),
    );
    let bytes = std::fs::read(input).with_context(|| format!("cannot read {}", input.display()))?;
    if bytes.starts_with(&MAGIC) {
        let external = mesh.map(read_mesh).transpose()?;
        with_blob(&bytes, external.as_ref(), query)
            .with_context(|| format!("{}: cannot use blob", input.display()))
    } else {
        if mesh.is_some() {
            bail!(
                "--mesh applies to blob inputs only; {} is a mesh file",
                input.display()
            );
        }
        drop(bytes);
        let data = read_mesh(input)?;
        with_built(&data, config, query)
    }
}

/// Builds a BVH of `data`, packs its triangles and runs `query`.
pub fn with_built<R>(
    data: &MeshData,
    config: &BuildConfig,
    query: impl FnOnce(Prepared<'_>) -> Result<R>,
) -> Result<R> {
    let mesh = MeshRef::new(&data.positions, &data.triangles).validate()?;
    let n = mesh.triangle_count();
    let mut nodes = vec![BvhNode::EMPTY; bvh::node_capacity(n)];
    let mut order = vec![0u32; n];
    let mut scratch = vec![PrimRef::EMPTY; n];
    let mut packed = vec![PackedTriangle::EMPTY; n];
    let start = Instant::now();
    let tree = Bvh::build(&mesh, config, &mut nodes, &mut order, &mut scratch)?;
    let triangles = tree.pack_triangles(&mesh, &mut packed)?;
    let prepare_seconds = start.elapsed().as_secs_f64();
    query(Prepared {
        tree,
        triangles,
        prepare_seconds,
    })
}

/// Validates a blob, decodes it into RAM and runs `query`.
fn with_blob<R>(
    bytes: &[u8],
    external: Option<&MeshData>,
    query: impl FnOnce(Prepared<'_>) -> Result<R>,
) -> Result<R> {
    let start = Instant::now();
    let view = match external {
        Some(data) => {
            let mesh = MeshRef::new(&data.positions, &data.triangles).validate()?;
            BlobView::parse_with_mesh(bytes, mesh)?
        }
        None => BlobView::parse(bytes).map_err(|e| match e {
            BlobError::MeshNotIncluded => anyhow!("{e} (pass it with --mesh)"),
            e => e.into(),
        })?,
    };
    let h = view.header();
    let mut nodes = vec![BvhNode::EMPTY; h.node_count as usize];
    let mut order = vec![0u32; h.triangle_count as usize];
    let mut packed = vec![PackedTriangle::EMPTY; h.triangle_count as usize];
    let tree = view.decode_tree(&mut nodes, &mut order)?;
    let triangles = view.decode_packed(&mut packed)?;
    let prepare_seconds = start.elapsed().as_secs_f64();
    query(Prepared {
        tree,
        triangles,
        prepare_seconds,
    })
}
