//! The uniform grid: the mesh bounds cut into about `λ · N` equal cells, each listing the
//! triangles it touches.
//!
//! - [`GridConfig`]: λ (cells per triangle) and the per-axis cap.
//! - [`GridLayout`]: the cells' geometry; [`Grid::measure`] the exact buffer sizes;
//!   [`Grid::build`] the counting-sort build into caller buffers, coarsening until it fits.
//! - [`Grid`]: the built grid, answering every query of the [query layer](crate::query): rays
//!   by Amanatides–Woo 3D-DDA with early exit, the rest best-first over halved cell ranges.
//!
//! A grid builds in a few linear passes and marches rays cheaply through evenly spread
//! geometry; with uneven geometry (a small detailed object in a large empty scene) most cells
//! are empty and the few full ones hold many triangles each.
//!
//! ```
//! use meshq::prelude::*;
//! use meshq::grid::{Grid, GridConfig};
//! # let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
//! # let triangles = [[0u32, 1, 2]];
//! let mesh = MeshRef::new(&positions, &triangles).validate()?;
//! let sizes = Grid::measure(&mesh, &GridConfig::default())?;
//! let (mut offsets, mut items) = (vec![0; sizes.offsets], vec![0; sizes.items]);
//! let grid = Grid::build(&mesh, &GridConfig::default(), &mut offsets, &mut items)?;
//! let hit = grid.with(&mesh).raycast(&Ray::new(Vec3::new(0.25, 0.25, 1.0), -Vec3::Z));
//! assert_eq!(hit.map(|h| h.tri), Some(0));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod build;
mod check;
mod config;
pub(crate) mod layout;
mod traverse;
mod tree;

pub use build::GridSizes;
#[cfg(feature = "alloc")]
pub(crate) use build::{for_each_cell, layout_within, reference_budget};
pub use config::GridConfig;
pub(crate) use layout::GridLayout;
pub use tree::Grid;
