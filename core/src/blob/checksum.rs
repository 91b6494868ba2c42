//! The checksums of the format: CRC-32/ISO-HDLC (the CRC of zlib, PNG and Ethernet).

use crate::mesh::ValidMesh;

/// The tables of the CRC, where the build has no `hardware_crc` (see `build.rs`): one (1 KiB)
/// on bare-metal targets, where flash is scarce and blobs are small; sixteen (16 KiB,
/// "slice-by-16", about ten times the speed) everywhere else, where checking a multi-megabyte
/// blob is a large part of its load. The same checksum either way. (Where the build has
/// `crc_lanes`, blobs are checked that way instead; the tables still serve the mesh checksum.)
#[cfg(not(hardware_crc))]
mod tables {
    use crc::{CRC_32_ISO_HDLC, Crc, Digest, Table};

    #[cfg(target_os = "none")]
    type Tables = Table<1>;
    #[cfg(not(target_os = "none"))]
    type Tables = Table<16>;

    static CRC32: Crc<u32, Tables> = Crc::<u32, Tables>::new(&CRC_32_ISO_HDLC);

    /// A running CRC by the tables.
    pub(super) type State = Digest<'static, u32, Tables>;

    /// The register before any byte.
    pub(super) fn start() -> State {
        CRC32.digest()
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
