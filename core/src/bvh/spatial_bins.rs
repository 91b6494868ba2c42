//! The search for the best spatial split of a node: references binned by where their parts
//! lie, each cut at the bin planes it crosses.

use glam::Vec3A;

use super::PrimRef;
use super::binning::batches;
use super::build_box::BuildBox;
use super::clip::{holds_something, lane, slab_parts};
use crate::mesh::ValidMesh;

/// Bins per axis of the spatial split search.
pub(super) const SPATIAL_BINS: usize = 32;

/// Set in an order entry, during a build with spatial splits, on a reference whose triangle
/// the tree holds more than once.
pub(super) const SPLIT_FLAG: u32 = 1 << 31;

/// A plane that cuts a node's references: those wholly below go left, wholly above right,
/// those across it both ways, each boxed by its part on that side.
#[derive(Clone, Copy, Debug)]
pub(super) struct SpatialSplit {
    pub axis: usize,
    pub plane: f32,
    /// `A_L·B(N_L) + A_R·B(N_R)` with the counts the bins predict (as the object split's).
    pub cost: f32,
}

/// The corners of the triangle behind order entry `entry` (its flag cleared).
pub(super) fn corners_of(mesh: &ValidMesh<'_>, entry: u32) -> Option<[Vec3A; 3]> {
    mesh.triangle(entry & !SPLIT_FLAG)
        .map(|t| [t.a, t.b, t.c].map(Vec3A::from))
}

/// Bin storage for one axis, reused across the nodes of a build.
pub(super) struct SpatialBinning {
    boxes: [BuildBox; SPATIAL_BINS],
    /// References whose part starts in each bin.
    enter: [u32; SPATIAL_BINS],
    /// References whose part ends in each bin.
    exit: [u32; SPATIAL_BINS],
    /// What lies at or above each bin: box and count.
    right: [(BuildBox, u32); SPATIAL_BINS],
}

impl SpatialBinning {
    pub const fn new() -> Self {
        Self {
            boxes: [BuildBox::EMPTY; SPATIAL_BINS],
            enter: [0; SPATIAL_BINS],
            exit: [0; SPATIAL_BINS],
            right: [(BuildBox::EMPTY, 0); SPATIAL_BINS],
        }
    }

    /// The spatial split of lowest cost over `bounds` (the node's box) for the references
    /// `prims` (triangles `tris`, order entries): planes at the `SPATIAL_BINS − 1` inner bin
    /// borders of each axis that the bins say repeat at most `max_repeats` references; ties
    /// go to the lower axis, then the lower plane. `None` when no such plane leaves
    /// references on both sides.
    pub fn find(
        &mut self,
        mesh: &ValidMesh<'_>,
        prims: &[PrimRef],
        tris: &[u32],
        bounds: &BuildBox,
        max_repeats: usize,
    ) -> Option<SpatialSplit> {
        let mut best: Option<SpatialSplit> = None;
        for axis in 0..3 {
            let (lo, hi) = (lane(bounds.min, axis), lane(bounds.max, axis));
            let width = (hi - lo) / SPATIAL_BINS as f32;
            if !(width > 0.0 && width.is_finite()) {
                continue;
            }
            self.bin_axis(mesh, prims, tris, axis, lo, width);
            if let Some((cost, border)) = self.sweep(prims.len(), max_repeats)
                && best.is_none_or(|b| cost < b.cost)
            {
                best = Some(SpatialSplit {
                    axis,
                    plane: plane(lo, width, border),
                    cost,
                });
            }
        }
        best
    }

    /// Bins every reference on `axis`: its part in each bin it spans grows that bin's box.
    fn bin_axis(
        &mut self,
        mesh: &ValidMesh<'_>,
        prims: &[PrimRef],
        tris: &[u32],
        axis: usize,
        lo: f32,
        width: f32,
    ) {
        self.boxes.fill(BuildBox::EMPTY);
        self.enter.fill(0);
        self.exit.fill(0);
        // `as` saturates (NaN to 0), and the clamp keeps the last bin's top inside.
        let bin = |x: f32| (((x - lo) / width) as usize).min(SPATIAL_BINS - 1);
        for (p, &entry) in prims.iter().zip(tris) {
            let (first, last) = (bin(lane(p.min, axis)), bin(lane(p.max, axis)));
            if let Some(e) = self.enter.get_mut(first) {
                *e += 1;
            }
            if let Some(e) = self.exit.get_mut(last) {
                *e += 1;
            }
            let own = p.bounds();
            let corners = (first != last).then(|| corners_of(mesh, entry)).flatten();
            let Some(corners) = corners else {
                if let Some(b) = self.boxes.get_mut(first) {
                    *b = b.union(own);
                }
                continue;
            };
            slab_parts(
                &corners,
                axis,
                (first, last),
                |b| plane(lo, width, b),
                bin,
                &own,
                |b, part| {
                    if holds_something(&part)
                        && let Some(bin_box) = self.boxes.get_mut(b)
                    {
                        *bin_box = bin_box.union(part);
                    }
                },
            );
        }
    }

    /// The cheapest border between bins that repeats at most `max_repeats` of the `total`
    /// references: `(cost, border)`, the border below bin `border`.
    fn sweep(&mut self, total: usize, max_repeats: usize) -> Option<(f32, usize)> {
        let mut run = (BuildBox::EMPTY, 0u32);
        for b in (1..SPATIAL_BINS).rev() {
            if let (Some(bx), Some(&n), Some(slot)) =
                (self.boxes.get(b), self.exit.get(b), self.right.get_mut(b))
            {
                run = (run.0.union(*bx), run.1 + n);
                *slot = run;
            }
        }
        let mut best: Option<(f32, usize)> = None;
        let mut left = (BuildBox::EMPTY, 0u32);
        for b in 0..SPATIAL_BINS - 1 {
            let (Some(bx), Some(&n), Some(&(right_box, right_count))) =
                (self.boxes.get(b), self.enter.get(b), self.right.get(b + 1))
            else {
                continue;
            };
            left = (left.0.union(*bx), left.1 + n);
            // A reference counted on both sides is repeated.
            let repeats = (left.1 as usize + right_count as usize).saturating_sub(total);
            if left.1 == 0 || right_count == 0 || repeats > max_repeats {
                continue;
            }
            let cost = left.0.half_area() * batches(left.1 as usize) as f32
                + right_box.half_area() * batches(right_count as usize) as f32;
            if best.is_none_or(|(c, _)| cost < c) {
                best = Some((cost, b + 1));
            }
        }
        best
    }
}

/// The border below bin `b`: `lo + width·b` (the same expression wherever a plane is needed).
#[inline(always)]
fn plane(lo: f32, width: f32, b: usize) -> f32 {
    lo + width * b as f32
}
