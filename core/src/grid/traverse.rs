//! Walking a grid: rays cell by cell along their path (3D-DDA), other queries by halving cell
//! ranges, nearest first.

use super::Grid;
use crate::cells::{Offer, Words};
use crate::geom::SlabRay;
use crate::math::Ray;
use crate::query::{Traverse, Visitor};

/// Relative slack on the ray's span inside the grid, as the query layer's box tests use.
const MARGIN: f32 = 1.0 / 65_536.0;

/// Deferred cell ranges of the non-ray walk: each halving defers one half, and there are at
/// most 30 halvings (three axes of at most 1024 cells).
const STACK: usize = 64;

/// The most rows of cells (runs along x) a range may span for the walk to check whether it is
/// empty before entering it: a row's references are one contiguous run of the offsets, so each
/// costs two reads, against the box tests of every cell below a range left unchecked.
const EMPTY_CHECK_ROWS: u32 = 64;

impl<W: Words> Traverse for Grid<W> {
    fn traverse<V: Visitor + ?Sized>(&self, visitor: &mut V) {
        if self.items.is_empty() {
            return;
        }
        let mut offer = Offer::new(visitor);
        match visitor.ray().copied() {
            Some(ray) => self.march(&ray, visitor, &mut offer),
            None => self.descend(visitor, &mut offer),
        }
    }
}

impl<W: Words> Grid<W> {
    /// Offers cell `c` (if it holds anything); `false` when the visitor breaks.
    #[inline(always)]
    fn visit<V: Visitor + ?Sized>(&self, c: [u32; 3], visitor: &mut V, offer: &mut Offer) -> bool {
        let Some((first, count)) = self.cell_range(self.layout.index(c)) else {
            return true;
        };
        if count == 0 {
            return true;
        }
        let Some(ids) = self.items.ids(first, count) else {
            return true;
        };
        offer
            .cell(visitor, ids, Some(self.layout.cell(c)))
            .is_continue()
    }

    /// Amanatides–Woo: from the cell where the ray enters the grid, step to the neighbour across
    /// whichever cell face the ray leaves through first, until the ray ends, leaves the grid,
    /// or the visitor's answer lies before the next cell (`revisit` of its entry `t`).
    fn march<V: Visitor + ?Sized>(&self, ray: &Ray, visitor: &mut V, offer: &mut Offer) {
        let layout = &self.layout;
        let b = layout.bounds;
        let (entry, exit) = SlabRay::new(ray).clip(b.min.to_array(), b.max.to_array());
        let (lo, hi) = (entry - entry.abs() * MARGIN, exit + exit.abs() * MARGIN);
        if !(lo <= hi) {
            return;
        }
        let start = ray.origin + ray.dir * lo;
        let (o, d, p) = (ray.origin.to_array(), ray.dir.to_array(), start.to_array());
        let mut cell = [0u32; 3];
        let mut step = [0i32; 3];
        let mut next = [f32::INFINITY; 3];
        for a in 0..3 {
            let (Some(&oa), Some(&da), Some(&pa)) = (o.get(a), d.get(a), p.get(a)) else {
                return;
            };
            let c = layout.coordinate_cell(a, pa);
            let s = if da > 0.0 {
                1
            } else if da < 0.0 {
                -1
            } else {
                0
            };
            if let (Some(ca), Some(sa), Some(na)) =
                (cell.get_mut(a), step.get_mut(a), next.get_mut(a))
            {
                (*ca, *sa, *na) = (c, s, crossing(layout.boundary(a, face(c, s)), oa, da, s));
            }
        }
        loop {
            if !self.visit(cell, visitor, offer) {
                return;
            }
            let [nx, ny, nz] = next;
            let axis = if nx <= ny && nx <= nz {
                0
            } else if ny <= nz {
                1
            } else {
                2
            };
            let t_exit = next.get(axis).copied().unwrap_or(f32::INFINITY);
            // Early exit: the next cell starts at `t_exit`; a hit before it cannot be beaten.
            if !(t_exit <= hi) || !visitor.revisit(t_exit) {
                return;
            }
            let (Some(c), Some(&s), Some(&n), Some(&oa), Some(&da)) = (
                cell.get_mut(axis),
                step.get(axis),
                layout.resolution.get(axis),
                o.get(axis),
                d.get(axis),
            ) else {
                return;
            };
            let moved = c.checked_add_signed(s).filter(|&m| m < n);
            let Some(m) = moved else {
                return;
            };
            *c = m;
            if let Some(na) = next.get_mut(axis) {
                *na = crossing(layout.boundary(axis, face(m, s)), oa, da, s);
            }
        }
    }

