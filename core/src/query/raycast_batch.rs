//! Many rays in one call (see
//! [`MeshQuery::raycast_batch`](crate::query::MeshQuery::raycast_batch)): cast in the given
//! order, runs of rays from one origin as packets on the structures that walk them.
//!
//! Large batches of rays from many origins on large structures are answered in the order of
//! [`ray_order`]: sorted by the line each ray draws through the structure's box. Other batches
//! keep the given order (a caller's order is usually coherent already: a camera's pixels).

use super::ray::{Nearest, NearestOne, Occluded};
use super::ray_order::ray_order;
use super::ray_packet::{BatchGoal, answer_in_order, answer_in_runs};
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
    match ray_order(rays, tree.batch_hint(), keys, out.len())? {
        Some(order) => {
            answer_in_order::<_, _, ClosestHits>(tree, source, rays, options, order, out)
        }
        None => answer_in_runs::<_, _, ClosestHits>(tree, source, rays, options, out, &mut true),
    }
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
    match ray_order(rays, tree.batch_hint(), keys, out.len())? {
        Some(order) => answer_in_order::<_, _, AnyHits>(tree, source, rays, options, order, out),
        None => answer_in_runs::<_, _, AnyHits>(tree, source, rays, options, out, &mut true),
    }
    Ok(())
}

/// Each ray's closest hit: [`Nearest`] per ray of a packet, [`NearestOne`] for a ray alone
/// (the goal a single [`raycast`](crate::query::MeshQuery::raycast) walks with, so the two
/// share one compiled walk).
struct ClosestHits;

impl BatchGoal for ClosestHits {
    type Answer = Option<RayHit>;
    type InPacket = Nearest;
    type Alone = NearestOne;
    fn in_packet() -> Nearest {
        Nearest(None)
    }
    fn alone() -> NearestOne {
        NearestOne::NONE
    }
    fn of_packet(goal: &Nearest) -> Option<RayHit> {
        goal.0
    }
    fn of_alone(goal: &NearestOne) -> Option<RayHit> {
        goal.hit()
    }
}

/// Whether each ray hits anything: [`Occluded`] both ways.
struct AnyHits;

impl BatchGoal for AnyHits {
    type Answer = bool;
    type InPacket = Occluded;
    type Alone = Occluded;
    fn in_packet() -> Occluded {
        Occluded(false)
    }
    fn alone() -> Occluded {
        Occluded(false)
    }
    fn of_packet(goal: &Occluded) -> bool {
        goal.0
    }
    fn of_alone(goal: &Occluded) -> bool {
        goal.0
    }
}
