//! [`CompactNode`]: a wide node whose four child boxes are 8-bit offsets from the node's own
//! box, half the bytes of a [`WideNode`].

use glam::Vec4;

use super::WideNode;
use crate::math::Aabb4;

/// One node of a quantized [`WideBvh`](super::WideBvh): a [`WideNode`] with its four child
/// boxes quantized to 8 bits per coordinate. 64 bytes, one cache line (a `WideNode` takes two).
///
/// | bytes | field | meaning |
/// |-------|-------|---------|
/// | 0–11 | `origin` | x, y, z (`f32` bits): the smallest corner of the used lanes' union |
/// | 12–14 | `exponent` | per axis `e`: the step of the offsets is `2^e` |
/// | 15–26 | `lo` | per axis, per lane: the box's minimum as steps above `origin`, rounded down |
/// | 27–38 | `hi` | per axis, per lane: the box's maximum as steps above `origin`, rounded up |
/// | 40–55 | `child` | as [`WideNode::child`] |
/// | 56–59 | `count` | as [`WideNode::count`] (leaves hold at most 255 triangles) |
///
/// Bytes 39 and 60–63 are padding. Lanes are in the [`WideNode`]'s order (inner lanes first).
///
/// Lane `i`'s box along axis `a` decodes as `origin[a] + lo[a][i] · 2^e[a]` to
/// `origin[a] + hi[a][i] · 2^e[a]`, in `f32`, a product (exact) then a sum (one rounding), the
/// same on every target. Each quantized box contains the box it was made from — the offsets
/// are rounded outward and checked against that very decoding — so it culls no less safely;
/// queries' answers are decided by the leaves and stay bit-identical. An unused lane decodes
/// to an empty box (`min > max` along x).
#[repr(C, align(64))]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CompactNode {
    /// The smallest corner of the used lanes' union, as `f32` bits.
    pub origin: [u32; 3],
    /// Per axis, the exponent `e` of the step `2^e` (−126 to 127).
    pub exponent: [i8; 3],
    /// Per axis, per lane: minimum offsets in steps, rounded down.
    pub lo: [[u8; 4]; 3],
    /// Per axis, per lane: maximum offsets in steps, rounded up.
    pub hi: [[u8; 4]; 3],
    /// Inner child: node index; leaf child: first order slot; unused: 0.
    pub child: [u32; 4],
    /// Leaf child: triangle count (1 to 255); inner child or unused: 0.
    pub count: [u8; 4],
}

const _: () = assert!(core::mem::size_of::<CompactNode>() == 64);

/// Smallest and largest step exponents (normal `f32` powers of two).
const MIN_EXPONENT: i32 = -126;
const MAX_EXPONENT: i32 = 127;

/// `2^e` for `e` in `MIN_EXPONENT..=MAX_EXPONENT` (clamped), exactly.
#[inline(always)]
fn step(e: i32) -> f32 {
    let biased = e.clamp(MIN_EXPONENT, MAX_EXPONENT) + 127;
    f32::from_bits((biased as u32) << 23)
}

/// The coordinate `q` steps above `origin`: the one formula both the encoder and the decoder
/// use, lane by lane or four at once.
#[inline(always)]
fn decode(origin: f32, step: f32, q: u8) -> f32 {
    origin + f32::from(q) * step
}

impl CompactNode {
    /// A node with four unused lanes, for initializing buffers.
    pub const EMPTY: Self = Self {
        origin: [0; 3],
        exponent: [0; 3],
        lo: [[u8::MAX; 4]; 3],
        hi: [[0; 4]; 3],
        child: [0; 4],
        count: [0; 4],
    };

    /// The four child boxes, decoded (see the type's docs).
    #[inline(always)]
    #[must_use]
    pub fn boxes(&self) -> Aabb4 {
        let axis = |a: usize| {
            let origin = Vec4::splat(self.origin.get(a).map_or(0.0, |&b| f32::from_bits(b)));
            let s = Vec4::splat(step(self.exponent.get(a).map_or(0, |&e| i32::from(e))));
            let lanes = |q: Option<&[u8; 4]>| {
                let [a, b, c, d] = q.copied().unwrap_or([0; 4]);
                Vec4::new(f32::from(a), f32::from(b), f32::from(c), f32::from(d))
            };
            (
                (origin + lanes(self.lo.get(a)) * s).to_array(),
                (origin + lanes(self.hi.get(a)) * s).to_array(),
            )
        };
        let ((min_x, max_x), (min_y, max_y), (min_z, max_z)) = (axis(0), axis(1), axis(2));
        Aabb4 {
            min_x,
            min_y,
            min_z,
            max_x,
            max_y,
            max_z,
        }
    }

