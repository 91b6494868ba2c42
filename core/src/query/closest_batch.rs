//! Many closest-point queries in one call (see
//! [`MeshQuery::closest_points`](crate::query::MeshQuery::closest_points)): answered in
//! Morton order of the points, each search seeded with the previous answer, so neighbouring
//! queries read the same nodes and triangles while they are still in cache and start with a
//! tight bound.

use glam::Vec3;

use super::batch_order::{answer_in_order, morton_order};
use super::closest::{answer, search};
use super::leaf_batches::LANES_PAY;
use super::{LeafTriangles, Traverse};
use crate::error::BatchError;
use crate::math::ClosestPoint;

/// [`MeshQuery::closest_points`](crate::query::MeshQuery::closest_points) through any structure.
pub(crate) fn closest_points<A: Traverse + ?Sized, S: LeafTriangles + ?Sized>(
    tree: &A,
    source: &S,
    points: &[Vec3],
    max_distance: f32,
    keys: &mut [u64],
    out: &mut [Option<ClosestPoint>],
) -> Result<(), BatchError> {
    closest_points_by::<A, S, LANES_PAY>(tree, source, points, max_distance, keys, out)
}

/// [`closest_points`] with the leaf test chosen by `LANES`.
pub(super) fn closest_points_by<
    A: Traverse + ?Sized,
    S: LeafTriangles + ?Sized,
    const LANES: bool,
>(
    tree: &A,
    source: &S,
    points: &[Vec3],
    max_distance: f32,
    keys: &mut [u64],
    out: &mut [Option<ClosestPoint>],
) -> Result<(), BatchError> {
    let order = morton_order(points.iter().copied(), keys, out.len())?;
    let mut seed = None;
    answer_in_order(points, order, out, |&p| {
        let best = search::<A, S, LANES>(tree, source, p, max_distance, seed, usize::MAX)
            .ok()
            .flatten();
        seed = best.or(seed);
        best.map(|b| answer(p, b))
    });
    Ok(())
}

/// One closest point seeded with `seed` (the triangle an earlier query nearby found, updated to
/// this one's): exactly [`MeshQuery::closest_point`](crate::query::MeshQuery::closest_point)'s
/// answer, found sooner when the seed is near, as in [`closest_points`].
pub(crate) fn closest_point_seeded<A: Traverse + ?Sized, S: LeafTriangles + ?Sized>(
    tree: &A,
    source: &S,
    point: Vec3,
    max_distance: f32,
    seed: &mut Option<(u32, crate::math::Triangle)>,
) -> Option<ClosestPoint> {
    let best = search::<A, S, LANES_PAY>(tree, source, point, max_distance, *seed, usize::MAX)
        .ok()
        .flatten();
    *seed = best.or(*seed);
    best.map(|b| answer(point, b))
}
