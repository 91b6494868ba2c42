//! The suites whose answers depend on how the CPU runs SIMD lanes — the wide trees, the query
//! layer, ray casts against brute force, spatial splits, large trees, blobs — in a binary of
//! their own, so that CI can build them again for another CPU (x86-64-v3, where eight lanes are
//! one AVX2 instruction) without compiling every suite a second time. `cargo test` leaves this
//! binary out (`test = false`): the integration binary runs the same modules.

mod blob_corruption;
mod blob_round_trip;
mod compact_nodes;
mod eight_wide;
mod large_trees;
mod query_layer;
mod raycast_vs_brute_force;
mod spatial_splits;
