//! Batches across threads (feature `parallel`, which links `std` and
//! [rayon](https://docs.rs/rayon)): the same batch queries as [`MeshQuery`], spread over
//! rayon's thread pool, with the same answers.
//!
//! Each call cuts its queries into runs of [`RUN`] consecutive queries and hands the runs to
//! the pool; a run is answered by the single-threaded batch call ([`MeshQuery::raycast_batch`]
//! and friends), whose answer for query `i` is exactly the single call's. A ray batch that the
//! single-threaded call would sort (a large batch on a large structure) is cut into one sorted
//! piece per thread when the pieces are large enough ([`SORTED_PIECE`]), and otherwise sorted
//! whole, on the pool, and cut into runs in that order. So `out[i]` is the
//! same, bit for bit, whatever the number of threads, the run length or the other queries —
//! and the same as on a target without threads. The pool is rayon's global one unless the
//! call runs inside [`rayon::ThreadPool::install`] (the `meshq` command's `--threads`).
//!
//! ```
//! use meshq::prelude::*;
//! let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
//! let mesh = MeshRef::new(&positions, &[[0, 1, 2]]).validate()?;
//! let scene = MeshBvh::build(&mesh, &BuildConfig::default())?;
//! let rays = [Ray::new(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z); 3];
//! let mut out = [None; 3];
//! meshq::parallel::raycast_batch(&scene, &rays, &RayOptions::default(), &mut out)?;
//! assert_eq!(out.map(|h| h.map(|h| h.tri)), [Some(0); 3]);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use alloc::vec;
use alloc::vec::Vec;

use rayon::prelude::*;

use crate::error::{BatchBuffer, BatchError};
use crate::inside::{SampleGrid, SignedDistance, WindingAccuracy, WindingTree};
use crate::math::{ClosestPoint, Ray, RayHit, Vec3};
use crate::query::batch_order::query_index;
use crate::query::ray_order::KeyGrid;
use crate::query::{MeshQuery, RayOptions};

/// Queries per run handed to a thread: long enough for the Morton order inside a run to keep
/// neighbouring queries together and for a thread's start-up to vanish, short enough for the
/// runs to spread evenly over the threads.
pub const RUN: usize = 4096;

/// The fewest rays per thread for which [`raycast_batch`] and [`raycast_any_batch`] sort each
/// thread's share of a large batch on its own rather than the whole batch on the pool. Fewer
/// rays per sort meet fewer others in each region; from this size on, a share sorts about as
/// well as the whole batch, and it spares the whole-batch sort, copy and write-back (measured
/// on 1.1M triangles on 2 threads, against one thread's call: 1M random rays 1.84–1.97× sorted
/// whole, 2.09× in two sorted pieces; 524,288 rays 1.85–1.96× whole, 1.94–2.15× in pieces;
/// 262,144 rays 1.91× whole, 1.83× in two pieces).
pub const SORTED_PIECE: usize = 1 << 18;

/// Answers `queries` in runs of [`RUN`] on the pool: `batch(run, keys, answers)` is the
/// single-threaded batch call for one run, with `keys` its scratch. `out` must hold at least
/// one element per query; nothing is written otherwise.
fn in_runs<T: Sync, O: Send>(
    queries: &[T],
    out: &mut [O],
    batch: impl Fn(&[T], &mut [u64], &mut [O]) -> Result<(), BatchError> + Sync + Send,
) -> Result<(), BatchError> {
    if out.len() < queries.len() {
        return Err(BatchError::BufferTooSmall {
            buffer: BatchBuffer::Results,
            needed: queries.len(),
            got: out.len(),
        });
    }
    queries
        .par_chunks(RUN)
        .zip(out.par_chunks_mut(RUN))
        .try_for_each(|(run, answers)| batch(run, &mut vec![0u64; run.len()], answers))
}

/// [`MeshQuery::raycast_batch`] on every thread of the pool: `out[i]` is exactly
/// [`MeshQuery::raycast_with`] for `rays[i]`. Elements of `out` past `rays.len()` are left
/// alone.
///
/// # Errors
/// [`BatchError::BufferTooSmall`] when `out` is shorter than `rays`; nothing is written then.
pub fn raycast_batch<Q: MeshQuery + Sync + ?Sized>(
    query: &Q,
    rays: &[Ray],
    options: &RayOptions,
    out: &mut [Option<RayHit>],
) -> Result<(), BatchError> {
    in_ray_order(query, rays, out, |run, keys, answers| {
        query.raycast_batch(run, options, keys, answers)
    })
}

/// [`MeshQuery::raycast_any_batch`] on every thread of the pool: `out[i]` is exactly
/// [`MeshQuery::raycast_any_with`] for `rays[i]`.
///
/// # Errors
/// As [`raycast_batch`].
pub fn raycast_any_batch<Q: MeshQuery + Sync + ?Sized>(
    query: &Q,
    rays: &[Ray],
    options: &RayOptions,
    out: &mut [bool],
) -> Result<(), BatchError> {
    in_ray_order(query, rays, out, |run, keys, answers| {
        query.raycast_any_batch(run, options, keys, answers)
    })
}

