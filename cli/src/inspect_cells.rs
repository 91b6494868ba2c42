//! `meshq inspect` on a blob holding a k-d tree, octree or grid: its config and cell figures.

use crate::output::say;
use meshq::advanced::BlobHeader;
use meshq::blob::{BlobStructure, StructureConfig};
use serde::Serialize;

/// What a cell-structure blob holds.
#[derive(Serialize)]
pub struct CellBlobReport {
    format_version: u16,
    structure: String,
    mesh_layout: String,
    triangles: u32,
    vertices: u32,
    /// Tree nodes (0 for a grid).
    nodes: usize,
    cells: usize,
    empty_cells: usize,
    references: usize,
    references_per_triangle: f64,
    /// The deepest leaf (the root is 0; a grid is 0).
    max_depth: usize,
    max_cell_references: usize,
    bounds_min: [f32; 3],
    bounds_max: [f32; 3],
    /// The build settings as `name = value` pairs, in the config's field order.
    config: Vec<(String, String)>,
    bytes: usize,
    bytes_per_triangle: f64,
    mesh_checksum: String,
    checksum: String,
}

/// The report of a validated cell-structure blob of `total` bytes.
pub fn cell_blob_report(
    h: &BlobHeader,
    structure: &BlobStructure<'_>,
    total: usize,
) -> CellBlobReport {
    let stats = structure
        .cell_stats(h.triangle_count as usize)
        .unwrap_or_default();
    CellBlobReport {
        format_version: h.version,
        structure: h.kind.to_string(),
        mesh_layout: h.mesh.name().to_owned(),
        triangles: h.triangle_count,
        vertices: h.vertex_count,
        nodes: stats.nodes,
        cells: stats.cells,
        empty_cells: stats.empty_cells,
        references: stats.references,
        references_per_triangle: stats.references_per_triangle(),
        max_depth: stats.max_depth,
        max_cell_references: stats.max_cell_references,
        bounds_min: h.bounds.min.to_array(),
        bounds_max: h.bounds.max.to_array(),
        config: config_pairs(&h.config),
        bytes: total,
        bytes_per_triangle: if h.triangle_count > 0 {
            total as f64 / f64::from(h.triangle_count)
        } else {
            0.0
        },
        mesh_checksum: format!("{:08x}", h.mesh_checksum),
        checksum: format!("{:08x}", h.checksum),
    }
}

fn config_pairs(config: &StructureConfig) -> Vec<(String, String)> {
    let pair = |k: &str, v: String| (k.to_owned(), v);
    match config {
        StructureConfig::KdTree(c) => vec![
            pair("max_depth", c.max_depth.to_string()),
            pair("leaf_size", c.leaf_size.to_string()),
            pair("traversal_cost", c.traversal_cost.to_string()),
            pair("triangle_cost", c.triangle_cost.to_string()),
            pair("empty_bonus", c.empty_bonus.to_string()),
        ],
        StructureConfig::Octree(c) => vec![
            pair("max_depth", c.max_depth.to_string()),
            pair("max_items", c.max_items.to_string()),
        ],
        StructureConfig::Grid { config, resolution } => vec![
            pair("cells_per_triangle", config.cells_per_triangle.to_string()),
            pair("max_resolution", config.max_resolution.to_string()),
            pair(
                "resolution",
                format!("{}x{}x{}", resolution[0], resolution[1], resolution[2]),
            ),
        ],
        _ => Vec::new(),
    }
}

pub fn print_cell_blob(r: &CellBlobReport) -> anyhow::Result<()> {
    say!(
        "meshq blob, format version {}: {} with mesh {}",
        r.format_version,
        r.structure,
        r.mesh_layout
    );
    say!(
        "  {} triangles, {} vertices, {} nodes, {} cells ({} empty), depth {}",
        r.triangles,
        r.vertices,
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
    say!("  bounds {:?} .. {:?}", r.bounds_min, r.bounds_max);
    let settings: Vec<String> = r.config.iter().map(|(k, v)| format!("{k} {v}")).collect();
    say!("  built with {}", settings.join(", "));
    say!(
        "  {} bytes ({:.1} per triangle)",
        r.bytes,
        r.bytes_per_triangle
    );
    say!("  checksums: blob {}, mesh {}", r.checksum, r.mesh_checksum);
    Ok(())
}
