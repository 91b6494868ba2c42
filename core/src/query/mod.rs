//! The query layer: every query meshq answers, written once over a small traversal trait that
//! every structure implements.
//!
//! - A structure ([`Bvh`](crate::bvh::Bvh), [`WideBvh`](crate::wide::WideBvh), a blob's tree,
//!   your own) implements [`Traverse`]: it walks its boxes (or cells) and leaves, asking a
//!   [`Visitor`] which boxes to enter and in what order, and when deferred work is no longer
//!   worth doing.
//! - The layer supplies the visitors — closest hit, any hit, every hit, closest point, box,
//!   sphere, triangle and oriented-box overlap, sweeps — with the leaf tests (four triangles at a time
//!   in SIMD lanes where the target has them), the tie rule and the Morton-ordered batches.
//! - [`Traverse::with`] pairs a structure with its triangles ([`LeafTriangles`]: the mesh, or
//!   [`PackedTriangles`] in the structure's slot order), and the pair answers every query of
//!   [`MeshQuery`].
//!
//! ```
//! use meshq::prelude::*;
//! # let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
//! # let triangles = [[0u32, 1, 2]];
//! let mesh = MeshRef::new(&positions, &triangles).validate()?;
//! let mut buffers = BvhBuffers::<1>::new();
//! let bvh = buffers.build(&mesh, &BuildConfig::default())?;
//! let hit = bvh.with(&mesh).raycast(&Ray::new(Vec3::new(0.25, 0.25, 1.0), -Vec3::Z));
//! assert_eq!(hit.map(|h| h.tri), Some(0));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Glossary
//! - *slot*: a position in a structure's array of triangle references (a BVH's `order`); a
//!   leaf holds consecutive slots, and packed triangles are stored by slot.
//! - *lane*: one of the four SIMD positions of a [`Aabb4`](crate::advanced::Aabb4) or a batch of
//!   four leaf triangles.
//! - *key*: the number a visitor gives a box it enters, ordering the walk (see [`Visitor`]).
//! - *distance*: Euclidean; ray queries speak of the ray parameter `t` instead.
//!
//! # Adding a structure
//! Implement [`Traverse`]: walk your structure, call [`Visitor::enter`] (or
//! [`Visitor::enter_lanes`] for four boxes at once) on each box before going into it, visit
//! entered boxes in ascending key order where you can, ask [`Visitor::revisit`] before
//! returning to a deferred box, and hand each leaf's triangles to [`Visitor::leaf`] until it
//! breaks. A structure that walks cells along a ray (a grid, a k-d tree) reads the ray from
//! [`Visitor::ray`] and stops at the first cell whose entry `t` fails `revisit`. Nothing else
//! is needed: the queries, their batches and their tests come from the layer.
//!
//! # The visitor's contract
//! A [`Visitor`] judges boxes ([`enter`](Visitor::enter) one, or a group of four or eight in
//! SIMD lanes: [`enter_lanes`](Visitor::enter_lanes), [`enter_lanes8`](Visitor::enter_lanes8),
//! [`enter_computed_lanes`](Visitor::enter_computed_lanes) for boxes the structure has just
//! computed), decides whether deferred work is still worth doing
//! ([`revisit`](Visitor::revisit)), takes leaves ([`leaf`](Visitor::leaf), or
//! [`leaf_in`](Visitor::leaf_in) with the leaf's box) and, for structures that march cells
//! along a ray, names its [`ray`](Visitor::ray). Everything a structure may skip for a
//! particular query is said once, in [`VisitorHints`] ([`hints`](Visitor::hints)): whether empty
//! lanes are ever entered, whether nearest-first order matters, whether repeats may be skipped,
//! whether cells and leaf boxes are read. Only `enter` and `leaf` have no default.
//!
//! The smallest structure is a scan: one leaf holding every triangle. It answers every query,
//! exactly as the BVH does:
//!
//! ```
//! use core::ops::ControlFlow;
//! use meshq::prelude::*;
//! use meshq::advanced::LeafTriangleIds;
//! use meshq::query::Visitor;
//!
//! /// Every triangle in one leaf, with the mesh's bounds as its box.
//! struct Scan<'a> {
//!     order: &'a [u32],
//!     bounds: Aabb,
//! }
//!
//! impl Traverse for Scan<'_> {
//!     fn traverse<V: Visitor + ?Sized>(&self, visitor: &mut V) {
//!         if visitor.enter(&self.bounds).is_some() {
//!             let _ = visitor.leaf(LeafTriangleIds::new(0, self.order));
//!         }
//!     }
//! }
//!
//! let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
//! let mesh = MeshRef::new(&positions, &[[0, 1, 2], [0, 1, 3]]).validate()?;
//! let scan = Scan { order: &[0, 1], bounds: mesh.bounds() };
//! let mut buffers = BvhBuffers::<2>::new();
//! let bvh = buffers.build(&mesh, &BuildConfig::default())?;
//!
//! let ray = Ray::new(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z);
//! assert_eq!(scan.with(&mesh).raycast(&ray), bvh.with(&mesh).raycast(&ray));
//! let p = Vec3::new(0.3, -1.0, 0.2);
//! assert_eq!(scan.with(&mesh).closest_point(p, f32::INFINITY),
//!            bvh.with(&mesh).closest_point(p, f32::INFINITY));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub(crate) mod batch_order;
pub(crate) mod cell;
mod closest;
mod closest_batch;
pub(crate) use closest_batch::closest_point_seeded;
mod closest_far;
pub(crate) mod leaf;
mod leaf_batches;
mod mesh_query;
mod overlap;
mod overlap_shapes;
mod ray;
mod ray_all;
pub(crate) mod ray_order;
mod ray_packet;
mod raycast_batch;
mod shapecast;
pub(crate) mod split_refs;
mod sweep;
pub(crate) mod traverse;

pub(crate) use cell::Cell;
pub(crate) use closest::{answer as closest_answer, nearest_triangle};
pub(crate) use leaf::LeafTriangleIds;
pub use leaf::{LeafTriangles, PackedTriangles};
pub use mesh_query::MeshQuery;
pub use overlap::OverlapCount;
pub use ray::{RayOptions, TriangleTest};
pub use ray_all::RayHits;
pub use ray_order::{sorts_ray_batch, sorts_ray_batches_of};
pub use shapecast::{BoundsOverlap, ShapeCast};
pub(crate) use split_refs::SplitRef;
pub(crate) use split_refs::SplitRefs;
pub use sweep::{SWEEP_TOLERANCE, SweepHit, SweepShape};
pub(crate) use traverse::BatchHint;
pub use traverse::{Traverse, Visitor, VisitorHints, With};
