//! CRC-32/ISO-HDLC over sixteen runs of a buffer at once, one run per byte lane of a 128-bit
//! vector: the blob checksum on targets with a byte shuffle (`i8x16.swizzle` in WebAssembly).
//!
//! A table-driven CRC does one table load per byte, and in WebAssembly each costs a shift, a
//! mask, an address and a load: about five instructions per byte. Here each of the sixteen
//! lanes keeps its own register, byte `k` of every lane's register in vector `k`, and one step
//! feeds every lane its next byte: the byte table is linear (`T[a ^ b] = T[a] ^ T[b]`), so
//! `T[i]` is `T[i & 15] ^ T[i & 240]`, and each 4-bit half indexes a 16-entry table with one
//! shuffle per output byte. Eight shuffles and a dozen other operations feed sixteen bytes.
//!
//! The runs are cut from one buffer, so their registers are combined at the end: a register
//! `s` followed by `n` bytes `X` becomes `s · x^(8n) mod P ⊕ R(0, X)` (the CRC is linear), with
//! the product taken in the reflected bit order the register uses.

use wide::u8x16;

/// The reflected polynomial of CRC-32/ISO-HDLC.
const POLY: u32 = 0xEDB8_8320;

/// Vectors of sixteen lanes.
const LANES: usize = 16;

/// Bytes each lane takes at a time: a 16 × 16 block of the runs is turned into sixteen vectors
/// of one byte per lane.
const BLOCK: usize = 16;

/// Below this many bytes per lane, the table CRC is as fast: setting up and combining the
/// lanes costs about what a few kilobytes of bytes do.
const MIN_RUN: usize = 1024;

/// `TABLE[n]`: the register after feeding byte `n` into a zero register.
static TABLE: [u32; 256] = byte_table();

// Evaluated at compile time: an index out of range fails the build, never a run.
#[allow(clippy::indexing_slicing)]
const fn byte_table() -> [u32; 256] {
    let mut table = [0u32; 256];
    let mut n = 0;
    while n < 256 {
        let mut r = n as u32;
        let mut bit = 0;
        while bit < 8 {
            r = if r & 1 == 1 { (r >> 1) ^ POLY } else { r >> 1 };
            bit += 1;
        }
        table[n] = r;
        n += 1;
    }
    table
}

/// The CRC register `register` after `bytes`, one byte at a time (no initial value or final
/// XOR applied: CRC-32/ISO-HDLC of `bytes` is `update(!0, bytes) ^ !0`).
pub(crate) fn update(register: u32, bytes: &[u8]) -> u32 {
    bytes.iter().fold(register, |r, &b| {
        let index = usize::from((r as u8) ^ b);
        TABLE.get(index).copied().unwrap_or(0) ^ (r >> 8)
    })
}

/// [`update`] with most of the buffer cut into sixteen runs fed side by side (see
/// [`sixteen_runs`]); the same register. Buffers too short to pay for the lanes are fed one
/// byte at a time.
pub(crate) fn update_lanes(register: u32, bytes: &[u8]) -> u32 {
    match sixteen_runs(register, bytes) {
        Some((register, rest)) => update(register, rest),
        None => update(register, bytes),
    }
}

