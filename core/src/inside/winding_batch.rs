//! Many winding numbers or signed distances in one call: answered in Morton order of the
//! points, [`PACKET`] neighbours per tree walk, each answer exactly the single call's.

use glam::Vec3;

use super::winding_walk::{GROUPS, PACKET};
use super::{SignedDistance, WindingAccuracy, WindingTree};
use crate::error::BatchError;
use crate::query::batch_order::{morton_order, query_index};
use crate::query::{MeshQuery, Traverse};

impl WindingTree<'_> {
    /// [`WindingTree::winding_number`] of each point into `out[i]`, bit for bit. `keys` is
    /// scratch, one `u64` per point: the points are taken in Morton order, neighbours sharing
    /// one walk of the tree. Elements of `out` past `points.len()` are left alone.
    ///
    /// # Errors
    /// [`BatchError::BufferTooSmall`] when `keys` or `out` is shorter than `points`,
    /// [`BatchError::TooLarge`] beyond `u32::MAX` points; nothing is written then.
    pub fn winding_numbers(
        &self,
        points: &[Vec3],
        accuracy: WindingAccuracy,
        keys: &mut [u64],
        out: &mut [f32],
    ) -> Result<(), BatchError> {
        let order = morton_order(points.iter().copied(), keys, out.len())?;
        for packet in order.chunks(PACKET) {
            let lanes = gather(points, packet);
            let numbers = self.winding_lanes(&grouped(lanes), accuracy);
            for (&key, w) in packet.iter().zip(numbers.as_flattened()) {
                if let Some(slot) = out.get_mut(query_index(key)) {
                    *slot = *w;
                }
            }
        }
        Ok(())
    }

    /// [`WindingTree::signed_distance`] of each point into `out[i]`, exactly. `keys` is
    /// scratch, one `u64` per point, as for [`WindingTree::winding_numbers`].
    ///
    /// # Errors
    /// As [`WindingTree::winding_numbers`].
    pub fn signed_distances(
        &self,
        points: &[Vec3],
        max_distance: f32,
        accuracy: WindingAccuracy,
        keys: &mut [u64],
        out: &mut [Option<SignedDistance>],
    ) -> Result<(), BatchError> {
        let order = morton_order(points.iter().copied(), keys, out.len())?;
        let (mesh, bvh) = (self.mesh(), self.bvh());
        let surface = bvh.with(&mesh);
        for packet in order.chunks(PACKET) {
            let mut lanes = gather(points, packet);
            let mut closest = [None; PACKET];
            for (c, p) in closest.iter_mut().zip(lanes.iter_mut()) {
                *c = surface.closest_point(*p, max_distance);
                if c.is_none() {
                    *p = Vec3::NAN; // No answer: the walk skips the lane.
                }
            }
            let numbers = self.winding_lanes(&grouped(lanes), accuracy);
            for ((&key, c), &w) in packet.iter().zip(closest).zip(numbers.as_flattened()) {
                let (Some(slot), Some(&p)) =
                    (out.get_mut(query_index(key)), points.get(query_index(key)))
                else {
                    continue;
                };
                *slot = c.map(|closest| SignedDistance::new(p, closest, w));
            }
        }
        Ok(())
    }
}

/// The points a packet of keys names; lanes past the packet's end hold NaN (skipped).
fn gather(points: &[Vec3], packet: &[u64]) -> [Vec3; PACKET] {
    let mut lanes = [Vec3::NAN; PACKET];
    for (lane, &key) in lanes.iter_mut().zip(packet) {
        if let Some(&p) = points.get(query_index(key)) {
            *lane = p;
        }
    }
    lanes
}

/// A packet's points in groups of four lanes.
fn grouped(lanes: [Vec3; PACKET]) -> [[Vec3; 4]; GROUPS] {
    let mut groups = [[Vec3::NAN; 4]; GROUPS];
    for (slot, p) in groups.as_flattened_mut().iter_mut().zip(lanes) {
        *slot = p;
    }
    groups
}
