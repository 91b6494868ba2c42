//! Sweeps: a sphere, a capsule or an oriented box moved along a segment against the mesh, and
//! the first time it touches (its time of impact).
//!
//! Each candidate triangle is approached by conservative advancement: at the shape's current
//! place, the closest points give the distance `δ` and the direction `n` from the triangle to
//! the shape; along `n` the gap between the two convex sets closes no faster than the motion's
//! component against `n`, so the shape may advance by `δ` over that speed without passing the
//! first contact (and never touches when the motion does not close the gap along `n`). The
//! walk goes down the tree in the order the shape's moving box enters the nodes and drops every
//! node it cannot enter before the earliest contact found.

use core::ops::ControlFlow;

use glam::Vec3;

use super::{LeafTriangleIds, LeafTriangles, Traverse, Visitor};
use crate::error::SweepError;
use crate::geom::{
    ClosestPair, closest_point_triangle, closest_points_obb_triangle,
    closest_points_segment_triangle, intersect_ray_aabb,
};
use crate::math::{Aabb, Obb, Ray, Triangle, dot, unit_scale};

/// A convex shape a sweep moves, at its place at the start of the motion.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SweepShape {
    /// The points within `radius` of `center`.
    Sphere {
        /// The centre.
        center: Vec3,
        /// The radius, `≥ 0` (0: a point, the sweep a ray).
        radius: f32,
    },
    /// The points within `radius` of the segment `[a, b]` (a character controller's body).
    Capsule {
        /// One end of the core segment.
        a: Vec3,
        /// The other end (equal to `a`: a sphere).
        b: Vec3,
        /// The radius, `≥ 0`.
        radius: f32,
    },
    /// An oriented box, solid.
    Box(Obb),
}

/// Where a sweep first touches the mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SweepHit {
    /// The fraction of the motion done at first contact, in `[0, 1]`: the shape touches the
    /// mesh when moved by `t · motion`. 0 when it touches at the start.
    pub t: f32,
    /// The contact point on the mesh.
    pub point: Vec3,
    /// The contact normal: a unit vector from the mesh toward the shape at contact (for a
    /// shape already in contact at the start, the triangle's normal turned toward the shape's
    /// centre, or against the motion when the centre lies in its plane).
    pub normal: Vec3,
    /// The mesh triangle touched.
    pub tri: u32,
}

/// How close (relative to the sweep's size: the shape's extent plus the motion's length) the
/// shape must come to a triangle to count as touching it: 2⁻¹⁸. The contact `t` is then
/// within that fraction of the motion of the first instant the shape touches.
pub const SWEEP_TOLERANCE: f32 = 1.0 / 262_144.0;

/// Most advancement steps toward one triangle. A contact on a face takes one step and one on
/// an edge or corner a few; grazing approaches take more, and one that has not closed to the
/// tolerance by then counts as touching where it stopped.
const MAX_STEPS: usize = 64;

impl SweepShape {
    /// Whether every coordinate is finite and the radius or box is proper.
    #[must_use]
    pub fn is_valid(&self) -> bool {
        match self {
            Self::Sphere { center, radius } => {
                center.is_finite() && radius.is_finite() && *radius >= 0.0
            }
            Self::Capsule { a, b, radius } => {
                a.is_finite() && b.is_finite() && radius.is_finite() && *radius >= 0.0
            }
            Self::Box(obb) => obb.is_valid(),
        }
    }

    /// A box holding the shape at its start.
    #[must_use]
    pub fn bounds(&self) -> Aabb {
        match self {
            Self::Sphere { center, radius } => Aabb::new(*center - *radius, *center + *radius),
            Self::Capsule { a, b, radius } => Aabb::new(a.min(*b) - *radius, a.max(*b) + *radius),
            Self::Box(obb) => obb.bounds(),
        }
    }

    /// The shape moved by `by`.
    #[must_use]
    pub fn moved(&self, by: Vec3) -> Self {
        match *self {
            Self::Sphere { center, radius } => Self::Sphere {
                center: center + by,
                radius,
            },
            Self::Capsule { a, b, radius } => Self::Capsule {
                a: a + by,
                b: b + by,
                radius,
            },
            Self::Box(obb) => Self::Box(Obb::new(obb.center + by, obb.axes, obb.half_extents)),
        }
    }