/// The register after the first `16 · run` bytes of `bytes`, fed as sixteen runs of `run`
/// bytes side by side (`run` the largest multiple of 16 that fits), and the bytes left after
/// them (fewer than 256); `None` when a run would be shorter than [`MIN_RUN`].
fn sixteen_runs(register: u32, bytes: &[u8]) -> Option<(u32, &[u8])> {
    let run = bytes.len() / (LANES * BLOCK) * BLOCK;
    if run < MIN_RUN {
        return None;
    }
    let (body, rest) = bytes.split_at_checked(run * LANES)?;
    let mut runs = body.chunks_exact(run);
    let runs: [&[u8]; LANES] = core::array::from_fn(|_| runs.next().unwrap_or_default());
    let tables = NibbleTables::new();
    let [r0, r1, r2, r3] = register.to_le_bytes();
    // Lane 0 starts from `register`, the others from zero: their runs are shifted onto it
    // when the lanes are combined.
    let first_lane = |b: u8| u8x16::new(core::array::from_fn(|i| if i == 0 { b } else { 0 }));
    let mut state = [
        first_lane(r0),
        first_lane(r1),
        first_lane(r2),
        first_lane(r3),
    ];
    for at in (0..run).step_by(BLOCK) {
        let rows: [u8x16; LANES] = runs.map(|r| {
            let block = r.get(at..).and_then(|b| b.first_chunk::<BLOCK>());
            u8x16::new(block.copied().unwrap_or_default())
        });
        for column in transpose(rows) {
            state = tables.step(state, column);
        }
    }
    let [b0, b1, b2, b3] = state.map(u8x16::to_array);
    let shift = x_pow_8n(run);
    let mut combined = 0;
    for lane in 0..LANES {
        let byte = |b: &[u8; LANES]| b.get(lane).copied().unwrap_or(0);
        let lane_register = u32::from_le_bytes([byte(&b0), byte(&b1), byte(&b2), byte(&b3)]);
        combined = multiply(shift, combined) ^ lane_register;
    }
    Some((combined, rest))
}

/// Byte `k` of `TABLE[n]` (`low`) and of `TABLE[n << 4]` (`high`) for `n < 16`, lane `n`.
struct NibbleTables {
    low: [u8x16; 4],
    high: [u8x16; 4],
}

impl NibbleTables {
    fn new() -> Self {
        let byte = |shift: usize, k: usize| -> u8x16 {
            u8x16::new(core::array::from_fn(|n| {
                let entry = TABLE.get(n << shift).copied().unwrap_or(0);
                entry.to_le_bytes().get(k).copied().unwrap_or(0)
            }))
        };
        Self {
            low: core::array::from_fn(|k| byte(0, k)),
            high: core::array::from_fn(|k| byte(4, k)),
        }
    }

    /// Every lane's register (byte `k` of each in `state[k]`) after its byte in `input`:
    /// `r' = T[(r ^ b) & 255] ^ (r >> 8)`.
    #[inline(always)]
    fn step(&self, [c0, c1, c2, c3]: [u8x16; 4], input: u8x16) -> [u8x16; 4] {
        let index = c0 ^ input;
        let low = index & u8x16::splat(15);
        let high = index.unbounded_shr_scalar(4);
        let [l0, l1, l2, l3] = self.low;
        let [h0, h1, h2, h3] = self.high;
        let entry = |l: u8x16, h: u8x16| l.shuffle(low) ^ h.shuffle(high);
        [
            entry(l0, h0) ^ c1,
            entry(l1, h1) ^ c2,
            entry(l2, h2) ^ c3,
            entry(l3, h3),
        ]
    }
}

/// Sixteen rows of sixteen bytes turned into sixteen columns (`out[j]` lane `i` is `rows[i]`
/// lane `j`): four rounds of interleaving row `i` with row `i + 8`.
#[inline(always)]
fn transpose(rows: [u8x16; LANES]) -> [u8x16; LANES] {
    let mut x = rows;
    for _ in 0..4 {
        x = interleave(x);
    }
    x
}

/// One round of [`transpose`]: `out[2i]`, `out[2i + 1]` are the low and high halves of rows `i`
/// and `i + 8` interleaved byte by byte.
#[inline(always)]
fn interleave(
    [
        a0,
        a1,
        a2,
        a3,
        a4,
        a5,
        a6,
        a7,
        a8,
        a9,
        a10,
        a11,
        a12,
        a13,
        a14,
        a15,
    ]: [u8x16; LANES],
) -> [u8x16; LANES] {
    let zip = |a, b| (u8x16::unpack_low(a, b), u8x16::unpack_high(a, b));
    let (b0, b1) = zip(a0, a8);
    let (b2, b3) = zip(a1, a9);
    let (b4, b5) = zip(a2, a10);
    let (b6, b7) = zip(a3, a11);
    let (b8, b9) = zip(a4, a12);
    let (b10, b11) = zip(a5, a13);
    let (b12, b13) = zip(a6, a14);
    let (b14, b15) = zip(a7, a15);
    [
        b0, b1, b2, b3, b4, b5, b6, b7, b8, b9, b10, b11, b12, b13, b14, b15,
    ]
}