/// [`in_runs`] over `rays` in the order a single-threaded batch of them would take on `query`
/// (sorted by line key when the batch and the structure are large, see
/// [`MeshQuery::raycast_batch`]).
///
/// A batch the single-threaded call sorts is answered in one of two ways. When every thread
/// gets at least [`SORTED_PIECE`] rays, the batch is cut into one piece of consecutive rays per
/// thread and each piece is a single-threaded batch call, which sorts that piece itself (no
/// memory beyond each piece's keys, no copy, no write-back). A smaller batch is sorted whole, on
/// the pool (so that rays crossing the same region still meet), copied in that order and cut
/// into runs, shorter than any sorted batch and so each answered as given; each answer is then
/// written back to its ray's place.
fn in_ray_order<Q: MeshQuery + Sync + ?Sized, O: Copy + Default + Send + Sync>(
    query: &Q,
    rays: &[Ray],
    out: &mut [O],
    batch: impl Fn(&[Ray], &mut [u64], &mut [O]) -> Result<(), BatchError> + Sync + Send,
) -> Result<(), BatchError> {
    let grid = KeyGrid::for_batch(rays, query.batch_hint());
    let (Some(grid), Some(first)) = (grid, rays.first()) else {
        return in_runs(rays, out, batch);
    };
    if out.len() < rays.len() {
        return Err(BatchError::BufferTooSmall {
            buffer: BatchBuffer::Results,
            needed: rays.len(),
            got: out.len(),
        });
    }
    if u32::try_from(rays.len()).is_err() {
        return Err(BatchError::TooLarge);
    }
    let threads = rayon::current_num_threads().max(1);
    if rays.len() / threads >= SORTED_PIECE {
        let piece = rays.len().div_ceil(threads);
        return rays
            .par_chunks(piece)
            .zip(out.par_chunks_mut(piece))
            .try_for_each(|(run, answers)| batch(run, &mut vec![0u64; run.len()], answers));
    }
    let mut keys: Vec<u64> = rays
        .par_iter()
        .enumerate()
        .map(|(i, ray)| grid.key(ray, i as u64))
        .collect();
    keys.par_sort_unstable();
    let sorted: Vec<Ray> = keys
        .par_iter()
        .map(|&key| rays.get(query_index(key)).copied().unwrap_or(*first))
        .collect();
    let mut answers = vec![O::default(); rays.len()];
    in_runs(&sorted, &mut answers, batch)?;
    // Where each ray's answer landed: the inverse of the order, so that the answers are
    // written back by a gather on the pool rather than a scatter.
    let mut place = vec![0u32; rays.len()];
    for (&key, at) in keys.iter().zip(0u32..) {
        if let Some(slot) = place.get_mut(query_index(key)) {
            *slot = at;
        }
    }
    out.par_iter_mut()
        .zip(place.par_iter())
        .for_each(|(slot, &at)| {
            if let Some(&answer) = answers.get(at as usize) {
                *slot = answer;
            }
        });
    Ok(())
}

/// [`MeshQuery::closest_points`] on every thread of the pool: `out[i]` is exactly
/// [`MeshQuery::closest_point`] for `points[i]` and `max_distance`.
///
/// # Errors
/// As [`raycast_batch`].
pub fn closest_points<Q: MeshQuery + Sync + ?Sized>(
    query: &Q,
    points: &[Vec3],
    max_distance: f32,
    out: &mut [Option<ClosestPoint>],
) -> Result<(), BatchError> {
    in_runs(points, out, |run, keys, answers| {
        query.closest_points(run, max_distance, keys, answers)
    })
}

/// [`WindingTree::winding_numbers`] on every thread of the pool: `out[i]` is exactly
/// [`WindingTree::winding_number`] for `points[i]`.
///
/// # Errors
/// As [`raycast_batch`].
pub fn winding_numbers(
    tree: &WindingTree<'_>,
    points: &[Vec3],
    accuracy: WindingAccuracy,
    out: &mut [f32],
) -> Result<(), BatchError> {
    in_runs(points, out, |run, keys, answers| {
        tree.winding_numbers(run, accuracy, keys, answers)
    })
}

/// [`WindingTree::signed_distances`] on every thread of the pool: `out[i]` is exactly
/// [`WindingTree::signed_distance`] for `points[i]`.
///
/// # Errors
/// As [`raycast_batch`].
pub fn signed_distances<Q: MeshQuery + Sync + ?Sized>(
    tree: &WindingTree<'_>,
    surface: &Q,
    points: &[Vec3],
    max_distance: f32,
    accuracy: WindingAccuracy,
    out: &mut [Option<SignedDistance>],
) -> Result<(), BatchError> {
    in_runs(points, out, |run, keys, answers| {
        tree.signed_distances(surface, run, max_distance, accuracy, keys, answers)
    })
}

/// [`WindingTree::signed_distance_grid`] for the whole of `grid` on every thread of the pool,
/// in runs of [`RUN`] samples: `out[i]` is exactly the single-threaded value.
///
/// # Errors
/// [`BatchError::BufferTooSmall`] when `out` does not hold exactly one value per sample.
pub fn signed_distance_grid<Q: MeshQuery + Sync + ?Sized>(
    tree: &WindingTree<'_>,
    surface: &Q,
    grid: &SampleGrid,
    band: f32,
    accuracy: WindingAccuracy,
    out: &mut [f32],
) -> Result<(), BatchError> {
    if out.len() != grid.len() {
        return Err(BatchError::BufferTooSmall {
            buffer: BatchBuffer::Results,
            needed: grid.len(),
            got: out.len(),
        });
    }
    out.par_chunks_mut(RUN)
        .enumerate()
        .try_for_each(|(run, values)| {
            tree.signed_distance_grid(surface, grid, band, accuracy, run * RUN, values)
        })
}
