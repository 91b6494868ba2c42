//! Many rays in one call (see
//! [`MeshQuery::raycast_batch`](crate::query::MeshQuery::raycast_batch)): cast in the given
//! order, runs of rays from one origin as packets on the structures that walk them.
//!
//! Rays are not reordered: sorting them by origin (as point batches are) made random rays
//! slower, gathering each ray and scattering its answer out of cache for no reuse of the tree,
//! and a caller's order is usually already coherent (a camera's pixels).

use super::batch_order::given_order;
use super::ray::{Nearest, NearestOne, Occluded};
use super::ray_packet::{BatchGoal, answer_in_packets};
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
    answer_in_packets::<_, _, ClosestHits>(tree, source, rays, options, order, out);
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
    answer_in_packets::<_, _, AnyHits>(tree, source, rays, options, order, out);
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
