//! `meshq inspect`: what a blob holds, after full validation of its structure; or, for a mesh
//! file, the shape of the structure `--structure` builds over it.

use std::path::PathBuf;

use std::time::Instant;

use anyhow::{Context, Result, bail};
use clap::Args;
use meshq::advanced::{BlobHeader, LEAF_HISTOGRAM_LEN, MAGIC, TreeStats};
use meshq::blob::{BlobStructure, BlobTree};
use meshq::bvh::{BuildConfig, SplitStrategy};
use meshq::error::BlobError;
use meshq::mesh::MeshRef;
use meshq::owned::{MeshIndex, StructureKind};
use serde::Serialize;

use crate::inspect_cells::{cell_blob_report, print_cell_blob};
use crate::mesh_file::read_mesh;
use crate::output;
use crate::output::say;
use crate::structure::check_blob_kind;
use crate::structure_arg::structure_parser;

#[derive(Args, Debug)]
#[command(after_help = "Examples:\n  \
    meshq inspect bunny.meshq\n  \
    meshq inspect spot.meshq --structure octree --json")]
pub struct InspectArgs {
    /// The blob, or a mesh file (OBJ, PLY, STL) to build a structure over.
    pub blob: PathBuf,
    /// For a mesh file: the structure to build and describe (default bvh). For a blob: the
    /// structure it must hold.
    #[arg(long, value_parser = structure_parser())]
    pub structure: Option<StructureKind>,
    /// Print everything as one JSON object.
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize)]
struct Report {
    format_version: u16,
    structure: String,
    mesh_layout: String,
    triangles: u32,
    vertices: u32,
    nodes: u32,
    leaves: usize,
    /// Leaf slots: the triangle count, more with spatial splits.
    references: u32,
    /// Entries of the split references (spatial splits; 0 otherwise).
    split_refs: u32,
    depth: u32,
    bounds_min: [f32; 3],
    bounds_max: [f32; 3],
    config: Config,
    sah_cost: f64,
    /// `[leaf size, leaves]` pairs for every size that occurs.
    leaf_sizes: Vec<[usize; 2]>,
    bytes: Bytes,
    mesh_checksum: String,
    checksum: String,
}

#[derive(Serialize)]
struct Config {
    /// `"sah"`, `"centre"` or `"sweep"`.
    split: &'static str,
    /// The sweep's step (triangles between weighed cuts); absent for the other strategies.
    #[serde(skip_serializing_if = "Option::is_none")]
    sweep_step: Option<u32>,
    bins: u32,
    max_leaf_size: u32,
    max_depth: u32,
    traversal_cost: f32,
    triangle_cost: f32,
}

#[derive(Serialize)]
struct Bytes {
    total: usize,
    header: usize,
    nodes: usize,
    order: usize,
    split_refs: usize,
    /// The collapse roles (version 5: two bits per node; 0 before).
    collapse_plan: usize,
    /// The winding-number expansions (version 6: 112 bytes per node when stored; 0 otherwise).
    winding: usize,
    mesh: usize,
    per_triangle: f64,
}

pub fn run(args: &InspectArgs) -> Result<()> {
    let bytes = std::fs::read(&args.blob)
        .with_context(|| format!("cannot read {}", args.blob.display()))?;
    if !bytes.starts_with(&MAGIC) {
        drop(bytes);
        return inspect_mesh(args);
    }
    check_blob_kind(&bytes, args.structure, &args.blob)?;
    let (header, structure) = BlobStructure::parse(&bytes)
        .with_context(|| format!("{}: invalid blob", args.blob.display()))?;
    // What the loaders check besides the structure (the stored mesh's references and bounds,
    // the mesh checksum, the order as a permutation): a blob every loader refuses is not
    // described as if it were fine. A blob without its mesh has nothing more to check.
    match MeshIndex::from_blob(&bytes) {
        Ok(_) | Err(BlobError::MeshNotIncluded) => {}
        Err(e) => {
            return Err(e).with_context(|| format!("{}: invalid blob", args.blob.display()));
        }
    }
    let (BlobStructure::Bvh(tree), Some(config)) = (structure, header.config.bvh()) else {
        let report = cell_blob_report(&header, &structure, bytes.len());
        if args.json {
            return output::json(&report);
        }
        return print_cell_blob(&report);
    };
    let report = report(&header, &tree, config, bytes.len());
    if args.json {
        return output::json(&report);
    }
    print(&report)
}

