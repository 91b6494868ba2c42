//! Binned SAH split search (Wald 2007, "On fast Construction of SAH-based Bounding Volume
//! Hierarchies").

use glam::Vec3A;

use super::build_box::BuildBox;
use super::lanes::clamped_indices;
use super::partition::{centroid_bounds, partition_by};
use super::{BuildConfig, PrimRef};

const MAX_BINS: usize = BuildConfig::MAX_BINS as usize;

/// Maps a (doubled) centroid to its bin on each axis. The same instance decides binning and
/// partitioning, so both always agree.
#[derive(Clone, Copy, Debug)]
pub(super) struct Binner {
    origin: Vec3A,
    scale: Vec3A,
    last: u32,
    /// `last` in every lane.
    last_lanes: Vec3A,
}

impl Binner {
    fn new(centroids: &BuildBox, bins: u32) -> Self {
        let e = centroids.extent();
        let k = bins as f32;
        // An axis with no extent gets scale 0: every centroid lands in bin 0 and no split
        // along it is valid.
        let s = |x: f32| if x > 0.0 { k / x } else { 0.0 };
        Self {
            origin: centroids.min,
            scale: Vec3A::new(s(e.x), s(e.y), s(e.z)),
            last: bins - 1,
            last_lanes: Vec3A::splat((bins - 1) as f32),
        }
    }

    /// `as` saturates (and maps NaN to 0), so no input can index past the bins.
    #[inline(always)]
    fn clamp(&self, f: f32) -> u32 {
        (f as u32).min(self.last)
    }

    /// The bin on every axis at once (one vector subtraction and multiplication).
    #[inline(always)]
    fn bins(&self, c2: Vec3A) -> [usize; 3] {
        clamped_indices((c2 - self.origin) * self.scale, self.last_lanes)
    }

    /// The bin on one axis: the same operations on one lane, so always the same answer as
    /// [`Binner::bins`].
    #[inline(always)]
    fn bin(&self, c2: Vec3A, axis: usize) -> u32 {
        let f = match axis {
            0 => (c2.x - self.origin.x) * self.scale.x,
            1 => (c2.y - self.origin.y) * self.scale.y,
            _ => (c2.z - self.origin.z) * self.scale.z,
        };
        self.clamp(f)
    }
}

/// The bins of one axis: a box and a triangle count each.
struct AxisBins {
    boxes: [BuildBox; MAX_BINS],
    counts: [u32; MAX_BINS],
}

impl AxisBins {
    const EMPTY: Self = Self {
        boxes: [BuildBox::EMPTY; MAX_BINS],
        counts: [0; MAX_BINS],
    };

    #[inline(always)]
    fn add(&mut self, bin: usize, p: &PrimRef) {
        if let (Some(b), Some(c)) = (self.boxes.get_mut(bin), self.counts.get_mut(bin)) {
            *b = b.union(p.bounds());
            *c += 1;
        }
    }

    /// Adds `other`'s first `used` bins into these.
    fn merge(&mut self, other: &Self, used: usize) {
        let mine = self.boxes.iter_mut().zip(self.counts.iter_mut());
        let theirs = other.boxes.iter().zip(&other.counts);
        for ((b, c), (ob, oc)) in mine.zip(theirs).take(used) {
            *b = b.union(*ob);
            *c += oc;
        }
    }

    fn reset(&mut self, used: usize) {
        if let (Some(b), Some(c)) = (self.boxes.get_mut(..used), self.counts.get_mut(..used)) {
            b.fill(BuildBox::EMPTY);
            c.fill(0);
        }
    }

    /// Union and total count of `bins`.
    fn total(&self, bins: core::ops::Range<usize>) -> (BuildBox, usize) {
        let boxes = self.boxes.get(bins.clone()).unwrap_or_default();
        let counts = self.counts.get(bins).unwrap_or_default();
        (
            boxes.iter().fold(BuildBox::EMPTY, |a, b| a.union(*b)),
            counts.iter().map(|&c| c as usize).sum(),
        )
    }
}

/// Triangles a query tests at once in a leaf (the lanes of its triangle test).
pub(super) const LEAF_BATCH: usize = 4;

/// The SAH's cost unit for `n` triangles: the batches of up to [`LEAF_BATCH`] a query tests
/// them in, `⌈n/4⌉`.
#[inline(always)]
pub(super) const fn batches(n: usize) -> usize {
    n.div_ceil(LEAF_BATCH)
}

/// The cheapest split found, with the exact bounds of both sides (their centroid bounds come
/// from [`partition`]).
#[derive(Clone, Copy, Debug)]
pub(super) struct Split {
    binner: Binner,
    axis: usize,
    /// Triangles whose bin is below this go left.
    bin: u32,
    /// `A_L·B(N_L) + A_R·B(N_R)` (half areas, and [`batches`] of triangles).
    pub cost: f32,
    pub left_count: usize,
    pub left: BuildBox,
    pub right: BuildBox,
}

