//! Shared helpers for meshq's integration tests and benchmarks: the bundled meshes, the
//! workloads of DESIGN.md (random rays, camera rays, closest-point queries) from a seeded
//! integer generator, owned BVH buffers, and brute-force oracles that scan every triangle with
//! the public primitive tests.

pub mod assets;
pub mod oracle;
pub mod owned;
pub mod workload;

pub use assets::{LoadedMesh, MESHES, load_mesh, load_obj};
pub use meshq_workload::SplitMix64;
pub use owned::{OwnedBvh, bake, encode};
