//! What the primitive tests share: a small deterministic generator (xorshift, so the tests
//! need no dependency) and the power-of-two scale check of the ray–triangle tests.

use glam::Vec3;

use super::{CullMode, TriangleHit};
use crate::math::{Ray, Triangle};

/// Xorshift64 drawing coordinates in `[-1, 1)` on a 2⁻²³ grid.
pub(super) struct Rng(pub(super) u64);

impl Rng {
    /// The next coordinate.
    pub(super) fn next(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        ((self.0 >> 40) as f32 / (1u64 << 24) as f32) * 2.0 - 1.0
    }

    /// A point of `[-scale, scale)³`.
    pub(super) fn vec(&mut self, scale: f32) -> Vec3 {
        Vec3::new(self.next(), self.next(), self.next()) * scale
    }
}

/// Random rays at random triangles, with every cull mode (every fourth aimed at a corner, every
/// fourth at an edge's midpoint): the triangle and the ray's origin scaled by `size` and its
/// direction by `along` (powers of two, some far past where the products overflow `f32`) must
/// give the unit answer's `u` and `v`, and its `t` times `size / along`, bit for bit.
pub(super) fn check_power_of_two_scales(
    test: impl Fn(&Ray, &Triangle, CullMode) -> Option<TriangleHit>,
) {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let scales = [
        (2f32.powi(45), 1.0),
        (2f32.powi(62), 2f32.powi(-40)),
        (2f32.powi(40), 2f32.powi(100)),
    ];
    let mut hits = 0;
    for round in 0..20_000 {
        let tri = Triangle::new(rng.vec(1.0), rng.vec(1.0), rng.vec(1.0));
        let origin = rng.vec(3.0);
        let target = match round % 4 {
            0 => tri.a,
            1 => (tri.b + tri.c) * 0.5,
            _ => (tri.a + tri.b + tri.c) / 3.0 + rng.vec(0.4),
        };
        let ray = Ray::new(origin, target - origin);
        let cull = [CullMode::None, CullMode::Back, CullMode::Front][round % 3];
        let unit = test(&ray, &tri, cull);
        hits += usize::from(unit.is_some());
        for (size, along) in scales {
            let far = Ray::new(origin * size, (target - origin) * along);
            let big = Triangle::new(tri.a * size, tri.b * size, tri.c * size);
            let expected = unit.map(|h| TriangleHit {
                t: h.t * size / along,
                ..h
            });
            let bits = |h: TriangleHit| [h.t, h.u, h.v].map(f32::to_bits);
            assert_eq!(
                test(&far, &big, cull).map(bits),
                expected.map(bits),
                "{size} {along}: {tri:?} {ray:?} {cull:?}"
            );
        }
    }
    assert!(hits > 4_000, "only {hits} hits");
}
