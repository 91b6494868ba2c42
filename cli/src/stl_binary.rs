//! Reading a binary STL: an 80-byte header, a little-endian triangle count, then 50 bytes per
//! triangle (a normal, three corners, two attribute bytes). Corners with the same bits become
//! one vertex, numbered in order of first appearance.

use std::collections::HashMap;

use anyhow::{Context, Result};

use crate::mesh_file::MeshData;

/// Bytes before the first triangle.
pub const HEADER_BYTES: usize = 84;
/// Bytes per triangle.
pub const TRIANGLE_BYTES: usize = 50;

/// The triangle count a binary STL of `bytes` declares, when its length is exactly what that
/// count needs (`None` otherwise: not a binary STL, or a damaged one).
pub fn declared_count(bytes: &[u8]) -> Option<u32> {
    let count = u32::from_le_bytes(bytes.get(80..84)?.try_into().ok()?);
    let expected = (count as usize)
        .checked_mul(TRIANGLE_BYTES)?
        .checked_add(HEADER_BYTES)?;
    (expected == bytes.len()).then_some(count)
}

/// Reads a binary STL whose length [`declared_count`] has checked.
pub fn read(bytes: &[u8]) -> Result<MeshData> {
    let body = bytes.get(HEADER_BYTES..).unwrap_or_default();
    let (records, _) = body.as_chunks::<TRIANGLE_BYTES>();
    let mut mesh = MeshData::default();
    let mut index_of: HashMap<[u32; 3], u32> = HashMap::new();
    for record in records {
        let mut triangle = [0u32; 3];
        for (corner, slot) in triangle.iter_mut().enumerate() {
            let at = 12 + 12 * corner;
            let bits: [u32; 3] = std::array::from_fn(|axis| {
                let o = at + 4 * axis;
                u32::from_le_bytes([record[o], record[o + 1], record[o + 2], record[o + 3]])
            });
            let next = u32::try_from(mesh.positions.len()).context("too many vertices")?;
            *slot = *index_of.entry(bits).or_insert_with(|| {
                mesh.positions.push(bits.map(f32::from_bits));
                next
            });
        }
        mesh.triangles.push(triangle);
    }
    Ok(mesh)
}