    /// The shape with every length multiplied by `s` (a power of two, so exactly).
    fn scaled(&self, s: f32) -> Self {
        match *self {
            Self::Sphere { center, radius } => Self::Sphere {
                center: center * s,
                radius: radius * s,
            },
            Self::Capsule { a, b, radius } => Self::Capsule {
                a: a * s,
                b: b * s,
                radius: radius * s,
            },
            Self::Box(obb) => Self::Box(Obb::new(obb.center * s, obb.axes, obb.half_extents * s)),
        }
    }

    /// The shape's centre (a capsule's segment midpoint).
    fn center(&self) -> Vec3 {
        match *self {
            Self::Sphere { center, .. } => center,
            Self::Capsule { a, b, .. } => (a + b) * 0.5,
            Self::Box(obb) => obb.center,
        }
    }

    /// The rounding radius around the shape's core (a point, a segment or a box).
    fn radius(&self) -> f32 {
        match *self {
            Self::Sphere { radius, .. } | Self::Capsule { radius, .. } => radius,
            Self::Box(_) => 0.0,
        }
    }

    /// The closest points of the shape's core (`on_first`) and `tri` (`on_second`).
    fn core_closest(&self, tri: &Triangle) -> ClosestPair {
        match *self {
            Self::Sphere { center, .. } => {
                let c = closest_point_triangle(center, tri);
                ClosestPair {
                    on_first: center,
                    on_second: c.point,
                    distance_squared: c.distance_squared,
                }
            }
            Self::Capsule { a, b, .. } => closest_points_segment_triangle(a, b, tri),
            Self::Box(obb) => closest_points_obb_triangle(&obb, tri),
        }
    }
}

/// The first contact of `shape` moving by `motion` with triangle `tri`, advancing from `t`
/// (at or before the first contact) up to `limit`: `(t, point on tri, normal)`.
fn time_of_impact(
    shape: &SweepShape,
    motion: Vec3,
    tri: &Triangle,
    t: f32,
    limit: f32,
    tolerance: f32,
) -> Option<(f32, Vec3, Vec3)> {
    // Worked at unit size: the closest-point arithmetic multiplies up to four lengths, which
    // overflows `f32` on triangles beyond about 10⁹. A power of two changes no `t`, and the
    // point is scaled back exactly.
    let b = shape.bounds();
    let reach = [
        tri.a,
        tri.b,
        tri.c,
        b.min,
        b.max,
        b.min + motion,
        b.max + motion,
    ]
    .iter()
    .map(|p| p.abs().max_element())
    .fold(0.0f32, f32::max);
    let s = unit_scale(reach);
    let tri_s = Triangle::new(tri.a * s, tri.b * s, tri.c * s);
    let (at, point, normal) = advance(
        &shape.scaled(s),
        motion * s,
        &tri_s,
        t,
        limit,
        tolerance * s,
    )?;
    Some((at, point / s, normal))
}

/// [`time_of_impact`] at the caller's scale.
fn advance(
    shape: &SweepShape,
    motion: Vec3,
    tri: &Triangle,
    mut t: f32,
    limit: f32,
    tolerance: f32,
) -> Option<(f32, Vec3, Vec3)> {
    let radius = shape.radius();
    for _ in 0..MAX_STEPS {
        let placed = shape.moved(motion * t);
        let c = placed.core_closest(tri);
        let core = libm::sqrtf(c.distance_squared);
        if !core.is_finite() {
            return None;
        }
        let gap = core - radius;
        if gap <= tolerance {
            return Some((
                t,
                c.on_second,
                contact_normal(&placed, tri, &c, core, motion),
            ));
        }
        let n = (c.on_first - c.on_second) / core;
        let closing = -dot(motion, n);
        if !(closing > 0.0) {
            return None;
        }
        t += gap / closing;
        if !(t <= limit) {
            return None;
        }
    }
    let placed = shape.moved(motion * t);
    let c = placed.core_closest(tri);
    let core = libm::sqrtf(c.distance_squared);
    Some((
        t,
        c.on_second,
        contact_normal(&placed, tri, &c, core, motion),
    ))
}