fn report(h: &BlobHeader, tree: &BlobTree<'_>, config: &BuildConfig, total: usize) -> Report {
    let stats = TreeStats::of(tree, config);
    let nodes = 32 * h.node_count as usize;
    let order = 4 * h.reference_count as usize;
    let split_refs = meshq::advanced::SPLIT_REF_BYTES * h.split_ref_count as usize;
    let collapse_plan = tree.collapse_roles().map_or(0, |r| r.bytes().len());
    let winding = tree
        .winding_nodes()
        .map_or(0, |w| 112 * meshq::inside::WindingNodes::count(&w));
    let leaf_sizes = (0..LEAF_HISTOGRAM_LEN)
        .filter_map(|k| {
            let n = *stats.leaf_sizes.get(k)?;
            (n > 0).then_some([k, n])
        })
        .collect();
    Report {
        format_version: h.version,
        structure: h.kind.to_string(),
        mesh_layout: h.mesh.name().to_owned(),
        triangles: h.triangle_count,
        vertices: h.vertex_count,
        nodes: h.node_count,
        leaves: stats.leaves,
        references: h.reference_count,
        split_refs: h.split_ref_count,
        depth: h.depth,
        bounds_min: h.bounds.min.to_array(),
        bounds_max: h.bounds.max.to_array(),
        config: Config {
            split: config.split.name(),
            sweep_step: match config.split {
                SplitStrategy::Sweep { step } => Some(step),
                _ => None,
            },
            bins: config.bins,
            max_leaf_size: config.max_leaf_size,
            max_depth: config.max_depth,
            traversal_cost: config.traversal_cost,
            triangle_cost: config.triangle_cost,
        },
        sah_cost: stats.sah_cost,
        leaf_sizes,
        bytes: Bytes {
            total,
            header: h.header_len,
            nodes,
            order,
            split_refs,
            collapse_plan,
            winding,
            // Everything else, with the varint lengths of the sequences.
            mesh: total.saturating_sub(
                h.header_len + nodes + order + split_refs + collapse_plan + winding,
            ),
            per_triangle: if h.triangle_count > 0 {
                total as f64 / f64::from(h.triangle_count)
            } else {
                0.0
            },
        },
        mesh_checksum: format!("{:08x}", h.mesh_checksum),
        checksum: format!("{:08x}", h.checksum),
    }
}

