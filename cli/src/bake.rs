//! `meshq bake`: a mesh file in, a blob out.

use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context, Result};
use clap::Args;
use meshq::blob::MeshLayout;
use meshq::mesh::MeshRef;
use meshq::owned::{MeshIndex, StructureKind};
use serde::Serialize;

use crate::atomic::AtomicFile;
use crate::mesh_file::read_mesh;
use crate::output::say;
use crate::quality::BuildChoice;
use crate::structure_arg::structure_parser;
use crate::threads::Threads;
use crate::{output, progress};

#[derive(Args, Debug)]
#[command(after_help = "Examples:\n  \
    meshq bake assets/stanford-bunny.obj -o bunny.meshq\n  \
    meshq bake assets/spot.obj -o spot.meshq --structure octree --packed --json\n  \
    meshq bake big-scan.ply -o big-scan.meshq --threads 0")]
pub struct BakeArgs {
    /// The mesh: OBJ, PLY or STL (polygons are fan-triangulated; vt/vn are ignored).
    pub mesh: PathBuf,
    /// Where to write the blob.
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
    /// The acceleration structure.
    #[arg(long, value_parser = structure_parser(), default_value = "bvh")]
    pub structure: StructureKind,
    #[command(flatten)]
    pub build: BuildChoice,
    /// Leave the mesh out (the reader supplies it; it is matched by checksum).
    #[arg(long, conflicts_with = "packed")]
    pub no_mesh: bool,
    /// Store triangles as corners in leaf order (36 bytes per triangle; per reference for the
    /// cell structures) for the fastest queries in place, instead of positions and indices.
    #[arg(long)]
    pub packed: bool,
    /// Store the winding-number expansions too (BVH only; 112 bytes per node), so that
    /// `meshq inside`, `meshq sdf`, `meshq closest --signed` and in-place readers (firmware, a
    /// `BlobView`) answer containment and signed distance without working them out.
    #[arg(long)]
    pub winding: bool,
    /// Threads building a BVH: 1 (the default), N, or 0 for one per core. The blob is the
    /// same, byte for byte, whatever the count.
    #[arg(long, value_name = "N", default_value_t = 1,
          value_parser = clap::value_parser!(u16).range(0..=crate::threads::MAX_THREADS))]
    pub threads: u16,
    /// Print the figures as one JSON object.
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize)]
struct Summary {
    structure: &'static str,
    triangles: usize,
    vertices: usize,
    nodes: usize,
    /// Triangle references in leaves (a BVH references each triangle once, a split triangle
    /// of a BVH with spatial splits once per leaf holding a part of it).
    references: usize,
    /// BVH: levels; k-d tree and octree: the deepest leaf (root 0); grid: 0.
    depth: u32,
    mesh_layout: &'static str,
    /// Whether the winding-number expansions are stored.
    winding: bool,
    build_seconds: f64,
    encode_seconds: f64,
    bytes: usize,
    bytes_per_triangle: f64,
}

pub fn run(args: &BakeArgs) -> Result<()> {
    crate::atomic::refuse_inputs(&args.output, &[&args.mesh])?;
    let spinner = progress::spinner("reading mesh");
    let data = read_mesh(&args.mesh)?;
    let mesh = MeshRef::new(&data.positions, &data.triangles)
        .validate()
        .with_context(|| format!("{}: invalid mesh", args.mesh.display()))?;
    let config = args.build.config();
    let spatial = args.build.spatial()?;
    if spatial.is_some() && args.structure != StructureKind::Bvh {
        anyhow::bail!("--spatial-splits applies to a BVH");
    }
    if args.winding && args.structure != StructureKind::Bvh {
        anyhow::bail!("--winding applies to a BVH (the expansions are per BVH node)");
    }
    let threads = Threads::new(args.threads)?;
    let n = mesh.triangle_count();
    let kind = args.structure;
    spinner.set_message(format!("building a {kind} over {n} triangles"));
    let start = Instant::now();
    let scene = match kind {
        StructureKind::Bvh => {
            let bvh = threads.build_bvh(&mesh, &config, spatial.as_ref())?;
            MeshIndex::Bvh(if args.winding {
                spinner.set_message("working out the winding-number expansions");
                bvh.with_winding_numbers()?
            } else {
                bvh
            })
        }
        other => MeshIndex::build(&mesh, other)?,
    };
    let build_seconds = start.elapsed().as_secs_f64();

    spinner.set_message("encoding");
    let layout = match (args.no_mesh, args.packed) {
        (true, _) => MeshLayout::Omitted,
        (false, true) => MeshLayout::Packed,
        (false, false) => MeshLayout::Indexed,
    };
    let start = Instant::now();
    let bytes = scene.to_blob(layout)?;
    let len = bytes.len();
    let encode_seconds = start.elapsed().as_secs_f64();
    spinner.set_message("writing");
    let mut file = AtomicFile::create(&args.output, &[&args.mesh])?;
    file.write_all(&bytes)
        .with_context(|| format!("cannot write {}", args.output.display()))?;
    file.commit()?;
    spinner.finish_and_clear();

    let (nodes, references, depth) = match (&scene, scene.cell_stats()) {
        (MeshIndex::Bvh(s), _) => (s.bvh().nodes().len(), s.reference_count(), s.bvh().depth()),
        (_, Some(c)) => (
            c.nodes,
            c.references,
            u32::try_from(c.max_depth).unwrap_or(u32::MAX),
        ),
        (_, None) => (0, 0, 0),
    };
    let summary = Summary {
        structure: kind.name(),
        triangles: n,
        vertices: mesh.vertex_count(),
        nodes,
        references,
        depth,
        mesh_layout: layout.name(),
        winding: args.winding,
        build_seconds,
        encode_seconds,
        bytes: len,
        bytes_per_triangle: if n > 0 { len as f64 / n as f64 } else { 0.0 },
    };
    if args.json {
        return output::json(&summary);
    }
    say!("baked {} -> {}", args.mesh.display(), args.output.display());
    say!(
        "  {}: {} triangles, {} vertices, {} nodes, {} references, depth {}, mesh {}{}",
        summary.structure,
        summary.triangles,
        summary.vertices,
        summary.nodes,
        summary.references,
        summary.depth,
        summary.mesh_layout,
        if args.winding {
            ", winding-number expansions"
        } else {
            ""
        }
    );
    say!(
        "  build {:.1} ms, encode {:.1} ms, {} bytes ({:.1} bytes/triangle)",
        build_seconds * 1e3,
        encode_seconds * 1e3,
        summary.bytes,
        summary.bytes_per_triangle
    );
    Ok(())
}