/// `a · b mod P` for polynomials in the register's reflected bit order (bit 31 is `x⁰`).
fn multiply(a: u32, mut b: u32) -> u32 {
    let mut product = 0;
    for bit in (0..32).rev() {
        product ^= b & 0u32.wrapping_sub((a >> bit) & 1);
        b = if b & 1 == 1 { (b >> 1) ^ POLY } else { b >> 1 };
    }
    product
}

/// `x^(8n) mod P` in the reflected bit order: what `n` zero bytes multiply a register by.
fn x_pow_8n(mut n: usize) -> u32 {
    let mut power = 1 << 31;
    let mut square = 1 << (31 - 8);
    while n > 0 {
        if n & 1 == 1 {
            power = multiply(power, square);
        }
        square = multiply(square, square);
        n >>= 1;
    }
    power
}

#[cfg(test)]
mod tests {
    use super::*;

    /// CRC-32/ISO-HDLC as the `crc` crate computes it.
    fn reference(bytes: &[u8]) -> u32 {
        crc::Crc::<u32>::new(&crc::CRC_32_ISO_HDLC).checksum(bytes)
    }

    /// Bytes from an xorshift generator seeded with `seed` (non-zero).
    fn noise(len: usize, mut seed: u64) -> std::vec::Vec<u8> {
        (0..len)
            .map(|_| {
                seed ^= seed << 13;
                seed ^= seed >> 7;
                seed ^= seed << 17;
                (seed >> 32) as u8
            })
            .collect()
    }

    /// The byte-at-a-time CRC and the lanes give the reference checksum for lengths on both
    /// sides of the lanes' threshold and of every block and lane boundary, from any register
    /// (a buffer fed in two parts gives the checksum of the whole).
    #[test]
    fn lanes_give_the_reference_checksum() {
        let min = MIN_RUN * LANES;
        let lengths = [
            0,
            1,
            15,
            255,
            4096,
            min - 1,
            min,
            min + 1,
            min + 255,
            min + 256,
        ];
        let lengths = lengths
            .into_iter()
            .chain([3 * min + 4097, 1 << 20, (1 << 20) + 12_345]);
        for (k, len) in lengths.enumerate() {
            let bytes = noise(len, 0x9E37_79B9_7F4A_7C15 + k as u64);
            let want = reference(&bytes);
            assert_eq!(update(!0, &bytes) ^ !0, want, "bytes, {len}");
            assert_eq!(update_lanes(!0, &bytes) ^ !0, want, "lanes, {len}");
            let cut = len / 3;
            let (head, rest) = bytes.split_at(cut);
            assert_eq!(
                update_lanes(update(!0, head), rest) ^ !0,
                want,
                "parts, {len}"
            );
        }
    }

    /// The sixteen runs alone give the reference register for the bytes they take, and take
    /// all but fewer than 256 bytes of a long buffer (so the test above exercises them).
    #[test]
    fn sixteen_runs_take_long_buffers() {
        for len in [MIN_RUN * LANES, MIN_RUN * LANES + 4097, 1 << 20] {
            let bytes = noise(len, len as u64);
            let Some((register, rest)) = sixteen_runs(!0, &bytes) else {
                panic!("{len} bytes not taken by the lanes");
            };
            assert!(rest.len() < LANES * BLOCK, "{} left of {len}", rest.len());
            let taken = bytes.get(..len - rest.len()).unwrap_or_default();
            assert_eq!(register, update(!0, taken), "{len}");
        }
        assert!(sixteen_runs(!0, &noise(MIN_RUN * LANES - 1, 3)).is_none());
    }

    /// Zero bytes multiply a register by `x^(8n)`: the rule that combines the lanes.
    #[test]
    fn zero_bytes_multiply_by_a_power_of_x() {
        for (n, register) in [(0, 0x1234_5678), (1, 0xFFFF_FFFF), (1000, 0x8000_0001)] {
            let zeros = std::vec![0u8; n];
            assert_eq!(
                update(register, &zeros),
                multiply(x_pow_8n(n), register),
                "{n}"
            );
        }
    }
}
