//! The checksums of the format: CRC-32/ISO-HDLC (the CRC of zlib, PNG and Ethernet).

use crc::{CRC_32_ISO_HDLC, Crc, Digest, Table};

use crate::mesh::ValidMesh;

/// Lookup tables of the CRC: one (1 KiB) on bare-metal targets, where flash is scarce and
/// blobs are small; sixteen (16 KiB, "slice-by-16", about ten times the speed) everywhere
/// else, where checking a multi-megabyte blob is a large part of its load. The same checksum
/// either way. (Targets with byte shuffles check a blob's bytes with `crc_lanes` instead; the
/// tables still serve the mesh checksum there.)
#[cfg(target_os = "none")]
type Tables = Table<1>;
#[cfg(not(target_os = "none"))]
type Tables = Table<16>;

static CRC32: Crc<u32, Tables> = Crc::<u32, Tables>::new(&CRC_32_ISO_HDLC);

/// A running CRC-32.
pub(crate) fn digest() -> Digest<'static, u32, Tables> {
    CRC32.digest()
}

/// The mesh checksum a blob records: CRC-32/ISO-HDLC of every position coordinate as a
/// little-endian `f32` (x, y, z per vertex, vertices in order) followed by every vertex index as a
/// little-endian `u32` (three per triangle, triangles in order).
///
/// A blob baked without its mesh ([`MeshLayout::Omitted`](super::MeshLayout::Omitted)) is
/// attached only to a mesh with this checksum, so a query never runs against the wrong mesh.
#[must_use]
pub fn mesh_checksum(mesh: &ValidMesh<'_>) -> u32 {
    let mut d = digest();
    for &[x, y, z] in mesh.positions() {
        d.update(&le_bytes_3(x.to_bits(), y.to_bits(), z.to_bits()));
    }
    for &[a, b, c] in mesh.triangles() {
        d.update(&le_bytes_3(a, b, c));
    }
    d.finalize()
}

/// Three words as 12 little-endian bytes.
fn le_bytes_3(a: u32, b: u32, c: u32) -> [u8; 12] {
    let [a0, a1, a2, a3] = a.to_le_bytes();
    let [b0, b1, b2, b3] = b.to_le_bytes();
    let [c0, c1, c2, c3] = c.to_le_bytes();
    [a0, a1, a2, a3, b0, b1, b2, b3, c0, c1, c2, c3]
}
