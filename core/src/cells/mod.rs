//! What the structures that cut space into cells share — the [k-d tree](crate::kdtree), the
//! [octree](crate::octree) and the [grid](crate::grid): which cells reference a triangle, how a
//! cell's triangles are offered to a query, packed triangles per reference, and the figures
//! `inspect` prints.
//!
//! A triangle is referenced from every cell it touches, so references outnumber triangles and
//! their count is only known once the cells are cut. Each structure therefore gives an exact
//! sizing pass and a builder that stays within the buffers it is handed. On geometry no cut
//! separates (copies of one triangle, slivers all crossing one point, triangles spanning the
//! whole box), cells would multiply references without end: the owned builds and
//! [`Grid::measure`](crate::grid::Grid::measure) stop refining at
//! [`REFERENCES_PER_TRIANGLE`] references per triangle.

/// The most references per triangle the owned cell builds (`owned::MeshCells`, feature `alloc`)
/// and [`Grid::measure`](crate::grid::Grid::measure) make: past it a k-d tree or octree keeps
/// its remaining cells as leaves, and a grid takes coarser cells (down to one). Ordinary meshes
/// need 2 to 6; the bound only binds on geometry cells cannot separate, and keeps time and
/// memory linear in the triangle count there.
pub const REFERENCES_PER_TRIANGLE: usize = 32;

mod cell_walk;
mod check;
#[cfg(feature = "blob-cells")]
mod coverage;
mod mailbox;
mod offer;
pub(crate) mod pack;
mod reference;
mod region;
mod sizes;
mod stats;
mod tree_build;
pub(crate) mod words;

pub(crate) use cell_walk::{CellNode, CellTree, for_each_cell, stats};
pub(crate) use check::{Visits, first_bad_reference};
#[cfg(feature = "blob-cells")]
pub(crate) use coverage::{Coverage, CoverageMesh, Held, first_uncovered_in_tree};
pub(crate) use mailbox::Mailbox;
pub(crate) use offer::Offer;
pub(crate) use reference::ReferencePad;
pub(crate) use region::{Region, Untracked};
pub use sizes::TreeSizes;

pub use stats::CellStats;
pub(crate) use tree_build::{Decision, MAX_ARITY, Splitter, build_tree};
#[cfg(feature = "blob")]
pub(crate) use words::LeWords;
pub(crate) use words::{TwoWordNode, Words};
