//! Isotropic remeshing in caller buffers (Botsch and Kobbelt 2004): triangles of one target
//! edge length, valences near 6, on the input's surface.
//!
//! The remesher works on a [`HalfEdgeMesh`]: the input's triangles as half-edges in buffers
//! the caller owns, built only from a manifold, consistently oriented mesh. Anything else is
//! refused with a [`RemeshError`](crate::error::RemeshError) naming the edge or vertex at
//! fault, so a scan with a branching edge or a bow-tie vertex is reported, not remeshed into
//! something worse. [`remesh`] then runs the iterations in place, projecting onto the input
//! through any [`MeshQuery`](crate::query::MeshQuery) (a BVH over the input).

mod capacity;
mod check;
mod config;
mod creases;
mod edit;
mod flips;
pub(crate) mod half_edge_edits;
mod half_edges;
mod moves;
mod quality;
mod relax;
mod remesher;
mod report;
mod shape;
mod smooth;
mod surface;

pub use capacity::RemeshCapacity;
#[cfg(feature = "alloc")]
pub use capacity::RemeshStorage;
pub use check::HalfEdgeDefect;
pub use config::{EdgeTarget, RemeshConfig};
pub use half_edges::{HalfEdgeBuffers, HalfEdgeMesh};
pub use quality::MeshQuality;
#[cfg(feature = "alloc")]
pub(crate) use remesher::remesh_with_progress;
pub use remesher::{remesh, remesh_observed};
pub use report::{RemeshObserver, RemeshReport, RemeshStep};
