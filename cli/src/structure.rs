//! The structure a query command runs on: built from a mesh file (a BVH, k-d tree, octree or
//! grid, as `--structure` says), or loaded from a blob (whichever structure it holds). Either
//! way queries run on the owned structure over packed triangles, the fastest path.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, anyhow, bail};
use clap::Args;
use meshq::advanced::{BlobHeader, MAGIC};
use meshq::bvh::{BuildConfig, SpatialSplits};
use meshq::error::BlobError;
use meshq::mesh::MeshRef;
use meshq::owned::{MeshBvh, MeshIndex, StructureKind};

use crate::mesh_file::{MeshData, read_mesh};
use crate::quality::BuildChoice;
use crate::structure_arg::structure_parser;
use crate::threads::Threads;

/// What a query command gets: the mesh with its trees, and how long preparing them took
/// (building from a mesh, or validating and decoding a blob; file reading excluded).
pub struct Prepared {
    pub scene: MeshIndex,
    pub prepare_seconds: f64,
    /// True when the input was a blob (the time is its validation and decoding), false when
    /// a mesh file was built.
    pub from_blob: bool,
}

/// The preparation time under a name that says what it timed, for JSON summaries.
#[derive(serde::Serialize)]
pub struct PrepareTime {
    /// Building the structure from a mesh file (reading the file excluded).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub build_seconds: Option<f64>,
    /// Validating and decoding a blob (reading the file excluded).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub blob_load_seconds: Option<f64>,
}

impl PrepareTime {
    /// The time, whichever it was.
    pub fn seconds(&self) -> f64 {
        self.build_seconds.or(self.blob_load_seconds).unwrap_or(0.0)
    }
}

impl Prepared {
    /// [`PrepareTime`] for this input.
    pub fn time(&self) -> PrepareTime {
        let t = Some(self.prepare_seconds);
        if self.from_blob {
            PrepareTime {
                build_seconds: None,
                blob_load_seconds: t,
            }
        } else {
            PrepareTime {
                build_seconds: t,
                blob_load_seconds: None,
            }
        }
    }

    /// "built in" or "blob loaded in", for text summaries.
    pub fn verb(&self) -> &'static str {
        if self.from_blob {
            "blob loaded in"
        } else {
            "built in"
        }
    }
}
/// The input of a query command: what to query and how to prepare it.
#[derive(Args, Debug)]
pub struct QueryInput {
    /// A mesh file (OBJ, PLY, STL; built first) or a blob.
    pub input: PathBuf,
    /// The mesh of a blob baked with --no-mesh.
    #[arg(long)]
    pub mesh: Option<PathBuf>,
    #[command(flatten)]
    pub build: BuildChoice,
    /// The structure to build when INPUT is a mesh (default bvh). For a blob, the structure
    /// it must hold.
    #[arg(long, value_parser = structure_parser())]
    pub structure: Option<StructureKind>,
    /// Threads answering the queries: 1 (the default) on this thread; N spread over N threads
    /// (0: one per core). The records are the same whatever the count.
    #[arg(long, value_name = "N", default_value_t = 1,
          value_parser = clap::value_parser!(u16).range(0..=crate::threads::MAX_THREADS))]
    pub threads: u16,
    /// Quantize the BVH's four-wide nodes to 8-bit child boxes before querying: half the
    /// node memory, the same records (BVH only; counted in the preparation time).
    #[arg(long)]
    pub compact_nodes: bool,
    /// Collapse the BVH eight-wide before querying: fewer node visits per ray, the same
    /// records (BVH only; counted in the preparation time). The default on x86-64, AArch64
    /// and WebAssembly.
    #[arg(long, conflicts_with_all = ["compact_nodes", "four_wide"])]
    pub eight_wide: bool,
    /// Collapse the BVH four-wide before querying: fewer node bytes than eight-wide, the same
    /// records (BVH only; counted in the preparation time). The default only on targets
    /// without 128-bit SIMD.
    #[arg(long, conflicts_with = "compact_nodes")]
    pub four_wide: bool,
}

impl QueryInput {
    /// The files this input reads.
    pub fn paths(&self) -> Vec<&Path> {
        let mut paths = vec![self.input.as_path()];
        paths.extend(self.mesh.as_deref());
        paths
    }
}

