//! Every integration test over real meshes, in one test binary: each file of this folder is
//! one module. One binary links and instantiates the core's generic walks once, where a binary
//! per file compiled and linked them 31 times over. Run one file's tests by its module name:
//! `cargo test -p meshq-tests --test integration eight_wide::`.

mod blob_corruption;
mod blob_round_trip;
mod cell_blobs;
mod cell_structures;
mod closest_point_vs_brute_force;
mod collapse_plan;
mod collapse_roles;
mod collide;
mod compact_nodes;
mod degenerate_builds;
mod degenerate_pairs;
mod doc_links;
mod edge_cases;
mod eight_wide;
mod exact_self_intersection;
mod geom_properties;
mod large_trees;
mod mesh_distance;
mod mesh_index;
mod module_layering;
mod overlap_and_refit;
mod parallel;
mod parity_golden;
mod query_layer;
mod raycast_ties;
mod raycast_vs_brute_force;
mod remesh;
mod remesh_creases;
mod remesh_distance;
mod remesh_golden;
mod remesh_hard_inputs;
mod remesh_invariants;
mod remesh_topology;
mod sorted_batches;
mod spatial_splits;
mod structure;
mod sweeps;
mod watertight;
mod wide_structure;
mod winding_numbers;

/// With `autotests = false` a file of this folder runs only if it is declared above: every `.rs`
/// file here but this one and `lanes.rs` (another binary's root) must be, or a new test file
/// would be skipped without a word.
#[test]
fn every_test_file_is_a_module() {
    let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let declared = include_str!("main.rs");
    let mut missing = Vec::new();
    for entry in std::fs::read_dir(&folder).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        if let Some(stem) = name.strip_suffix(".rs")
            && stem != "main"
            && stem != "lanes"
            && !declared.lines().any(|l| l == format!("mod {stem};"))
        {
            missing.push(name);
        }
    }
    assert!(
        missing.is_empty(),
        "not declared in tests/tests/main.rs: {missing:?}"
    );
}
