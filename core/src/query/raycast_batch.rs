//! Many rays in one call (see
//! [`MeshQuery::raycast_batch`](crate::query::MeshQuery::raycast_batch)): cast in the given
//! order, runs of rays from one origin as packets on the structures that walk them.
//!
//! Rays are not reordered: sorting them by origin (as point batches are) made random rays
//! slower, gathering each ray and scattering its answer out of cache for no reuse of the tree,
//! and a caller's order is usually already coherent (a camera's pixels).

use super::batch_order::given_order;
use super::ray::{Nearest, Occluded};
use super::ray_packet::answer_in_packets;
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
    let order = given_order(rays.len(), keys, out.len())?;
    answer_in_packets(
        tree,
        source,
        rays,
        options,
        order,
        out,
        || Nearest(None),
        |g| g.0,
    );
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
    let order = given_order(rays.len(), keys, out.len())?;
    answer_in_packets(
        tree,
        source,
        rays,
        options,
        order,
        out,
        || Occluded(false),
        |g| g.0,
    );
    Ok(())
}
