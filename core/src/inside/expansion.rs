//! The per-node dipole expansions of the fast winding number, and their bottom-up build.

use glam::Vec3;
use serde::{Deserialize, Serialize};

use crate::bvh::{BvhNode, TreeArrays};
use crate::math::{Triangle, dot};
use crate::query::{LeafTriangles, SplitRefs};

/// What a BVH node's triangles look like from far away: the winding number's expansion to
/// second order about an area-weighted centre (Barill et al. 2018), in the form its evaluation
/// reads, 112 bytes. One per node of the binary tree, at the node's index.
///
/// Lengths are in the tree's units ([`WindingTree::scale`](super::WindingTree::scale)): the
/// mesh's coordinates times a power of two that brings the tree's box to a size near 1, so
/// that the moments stay within `f32` for every valid mesh.
///
/// Writing `aₜ` for a triangle's area, `nₜ` for its unit normal, `cₜ` for its centroid and `x`
/// for a point's offset from `centre`, over the node's triangles:
/// - `centre` = `Σ aₜ·cₜ / Σ aₜ` (the middle of the triangles' corners when the area is 0);
/// - `radius` = the largest distance from `centre` to a corner of a triangle;
/// - `normal` = `N` = `Σ aₜ·nₜ`, the area-weighted normal (units: length²); `area` = `Σ aₜ`;
/// - with the first moment `Cᵢⱼ = Σ nₜᵢ·∫ₜ xⱼ dA` (length³) and the second
///   `Dᵢⱼₖ = Σ nₜᵢ·∫ₜ xⱼxₖ dA` (length⁴), the coefficients of the solid angle's terms in the
///   unit direction `u` from the point to `centre`:
///   - `first[0]` = `tr C`, and `first[1..7]` the coefficients of `uₓ², u_y², u_z², uₓu_y,
///     uₓu_z, u_yu_z` in `−3·uᵀCu`;
///   - `second[0..10]` the coefficients of `uₓ³, uₓ²u_y, uₓ²u_z, uₓu_y², uₓu_yu_z, uₓu_z², u_y³,
///     u_y²u_z, u_yu_z², u_z³` in `7.5·Σ Dᵢⱼₖuᵢuⱼuₖ`, and `second[10..13]` the vector `L` with
///     `L·u = −1.5·(2·Σ Dᵢᵢₖuₖ + Σ uᵢDᵢⱼⱼ)`;
///
/// so that at distance `d` the node's solid angle is
/// `N·u / d² + (first[0] + Σ first·u²) / d³ + (Σ second·u³ + L·u) / d⁴`.
///
/// A triangle that spatial splits put in several leaves counts in the leaf holding its first
/// reference only. Triangles of zero area count nothing.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct WindingNode {
    /// Area-weighted centre of the node's triangles.
    pub centre: [f32; 3],
    /// The largest distance from `centre` to a corner of the node's triangles.
    pub radius: f32,
    /// Area-weighted normal, `Σ aₜ·nₜ`.
    pub normal: [f32; 3],
    /// Total area of the node's triangles.
    pub area: f32,
    /// The first-moment term's coefficients (see the type).
    pub first: [f32; 7],
    /// The second-moment term's coefficients (see the type).
    pub second: [f32; 13],
}

impl WindingNode {
    /// A placeholder for initialising buffers: no area, radius 0 at the origin.
    pub const EMPTY: Self = Self {
        centre: [0.0; 3],
        radius: 0.0,
        normal: [0.0; 3],
        area: 0.0,
        first: [0.0; 7],
        second: [0.0; 13],
    };

    /// `centre` as a vector.
    #[inline]
    #[must_use]
    pub fn centre(&self) -> Vec3 {
        Vec3::from_array(self.centre)
    }

    /// `normal` as a vector.
    #[inline]
    #[must_use]
    pub fn normal(&self) -> Vec3 {
        Vec3::from_array(self.normal)
    }