/// Bin storage reused across every node of a build, so a node only resets the bins it uses.
pub(super) struct Binning {
    axes: [AxisBins; 3],
    /// A second set that takes every other triangle of large nodes: consecutive triangles
    /// often share a bin, and alternating sets keeps each read-modify-write of a bin from
    /// waiting on the one just before it.
    odd: [AxisBins; 3],
    /// Half area of bins `[i, wanted)`, one lane per axis.
    right_area: [Vec3A; MAX_BINS],
    /// Batches of triangles in bins `[i, wanted)` ([`batches`], as `f32` like the SAH cost),
    /// one lane per axis.
    right_count: [Vec3A; MAX_BINS],
}

/// Half areas of three boxes at once, one per lane, each `xy + yz + zx` of its extent in that
/// order (empty boxes give meaningless values; callers mask them by count).
#[inline(always)]
fn half_areas(b: &[BuildBox; 3]) -> Vec3A {
    let [e0, e1, e2] = b.map(|b| b.extent());
    let ex = Vec3A::new(e0.x, e1.x, e2.x);
    let ey = Vec3A::new(e0.y, e1.y, e2.y);
    let ez = Vec3A::new(e0.z, e1.z, e2.z);
    ex * ey + ey * ez + ez * ex
}

impl Binning {
    /// Nodes with at least this many triangles bin into two sets.
    const TWO_SETS_FROM: usize = 256;

    pub const fn new() -> Self {
        Self {
            axes: [AxisBins::EMPTY, AxisBins::EMPTY, AxisBins::EMPTY],
            odd: [AxisBins::EMPTY, AxisBins::EMPTY, AxisBins::EMPTY],
            right_area: [Vec3A::ZERO; MAX_BINS],
            right_count: [Vec3A::ZERO; MAX_BINS],
        }
    }

    /// Adds bin `i` of every axis to the running boxes and counts.
    #[inline(always)]
    fn accumulate(&self, i: usize, run: &mut [BuildBox; 3], count: &mut [u32; 3]) {
        for ((bins, r), c) in self.axes.iter().zip(run.iter_mut()).zip(count.iter_mut()) {
            if let (Some(b), Some(n)) = (bins.boxes.get(i), bins.counts.get(i)) {
                *r = r.union(*b);
                *c += n;
            }
        }
    }

    /// Bins `prims` by centroid on all three axes in one pass and returns the split with the
    /// lowest SAH cost (ties: lower axis, then lower bin), or `None` when no axis separates the
    /// centroids (or every cost overflows). Small nodes use at most one bin per triangle: more
    /// bins would mostly stay empty and only cost sweep time. The sweeps run on all three axes
    /// at once, one SIMD lane each.
    pub fn find_split(
        &mut self,
        prims: &[PrimRef],
        centroids: &BuildBox,
        bins: u32,
    ) -> Option<Split> {
        let (wanted, binner) = Self::binner(prims.len(), centroids, bins);
        for axis in &mut self.axes {
            axis.reset(wanted);
        }
        let [xs, ys, zs] = &mut self.axes;
        if prims.len() < Self::TWO_SETS_FROM {
            for p in prims {
                let [bx, by, bz] = binner.bins(p.centroid2());
                xs.add(bx, p);
                ys.add(by, p);
                zs.add(bz, p);
            }
        } else {
            for axis in &mut self.odd {
                axis.reset(wanted);
            }
            let [xo, yo, zo] = &mut self.odd;
            let mut pairs = prims.chunks_exact(2);
            for pair in &mut pairs {
                if let [p, q] = pair {
                    let [bx, by, bz] = binner.bins(p.centroid2());
                    let [cx, cy, cz] = binner.bins(q.centroid2());
                    xs.add(bx, p);
                    ys.add(by, p);
                    zs.add(bz, p);
                    xo.add(cx, q);
                    yo.add(cy, q);
                    zo.add(cz, q);
                }
            }
            for p in pairs.remainder() {
                let [bx, by, bz] = binner.bins(p.centroid2());
                xs.add(bx, p);
                ys.add(by, p);
                zs.add(bz, p);
            }
            for (even, odd) in self.axes.iter_mut().zip(&self.odd) {
                even.merge(odd, wanted);
            }
        }
        self.sweep(wanted, binner)
    }

