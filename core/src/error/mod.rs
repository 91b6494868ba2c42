//! One error type per stage. All are `#[non_exhaustive]`, `Copy`, carry small integer payloads,
//! implement `Display` and `core::error::Error`, and document when they happen and how to fix
//! them.

mod batch;
#[cfg(feature = "blob")]
mod blob;
mod build;
mod collide;
mod mesh;
mod remesh;
mod structure;
mod sweep;
mod transform;

pub use batch::{BatchBuffer, BatchError};
#[cfg(feature = "blob")]
pub use blob::{BlobError, BlobSection};
pub use build::{BufferKind, BuildError};
pub use collide::PairBudgetSpent;
pub use mesh::{FlatSlice, MeshError};
pub use remesh::{RemeshBuffer, RemeshError};
pub use structure::StructureError;
pub use sweep::SweepError;
pub use transform::TransformError;
