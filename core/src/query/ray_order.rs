//! The order a batch of rays is answered in. A large batch of rays from many origins, cast at a
//! structure too large for the caches, is sorted by the line each ray draws through the
//! structure's box, so that rays crossing the same region in about the same direction run one
//! after another and find the same nodes and triangles still in cache. Other batches — small
//! ones, small structures, rays from one origin (a camera's, whose runs of eight walk as
//! packets) — keep the given order. Answers never depend on the order.

use glam::Vec3A;

use super::BatchHint;
use super::batch_order::{checked_keys, fill_given_order};
use crate::error::BatchError;
use crate::math::{Aabb, Ray};

/// Bits per coordinate of a line key: six coordinates (the entry and exit points) make a
/// 30-bit key, which leaves the key's low 32 bits to the ray's index.
const BITS: u32 = 5;

/// The fewest rays a batch sorts. Sorting costs a key, a share of the sort, and a scattered
/// read of each ray and write of its answer; it pays back when each ray meets many others
/// crossing the same cells, so more rays gain more (measured in a loop of calls, against
/// calls of 16,384 rays in the given order: on 1.1M triangles 262,144 random rays 1.27–1.39×
/// as fast and 1M 1.55×; on 69,451, 65,536 rays 1.06×, 262,144 1.14×, 1M 1.13–1.20×).
pub(crate) const SORT_MIN_RAYS: usize = 1 << 16;

/// The fewest triangles of a structure whose batches are sorted. Below, nodes and triangles
/// mostly stay in the caches in any order and sorting is mostly cost (measured with 1M
/// random rays, one call against calls of 16,384: 5,804 triangles 0.88×, 12,946 0.90×,
/// 69,451 1.13–1.20× in a loop of calls but level to 0.88× in the `meshq` command, whose
/// scratch for a whole batch is fresh memory; 277,804 1.40×; 1.1M 1.55×).
pub(crate) const SORT_MIN_TRIANGLES: usize = 1 << 17;

// The numbers `MeshQuery::raycast_batch` documents.
const _: () = assert!(SORT_MIN_RAYS == 65_536 && SORT_MIN_TRIANGLES == 131_072);

/// Checks a batch of `rays.len()` rays against its `keys` scratch and its `out_len` answers,
/// then fills the first keys with the ray indices in the order to answer them (the key in the
/// high 32 bits, the index in the low 32) and returns those keys when they are sorted, `None`
/// when they are the given order; read the index back with
/// [`query_index`](super::batch_order::query_index).
///
/// The order: ascending [`KeyGrid::line_key`] over the hint's box (equal keys in the given
/// order) when the batch holds at least [`SORT_MIN_RAYS`] rays, the `hint` names at least
/// [`SORT_MIN_TRIANGLES`] triangles in a finite box, and the valid rays' origins are not all
/// one point; otherwise the given order.
///
/// # Errors
/// [`BatchError::TooLarge`] beyond `u32::MAX` rays; [`BatchError::BufferTooSmall`] for a
/// short `keys` or `out_len`. Nothing is written then.
pub(crate) fn ray_order<'k>(
    rays: &[Ray],
    hint: Option<BatchHint>,
    keys: &'k mut [u64],
    out_len: usize,
) -> Result<Option<&'k [u64]>, BatchError> {
    let keys = checked_keys(rays.len(), keys, out_len)?;
    match KeyGrid::for_batch(rays, hint) {
        Some(grid) => {
            for ((key, ray), i) in keys.iter_mut().zip(rays).zip(0u64..) {
                *key = grid.key(ray, i);
            }
            keys.sort_unstable();
            Ok(Some(keys))
        }
        None => {
            fill_given_order(keys);
            Ok(None)
        }
    }
}

/// Whether [`MeshQuery::raycast_batch`](super::MeshQuery::raycast_batch) (and
/// [`raycast_any_batch`](super::MeshQuery::raycast_any_batch)) answer `rays` on `structure`
/// sorted rather than in the given order: at least 65,536 rays whose origins are not all one
/// point, on a structure whose [`Traverse::batch_hint`](super::Traverse::batch_hint) names at
/// least 131,072 triangles in a finite box. A caller that cuts a large batch into calls gains
/// by keeping such a batch whole, and only such a batch: any other is answered as fast in
/// short calls, whose scratch stays in cache.
#[must_use]
pub fn sorts_ray_batch<T: super::Traverse + ?Sized>(structure: &T, rays: &[Ray]) -> bool {
    KeyGrid::for_batch(rays, structure.batch_hint()).is_some()
}

/// Whether a batch of `count` rays on `structure` is answered sorted when its rays' origins
/// are not all one point (see [`sorts_ray_batch`]): `count` is at least 65,536 and the
/// structure's [`Traverse::batch_hint`](super::Traverse::batch_hint) names at least 131,072
/// triangles in a finite box. For a caller that reads a batch in passes and must choose their
/// length before it has read the rays.
#[must_use]
pub fn sorts_ray_batches_of<T: super::Traverse + ?Sized>(structure: &T, count: usize) -> bool {
    count >= SORT_MIN_RAYS && sorting_bounds(structure.batch_hint()).is_some()
}