    /// The evaluation form of a node's moments, with its `radius`.
    #[inline]
    pub(super) fn of(m: &Moments, radius: f32) -> Self {
        let c = |i: usize, j: usize| m.first_moment.get(3 * i + j).copied().unwrap_or(0.0);
        let first = [
            c(0, 0) + c(1, 1) + c(2, 2),
            -3.0 * c(0, 0),
            -3.0 * c(1, 1),
            -3.0 * c(2, 2),
            -3.0 * (c(0, 1) + c(1, 0)),
            -3.0 * (c(0, 2) + c(2, 0)),
            -3.0 * (c(1, 2) + c(2, 1)),
        ];
        // Σ Dᵢⱼₖuᵢuⱼuₖ gathered by monomial: each ordered (i, j, k) adds Dᵢ(jk) to the
        // monomial of its indices. Rows of D pack the pairs xx, xy, xz, yy, yz, zz.
        let [
            [x00, x01, x02, x11, x12, x22],
            [y00, y01, y02, y11, y12, y22],
            [z00, z01, z02, z11, z12, z22],
        ] = rows(&m.second_moment);
        let cubic = [
            x00,
            2.0 * x01 + y00,
            2.0 * x02 + z00,
            x11 + 2.0 * y01,
            2.0 * (x12 + y02 + z01),
            x22 + 2.0 * z02,
            y11,
            2.0 * y12 + z11,
            y22 + 2.0 * z12,
            z22,
        ];
        // 2·Σᵢ Dᵢ(ik) + Σⱼ Dₖ(jj), component k.
        let linear = [
            2.0 * (x00 + y01 + z02) + (x00 + x11 + x22),
            2.0 * (x01 + y11 + z12) + (y00 + y11 + y22),
            2.0 * (x02 + y12 + z22) + (z00 + z11 + z22),
        ];
        let mut second = [0.0f32; 13];
        for (out, x) in second.iter_mut().zip(cubic) {
            *out = 7.5 * x;
        }
        for (out, l) in second.iter_mut().skip(10).zip(linear) {
            *out = -1.5 * l;
        }
        Self {
            centre: m.centre.to_array(),
            radius,
            normal: m.normal.to_array(),
            area: m.area,
            first,
            second,
        }
    }
}

impl Default for WindingNode {
    fn default() -> Self {
        Self::EMPTY
    }
}

/// The three packed rows of a second moment.
#[inline]
fn rows(d: &[f32; 18]) -> [[f32; 6]; 3] {
    let [
        a0,
        a1,
        a2,
        a3,
        a4,
        a5,
        b0,
        b1,
        b2,
        b3,
        b4,
        b5,
        c0,
        c1,
        c2,
        c3,
        c4,
        c5,
    ] = *d;
    [
        [a0, a1, a2, a3, a4, a5],
        [b0, b1, b2, b3, b4, b5],
        [c0, c1, c2, c3, c4, c5],
    ]
}

/// A node's moments in full, as the bottom-up build carries them: the centre, area and
/// area-weighted normal, `first_moment[3·i + j]` = `Cᵢⱼ` and `second_moment[6·i + s]` = `Dᵢⱼₖ`
/// for the pairs `(j, k)` of [`PAIRS`] (see [`WindingNode`]), and a bound on the radius.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Moments {
    pub(super) centre: Vec3,
    pub(super) radius: f32,
    pub(super) normal: Vec3,
    pub(super) area: f32,
    pub(super) first_moment: [f32; 9],
    pub(super) second_moment: [f32; 18],
}

/// Whether the reference in `slot` is the one that counts triangle `tri`: always for a triangle
/// held once, otherwise when `slot` is its first reference.
#[inline]
pub(super) fn counts_here(splits: &SplitRefs<'_>, slot: usize, tri: u32) -> bool {
    splits
        .of(tri)
        .next()
        .is_none_or(|r| r.slot as usize == slot)
}

/// The triangles a leaf counts, by slot order, their corners multiplied by `scale` (a power of
/// two: exactly), from any tree and triangle source (a tree in slices and its mesh, or a
/// blob's tree and triangles read in place).
pub(super) fn leaf_triangles<'m, T: TreeArrays + ?Sized, S: LeafTriangles + ?Sized>(
    tree: &'m T,
    triangles: &'m S,
    node: &BvhNode,
    scale: f32,
) -> impl Iterator<Item = Triangle> + Clone + 'm {
    let (first, count) = (node.first as usize, node.count as usize);
    let splits = tree.split_refs();
    // An empty run for a range the tree does not have (never, for a validated tree): one
    // iterator type either way, without `Option`'s flattening in the loop.
    tree.leaf_triangles(first, count)
        .unwrap_or_else(|| crate::query::LeafTriangleIds::new(first, &[]))
        .filter(move |&(slot, tri)| counts_here(&splits, slot, tri))
        .filter_map(move |(slot, tri)| triangles.corners(slot, tri))
        .map(move |t| Triangle::new(t.a * scale, t.b * scale, t.c * scale))
}

/// The power of two nearest above `1 / extent` for the largest side of the root box of `tree`
/// (1 for an empty tree or one flat to a point): multiplying by it is exact, and it brings the
/// mesh to a size near 1, where the moments (up to the fourth power of a length) neither
/// overflow nor underflow.
pub(super) fn unit_scale<T: TreeArrays + ?Sized>(tree: &T) -> f32 {
    let bounds = tree.node(0).map_or(crate::math::Aabb::EMPTY, |n| n.aabb());
    crate::math::unit_scale((bounds.max - bounds.min).max_element())
}

/// `|v|` through `libm`.
#[inline]
fn length(v: Vec3) -> f32 {
    libm::sqrtf(dot(v, v))
}

/// `moment += a ⊗ b` (row `i`, column `j`: `a[i]·b[j]`).
#[inline]
fn add_outer(moment: &mut [f32; 9], a: Vec3, b: Vec3) {
    let (a, b) = (a.to_array(), b.to_array());
    for (i, row) in moment.chunks_exact_mut(3).enumerate() {
        let ai = a.get(i).copied().unwrap_or(0.0);
        for (m, bj) in row.iter_mut().zip(b) {
            *m += ai * bj;
        }
    }
}

