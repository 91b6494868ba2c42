//! The builder's per-lane vector operations, with one meaning on every target.
//!
//! Each rule picks an operand by comparison, as [`min_f32`](crate::math::min_f32) does, so
//! signed zeros and NaN resolve the same way everywhere and builds stay bit-identical. On x86
//! and on WebAssembly with SIMD, glam's `min`/`max` are single instructions (MINPS/MAXPS,
//! `f32x4.pmin`/`pmax`) defined by exactly such a rule, so they are called with the operand
//! order that gives it; other targets use the portable form. The golden blob bytes, checked
//! natively and in WebAssembly, catch any dependency update that changes this.

use glam::Vec3A;

/// Targets whose glam `min`/`max` are the comparison-rule instructions named above.
const GLAM_FOLLOWS_A_RULE: bool = cfg!(any(
    all(
        any(target_arch = "x86", target_arch = "x86_64"),
        target_feature = "sse2"
    ),
    all(target_arch = "wasm32", target_feature = "simd128")
));

/// The operand order that makes glam's `x.min(y)` mean `a < b ? a : b` and `x.max(y)` mean
/// `a > b ? a : b`: MINPS/MAXPS return their second operand unless the first wins, while
/// `pmin`/`pmax` return their first unless the second wins.
#[inline(always)]
fn glam_order(a: Vec3A, b: Vec3A) -> (Vec3A, Vec3A) {
    if cfg!(target_arch = "wasm32") {
        (b, a)
    } else {
        (a, b)
    }
}

/// `a < b ? a : b` in every lane.
#[inline(always)]
pub(super) fn min_lanes(a: Vec3A, b: Vec3A) -> Vec3A {
    if GLAM_FOLLOWS_A_RULE {
        let (x, y) = glam_order(a, b);
        x.min(y)
    } else {
        Vec3A::select(a.cmplt(b), a, b)
    }
}

/// `a > b ? a : b` in every lane.
#[inline(always)]
pub(super) fn max_lanes(a: Vec3A, b: Vec3A) -> Vec3A {
    if GLAM_FOLLOWS_A_RULE {
        let (x, y) = glam_order(a, b);
        x.max(y)
    } else {
        Vec3A::select(a.cmpgt(b), a, b)
    }
}

/// Each lane of `f` clamped to `[0, last]` and truncated toward zero: `(x as u32).min(last)`
/// for every lane (NaN gives 0). `last` is a whole number below 2²⁴.
#[inline(always)]
pub(super) fn clamped_indices(f: Vec3A, last: Vec3A) -> [usize; 3] {
    // `0 < x ? x : 0` sends NaN and negatives to 0; the clamped value then truncates exactly.
    let f = min_lanes(last, max_lanes(f, Vec3A::ZERO));
    #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
    {
        use core::arch::wasm32::{i32x4_trunc_sat_f32x4, u32x4_extract_lane};
        let i = i32x4_trunc_sat_f32x4(f.into());
        [
            u32x4_extract_lane::<0>(i) as usize,
            u32x4_extract_lane::<1>(i) as usize,
            u32x4_extract_lane::<2>(i) as usize,
        ]
    }
    #[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
    {
        [
            f.x as i32 as usize,
            f.y as i32 as usize,
            f.z as i32 as usize,
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rules, lane by lane, against the scalar helpers they must match on every target.
    #[test]
    fn lanes_follow_the_comparison_rules() {
        let cases = [
            (0.0, -0.0),
            (-0.0, 0.0),
            (1.0, f32::NAN),
            (f32::NAN, 1.0),
            (-3.5, 2.0),
            (f32::INFINITY, f32::NEG_INFINITY),
        ];
        for (a, b) in cases {
            let (va, vb) = (Vec3A::splat(a), Vec3A::splat(b));
            let min = min_lanes(va, vb);
            let max = max_lanes(va, vb);
            for lane in min.to_array() {
                assert_eq!(
                    lane.to_bits(),
                    crate::math::min_f32(a, b).to_bits(),
                    "min({a}, {b})"
                );
            }
            for lane in max.to_array() {
                assert_eq!(
                    lane.to_bits(),
                    crate::math::max_f32(a, b).to_bits(),
                    "max({a}, {b})"
                );
            }
        }
        let last = Vec3A::splat(31.0);
        for (f, want) in [
            (f32::NAN, 0),
            (-1.0, 0),
            (0.99, 0),
            (7.0, 7),
            (30.999, 30),
            (31.0, 31),
            (1e30, 31),
            (f32::INFINITY, 31),
        ] {
            assert_eq!(
                clamped_indices(Vec3A::splat(f), last),
                [want; 3],
                "bin of {f}"
            );
        }
    }
}