    /// Best-first over cell ranges: enter a range's box, halve it along its longest run of
    /// cells, visit the half with the smaller key first; single cells are leaves.
    fn descend<V: Visitor + ?Sized>(&self, visitor: &mut V, offer: &mut Offer) {
        let layout = &self.layout;
        let whole = ([0u32; 3], layout.resolution);
        let Some(key) = visitor.enter(&layout.range_box(whole.0, whole.1)) else {
            return;
        };
        let mut stack = [(whole.0, whole.1, 0.0f32); STACK];
        let mut top = 0usize;
        let mut current = Some((whole.0, whole.1, key));
        loop {
            let Some((lo, hi, key)) = current.take().or_else(|| {
                top = top.checked_sub(1)?;
                stack.get(top).copied()
            }) else {
                return;
            };
            if !visitor.revisit(key) {
                continue;
            }
            let runs = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
            let [rx, ry, rz] = runs;
            if rx * ry * rz <= 1 {
                if !self.visit(lo, visitor, offer) {
                    return;
                }
                continue;
            }
            let axis = if rx >= ry && rx >= rz {
                0
            } else if ry >= rz {
                1
            } else {
                2
            };
            let (mut mid_hi, mut mid_lo) = (hi, lo);
            let mid = lo.get(axis).copied().unwrap_or(0) + runs.get(axis).copied().unwrap_or(0) / 2;
            if let (Some(h), Some(l)) = (mid_hi.get_mut(axis), mid_lo.get_mut(axis)) {
                (*h, *l) = (mid, mid);
            }
            let mut enter = |lo: [u32; 3], hi: [u32; 3]| {
                if self.holds_nothing(lo, hi) {
                    return None;
                }
                visitor
                    .enter(&layout.range_box(lo, hi))
                    .map(|k| (lo, hi, k))
            };
            let first = enter(lo, mid_hi);
            let second = enter(mid_lo, hi);
            let (near, far) = match (first, second) {
                (Some(a), Some(b)) if b.2 < a.2 => (Some(b), Some(a)),
                (a, b) => (a.or(b), a.and(b)),
            };
            if let (Some(far), Some(slot)) = (far, stack.get_mut(top)) {
                *slot = far;
                top += 1;
            }
            current = near;
        }
    }
}

impl<W: Words> Grid<W> {
    /// Whether the cells `lo..hi` (per axis, `hi` exclusive) are known to reference nothing:
    /// checked row by row when the range spans at most [`EMPTY_CHECK_ROWS`] rows, otherwise
    /// `false` (unknown). Only a skip: the answer never depends on it.
    fn holds_nothing(&self, lo: [u32; 3], hi: [u32; 3]) -> bool {
        let rows = (hi[1] - lo[1]).saturating_mul(hi[2] - lo[2]);
        if rows > EMPTY_CHECK_ROWS || hi[0] <= lo[0] {
            return false;
        }
        for z in lo[2]..hi[2] {
            for y in lo[1]..hi[1] {
                let first = self.layout.index([lo[0], y, z]);
                let end = self.layout.index([hi[0] - 1, y, z]) + 1;
                match (self.offsets.word(first), self.offsets.word(end)) {
                    (Some(a), Some(b)) if a == b => {}
                    _ => return false,
                }
            }
        }
        true
    }
}

/// The boundary index of the face a ray stepping `s` leaves cell `c` through.
#[inline(always)]
fn face(c: u32, s: i32) -> u32 {
    if s > 0 { c + 1 } else { c }
}

/// The `t` where coordinate `o + t·d` reaches `boundary` (infinite when the ray does not move
/// along the axis).
#[inline(always)]
fn crossing(boundary: f32, o: f32, d: f32, s: i32) -> f32 {
    if s == 0 {
        f32::INFINITY
    } else {
        (boundary - o) / d
    }
}
