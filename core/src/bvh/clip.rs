//! The box of the part of a triangle between two planes of one axis: how a spatial split
//! bounds each side of a triangle it cuts.

use glam::{BVec3A, Vec3A};

use super::build_box::BuildBox;

/// Relative margin added around a point where an edge crosses a plane: the crossing is
/// computed as `p + (q − p)·s`, off by a few units in the last place of `|p| + |q|`, and the
/// box must hold the exact part of the triangle (2⁻²¹ is eight times the bound).
const CROSSING_MARGIN: f32 = 1.0 / 2_097_152.0;

/// Component `axis` of `v` (0, 1, anything else z).
#[inline(always)]
pub(super) fn lane(v: Vec3A, axis: usize) -> f32 {
    match axis {
        0 => v.x,
        1 => v.y,
        _ => v.z,
    }
}

/// The lane mask of `axis` (0, 1, anything else z), for replacing that component by a select
/// (a write to one lane of a register would go through memory).
#[inline(always)]
fn lane_mask(axis: usize) -> BVec3A {
    BVec3A::new(axis == 0, axis == 1, axis >= 2)
}

/// A box holding the points where the edges of triangle `corners` cross the plane
/// `axis = plane` (empty when none does), each grown by the rounding of its computation.
#[inline(always)]
fn crossings(corners: &[Vec3A; 3], axis: usize, plane: f32) -> BuildBox {
    let on_axis = lane_mask(axis);
    let at_plane = Vec3A::splat(plane);
    let mut b = BuildBox::EMPTY;
    for (i, &p) in corners.iter().enumerate() {
        let q = corners.get((i + 1) % 3).copied().unwrap_or(p);
        let (pa, qa) = (lane(p, axis), lane(q, axis));
        if (pa < plane && plane < qa) || (qa < plane && plane < pa) {
            let x = p + (q - p) * ((plane - pa) / (qa - pa));
            let m = (p.abs() + q.abs()) * CROSSING_MARGIN;
            b = b
                .grown(Vec3A::select(on_axis, at_plane, x - m))
                .grown(Vec3A::select(on_axis, at_plane, x + m));
        }
    }
    b
}

/// `b` cut down to `within`.
#[inline(always)]
fn limited(b: BuildBox, within: &BuildBox) -> BuildBox {
    BuildBox {
        min: b.min.max(within.min),
        max: b.max.min(within.max),
    }
}

/// A box holding the part of triangle `corners` whose coordinate `axis` lies in `[lo, hi]`,
/// intersected with `within` (the box of the part already kept by earlier cuts). Empty when
/// that part is. Conservative: the exact part is inside, whatever the rounding.
pub(super) fn clipped(
    corners: &[Vec3A; 3],
    axis: usize,
    lo: f32,
    hi: f32,
    within: &BuildBox,
) -> BuildBox {
    let mut b = crossings(corners, axis, lo).union(crossings(corners, axis, hi));
    for &p in corners {
        let pa = lane(p, axis);
        if pa >= lo && pa <= hi {
            b = b.grown(p);
        }
    }
    limited(b, within)
}

/// Calls `part(b, box)` for each slab `b` of `first..=last` along `axis`, whose lower plane is
/// `plane(b)` (the first slab reaching down and the last up without bound), with a box of the
/// part of triangle `corners` in it, intersected with `within`: what [`clipped`] gives for
/// each slab, with each plane's crossings computed once. For estimates: a corner lying
/// exactly on an inner plane counts in the slab `slab_of` puts it in only.
pub(super) fn slab_parts(
    corners: &[Vec3A; 3],
    axis: usize,
    (first, last): (usize, usize),
    plane: impl Fn(usize) -> f32,
    slab_of: impl Fn(f32) -> usize,
    within: &BuildBox,
    mut part: impl FnMut(usize, BuildBox),
) {
    let slabs = corners.map(|p| slab_of(lane(p, axis)).clamp(first, last));
    let mut below = BuildBox::EMPTY;
    for b in first..=last {
        let above = if b < last {
            crossings(corners, axis, plane(b + 1))
        } else {
            BuildBox::EMPTY
        };
        let mut bx = below.union(above);
        for (&p, &s) in corners.iter().zip(&slabs) {
            if s == b {
                bx = bx.grown(p);
            }
        }
        part(b, limited(bx, within));
        below = above;
    }
}

/// Whether `b` holds anything (`min ≤ max` on every axis).
#[inline(always)]
pub(super) fn holds_something(b: &BuildBox) -> bool {
    b.min.cmple(b.max).all()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn corners() -> [Vec3A; 3] {
        [
            Vec3A::new(0.0, 0.0, 0.0),
            Vec3A::new(4.0, 2.0, 0.0),
            Vec3A::new(0.0, 4.0, 1.0),
        ]
    }

    fn whole() -> BuildBox {
        BuildBox {
            min: Vec3A::splat(-10.0),
            max: Vec3A::splat(10.0),
        }
    }

    /// Samples of the triangle (barycentric grid) inside the slab lie in the clipped box.
    #[test]
    fn the_clipped_box_holds_every_point_of_the_part() {
        let t = corners();
        for axis in 0..3 {
            for (lo, hi) in [(-1.0, 1.0), (1.0, 2.5), (0.3, 0.31), (2.0, 9.0)] {
                let b = clipped(&t, axis, lo, hi, &whole());
                let n = 60;
                for i in 0..=n {
                    for j in 0..=n - i {
                        let (u, v) = (i as f32 / n as f32, j as f32 / n as f32);
                        let p = t[0] + (t[1] - t[0]) * u + (t[2] - t[0]) * v;
                        let a = lane(p, axis);
                        if a >= lo && a <= hi {
                            assert!(
                                p.cmpge(b.min).all() && p.cmple(b.max).all(),
                                "{p:?} outside {b:?} (axis {axis}, [{lo}, {hi}])"
                            );
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn a_slab_that_misses_the_triangle_gives_an_empty_box() {
        let b = clipped(&corners(), 0, 5.0, 6.0, &whole());
        assert!(!holds_something(&b));
        let b = clipped(&corners(), 2, -3.0, -2.0, &whole());
        assert!(!holds_something(&b));
    }

    #[test]
    fn the_clipped_box_is_tight_up_to_the_margin() {
        // The part with x in [0, 1]: the corner (0,0,0), (0,4,1) and the edge crossings at
        // x = 1: (1, 0.5, 0) on a–b and (1, 3.5, 0.75) on b–c.
        let b = clipped(&corners(), 0, 0.0, 1.0, &whole());
        let close = |x: f32, y: f32| (x - y).abs() < 1e-5;
        assert!(close(b.min.x, 0.0) && close(b.max.x, 1.0));
        assert!(close(b.min.y, 0.0) && close(b.max.y, 4.0));
        assert!(close(b.min.z, 0.0) && close(b.max.z, 1.0));
        let b = clipped(&corners(), 0, 3.0, 4.0, &whole());
        assert!(close(b.min.x, 3.0) && close(b.max.x, 4.0));
        assert!(close(b.min.y, 1.5) && close(b.max.y, 2.5));
        assert!(close(b.min.z, 0.0) && close(b.max.z, 0.25));
    }
}