    /// Lane `lane`'s child: node index, first order slot, or 0.
    #[inline(always)]
    #[must_use]
    pub fn child(&self, lane: usize) -> u32 {
        self.child.get(lane).copied().unwrap_or(0)
    }

    /// Lane `lane`'s triangle count (0 for an inner or unused lane).
    #[inline(always)]
    #[must_use]
    pub fn count(&self, lane: usize) -> u32 {
        self.count.get(lane).map_or(0, |&c| u32::from(c))
    }

    /// `node` quantized, or `None` when a leaf holds more than 255 triangles or a box is not
    /// finite. Deterministic: the same node gives the same bits on every target.
    #[must_use]
    pub fn quantize(node: &WideNode) -> Option<Self> {
        let used = node.lanes();
        let mut out = Self::EMPTY;
        if used == 0 {
            return Some(out);
        }
        for lane in 0..4 {
            let count = node.count.get(lane).copied().unwrap_or(0);
            let (c, n) = (out.child.get_mut(lane)?, out.count.get_mut(lane)?);
            *c = node.child.get(lane).copied().unwrap_or(0);
            *n = u8::try_from(count).ok()?;
        }
        let b = &node.bounds;
        for (a, (mins, maxs)) in [(b.min_x, b.max_x), (b.min_y, b.max_y), (b.min_z, b.max_z)]
            .into_iter()
            .enumerate()
        {
            let (mins, maxs) = (mins.get(..used)?, maxs.get(..used)?);
            if mins.iter().chain(maxs).any(|v| !v.is_finite()) {
                return None;
            }
            let origin = mins
                .iter()
                .copied()
                .fold(f32::INFINITY, crate::math::min_f32);
            let top = maxs
                .iter()
                .copied()
                .fold(f32::NEG_INFINITY, crate::math::max_f32);
            let e = exponent_for(origin, top);
            let s = step(e);
            *out.origin.get_mut(a)? = origin.to_bits();
            *out.exponent.get_mut(a)? = i8::try_from(e).ok()?;
            for lane in 0..used {
                let lo = round_down(origin, s, *mins.get(lane)?);
                let hi = round_up(origin, s, *maxs.get(lane)?);
                *out.lo.get_mut(a)?.get_mut(lane)? = lo;
                *out.hi.get_mut(a)?.get_mut(lane)? = hi;
            }
        }
        Some(out)
    }
}

/// The smallest exponent whose 255 steps above `origin` reach `top` and move off `origin` (so
/// an unused lane, 255 to 0 steps, decodes empty).
fn exponent_for(origin: f32, top: f32) -> i32 {
    let reaches = |e: i32| {
        let end = decode(origin, step(e), u8::MAX);
        end >= top && end > origin
    };
    // A first guess from the extent's binary exponent (255 steps are just under 2⁸ of them),
    // then a few steps either way to the smallest that works.
    let extent = top - origin;
    let guess = ((extent.to_bits() >> 23) & 0xFF) as i32 - 127 - 7;
    let mut e = guess.clamp(MIN_EXPONENT, MAX_EXPONENT);
    while !reaches(e) && e < MAX_EXPONENT {
        e += 1;
    }
    while e > MIN_EXPONENT && reaches(e - 1) {
        e -= 1;
    }
    e
}

/// The largest `q` whose decoding is at most `v` (0 decodes to `origin ≤ v`).
fn round_down(origin: f32, s: f32, v: f32) -> u8 {
    let guess = ((v - origin) / s).clamp(0.0, 255.0) as u8;
    let mut q = guess;
    while q > 0 && decode(origin, s, q) > v {
        q -= 1;
    }
    while q < u8::MAX && decode(origin, s, q + 1) <= v {
        q += 1;
    }
    q
}

/// The smallest `q` whose decoding is at least `v` (255 decodes past the node's top).
fn round_up(origin: f32, s: f32, v: f32) -> u8 {
    let guess = ((v - origin) / s).clamp(0.0, 255.0) as u8;
    let mut q = guess;
    while q < u8::MAX && decode(origin, s, q) < v {
        q += 1;
    }
    while q > 0 && decode(origin, s, q - 1) >= v {
        q -= 1;
    }
    q
}
