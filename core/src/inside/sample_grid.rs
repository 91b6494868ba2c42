//! [`SampleGrid`]: the lattice of points a signed-distance volume samples.

use glam::Vec3;

use crate::math::Aabb;

/// A regular lattice of sample points over a box: `counts[0] × counts[1] × counts[2]` points
/// `min + (i, j, k) · spacing`, from the box's `min` corner to its `max` corner inclusive (a
/// count of 1 puts the one sample at `min`). Sample `(i, j, k)` has index `i + nx·(j + ny·k)`:
/// x fastest, then y, then z, the order of a 3D texture and of NRRD and raw volume files.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SampleGrid {
    min: Vec3,
    spacing: Vec3,
    counts: [u32; 3],
}

impl SampleGrid {
    /// The grid of `counts` samples spanning `bounds`. `None` when a count is 0, the product
    /// of the counts overflows `usize`, or the box is empty or not finite.
    #[must_use]
    pub fn new(bounds: Aabb, counts: [u32; 3]) -> Option<Self> {
        let extent = bounds.max - bounds.min;
        if !(bounds.min.is_finite() && extent.is_finite() && extent.min_element() >= 0.0) {
            return None;
        }
        counts
            .iter()
            .try_fold(1usize, |n, &c| n.checked_mul(usize::try_from(c).ok()?))
            .filter(|&n| n > 0)?;
        let step = |e: f32, c: u32| if c > 1 { e / (c - 1) as f32 } else { 0.0 };
        Some(Self {
            min: bounds.min,
            spacing: Vec3::new(
                step(extent.x, counts[0]),
                step(extent.y, counts[1]),
                step(extent.z, counts[2]),
            ),
            counts,
        })
    }

    /// The grid over `bounds` grown by `padding` times its largest side on every side, with
    /// cubic cells (one spacing on every axis, exactly) and `resolution` samples along the
    /// longest axis (the others in proportion, at least one each, centred on the box). `None` as for [`SampleGrid::new`], or for a `resolution` below 2 or
    /// a negative or non-finite `padding`.
    #[must_use]
    pub fn cubic(bounds: Aabb, resolution: u32, padding: f32) -> Option<Self> {
        if resolution < 2 || !(padding >= 0.0 && padding.is_finite()) {
            return None;
        }
        let side = (bounds.max - bounds.min).max_element();
        let grow = Vec3::splat(side * padding);
        let (min, max) = (bounds.min - grow, bounds.max + grow);
        let cell = (max - min).max_element() / (resolution - 1) as f32;
        if !(cell > 0.0) {
            return Self::new(Aabb::new(min, max), [resolution; 3]);
        }
        // Whole cells along the shorter axes, centred on the box.
        let along = |e: f32| libm::ceilf(e / cell).clamp(0.0, (resolution - 1) as f32);
        let cells = Vec3::new(
            along(max.x - min.x),
            along(max.y - min.y),
            along(max.z - min.z),
        );
        let centre = (min + max) * 0.5;
        let counts = [cells.x as u32 + 1, cells.y as u32 + 1, cells.z as u32 + 1];
        // The same spacing on every axis, exactly: the cells are cubes.
        Some(Self {
            min: centre - cells * (cell * 0.5),
            spacing: Vec3::splat(cell),
            counts,
        })
        .filter(|g| g.min.is_finite())
    }

    /// Samples along x, y and z.
    #[must_use]
    pub const fn counts(&self) -> [u32; 3] {
        self.counts
    }

    /// The first sample, the box's `min` corner.
    #[must_use]
    pub const fn min(&self) -> Vec3 {
        self.min
    }

    /// The distance between neighbouring samples along each axis.
    #[must_use]
    pub const fn spacing(&self) -> Vec3 {
        self.spacing
    }

    /// The number of samples.
    #[must_use]
    pub fn len(&self) -> usize {
        self.counts.iter().map(|&c| c as usize).product()
    }

    /// Never true: a grid holds at least one sample.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Sample `index` (x fastest); points past the end continue the last z layer's pattern.
    #[must_use]
    pub fn point(&self, index: usize) -> Vec3 {
        let [nx, ny, _] = self.counts.map(|c| c.max(1) as usize);
        let (i, j, k) = (index % nx, (index / nx) % ny, index / (nx * ny));
        self.min + self.spacing * Vec3::new(i as f32, j as f32, k as f32)
    }
}