/// The box a structure's large batches are sorted over: the hint's, when it names at least
/// [`SORT_MIN_TRIANGLES`] triangles in a finite, non-empty box.
fn sorting_bounds(hint: Option<BatchHint>) -> Option<Aabb> {
    let hint = hint?;
    let bounds = hint.bounds;
    (hint.triangles >= SORT_MIN_TRIANGLES
        && !bounds.is_empty()
        && bounds.min.is_finite()
        && bounds.max.is_finite())
    .then_some(bounds)
}

/// Moves bit `k` of a [`BITS`]-bit value to bit `6k`: five copies of the value, five bits
/// apart, put bit `k` of copy `k` there (the copies cannot carry into each other).
const fn spread(v: u32) -> u32 {
    (v & 0x1F).wrapping_mul(0x0010_8421) & 0x0104_1041
}

/// The box a batch's line keys quantize over, `2^BITS` cells per axis.
pub(crate) struct KeyGrid {
    min: Vec3A,
    max: Vec3A,
    /// Cells per unit length on each axis (0 on a flat axis).
    scale: Vec3A,
}

impl KeyGrid {
    /// The grid to sort `rays` on a structure described by `hint` by, or `None` when they
    /// keep the given order (see [`ray_order`]).
    pub(crate) fn for_batch(rays: &[Ray], hint: Option<BatchHint>) -> Option<Self> {
        if rays.len() < SORT_MIN_RAYS {
            return None;
        }
        let bounds = sorting_bounds(hint)?;
        let mut valid = rays.iter().filter(|r| r.is_valid());
        let origin = valid.next()?.origin.to_array().map(f32::to_bits);
        valid
            .any(|r| r.origin.to_array().map(f32::to_bits) != origin)
            .then(|| Self::over(&bounds))
    }

    /// The sort key of `ray`, ray `index` of its batch: its [`Self::line_key`] in the high 32
    /// bits, the index in the low 32 (so equal line keys keep the given order).
    #[inline(always)]
    pub(crate) fn key(&self, ray: &Ray, index: u64) -> u64 {
        (u64::from(self.line_key(ray)) << 32) | index
    }

    /// The grid over `bounds` (finite, not empty).
    fn over(bounds: &Aabb) -> Self {
        let (min, max) = (Vec3A::from(bounds.min), Vec3A::from(bounds.max));
        let extent = max - min;
        let cells = (1u32 << BITS) as f32;
        let per = |e: f32| if e > 0.0 { cells / e } else { 0.0 };
        Self {
            min,
            max,
            scale: Vec3A::new(per(extent.x), per(extent.y), per(extent.z)),
        }
    }

    /// The cell of `p` on each axis: its offset in cells, clamped to the grid and rounded to
    /// the nearest whole cell (a key only has to put near points together).
    #[inline(always)]
    fn cell(&self, p: Vec3A) -> [u32; 3] {
        let top = (1u32 << BITS) - 1;
        let q = ((p - self.min) * self.scale)
            .max(Vec3A::ZERO)
            .min(Vec3A::splat(top as f32));
        // Adding 2^23 leaves the whole number nearest to each lane in the low bits of its
        // significand: a cast without branches (a saturating `as` compares and branches per
        // coordinate, and random rays mispredict those branches).
        let whole = q + Vec3A::splat(8_388_608.0);
        [whole.x, whole.y, whole.z].map(|v| v.to_bits() & top)
    }

    /// A 30-bit key of the line `ray` draws through the grid's box: the cells of the points
    /// where the ray (within its interval) enters and leaves the box, the six coordinates'
    /// bits interleaved, most significant first (entry x, y, z, then exit x, y, z). A ray that
    /// misses the box keys on its origin alone. Rays with close keys cross the same region in
    /// about the same direction.
    #[inline(always)]
    fn line_key(&self, ray: &Ray) -> u32 {
        let (o, d) = (Vec3A::from(ray.origin), Vec3A::from(ray.dir));
        let inv = d.recip();
        let (a, b) = ((self.min - o) * inv, (self.max - o) * inv);
        // An axis the ray does not move along gives NaN or infinite distances; the interval
        // then comes out empty or infinite, and the ray keys on its origin.
        let t0 = a.min(b).max_element().max(ray.t_min);
        let t1 = a.max(b).min_element().min(ray.t_max);
        let crosses = t0 <= t1 && t0.is_finite() && t1.is_finite();
        let (t0, t1) = if crosses { (t0, t1) } else { (0.0, 0.0) };
        let [ex, ey, ez] = self.cell(o + d * t0);
        let [xx, xy, xz] = self.cell(o + d * t1);
        (spread(ex) << 5)
            | (spread(ey) << 4)
            | (spread(ez) << 3)
            | (spread(xx) << 2)
            | (spread(xy) << 1)
            | spread(xz)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::query::batch_order::query_index;

    fn ray(o: [f32; 3], d: [f32; 3]) -> Ray {
        Ray::new(glam::Vec3::from_array(o), glam::Vec3::from_array(d))
    }

    /// `n` rays from random origins in `[-1, 1]³` in random directions, then the oddities.
    fn random_rays(n: usize) -> Vec<Ray> {
        let mut state = 0x1234_5678_u32;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            (state >> 8) as f32 / (1u32 << 24) as f32 * 2.0 - 1.0
        };
        let mut rays: Vec<Ray> = (0..n)
            .map(|_| ray([next(), next(), next()], [next(), next(), next()]))
            .collect();
        rays.push(ray([f32::NAN, 0.0, 0.0], [1.0, 0.0, 0.0]));
        rays.push(ray([0.0, 0.0, 0.0], [0.0, 0.0, 0.0]));
        rays.push(ray([5.0, 5.0, 5.0], [1.0, 1.0, 1.0]));
        rays
    }