/// The pairs `(j, k)`, `j ≤ k`, of a packed symmetric 3 × 3 matrix, in storage order.
pub(super) const PAIRS: [(usize, usize); 6] = [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)];

/// `second += a ⊗ S` for the symmetric matrix `S` given as a function of `(j, k)`.
#[inline]
fn add_outer_symmetric(second: &mut [f32; 18], a: Vec3, s: impl Fn(usize, usize) -> f32) {
    let a = a.to_array();
    for (i, row) in second.chunks_exact_mut(6).enumerate() {
        let ai = a.get(i).copied().unwrap_or(0.0);
        for (m, &(j, k)) in row.iter_mut().zip(&PAIRS) {
            *m += ai * s(j, k);
        }
    }
}

/// Component `i` of `v`.
#[inline]
fn at(v: Vec3, i: usize) -> f32 {
    v.to_array().get(i).copied().unwrap_or(0.0)
}

/// A leaf's moments from its triangles.
pub(super) fn leaf_moments(triangles: impl Iterator<Item = Triangle> + Clone) -> Moments {
    let (mut area, mut weighted, mut normal) = (0.0f32, Vec3::ZERO, Vec3::ZERO);
    let (mut low, mut high) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
    for t in triangles.clone() {
        let n = t.normal() * 0.5;
        let a = length(n);
        area += a;
        weighted += centroid(&t) * a;
        normal += n;
        let b = t.bounds();
        (low, high) = (low.min(b.min), high.max(b.max));
    }
    let centre = if area > 0.0 {
        weighted / area
    } else if low.x <= high.x {
        (low + high) * 0.5
    } else {
        Vec3::ZERO
    };
    let (mut first_moment, mut second_moment, mut radius) = ([0.0f32; 9], [0.0f32; 18], 0.0f32);
    for t in triangles {
        let n = t.normal() * 0.5;
        add_outer(&mut first_moment, n, centroid(&t) - centre);
        // ∫ x xᵀ dA over a triangle is a/12 · (Σ vᵢvᵢᵀ + s sᵀ), s = Σ vᵢ; with the normal's
        // length a folded in, n/12 carries it.
        let (a, b, c) = (t.a - centre, t.b - centre, t.c - centre);
        let sum = a + b + c;
        add_outer_symmetric(&mut second_moment, n * (1.0 / 12.0), |j, k| {
            at(a, j) * at(a, k)
                + at(b, j) * at(b, k)
                + at(c, j) * at(c, k)
                + at(sum, j) * at(sum, k)
        });
        for corner in [t.a, t.b, t.c] {
            radius = radius.max(length(corner - centre));
        }
    }
    Moments {
        centre,
        radius,
        normal,
        area,
        first_moment,
        second_moment,
    }
}

/// An inner node's moments from its two children's: the moments move to the new centre
/// (with `δ` a child's centre less the new one, `C + N ⊗ δ` and
/// `D + C ⊗ δ + (C ⊗ δ)ᵀ⁽ʲᵏ⁾ + N ⊗ δ ⊗ δ`), the radius bounds both children's balls.
#[inline]
pub(super) fn merged_moments(left: &Moments, right: &Moments) -> Moments {
    let area = left.area + right.area;
    let (cl, cr) = (left.centre, right.centre);
    let centre = if area > 0.0 {
        (cl * left.area + cr * right.area) / area
    } else {
        (cl + cr) * 0.5
    };
    let mut first_moment = [0.0f32; 9];
    let mut second_moment = [0.0f32; 18];
    for child in [left, right] {
        let shift = child.centre - centre;
        // The second moment moves with the child's first moment, taken before it moves.
        let first = |i: usize, j: usize| child.first_moment.get(3 * i + j).copied().unwrap_or(0.0);
        for (i, row) in second_moment.chunks_exact_mut(6).enumerate() {
            let own = child
                .second_moment
                .get(6 * i..6 * i + 6)
                .unwrap_or_default();
            let ni = at(child.normal, i);
            for ((m, &(j, k)), &d) in row.iter_mut().zip(&PAIRS).zip(own) {
                *m += d
                    + first(i, j) * at(shift, k)
                    + first(i, k) * at(shift, j)
                    + ni * at(shift, j) * at(shift, k);
            }
        }
        for (m, &c) in first_moment.iter_mut().zip(&child.first_moment) {
            *m += c;
        }
        add_outer(&mut first_moment, child.normal, shift);
    }
    let radius = (left.radius + length(cl - centre)).max(right.radius + length(cr - centre));
    Moments {
        centre,
        radius,
        normal: left.normal + right.normal,
        area,
        first_moment,
        second_moment,
    }
}

/// The centroid `(a + b + c) / 3`.
#[inline]
fn centroid(t: &Triangle) -> Vec3 {
    (t.a + t.b + t.c) * (1.0 / 3.0)
}