/// Loads the input — a blob when the file starts with the blob magic, otherwise a mesh file
/// built with the chosen quality — and runs `query` on it.
pub fn with_structure<R>(
    args: &QueryInput,
    query: impl FnOnce(Prepared) -> Result<R>,
) -> Result<R> {
    let (compact, eight, four) = (args.compact_nodes, args.eight_wide, args.four_wide);
    let query = |prepared: Prepared| {
        query(if compact {
            relaid(prepared, "--compact-nodes", MeshBvh::with_compact_nodes)?
        } else if eight {
            relaid(prepared, "--eight-wide", MeshBvh::with_eight_wide_nodes)?
        } else if four {
            relaid(prepared, "--four-wide", MeshBvh::with_four_wide_nodes)?
        } else {
            prepared
        })
    };
    let (input, mesh, config) = (
        args.input.as_path(),
        args.mesh.as_deref(),
        &args.build.config(),
    );
    let bytes = std::fs::read(input).with_context(|| format!("cannot read {}", input.display()))?;
    if bytes.starts_with(&MAGIC) {
        check_blob_kind(&bytes, args.structure, input)?;
        let external = mesh.map(read_mesh).transpose()?;
        with_blob(&bytes, external.as_ref(), input, query)
    } else {
        if mesh.is_some() {
            bail!(
                "--mesh applies to blob inputs only; {} is a mesh file",
                input.display()
            );
        }
        let kind = args.structure.unwrap_or_default();
        let spatial = args.build.spatial()?;
        if spatial.is_some() && kind != StructureKind::Bvh {
            bail!("--spatial-splits applies to a BVH");
        }
        drop(bytes);
        let data = read_mesh(input)?;
        with_built(
            &data,
            input,
            kind,
            (config, spatial.as_ref()),
            &Threads::new(args.threads)?,
            query,
        )
    }
}

/// `prepared` with its BVH's query nodes laid out again by `relay` (`--compact-nodes`,
/// `--eight-wide`, named by `flag`), the time added.
fn relaid(
    prepared: Prepared,
    flag: &str,
    relay: impl FnOnce(MeshBvh) -> Result<MeshBvh, meshq::error::BuildError>,
) -> Result<Prepared> {
    let start = Instant::now();
    let scene = match prepared.scene {
        MeshIndex::Bvh(bvh) => MeshIndex::Bvh(relay(bvh)?),
        other => bail!("{flag} applies to a BVH, not a {}", other.kind()),
    };
    Ok(Prepared {
        scene,
        prepare_seconds: prepared.prepare_seconds + start.elapsed().as_secs_f64(),
        from_blob: prepared.from_blob,
    })
}

/// Refuses a blob that holds another structure than `--structure` names.
pub fn check_blob_kind(
    bytes: &[u8],
    wanted: Option<StructureKind>,
    input: &std::path::Path,
) -> Result<()> {
    let Some(wanted) = wanted else {
        return Ok(());
    };
    let header =
        BlobHeader::read(bytes).with_context(|| format!("{}: invalid blob", input.display()))?;
    if header.kind != wanted {
        bail!(
            "{} is a blob holding a {}, not a {wanted}; bake it with --structure {wanted}",
            input.display(),
            header.kind
        );
    }
    Ok(())
}

/// Builds a structure of `kind` over `data`, read from `path` (a BVH with `config`, the others with their default
/// configs) and runs `query`.
pub fn with_built<R>(
    data: &MeshData,
    path: &Path,
    kind: StructureKind,
    (config, spatial): (&BuildConfig, Option<&SpatialSplits>),
    threads: &Threads,
    query: impl FnOnce(Prepared) -> Result<R>,
) -> Result<R> {
    let mesh = MeshRef::new(&data.positions, &data.triangles)
        .validate()
        .with_context(|| format!("{}: invalid mesh", path.display()))?;
    let start = Instant::now();
    let scene = match kind {
        StructureKind::Bvh => MeshIndex::Bvh(threads.build_bvh(&mesh, config, spatial)?),
        other => MeshIndex::build(&mesh, other)?,
    };
    let prepare_seconds = start.elapsed().as_secs_f64();
    query(Prepared {
        scene,
        prepare_seconds,
        from_blob: false,
    })
}

/// Validates a blob, decodes it into RAM and runs `query`.
fn with_blob<R>(
    bytes: &[u8],
    external: Option<&MeshData>,
    input: &Path,
    query: impl FnOnce(Prepared) -> Result<R>,
) -> Result<R> {
    let start = Instant::now();
    let scene = (|| -> Result<MeshIndex> {
        Ok(match external {
            Some(data) => {
                let mesh = MeshRef::new(&data.positions, &data.triangles)
                    .validate()
                    .context("the mesh given with --mesh is invalid")?;
                MeshIndex::from_blob_with_mesh(bytes, &mesh)?
            }
            None => MeshIndex::from_blob(bytes).map_err(|e| match e {
                BlobError::MeshNotIncluded => anyhow!("{e} (pass it with --mesh)"),
                e => e.into(),
            })?,
        })
    })()
    .with_context(|| format!("{}: cannot use blob", input.display()))?;
    let prepare_seconds = start.elapsed().as_secs_f64();
    query(Prepared {
        scene,
        prepare_seconds,
        from_blob: true,
    })
}