    /// A hint that asks for sorting: a large structure in `[-0.5, 0.5]³`.
    const LARGE: BatchHint = BatchHint {
        bounds: Aabb {
            min: glam::Vec3::splat(-0.5),
            max: glam::Vec3::splat(0.5),
        },
        triangles: SORT_MIN_TRIANGLES,
    };

    fn is_given(order: &[u64]) -> bool {
        order.iter().enumerate().all(|(i, &k)| query_index(k) == i)
    }

    /// A large batch on a large structure is sorted by key: every index once, keys ascending,
    /// and not the given order (the rays are random).
    #[test]
    fn large_batches_are_sorted_permutations() {
        let rays = random_rays(SORT_MIN_RAYS);
        let mut keys = vec![0u64; rays.len()];
        let order = ray_order(&rays, Some(LARGE), &mut keys, rays.len())
            .unwrap()
            .expect("sorted");
        let mut seen = vec![false; rays.len()];
        for &k in order {
            assert!(!core::mem::replace(&mut seen[query_index(k)], true));
        }
        assert!(seen.iter().all(|&s| s));
        assert!(order.windows(2).all(|w| w[0] <= w[1]));
        assert!(!is_given(order));
    }

    /// Everything short of the thresholds keeps the given order: no hint, a small structure,
    /// a small batch, an unusable box, rays from one origin.
    #[test]
    fn other_batches_keep_the_given_order() {
        let rays = random_rays(SORT_MIN_RAYS);
        let mut keys = vec![0u64; rays.len()];
        let small = BatchHint {
            triangles: SORT_MIN_TRIANGLES - 1,
            ..LARGE
        };
        let infinite = BatchHint {
            bounds: Aabb::new(glam::Vec3::ZERO, glam::Vec3::INFINITY),
            ..LARGE
        };
        for hint in [None, Some(small), Some(infinite)] {
            keys.fill(7);
            assert_eq!(ray_order(&rays, hint, &mut keys, rays.len()), Ok(None));
            assert!(is_given(&keys));
        }
        let few = &rays[..SORT_MIN_RAYS - 1];
        keys.fill(7);
        assert_eq!(ray_order(few, Some(LARGE), &mut keys, few.len()), Ok(None));
        assert!(is_given(&keys[..few.len()]));
        let camera: Vec<Ray> = (0..SORT_MIN_RAYS)
            .map(|i| ray([1.0, 2.0, 3.0], [(i % 512) as f32 - 256.0, 1.0, -300.0]))
            .collect();
        keys.fill(7);
        assert_eq!(
            ray_order(&camera, Some(LARGE), &mut keys, camera.len()),
            Ok(None)
        );
        assert!(is_given(&keys[..camera.len()]));
    }

    /// Rays along the same line key alike; rays crossing the box far apart do not.
    #[test]
    fn keys_follow_the_line() {
        let grid = KeyGrid::over(&Aabb::new(glam::Vec3::ZERO, glam::Vec3::splat(32.0)));
        let a = grid.line_key(&ray([0.2, 0.2, 0.2], [1.0, 1.0, 1.0]));
        let b = grid.line_key(&ray([0.3, 0.4, 0.2], [1.0, 1.0, 1.0]));
        let c = grid.line_key(&ray([31.8, 0.2, 0.2], [-1.0, 1.0, 1.0]));
        assert_eq!(a, b);
        assert_ne!(a, c);
        // Entering at the box's lowest corner and leaving at its highest: every entry bit 0,
        // every exit bit 1.
        assert_eq!(a, 0b000111_000111_000111_000111_000111);
        // A ray that misses the box keys on its origin: both points are its (clamped) cell.
        // NaN coordinates key as cell 0, infinite ones as the last cell.
        assert_eq!(
            grid.cell(Vec3A::new(f32::NAN, f32::INFINITY, -1e30)),
            [0, 31, 0]
        );
        let away = grid.line_key(&ray([40.0, 0.2, 0.2], [1.0, 0.0, 0.0]));
        assert_eq!(away, 0b100100_100100_100100_100100_100100);
        // A ray that starts inside keys on its origin's cell (16, 16, 16), then the cell
        // where it leaves (31, 16, 16).
        let inside = grid.line_key(&ray([16.2, 16.2, 16.2], [1.0, 0.0, 0.0]));
        assert_eq!(inside, 0b111111_000100_000100_000100_000100);
    }
}
