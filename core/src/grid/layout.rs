//! Where a grid's cells are: its bounds cut into `nx × ny × nz` equal cells.

use core::ops::ControlFlow;

use glam::Vec3;

use crate::cells::ReferencePad;
use crate::math::{Aabb, Triangle, max_f32};
use crate::query::Cell;

/// A grid's geometry: the box it covers and its resolution. Cell `(i, j, k)` has index
/// `i + nx · (j + ny · k)`; its box runs between the cell boundaries
/// [`boundary`](Self::boundary)`(axis, i)` and `boundary(axis, i + 1)` on each axis, so
/// neighbouring cells share their faces exactly.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridLayout {
    /// The box the cells cover (the mesh bounds).
    pub bounds: Aabb,
    /// Cells along x, y and z, each at least 1.
    pub resolution: [u32; 3],
}

impl GridLayout {
    /// Calls `each(cell index)` for every cell `t` touches (cells padded by `pad`, as a build
    /// decides which cells list a triangle), in ascending index order, until `each` breaks
    /// (what it then returns).
    pub(crate) fn for_each_cell_touched(
        &self,
        pad: ReferencePad,
        t: &Triangle,
        mut each: impl FnMut(usize) -> ControlFlow<()>,
    ) -> ControlFlow<()> {
        let (lo, hi) = self.cells_touching(&pad.grow(&t.bounds()));
        if lo == hi {
            // The padded bounds lie in one cell, which the triangle therefore touches.
            return each(self.index(lo));
        }
        // Cell boxes from the boundaries directly: the same values as `self.cell`.
        let [bx, by, bz] = self.boundaries();
        for k in lo[2]..=hi[2] {
            let (z0, z1) = (bz.at(k), bz.at(k + 1));
            for j in lo[1]..=hi[1] {
                let (y0, y1) = (by.at(j), by.at(j + 1));
                for i in lo[0]..=hi[0] {
                    let cell =
                        Aabb::new(Vec3::new(bx.at(i), y0, z0), Vec3::new(bx.at(i + 1), y1, z1));
                    if pad.touches(t, &cell) {
                        each(self.index([i, j, k]))?;
                    }
                }
            }
        }
        ControlFlow::Continue(())
    }

    /// The layout for `triangles` triangles in `bounds` with about `cells_per_triangle` cells
    /// per triangle, at most `max_resolution` along an axis. Cells are as near cubic as the
    /// bounds allow: each axis gets `extent · ∛(λN / volume)` cells, rounded up, where a flat
    /// axis counts as a thousandth of the largest extent.
    #[must_use]
    pub(crate) fn for_triangles(
        bounds: Aabb,
        triangles: usize,
        cells_per_triangle: f32,
        max_resolution: u32,
    ) -> Self {
        let e = bounds.extent();
        let largest = max_f32(max_f32(e.x, e.y), e.z);
        let mut resolution = [1u32; 3];
        if largest > 0.0 && largest.is_finite() && triangles > 0 {
            let floor = largest / 1000.0;
            let e = e.max(Vec3::splat(floor));
            let volume = f64::from(e.x) * f64::from(e.y) * f64::from(e.z);
            let cells = f64::from(cells_per_triangle) * triangles as f64;
            let per_unit = libm::cbrt(cells / volume);
            for (r, extent) in resolution.iter_mut().zip(e.to_array()) {
                let n = libm::ceil(f64::from(extent) * per_unit);
                // `as` saturates; the clamp keeps every axis in 1..=max.
                *r = (n as u32).clamp(1, max_resolution.max(1));
            }
        }
        Self { bounds, resolution }
    }

    /// Cells in all (`nx · ny · nz`), or `None` past `usize`.
    #[must_use]
    pub fn cell_count(&self) -> Option<usize> {
        let [x, y, z] = self.resolution.map(|r| r as usize);
        x.checked_mul(y)?.checked_mul(z)
    }

    /// The `i`-th boundary along `axis` (0 is the bounds' `min`, `resolution[axis]` its `max`):
    /// `min + i · (extent / n)`, never past `max`. Increasing in `i`.
    #[inline(always)]
    #[must_use]
    pub fn boundary(&self, axis: usize, i: u32) -> f32 {
        let (lo, hi) = (self.bounds.min.to_array(), self.bounds.max.to_array());
        let (Some(&lo), Some(&hi), Some(&n)) =
            (lo.get(axis), hi.get(axis), self.resolution.get(axis))
        else {
            return 0.0;
        };
        Boundaries::new(lo, hi, n).at(i)
    }

    /// The boundaries of each axis, for walking many cells (the same values as
    /// [`boundary`](Self::boundary)).
    #[inline(always)]
    pub(crate) fn boundaries(&self) -> [Boundaries; 3] {
        let (lo, hi) = (self.bounds.min.to_array(), self.bounds.max.to_array());
        let [nx, ny, nz] = self.resolution;
        [
            Boundaries::new(lo[0], hi[0], nx),
            Boundaries::new(lo[1], hi[1], ny),
            Boundaries::new(lo[2], hi[2], nz),
        ]
    }

