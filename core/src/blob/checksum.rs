//! The checksums of the format: CRC-32/ISO-HDLC (the CRC of zlib, PNG and Ethernet).

use crate::mesh::ValidMesh;

/// The tables of the CRC, where the build has no `hardware_crc` (see `build.rs`) and is not
/// bare metal: sixteen (16 KiB, "slice-by-16"), since checking a multi-megabyte blob is a
/// large part of its load. (Where the build has `crc_lanes`, blobs are checked that way
/// instead; the tables still serve the mesh checksum.)
#[cfg(all(not(hardware_crc), not(target_os = "none")))]
mod tables {
    use crc::{CRC_32_ISO_HDLC, Crc, Digest, Table};

    static CRC32: Crc<u32, Table<16>> = Crc::<u32, Table<16>>::new(&CRC_32_ISO_HDLC);

    /// A running CRC by the tables.
    pub(super) type State = Digest<'static, u32, Table<16>>;

    /// The register before any byte.
    pub(super) fn start() -> State {
        CRC32.digest()
    }
}

/// On bare metal, where flash is scarce and blobs small, the CRC half a byte at a time: a
/// table of 16 words (64 bytes) instead of the byte-wise table's 256 (1 KiB), for two look-ups
/// per byte instead of one. The same checksum.
#[cfg(all(not(hardware_crc), target_os = "none"))]
mod tables {
    /// A running CRC, half a byte per step.
    pub(super) type State = super::NibbleCrc;

    /// The register before any byte.
    pub(super) fn start() -> State {
        super::NibbleCrc::new()
    }
}

/// The register's next value for each low half-byte: four steps of the bitwise CRC with the
/// reflected polynomial `0xEDB8_8320` (the tests derive each entry from the definition).
const NIBBLE_TABLE: [u32; 16] = [
    0x0000_0000,
    0x1DB7_1064,
    0x3B6E_20C8,
    0x26D9_30AC,
    0x76DC_4190,
    0x6B6B_51F4,
    0x4DB2_6158,
    0x5005_713C,
    0xEDB8_8320,
    0xF00F_9344,
    0xD6D6_A3E8,
    0xCB61_B38C,
    0x9B64_C2B0,
    0x86D3_D2D4,
    0xA00A_E278,
    0xBDBD_F21C,
];

/// CRC-32/ISO-HDLC from a 16-entry table, half a byte per look-up (the bare-metal form; on
/// other targets only its test builds it).
#[cfg_attr(not(all(not(hardware_crc), target_os = "none")), allow(dead_code))]
pub(crate) struct NibbleCrc {
    register: u32,
}

#[cfg_attr(not(all(not(hardware_crc), target_os = "none")), allow(dead_code))]
impl NibbleCrc {
    /// The register before any byte.
    pub(crate) const fn new() -> Self {
        Self { register: !0 }
    }

    /// Feeds `bytes`.
    pub(crate) fn update(&mut self, bytes: &[u8]) {
        let step = |r: u32| (r >> 4) ^ NIBBLE_TABLE.get((r & 15) as usize).copied().unwrap_or(0);
        for &byte in bytes {
            self.register = step(step(self.register ^ u32::from(byte)));
        }
    }

    /// The CRC of every byte fed.
    pub(crate) const fn finalize(self) -> u32 {
        !self.register
    }
}

/// CRC-32 of `head` followed by `payload` (a blob's bytes around its checksum), by the quickest
/// means this build has; the same value by each:
/// - with the `std` feature on x86, x86-64 and AArch64, the `crc32fast` crate, which uses the
///   CPU's carry-less multiply (PCLMULQDQ) or CRC32 instructions where they are present, found
///   at run time (only the standard library can ask), and its tables elsewhere;
/// - else, on targets with a byte shuffle (WebAssembly SIMD, SSSE3, NEON), sixteen runs in byte
///   lanes (`crc_lanes`);
/// - else tables.
pub(crate) fn crc_of_parts(head: &[u8], payload: &[u8]) -> u32 {
    #[cfg(crc_lanes)]
    {
        use super::crc_lanes::{update, update_lanes};
        !update_lanes(update(!0, head), payload)
    }
    #[cfg(not(crc_lanes))]
    {
        let mut d = Running::new();
        d.update(head);
        d.update(payload);
        d.finalize()
    }
}

/// A running CRC-32: `crc32fast` where the build has `hardware_crc` (see `build.rs`), else
/// tables.
pub(crate) struct Running {
    #[cfg(hardware_crc)]
    state: crc32fast::Hasher,
    #[cfg(not(hardware_crc))]
    state: tables::State,
}

impl Running {
    /// The register before any byte.
    pub(crate) fn new() -> Self {
        Self {
            #[cfg(hardware_crc)]
            state: crc32fast::Hasher::new(),
            #[cfg(not(hardware_crc))]
            state: tables::start(),
        }
    }

