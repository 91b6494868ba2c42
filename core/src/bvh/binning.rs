//! Binned SAH split search (Wald 2007, "On fast Construction of SAH-based Bounding Volume
//! Hierarchies").

use glam::Vec3;

use super::{BuildConfig, PrimRef};
use crate::math::Aabb;

const MAX_BINS: usize = BuildConfig::MAX_BINS as usize;

/// Maps a centroid to its bin along an axis. The same instance decides binning and
/// partitioning, so both always agree.
#[derive(Clone, Copy, Debug)]
pub(super) struct Binner {
    origin: Vec3,
    scale: Vec3,
    last: u32,
}

impl Binner {
    fn new(centers: &Aabb, bins: u32) -> Self {
        let e = centers.extent();
        let k = bins as f32;
        // An axis with no extent gets scale 0: every centroid lands in bin 0 and no split
        // along it is valid.
        let s = |x: f32| if x > 0.0 { k / x } else { 0.0 };
        Self {
            origin: centers.min,
            scale: Vec3::new(s(e.x), s(e.y), s(e.z)),
            last: bins - 1,
        }
    }

    #[inline(always)]
    fn bin(&self, c: Vec3, axis: usize) -> u32 {
        let f = match axis {
            0 => (c.x - self.origin.x) * self.scale.x,
            1 => (c.y - self.origin.y) * self.scale.y,
            _ => (c.z - self.origin.z) * self.scale.z,
        };
        // `as` saturates (and maps NaN to 0), so no input can index past the bins.
        (f as u32).min(self.last)
    }
}

#[derive(Clone, Copy)]
struct Bin {
    bounds: Aabb,
    count: u32,
}

const EMPTY_BIN: Bin = Bin {
    bounds: Aabb::EMPTY,
    count: 0,
};

fn merge(a: Bin, b: &Bin) -> Bin {
    Bin {
        bounds: a.bounds.union(b.bounds),
        count: a.count + b.count,
    }
}

/// The cheapest split found, with the exact bounds of both sides (their centroid bounds come
/// from [`partition`]).
#[derive(Clone, Copy, Debug)]
pub(super) struct Split {
    binner: Binner,
    axis: usize,
    /// Triangles whose bin is below this go left.
    bin: u32,
    /// `A_L·N_L + A_R·N_R` (half areas).
    pub cost: f32,
    pub left_count: usize,
    pub left: Aabb,
    pub right: Aabb,
}

/// Bin storage reused across every node of a build, so a node only resets the bins it uses.
pub(super) struct Binning {
    bins: [[Bin; MAX_BINS]; 3],
    /// Half area and count of bins `[0, i]` on the axis being swept.
    prefix_area: [f32; MAX_BINS],
    prefix_count: [u32; MAX_BINS],
}

impl Binning {
    pub const fn new() -> Self {
        Self {
            bins: [[EMPTY_BIN; MAX_BINS]; 3],
            prefix_area: [0.0; MAX_BINS],
            prefix_count: [0; MAX_BINS],
        }
    }

    /// Bins `prims` by centroid on all three axes in one pass and returns the split with the
    /// lowest SAH cost (ties: lower axis, then lower bin), or `None` when no axis separates the
    /// centroids. Small nodes use at most one bin per triangle: more bins would mostly stay
    /// empty and only cost sweep time.
    pub fn find_split(&mut self, prims: &[PrimRef], centers: &Aabb, bins: u32) -> Option<Split> {
        let wanted = (bins as usize).min(prims.len()).clamp(2, MAX_BINS);
        let binner = Binner::new(centers, wanted as u32);
        for axis_bins in &mut self.bins {
            if let Some(used) = axis_bins.get_mut(..wanted) {
                used.fill(EMPTY_BIN);
            }
        }
        let [xs, ys, zs] = &mut self.bins;
        for p in prims {
            let slots = [
                xs.get_mut(binner.bin(p.center, 0) as usize),
                ys.get_mut(binner.bin(p.center, 1) as usize),
                zs.get_mut(binner.bin(p.center, 2) as usize),
            ];
            for b in slots.into_iter().flatten() {
                b.bounds = b.bounds.union(p.bounds);
                b.count += 1;
            }
        }
        let mut best: Option<(usize, u32, f32, usize)> = None;
        for axis in 0..3 {
            let Some(axis_bins) = self.bins.get(axis).and_then(|b| b.get(..wanted)) else {
                continue;
            };
            let mut run = EMPTY_BIN;
            for ((area, count), b) in self
                .prefix_area
                .iter_mut()
                .zip(self.prefix_count.iter_mut())
                .zip(axis_bins)
            {
                if b.count > 0 {
                    run = merge(run, b);
                }
                *area = run.bounds.half_area();
                *count = run.count;
            }
            let mut right = EMPTY_BIN;
            for i in (1..wanted).rev() {
                let (Some(b), Some(&left_area), Some(&left_count)) = (
                    axis_bins.get(i),
                    self.prefix_area.get(i - 1),
                    self.prefix_count.get(i - 1),
                ) else {
                    continue;
                };
                if b.count > 0 {
                    right = merge(right, b);
                }
                if left_count == 0 || right.count == 0 {
                    continue;
                }
                let cost =
                    left_area * left_count as f32 + right.bounds.half_area() * right.count as f32;
                // Sweeping down, `<=` keeps the lowest bin among equal costs of this axis; a
                // later axis must be strictly better.
                let better = best.is_none_or(|(a, _, c, _)| cost < c || (cost == c && a == axis));
                if better {
                    best = Some((axis, i as u32, cost, left_count as usize));
                }
            }
        }
        let (axis, bin, cost, left_count) = best?;
        // Rebuild both sides' exact bounds from the chosen axis's bins.
        let axis_bins = self.bins.get(axis)?.get(..wanted)?;
        let (left_bins, right_bins) = axis_bins.split_at(bin as usize);
        let left = left_bins.iter().fold(EMPTY_BIN, merge);
        let right = right_bins.iter().fold(EMPTY_BIN, merge);
        Some(Split {
            binner,
            axis,
            bin,
            cost,
            left_count,
            left: left.bounds,
            right: right.bounds,
        })
    }
}

/// Reorders `prims` so that those binned below `split.bin` come first; returns how many, and
/// the centroid bounds of both sides (gathered here, in the pass that touches every triangle
/// anyway).
pub(super) fn partition(prims: &mut [PrimRef], split: &Split) -> (usize, Aabb, Aabb) {
    let mut i = 0;
    let mut j = prims.len();
    let (mut left, mut right) = (Aabb::EMPTY, Aabb::EMPTY);
    while i < j {
        let Some(p) = prims.get(i) else {
            break;
        };
        if split.binner.bin(p.center, split.axis) < split.bin {
            left = left.grown(p.center);
            i += 1;
        } else {
            right = right.grown(p.center);
            j -= 1;
            prims.swap(i, j);
        }
    }
    (i, left, right)
}