    /// The box of the cells `lo..hi` (per axis, `hi` exclusive).
    #[inline(always)]
    #[must_use]
    pub(crate) fn range_box(&self, lo: [u32; 3], hi: [u32; 3]) -> Aabb {
        Aabb::new(
            Vec3::new(
                self.boundary(0, lo[0]),
                self.boundary(1, lo[1]),
                self.boundary(2, lo[2]),
            ),
            Vec3::new(
                self.boundary(0, hi[0]),
                self.boundary(1, hi[1]),
                self.boundary(2, hi[2]),
            ),
        )
    }

    /// The cell `(i, j, k)` as a [`Cell`]: its box, owning its `max` faces on the grid's.
    #[inline(always)]
    #[must_use]
    pub fn cell(&self, c: [u32; 3]) -> Cell {
        let hi = [c[0] + 1, c[1] + 1, c[2] + 1];
        let [nx, ny, nz] = self.resolution;
        Cell::new(
            self.range_box(c, hi),
            [hi[0] >= nx, hi[1] >= ny, hi[2] >= nz],
        )
    }

    /// The index of cell `(i, j, k)`.
    #[inline(always)]
    #[must_use]
    pub fn index(&self, c: [u32; 3]) -> usize {
        let [nx, ny, _] = self.resolution.map(|r| r as usize);
        c[0] as usize + nx * (c[1] as usize + ny * c[2] as usize)
    }

    /// The cell along `axis` holding coordinate `x`, clamped into the grid (may be one off where
    /// `x` is within rounding of a boundary: callers widen by one where that matters).
    #[inline(always)]
    #[must_use]
    pub(crate) fn coordinate_cell(&self, axis: usize, x: f32) -> u32 {
        let (lo, hi) = (self.bounds.min.to_array(), self.bounds.max.to_array());
        let (Some(&lo), Some(&hi), Some(&n)) =
            (lo.get(axis), hi.get(axis), self.resolution.get(axis))
        else {
            return 0;
        };
        let extent = hi - lo;
        if !(extent > 0.0) || !(x > lo) {
            return 0;
        }
        let c = ((x - lo) / extent * n as f32) as u32; // `as` saturates (and maps NaN to 0)
        c.min(n - 1)
    }

    /// The cells whose boxes touch `aabb` (faces included): per axis, `lo..=hi`, clamped into
    /// the grid. Exact against [`boundary`](Self::boundary): the first guess from the
    /// coordinate is corrected by comparing with the boundaries themselves.
    #[must_use]
    pub(crate) fn cells_touching(&self, aabb: &Aabb) -> ([u32; 3], [u32; 3]) {
        let (mut lo, mut hi) = ([0u32; 3], [0u32; 3]);
        let (a, b) = (aabb.min.to_array(), aabb.max.to_array());
        let (min, max) = (self.bounds.min.to_array(), self.bounds.max.to_array());
        let axes = a.iter().zip(&b).zip(min.iter().zip(&max));
        for (axis, (((&a, &b), (&start, &end)), (l, h))) in
            axes.zip(lo.iter_mut().zip(hi.iter_mut())).enumerate()
        {
            let n = self.resolution.get(axis).copied().unwrap_or(1);
            let boundary = Boundaries::new(start, end, n);
            // Lowest cell whose box reaches `a`: its upper boundary is at least `a`.
            let mut first = self.coordinate_cell(axis, a);
            while first > 0 && boundary.at(first) >= a {
                first -= 1;
            }
            while first + 1 < n && boundary.at(first + 1) < a {
                first += 1;
            }
            // Highest cell whose box starts at or below `b`.
            let mut last = self.coordinate_cell(axis, b).max(first);
            while last + 1 < n && boundary.at(last + 1) <= b {
                last += 1;
            }
            while last > first && boundary.at(last) > b {
                last -= 1;
            }
            (*l, *h) = (first, last);
        }
        (lo, hi)
    }
}

/// The cell boundaries of one axis, `n` cells from `lo` to `hi`, with the step worked out once.
#[derive(Clone, Copy)]
pub(crate) struct Boundaries {
    lo: f32,
    hi: f32,
    n: u32,
    step: f32,
}

impl Boundaries {
    #[inline(always)]
    fn new(lo: f32, hi: f32, n: u32) -> Self {
        Self {
            lo,
            hi,
            n,
            step: (hi - lo) / n as f32,
        }
    }

    /// Boundary `i` (see [`GridLayout::boundary`]).
    #[inline(always)]
    pub(crate) fn at(self, i: u32) -> f32 {
        if i >= self.n {
            return self.hi;
        }
        (self.lo + i as f32 * self.step).min(self.hi)
    }
}