    /// [`Binning::find_split`] with the triangles binned on rayon's thread pool, in runs
    /// whose bins are then merged: a bin's box is a union and its count a sum, both exact in
    /// any order, so the split is the one `find_split` finds, bit for bit.
    #[cfg(feature = "parallel")]
    pub fn find_split_parallel(
        &mut self,
        prims: &[PrimRef],
        centroids: &BuildBox,
        bins: u32,
    ) -> Option<Split> {
        use rayon::prelude::*;
        /// Triangles binned per task.
        const RUN: usize = 16 * 1024;
        let (wanted, binner) = Self::binner(prims.len(), centroids, bins);
        let empty = || [AxisBins::EMPTY, AxisBins::EMPTY, AxisBins::EMPTY];
        let merged = prims
            .par_chunks(RUN)
            .map(|run| {
                let mut axes = empty();
                let [xs, ys, zs] = &mut axes;
                for p in run {
                    let [bx, by, bz] = binner.bins(p.centroid2());
                    xs.add(bx, p);
                    ys.add(by, p);
                    zs.add(bz, p);
                }
                axes
            })
            .reduce(empty, |mut a, b| {
                for (x, y) in a.iter_mut().zip(&b) {
                    x.merge(y, wanted);
                }
                a
            });
        for (axis, bins) in self.axes.iter_mut().zip(&merged) {
            axis.reset(wanted);
            axis.merge(bins, wanted);
        }
        self.sweep(wanted, binner)
    }

    /// How many bins a node of `count` triangles uses, and the binner for them.
    fn binner(count: usize, centroids: &BuildBox, bins: u32) -> (usize, Binner) {
        let wanted = (bins as usize).min(count).clamp(2, MAX_BINS);
        (wanted, Binner::new(centroids, wanted as u32))
    }

    /// The cheapest split over the filled bins (see [`Binning::find_split`]).
    fn sweep(&mut self, wanted: usize, binner: Binner) -> Option<Split> {
        let as_f32 = |c: [u32; 3]| {
            let [x, y, z] = c.map(|n| batches(n as usize) as f32);
            Vec3A::new(x, y, z)
        };
        // Right to left: what lies at or above each bin.
        let mut run = [BuildBox::EMPTY; 3];
        let mut count = [0u32; 3];
        for i in (1..wanted).rev() {
            self.accumulate(i, &mut run, &mut count);
            if let (Some(area), Some(n)) = (self.right_area.get_mut(i), self.right_count.get_mut(i))
            {
                *area = half_areas(&run);
                *n = as_f32(count);
            }
        }
        // Left to right: split below bin i + 1. Strictly better only, so the lowest bin wins a
        // tie within an axis.
        let mut run = [BuildBox::EMPTY; 3];
        let mut count = [0u32; 3];
        let mut best_cost = Vec3A::INFINITY;
        let mut best_bin = Vec3A::ZERO;
        for i in 0..wanted - 1 {
            self.accumulate(i, &mut run, &mut count);
            let (Some(&right_area), Some(&right_count)) =
                (self.right_area.get(i + 1), self.right_count.get(i + 1))
            else {
                continue;
            };
            let left_count = as_f32(count);
            let cost = half_areas(&run) * left_count + right_area * right_count;
            let better = left_count.cmpgt(Vec3A::ZERO)
                & right_count.cmpgt(Vec3A::ZERO)
                & cost.cmplt(best_cost);
            best_cost = Vec3A::select(better, cost, best_cost);
            best_bin = Vec3A::select(better, Vec3A::splat((i + 1) as f32), best_bin);
        }
        // The lowest axis wins a tie between axes.
        let mut best: Option<(usize, usize, f32)> = None;
        for (axis, (cost, bin)) in best_cost
            .to_array()
            .into_iter()
            .zip(best_bin.to_array())
            .enumerate()
        {
            if cost < best.map_or(f32::INFINITY, |b| b.2) {
                best = Some((axis, bin as usize, cost));
            }
        }
        let (axis, bin, cost) = best?;
        // Rebuild both sides' exact bounds from the chosen axis's bins.
        let chosen = self.axes.get(axis)?;
        let (left, left_count) = chosen.total(0..bin);
        let (right, _) = chosen.total(bin..wanted);
        Some(Split {
            binner,
            axis,
            bin: bin as u32,
            cost,
            left_count,
            left,
            right,
        })
    }
}

/// Reorders `prims`, and `tris` alongside, so that those binned below `split.bin` come first;
/// returns how many, and the (doubled) centroid bounds of both sides. `prims` and `tris` have
/// the same length.
pub(super) fn partition(
    prims: &mut [PrimRef],
    tris: &mut [u32],
    split: &Split,
) -> (usize, BuildBox, BuildBox) {
    let k = partition_by(prims, tris, |c| split.binner.bin(c, split.axis) < split.bin);
    let (left, right) = prims.split_at(k.min(prims.len()));
    (k, centroid_bounds(left), centroid_bounds(right))
}
