//! The walk behind every winding number: one tree walk for a packet of points in groups of four
//! SIMD lanes, each lane summing exactly what it would alone.
//!
//! A lane follows the single-point rule: a node whose centre is farther than the accuracy's
//! ratio times its radius counts by its expansion, and the walk goes on below a node only for
//! the lanes that found it near. The walk visits nodes depth first, left child first, so each
//! lane adds its terms in the order a walk for its point alone would, with the same operations
//! (each lane of a SIMD operation rounds as the scalar one): a packet's answers are the single
//! answers, bit for bit, on every target. Points of a packet that lie close together (a batch
//! in Morton order) share most of the walk.

use glam::{BVec4A, Vec3, Vec4};

use super::expansion::{WindingNode, leaf_triangles};
use super::{WindingAccuracy, WindingNodes, WindingTree};
use crate::bvh::{MAX_DEPTH, TreeArrays};
use crate::geom::solid_angle_triangle;
use crate::query::LeafTriangles;

/// Groups of four lanes per packet of a batch.
pub(super) const GROUPS: usize = 2;

/// Points per packet of a batch.
pub(super) const PACKET: usize = 4 * GROUPS;

/// `4π`: the solid angle of the whole sphere.
const FOUR_PI: f32 = 4.0 * core::f32::consts::PI;

/// Four points, one per lane.
#[derive(Clone, Copy)]
struct Lanes {
    x: Vec4,
    y: Vec4,
    z: Vec4,
}

impl<T: TreeArrays, S: LeafTriangles, E: WindingNodes> WindingTree<'_, T, S, E> {
    /// The winding number of each of `points` (see [`WindingTree::winding_number`]): `4·G`
    /// points, `G` ≤ 8.
    pub(super) fn winding_lanes<const G: usize>(
        &self,
        points: &[[Vec3; 4]; G],
        accuracy: WindingAccuracy,
    ) -> [[f32; 4]; G] {
        let mut angle = [Vec4::ZERO; G];
        let mut lanes = [Lanes {
            x: Vec4::ZERO,
            y: Vec4::ZERO,
            z: Vec4::ZERO,
        }; G];
        let mut live = 0u32;
        let mut not_finite = [[false; 4]; G];
        for (g, (group, out)) in points.iter().zip(lanes.iter_mut()).enumerate() {
            let mut coords = [[0.0f32; 4]; 3];
            for (k, p) in group.iter().enumerate() {
                let scaled = *p * self.scale();
                if !p.is_finite() {
                    if let Some(flag) = not_finite.get_mut(g).and_then(|f| f.get_mut(k)) {
                        *flag = true;
                    }
                } else if scaled.is_finite() {
                    // (A finite point that overflows when scaled is so far away that the
                    // mesh's angle there is below any f32 sum: it stays 0.)
                    live |= 1 << (4 * g + k);
                    for (axis, value) in coords.iter_mut().zip(scaled.to_array()) {
                        if let Some(c) = axis.get_mut(k) {
                            *c = value;
                        }
                    }
                }
            }
            let [x, y, z] = coords.map(Vec4::from_array);
            *out = Lanes { x, y, z };
        }
        let (tree, expansions) = (self.tree(), self.expansions());
        let mut stack = [(0u32, live); MAX_DEPTH as usize + 1];
        let mut sp = usize::from(live != 0 && expansions.count() > 0);
        while sp > 0 {
            sp -= 1;
            let (index, active) = stack.get(sp).copied().unwrap_or_default();
            let (Some(node), Some(e)) = (
                tree.node(index as usize),
                expansions.expansion(index as usize),
            ) else {
                continue;
            };
            let e = &e;
            if e.area == 0.0 {
                continue; // Nothing but zero-area triangles: they count nothing.
            }
            let reach = accuracy.far_ratio() * e.radius;
            let reach_squared = Vec4::splat(reach * reach);
            let centre = e.centre();
            let mut near = 0u32;
            for (g, (group, sum)) in lanes.iter().zip(angle.iter_mut()).enumerate() {
                let group_active = (active >> (4 * g)) & 0xF;
                if group_active == 0 {
                    continue;
                }
                let offset = Lanes {
                    x: Vec4::splat(centre.x) - group.x,
                    y: Vec4::splat(centre.y) - group.y,
                    z: Vec4::splat(centre.z) - group.z,
                };
                let squared = offset.x * offset.x + offset.y * offset.y + offset.z * offset.z;
                // NaN never occurs (live lanes are finite); were it to, the lane would go near.
                let far_mask = squared.cmpgt(reach_squared);
                let far = far_mask.bitmask() & group_active;
                near |= (group_active & !far) << (4 * g);
                if far != 0 {
                    let terms = far_field(e, &offset, squared);
                    // Adding +0 to a sum that is never −0 leaves it as it was.
                    *sum += Vec4::select(mask_of(far), terms, Vec4::ZERO);
                }
            }
            if near == 0 {
                continue;
            }
            if node.is_leaf() {
                for t in leaf_triangles(tree, self.triangles(), &node, self.scale()) {
                    for (g, (group, sum)) in lanes.iter().zip(angle.iter_mut()).enumerate() {
                        let mut added = sum.to_array();
                        let (xs, ys, zs) =
                            (group.x.to_array(), group.y.to_array(), group.z.to_array());
                        for (k, a) in added.iter_mut().enumerate() {
                            if near >> (4 * g + k) & 1 == 1 {
                                let p = Vec3::new(
                                    xs.get(k).copied().unwrap_or(0.0),
                                    ys.get(k).copied().unwrap_or(0.0),
                                    zs.get(k).copied().unwrap_or(0.0),
                                );
                                *a += solid_angle_triangle(&t, p);
                            }
                        }
                        *sum = Vec4::from_array(added);
                    }
                }
            } else {
                // Right first, so the left child is summed first: a fixed order.
                for child in [node.first.wrapping_add(1), node.first] {
                    if let Some(slot) = stack.get_mut(sp) {
                        *slot = (child, near);
                        sp += 1;
                    }
                }
            }
        }
        let mut out = [[0.0f32; 4]; G];
        for ((o, sum), flags) in out.iter_mut().zip(angle).zip(not_finite) {
            *o = (sum / FOUR_PI).to_array();
            for (w, bad) in o.iter_mut().zip(flags) {
                if bad {
                    *w = f32::NAN;
                }
            }
        }
        out
    }
}

