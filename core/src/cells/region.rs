//! What a walk through cells remembers of the cell it is in: the cell itself, for visitors that
//! need it, or nothing at all, so a ray walk that never reads cells does not compute them.

use crate::math::Aabb;
use crate::query::Cell;

/// The cell a walk is in, as far as the visitor needs to know it.
pub(crate) trait Region: Copy {
    /// The whole structure's cell, with box `aabb`.
    fn root(aabb: Aabb) -> Self;

    /// The two halves of this cell at `at` along `axis` (below, above), as [`Cell::split`].
    fn split(&self, axis: usize, at: f32) -> (Self, Self);

    /// The cell, when tracked.
    fn cell(&self) -> Option<Cell>;
}

impl Region for Cell {
    #[inline(always)]
    fn root(aabb: Aabb) -> Self {
        Self::root(aabb)
    }

    #[inline(always)]
    fn split(&self, axis: usize, at: f32) -> (Self, Self) {
        Self::split(self, axis, at)
    }

    #[inline(always)]
    fn cell(&self) -> Option<Cell> {
        Some(*self)
    }
}

/// No cell tracked: for visitors whose [`needs_cells`](crate::query::VisitorHints::needs_cells) hint is
/// false.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Untracked;

impl Region for Untracked {
    #[inline(always)]
    fn root(_: Aabb) -> Self {
        Self
    }

    #[inline(always)]
    fn split(&self, _: usize, _: f32) -> (Self, Self) {
        (Self, Self)
    }

    #[inline(always)]
    fn cell(&self) -> Option<Cell> {
        None
    }
}
