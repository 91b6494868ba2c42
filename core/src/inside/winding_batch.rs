//! Many winding numbers or signed distances in one call: answered in Morton order of the
//! points, [`PACKET`] neighbours per tree walk, each answer exactly the single call's.

use glam::Vec3;

use super::winding_walk::{GROUPS, PACKET};
use super::{SampleGrid, SignedDistance, WindingAccuracy, WindingNodes, WindingTree};
use crate::bvh::TreeArrays;
use crate::error::BatchError;
use crate::query::LeafTriangles;
use crate::query::batch_order::{morton_order, query_index};
use crate::query::{MeshQuery, closest_point_seeded};

impl<T: TreeArrays, S: LeafTriangles, E: WindingNodes> WindingTree<'_, T, S, E> {
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

    /// [`WindingTree::signed_distance`] of each point into `out[i]`, exactly, the closest
    /// points found by `surface`: any structure over this tree's mesh with its triangles — the
    /// owned `MeshBvh` (feature `alloc`) that holds this tree (its wide nodes over
    /// packed triangles, the fastest), a blob's view, or `tree.bvh().with(&tree.mesh())` —
    /// each finds the same points, bit for bit. `keys` is scratch, one `u64` per point, as for
    /// [`WindingTree::winding_numbers`].
    ///
    /// # Errors
    /// As [`WindingTree::winding_numbers`].
    pub fn signed_distances<Q: MeshQuery + ?Sized>(
        &self,
        surface: &Q,
        points: &[Vec3],
        max_distance: f32,
        accuracy: WindingAccuracy,
        keys: &mut [u64],
        out: &mut [Option<SignedDistance>],
    ) -> Result<(), BatchError> {
        let order = morton_order(points.iter().copied(), keys, out.len())?;
        // Each search seeded with the last one's triangle, a Morton neighbour's.
        let mut seed = None;
        for packet in order.chunks(PACKET) {
            let mut lanes = gather(points, packet);
            let mut closest = [None; PACKET];
            for (c, p) in closest.iter_mut().zip(lanes.iter_mut()) {
                *c = closest_point_seeded(surface, surface, *p, max_distance, &mut seed);
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

impl<T: TreeArrays, S: LeafTriangles, E: WindingNodes> WindingTree<'_, T, S, E> {
    /// The signed distance at every sample of `grid` into `out[index]` (x fastest; see
    /// [`SampleGrid`]), negative inside; samples farther than `band` from the surface get
    /// `±band` with their side's sign (`f32::INFINITY`: no band, every sample exact). Each
    /// value is [`WindingTree::signed_distance`]'s `distance` for the sample with
    /// `max_distance = band` where that finds a surface point (the closest points found by
    /// `surface`, as for [`WindingTree::signed_distances`]). Runs of eight samples along x
    /// walk the tree together. Answers `out[first..]` for the samples `first..first +
    /// out.len()` (clipped to the grid), so a volume can be filled in slices.
    ///
    /// # Errors
    /// [`BatchError::BufferTooSmall`] when `out` is empty or reaches past the grid's end;
    /// nothing is written then.
    pub fn signed_distance_grid<Q: MeshQuery + ?Sized>(
        &self,
        surface: &Q,
        grid: &SampleGrid,
        band: f32,
        accuracy: WindingAccuracy,
        first: usize,
        out: &mut [f32],
    ) -> Result<(), BatchError> {
        let needed = first.saturating_add(out.len());
        if out.is_empty() || needed > grid.len() {
            return Err(BatchError::BufferTooSmall {
                buffer: crate::error::BatchBuffer::Results,
                needed: grid.len().saturating_sub(first).max(1),
                got: out.len(),
            });
        }
        // Each search seeded with the last one's triangle, a sample away.
        let mut seed = None;
        for (run, values) in out.chunks_mut(PACKET).enumerate() {
            let start = first + run * PACKET;
            let mut lanes = [Vec3::NAN; PACKET];
            let mut closest = [None; PACKET];
            for (k, (lane, c)) in lanes
                .iter_mut()
                .zip(closest.iter_mut())
                .enumerate()
                .take(values.len())
            {
                *lane = grid.point(start + k);
                *c = closest_point_seeded(surface, surface, *lane, band, &mut seed);
            }
            let numbers = self.winding_lanes(&grouped(lanes), accuracy);
            for (((v, c), &w), &p) in values
                .iter_mut()
                .zip(closest)
                .zip(numbers.as_flattened())
                .zip(&lanes)
            {
                let inside = w.abs() >= 0.5;
                *v = match c {
                    Some(c) => SignedDistance::new(p, c, w).distance,
                    None if inside => -band,
                    None => band,
                };
            }
        }
        Ok(())
    }
}
