//! Borrowed triangle meshes and their validation.
//!
//! A [`MeshRef`] borrows positions and triangle indices (as arrays of triples or, without
//! copying, as the flat buffers three.js uses) and is never mutated. [`MeshRef::validate`] checks
//! every index and coordinate once and returns a [`ValidMesh`], the only form the structures
//! accept, so no query ever re-checks its input.

mod mesh_ref;
mod valid_mesh;

pub use mesh_ref::MeshRef;
#[cfg(feature = "blob")]
pub(crate) use mesh_ref::{check_triangle, check_vertex};
pub use valid_mesh::ValidMesh;

pub use crate::math::MAX_COORDINATE;
