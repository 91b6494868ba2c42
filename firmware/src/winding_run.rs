//! `--features winding`: containment and signed distance straight from the blob in flash (a
//! geofence on a device), from the winding-number expansions stored in it, checked against
//! the golden winding file the native and WebAssembly tests check too.

use glam::Vec3;
use meshq::blob::{BlobMesh, BlobView};
use meshq::inside::WindingAccuracy;
use meshq::math::Aabb;
use meshq_workload::{
    QueryPoints, WINDING_SEED, WindingDigest, WindingDigester, find_winding_golden,
};

/// The golden winding-number file.
static GOLDEN: &str = include_str!("../../tests/golden/winding.txt");

/// Why the winding check could not compare.
pub enum Unusable {
    /// The blob holds no expansions.
    NoExpansions,
    /// The blob's mesh is not stored indexed (the golden points come from its vertices' box).
    NotIndexed,
    /// No usable golden line.
    Golden(meshq_workload::GoldenError),
}

/// The digest of the winding numbers and signed distances of the golden points, with the
/// golden one. Points are taken one at a time (no buffers): each winding number and signed
/// distance is exactly what the batch calls native tests use give.
#[inline(never)]
pub fn run(view: &BlobView<'_>, mesh: &str) -> Result<(WindingDigest, WindingDigest), Unusable> {
    let tree = view.winding_tree().ok_or(Unusable::NoExpansions)?;
    let golden = find_winding_golden(GOLDEN, mesh).map_err(Unusable::Golden)?;
    let BlobMesh::Indexed { positions, .. } = view.mesh() else {
        return Err(Unusable::NotIndexed);
    };
    // The vertices' box, as the tests take it from the mesh file.
    let bounds = positions.iter().fold(Aabb::EMPTY, |b, bytes| {
        let (words, _) = bytes.as_chunks::<4>();
        let at = |k: usize| words.get(k).map_or(0.0, |w| f32::from_le_bytes(*w));
        b.grown(Vec3::new(at(0), at(1), at(2)))
    });
    let accuracy = WindingAccuracy::DEFAULT;
    let mut digest = WindingDigester::default();
    for p in QueryPoints::new(bounds, WINDING_SEED).take(golden.points as usize) {
        let w = tree.winding_number(p, accuracy);
        let d = tree
            .signed_distance(p, f32::INFINITY, accuracy)
            .map_or(f32::NAN, |s| s.distance);
        digest.add(w, d);
    }
    Ok((digest.finish(), golden))
}
