//! The mesh file loaders of the `meshq` command, as a library so that the fuzz target
//! (`fuzz/fuzz_targets/mesh_load.rs`) runs exactly the code the command does.

pub mod mesh_file;
mod ply_limits;
mod stl_binary;