fn print(r: &Report) -> Result<()> {
    say!(
        "meshq blob, format version {}: {} with mesh {}",
        r.format_version,
        r.structure,
        r.mesh_layout
    );
    say!(
        "  {} triangles, {} vertices, {} nodes ({} leaves), depth {}",
        r.triangles,
        r.vertices,
        r.nodes,
        r.leaves,
        r.depth
    );
    if r.split_refs > 0 {
        say!(
            "  spatial splits: {} references ({} split references)",
            r.references,
            r.split_refs
        );
    }
    say!("  bounds {:?} .. {:?}", r.bounds_min, r.bounds_max);
    let c = &r.config;
    if c.split == "centre" {
        say!(
            "  built with centre splits, leaves up to {}, max depth {}",
            c.max_leaf_size,
            c.max_depth
        );
    } else if let Some(step) = c.sweep_step {
        say!(
            "  built with sweep SAH: a cut weighed every {} triangles, leaves up to {}, max depth {}, costs traversal {} / triangle {}",
            step,
            c.max_leaf_size,
            c.max_depth,
            c.traversal_cost,
            c.triangle_cost
        );
    } else {
        say!(
            "  built with binned SAH: {} bins, leaves up to {}, max depth {}, costs traversal {} / triangle {}",
            c.bins,
            c.max_leaf_size,
            c.max_depth,
            c.traversal_cost,
            c.triangle_cost
        );
    }
    say!("  SAH cost {:.2}", r.sah_cost);
    let sizes: Vec<String> = r
        .leaf_sizes
        .iter()
        .map(|[size, n]| format!("{size}: {n}"))
        .collect();
    say!("  leaf sizes (triangles: leaves) {}", sizes.join(", "));
    let b = &r.bytes;
    say!(
        "  {} bytes ({:.1} per triangle): header {}, nodes {}, order {}, {}{}{}mesh {}",
        b.total,
        b.per_triangle,
        b.header,
        b.nodes,
        b.order,
        if b.split_refs > 0 {
            format!("split references {}, ", b.split_refs)
        } else {
            String::new()
        },
        if b.collapse_plan > 0 {
            format!("collapse plan {}, ", b.collapse_plan)
        } else {
            String::new()
        },
        if b.winding > 0 {
            format!("winding-number expansions {}, ", b.winding)
        } else {
            String::new()
        },
        b.mesh
    );
    say!("  checksums: blob {}, mesh {}", r.checksum, r.mesh_checksum);
    Ok(())
}

/// The shape of a structure built over a mesh file.
#[derive(Serialize)]
struct StructureReport {
    structure: String,
    triangles: usize,
    build_seconds: f64,
    /// Nodes (BVH: binary nodes; grid: 0).
    nodes: usize,
    /// Leaf cells (k-d tree, octree, grid) or leaves (BVH).
    cells: usize,
    empty_cells: usize,
    references: usize,
    references_per_triangle: f64,
    max_depth: usize,
    max_cell_references: usize,
}

fn inspect_mesh(args: &InspectArgs) -> Result<()> {
    let data = read_mesh(&args.blob)?;
    let mesh = MeshRef::new(&data.positions, &data.triangles)
        .validate()
        .with_context(|| format!("{}: invalid mesh", args.blob.display()))?;
    let kind = args.structure.unwrap_or_default();
    let start = Instant::now();
    let index = MeshIndex::build(&mesh, kind)?;
    let build_seconds = start.elapsed().as_secs_f64();
    let n = mesh.triangle_count();
    let report = match (&index, index.cell_stats()) {
        (MeshIndex::Bvh(s), _) => {
            let stats = TreeStats::of(&s.bvh(), s.config());
            StructureReport {
                structure: kind.to_string(),
                triangles: n,
                build_seconds,
                nodes: stats.nodes,
                cells: stats.leaves,
                empty_cells: 0,
                references: n,
                references_per_triangle: if n > 0 { 1.0 } else { 0.0 },
                max_depth: s.bvh().depth() as usize,
                max_cell_references: stats.leaf_sizes.iter().rposition(|&c| c > 0).unwrap_or(0),
            }
        }
        (_, Some(c)) => StructureReport {
            structure: kind.to_string(),
            triangles: n,
            build_seconds,
            nodes: c.nodes,
            cells: c.cells,
            empty_cells: c.empty_cells,
            references: c.references,
            references_per_triangle: c.references_per_triangle(),
            max_depth: c.max_depth,
            max_cell_references: c.max_cell_references,
        },
        (_, None) => bail!("no figures for {kind}"),
    };
    if args.json {
        return output::json(&report);
    }
    let r = &report;
    say!(
        "{} over {} ({} triangles), built in {:.1} ms",
        r.structure,
        args.blob.display(),
        r.triangles,
        r.build_seconds * 1e3
    );
    say!(
        "  {} nodes, {} cells ({} empty), depth {}",
        r.nodes,
        r.cells,
        r.empty_cells,
        r.max_depth
    );
    say!(
        "  {} references ({:.2} per triangle), at most {} in one cell",
        r.references,
        r.references_per_triangle,
        r.max_cell_references
    );
    Ok(())
}
