//! Many rays in one call (see
//! [`MeshQuery::raycast_batch`](crate::query::MeshQuery::raycast_batch)): cast in Morton order
//! of their origins, so rays that start close together read the same nodes and triangles
//! while they are still in cache.

use super::batch_order::{answer_in_order, morton_order};
use super::ray::{raycast_any_with, raycast_with};
use super::{LeafTriangles, RayOptions, Traverse};
use crate::error::BatchError;
use crate::math::{Ray, RayHit};

/// [`MeshQuery::raycast_batch`](crate::query::MeshQuery::raycast_batch) through any structure.
pub(crate) fn raycast_batch<A: Traverse + ?Sized, S: LeafTriangles + ?Sized>(
    tree: &A,
    source: &S,
    rays: &[Ray],
    options: &RayOptions,
    keys: &mut [u64],
    out: &mut [Option<RayHit>],
) -> Result<(), BatchError> {
    let order = morton_order(rays.iter().map(|r| r.origin), keys, out.len())?;
    answer_in_order(rays, order, out, |ray| {
        raycast_with(tree, source, ray, options)
    });
    Ok(())
}

/// [`MeshQuery::raycast_any_batch`](crate::query::MeshQuery::raycast_any_batch) over any
/// storage.
pub(crate) fn raycast_any_batch<A: Traverse + ?Sized, S: LeafTriangles + ?Sized>(
    tree: &A,
    source: &S,
    rays: &[Ray],
    options: &RayOptions,
    keys: &mut [u64],
    out: &mut [bool],
) -> Result<(), BatchError> {
    let order = morton_order(rays.iter().map(|r| r.origin), keys, out.len())?;
    answer_in_order(rays, order, out, |ray| {
        raycast_any_with(tree, source, ray, options)
    });
    Ok(())
}
