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
    pub fn new(centers: &Aabb, bins: u32) -> Self {
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
    pub fn bin(&self, c: Vec3, axis: usize) -> u32 {
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
    centers: Aabb,
    count: u32,
}

const EMPTY_BIN: Bin = Bin {
    bounds: Aabb::EMPTY,
    centers: Aabb::EMPTY,
    count: 0,
};

/// The cheapest split found, with the exact bounds of both sides.
#[derive(Clone, Copy, Debug)]
pub(super) struct Split {
    pub binner: Binner,
    pub axis: usize,
    /// Triangles whose bin is below this go left.
    pub bin: u32,
    /// `A_L·N_L + A_R·N_R` (half areas).
    pub cost: f32,
    pub left_count: usize,
    pub left: (Aabb, Aabb),
    pub right: (Aabb, Aabb),
}

/// Bins `prims` by centroid on all three axes in one pass and returns the split with the lowest
/// SAH cost (ties: lower axis, then lower bin), or `None` when no axis separates the centroids.
pub(super) fn find_split(prims: &[PrimRef], centers: &Aabb, bins: u32) -> Option<Split> {
    let binner = Binner::new(centers, bins);
    let nbins = (bins as usize).min(MAX_BINS);
    let mut acc = [[EMPTY_BIN; MAX_BINS]; 3];
    for p in prims {
        for (axis, axis_bins) in acc.iter_mut().enumerate() {
            if let Some(b) = axis_bins.get_mut(binner.bin(p.center, axis) as usize) {
                b.bounds = b.bounds.union(p.bounds);
                b.centers = b.centers.grown(p.center);
                b.count += 1;
            }
        }
    }
    let mut best: Option<Split> = None;
    for (axis, axis_bins) in acc.iter().enumerate() {
        let Some(axis_bins) = axis_bins.get(..nbins) else {
            continue;
        };
        // Prefix sweep: left side of a split before bin i is bins [0, i).
        let mut prefix = [EMPTY_BIN; MAX_BINS];
        let mut run = EMPTY_BIN;
        for (slot, b) in prefix.iter_mut().zip(axis_bins) {
            run = merge(run, *b);
            *slot = run;
        }
        let mut right = EMPTY_BIN;
        for i in (1..nbins).rev() {
            let (Some(b), Some(left)) = (axis_bins.get(i), prefix.get(i - 1)) else {
                continue;
            };
            right = merge(right, *b);
            if left.count == 0 || right.count == 0 {
                continue;
            }
            let cost = left.bounds.half_area() * left.count as f32
                + right.bounds.half_area() * right.count as f32;
            let better = match &best {
                None => true,
                Some(s) => cost < s.cost || (cost == s.cost && s.axis == axis),
            };
            if better {
                best = Some(Split {
                    binner,
                    axis,
                    bin: i as u32,
                    cost,
                    left_count: left.count as usize,
                    left: (left.bounds, left.centers),
                    right: (right.bounds, right.centers),
                });
            }
        }
    }
    best
}

fn merge(a: Bin, b: Bin) -> Bin {
    Bin {
        bounds: a.bounds.union(b.bounds),
        centers: a.centers.union(b.centers),
        count: a.count + b.count,
    }
}

/// Reorders `prims` so that those binned below `split.bin` come first; returns how many.
pub(super) fn partition(prims: &mut [PrimRef], split: &Split) -> usize {
    let goes_left = |p: &PrimRef| split.binner.bin(p.center, split.axis) < split.bin;
    let mut i = 0;
    let mut j = prims.len();
    while i < j {
        if prims.get(i).is_some_and(goes_left) {
            i += 1;
        } else {
            j -= 1;
            prims.swap(i, j);
        }
    }
    i
}
