//! Morton (Z-order) codes: points that are close in space get close codes, so sorting by code
//! makes a batch of queries walk the same parts of a tree one after another.

use glam::Vec3;

use super::Aabb;

/// Bits per axis in a [`morton_code`].
const BITS: u32 = 10;

/// The 30-bit Morton code of `p` in a `1024³` grid over `bounds`: bit `3k + 2` is bit `k` of
/// the x cell, `3k + 1` of y and `3k` of z. Coordinates outside `bounds` go to the nearest
/// border cell; an axis where `bounds` is flat (or empty, or a coordinate NaN) gives cell 0.
#[must_use]
pub(crate) fn morton_code(p: Vec3, bounds: &Aabb) -> u32 {
    let cells = (1u32 << BITS) as f32;
    let cell = |v: f32, lo: f32, hi: f32| -> u32 {
        let extent = hi - lo;
        if !(extent > 0.0) {
            return 0;
        }
        // `as` saturates (and sends NaN to 0), so the clamp only needs the top.
        (((v - lo) / extent * cells) as u32).min((1 << BITS) - 1)
    };
    let x = cell(p.x, bounds.min.x, bounds.max.x);
    let y = cell(p.y, bounds.min.y, bounds.max.y);
    let z = cell(p.z, bounds.min.z, bounds.max.z);
    (spread(x) << 2) | (spread(y) << 1) | spread(z)
}

/// Moves bit `k` of a 10-bit value to bit `3k`.
const fn spread(v: u32) -> u32 {
    let v = v & 0x3FF;
    let v = (v | (v << 16)) & 0x0300_00FF;
    let v = (v | (v << 8)) & 0x0300_F00F;
    let v = (v | (v << 4)) & 0x030C_30C3;
    (v | (v << 2)) & 0x0924_9249
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The code built one bit at a time, as the definition reads.
    fn by_bits(x: u32, y: u32, z: u32) -> u32 {
        (0..BITS).fold(0, |code, k| {
            code | (((x >> k) & 1) << (3 * k + 2))
                | (((y >> k) & 1) << (3 * k + 1))
                | (((z >> k) & 1) << (3 * k))
        })
    }

    #[test]
    fn codes_interleave_the_cells_bit_by_bit() {
        let unit = Aabb::new(Vec3::ZERO, Vec3::splat(1024.0));
        let mut state = 0x2545_F491_u32;
        for _ in 0..20_000 {
            let mut next = || {
                state ^= state << 13;
                state ^= state >> 17;
                state ^= state << 5;
                state % 1024
            };
            let (x, y, z) = (next(), next(), next());
            let centre = Vec3::new(x as f32, y as f32, z as f32) + 0.5;
            assert_eq!(morton_code(centre, &unit), by_bits(x, y, z), "{x} {y} {z}");
        }
    }

    #[test]
    fn outside_points_clamp_and_flat_axes_give_zero() {
        let b = Aabb::new(Vec3::new(-1.0, -1.0, 2.0), Vec3::new(1.0, 1.0, 2.0));
        let top = by_bits(1023, 0, 0);
        assert_eq!(morton_code(Vec3::new(5.0, -7.0, 9.0), &b), top);
        assert_eq!(morton_code(Vec3::new(f32::NAN, -1.0, 2.0), &b), 0);
        assert_eq!(morton_code(Vec3::ZERO, &Aabb::EMPTY), 0);
        assert_eq!(
            morton_code(Vec3::new(0.0, 0.0, 2.0), &b),
            by_bits(512, 512, 0)
        );
    }
}