/// The unit normal at a contact: from the triangle's point toward the shape's core, or, when
/// they coincide, the triangle's normal turned toward the shape's centre (against the motion
/// when the centre lies in its plane; the reversed motion's direction for a degenerate
/// triangle).
fn contact_normal(
    placed: &SweepShape,
    tri: &Triangle,
    c: &ClosestPair,
    core: f32,
    motion: Vec3,
) -> Vec3 {
    if core > 0.0 {
        return (c.on_first - c.on_second) / core;
    }
    let against = -motion.normalize_or_zero();
    let Some(n) = tri.unit_normal() else {
        return against;
    };
    let side = dot(placed.center() - c.on_second, n);
    let side = if side == 0.0 { dot(against, n) } else { side };
    if side < 0.0 { -n } else { n }
}

/// The sweep's walk: nodes in the order the shape's moving box enters them.
struct Sweeper<'s, S: ?Sized> {
    source: &'s S,
    shape: SweepShape,
    motion: Vec3,
    /// Half the size of the shape's box, which grows every node box it is tested against.
    half: Vec3,
    /// The ray the box's centre follows, `t` in `[0, 1]`; `None` for no motion.
    path: Option<Ray>,
    center: Vec3,
    tolerance: f32,
    best: Option<SweepHit>,
}

impl<S: LeafTriangles + ?Sized> Sweeper<'_, S> {
    /// When the shape's box first meets `aabb` within the motion (before the best contact).
    fn entry(&self, aabb: &Aabb) -> Option<f32> {
        let grown = Aabb::new(aabb.min - self.half, aabb.max + self.half);
        let limit = self.best.map_or(1.0, |b| b.t);
        match &self.path {
            None => grown.contains_point(self.center).then_some(0.0),
            Some(ray) => intersect_ray_aabb(ray, &grown)
                .map(|(t, _)| t)
                .filter(|&t| t <= limit),
        }
    }
}

impl<S: LeafTriangles + ?Sized> Visitor for Sweeper<'_, S> {
    fn enter(&mut self, aabb: &Aabb) -> Option<f32> {
        self.entry(aabb)
    }

    fn revisit(&self, key: f32) -> bool {
        self.best.is_none_or(|b| key <= b.t)
    }

    fn leaf(&mut self, tris: LeafTriangleIds<'_>) -> ControlFlow<()> {
        for (slot, tri) in tris {
            let Some(t) = self.source.corners(slot, tri) else {
                continue;
            };
            if t.is_degenerate() {
                continue;
            }
            let Some(start) = self.entry(&t.bounds()) else {
                continue;
            };
            let limit = self.best.map_or(1.0, |b| b.t);
            let Some((at, point, normal)) =
                time_of_impact(&self.shape, self.motion, &t, start, limit, self.tolerance)
            else {
                continue;
            };
            let better = self
                .best
                .is_none_or(|b| at < b.t || (at == b.t && tri < b.tri));
            if better {
                self.best = Some(SweepHit {
                    t: at,
                    point,
                    normal,
                    tri,
                });
            }
        }
        ControlFlow::Continue(())
    }
}

/// The first contact of `shape` moved by `motion` (see
/// [`MeshQuery::sweep`](super::MeshQuery::sweep)).
pub(crate) fn sweep<A, S>(
    tree: &A,
    source: &S,
    shape: &SweepShape,
    motion: Vec3,
) -> Result<Option<SweepHit>, SweepError>
where
    A: Traverse + ?Sized,
    S: LeafTriangles + ?Sized,
{
    if !shape.is_valid() {
        return Err(SweepError::InvalidShape);
    }
    if !motion.is_finite() {
        return Err(SweepError::InvalidMotion);
    }
    let bounds = shape.bounds();
    let center = bounds.center();
    let half = bounds.extent() * 0.5;
    let reach = center.abs().max_element() + half.max_element();
    let size = 2.0 * half.length() + motion.length();
    // Rounding in the distances grows with the coordinates' magnitude, so the tolerance never
    // falls below a few units of it.
    let tolerance = (size * SWEEP_TOLERANCE).max(reach * (16.0 * f32::EPSILON));
    let path = (motion != Vec3::ZERO).then(|| {
        let mut ray = Ray::new(center, motion);
        ray.t_max = 1.0;
        ray
    });
    let mut v = Sweeper {
        source,
        shape: *shape,
        motion,
        half,
        path,
        center,
        tolerance,
        best: None,
    };
    tree.traverse(&mut v);
    Ok(v.best)
}