/// The lanes whose bits are set in `bits` (bit `k` for lane `k`).
#[inline(always)]
fn mask_of(bits: u32) -> BVec4A {
    BVec4A::new(bits & 1 != 0, bits & 2 != 0, bits & 4 != 0, bits & 8 != 0)
}

/// Lane-wise square root through `libm`, correctly rounded, as every target rounds it.
#[inline(always)]
fn sqrt_lanes(v: Vec4) -> Vec4 {
    Vec4::new(
        libm::sqrtf(v.x),
        libm::sqrtf(v.y),
        libm::sqrtf(v.z),
        libm::sqrtf(v.w),
    )
}

/// A node's solid angle at four points `centre − offset` from its expansion (see
/// [`WindingNode`] for the terms): `N·u / d² + (first[0] + Σ first·u²) / d³ +
/// (Σ second·u³ + L·u) / d⁴`, with `u = offset / d`.
#[inline(always)]
fn far_field(e: &WindingNode, offset: &Lanes, squared: Vec4) -> Vec4 {
    let [nx, ny, nz] = e.normal;
    let [trace, fxx, fyy, fzz, fxy, fxz, fyz] = e.first;
    let [xxx, xxy, xxz, xyy, xyz, xzz, yyy, yyz, yzz, zzz, lx, ly, lz] = e.second;
    // One square root and one division; every other power of 1/d by multiplication.
    let inverse = Vec4::ONE / sqrt_lanes(squared);
    let inverse_squared = inverse * inverse;
    let (ux, uy, uz) = (offset.x * inverse, offset.y * inverse, offset.z * inverse);
    let (xx, yy, zz, xy, xz, yz) = (ux * ux, uy * uy, uz * uz, ux * uy, ux * uz, uy * uz);
    let dipole = (ux * nx + uy * ny + uz * nz) * inverse_squared;
    let first = ((xx * fxx + yy * fyy + zz * fzz) + (xy * fxy + xz * fxz + yz * fyz) + trace)
        * (inverse_squared * inverse);
    let cubic = ux * ((xx * xxx + xy * xxy + xz * xxz) + (yy * xyy + yz * xyz + zz * xzz))
        + uy * (yy * yyy + yz * yyz + zz * yzz)
        + uz * (zz * zzz);
    let second = (cubic + (ux * lx + uy * ly + uz * lz)) * (inverse_squared * inverse_squared);
    dipole + first + second
}