    /// Feeds `bytes`.
    pub(crate) fn update(&mut self, bytes: &[u8]) {
        self.state.update(bytes);
    }

    /// The CRC of every byte fed.
    pub(crate) fn finalize(self) -> u32 {
        self.state.finalize()
    }
}

/// Mesh records (12 bytes each) gathered before each update: the carry-less multiply paths
/// take only longer runs, and fewer calls cost the tables less too.
const MESH_RECORDS: usize = 32;

/// The mesh checksum a blob records: CRC-32/ISO-HDLC of every position coordinate as a
/// little-endian `f32` (x, y, z per vertex, vertices in order) followed by every vertex index as a
/// little-endian `u32` (three per triangle, triangles in order).
///
/// A blob baked without its mesh ([`MeshLayout::Omitted`](super::MeshLayout::Omitted)) is
/// attached only to a mesh with this checksum, so a query never runs against the wrong mesh.
#[must_use]
pub fn mesh_checksum(mesh: &ValidMesh<'_>) -> u32 {
    let mut d = Running::new();
    let positions = mesh
        .positions()
        .iter()
        .map(|&[x, y, z]| le_bytes_3(x.to_bits(), y.to_bits(), z.to_bits()));
    let indices = mesh
        .triangles()
        .iter()
        .map(|&[a, b, c]| le_bytes_3(a, b, c));
    let mut records = positions.chain(indices);
    let mut buffer = [0u8; 12 * MESH_RECORDS];
    loop {
        let mut filled = 0usize;
        for (slot, record) in buffer.chunks_exact_mut(12).zip(&mut records) {
            slot.copy_from_slice(&record);
            filled += 12;
        }
        d.update(buffer.get(..filled).unwrap_or_default());
        if filled < buffer.len() {
            return d.finalize();
        }
    }
}

/// Three words as 12 little-endian bytes.
fn le_bytes_3(a: u32, b: u32, c: u32) -> [u8; 12] {
    let [a0, a1, a2, a3] = a.to_le_bytes();
    let [b0, b1, b2, b3] = b.to_le_bytes();
    let [c0, c1, c2, c3] = c.to_le_bytes();
    [a0, a1, a2, a3, b0, b1, b2, b3, c0, c1, c2, c3]
}

#[cfg(test)]
mod tests {
    use super::crc_of_parts;

    /// CRC-32/ISO-HDLC by its definition, a bit at a time.
    fn bitwise(bytes: impl Iterator<Item = u8>) -> u32 {
        let mut register = !0u32;
        for byte in bytes {
            register ^= u32::from(byte);
            for _ in 0..8 {
                register = (register >> 1) ^ (0xEDB8_8320 & 0u32.wrapping_sub(register & 1));
            }
        }
        !register
    }

    /// The bare-metal form, half a byte at a time, is the CRC by its definition, on this
    /// host as on the device.
    #[test]
    fn the_half_byte_crc_is_the_crc() {
        let bytes: std::vec::Vec<u8> = (0u32..5_000)
            .map(|i| (i.wrapping_mul(2_654_435_761) >> 11) as u8)
            .collect();
        for len in [0, 1, 9, 255, 5_000] {
            let mut crc = super::NibbleCrc::new();
            let (a, b) = bytes[..len].split_at(len / 3);
            crc.update(a);
            crc.update(b);
            assert_eq!(
                crc.finalize(),
                bitwise(bytes[..len].iter().copied()),
                "{len}"
            );
        }
        for (i, &entry) in super::NIBBLE_TABLE.iter().enumerate() {
            let mut register = i as u32;
            for _ in 0..4 {
                register = (register >> 1) ^ (0xEDB8_8320 & 0u32.wrapping_sub(register & 1));
            }
            assert_eq!(entry, register, "entry {i}");
        }
        let mut check = super::NibbleCrc::new();
        check.update(b"123456789");
        assert_eq!(check.finalize(), 0xCBF4_3926);
    }

    /// Whichever way this build computes it, the checksum of a head and a payload is the
    /// CRC of the two one after the other: lengths below, at and far above the point where
    /// the fast ways take over, any split between the two parts.
    #[test]
    fn the_checksum_of_two_parts_is_the_crc_of_both() {
        let bytes: std::vec::Vec<u8> = (0u32..70_000)
            .map(|i| (i.wrapping_mul(2_654_435_761) >> 13) as u8)
            .collect();
        assert_eq!(bitwise(b"123456789".iter().copied()), 0xCBF4_3926);
        for len in [
            0, 1, 15, 16, 17, 255, 4096, 16_383, 16_384, 16_400, 40_000, 70_000,
        ] {
            for head in [0, 1, 7, 40, 200] {
                let all = &bytes[..len];
                let (h, p) = all.split_at(head.min(len));
                let want = bitwise(all.iter().copied());
                assert_eq!(crc_of_parts(h, p), want, "length {len}, head {head}");
            }
        }
    }
}
