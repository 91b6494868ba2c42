//! A leaf's triangles four at a time, in SIMD lanes, for the leaf tests that take four at once.

use core::ops::ControlFlow;

use glam::Vec3;

use super::{LeafTriangleIds, LeafTriangles};
use crate::geom::TriangleLanes;
use crate::math::{PackedTriangle, Triangle};

/// Whether the target has 128-bit SIMD for glam's `Vec4`, so four triangles in lanes cost
/// about what one does. Without it (a Cortex-M4) the lanes would be four scalar tests with no
/// branches to skip work: bigger and slower. Queries give the same answers either way.
pub(crate) const LANES_PAY: bool = cfg!(any(
    target_feature = "sse2",
    target_feature = "simd128",
    all(target_arch = "aarch64", target_feature = "neon")
));

/// Up to four triangles of a leaf: their corners in lanes, and each one's mesh index and
/// corners for the scalar test that decides.
pub(crate) struct Batch<'r> {
    /// The corners, lane `i` for triangle `i`; unused lanes repeat lane 0.
    pub(crate) lanes: TriangleLanes,
    /// Bit `i` set for each used lane.
    pub(crate) used: u32,
    ids: [u32; 4],
    corners: Corners<'r>,
}

enum Corners<'r> {
    /// A run of packed triangles, read in place.
    Run(&'r [PackedTriangle]),
    /// Corners fetched one by one.
    Gathered([Triangle; 4]),
}

impl Batch<'_> {
    /// Lane `lane`'s mesh triangle index and corners, if the lane is used.
    #[inline(always)]
    pub(crate) fn triangle(&self, lane: usize) -> Option<(u32, Triangle)> {
        if self.used & (1 << lane) == 0 {
            return None;
        }
        let corners = match &self.corners {
            Corners::Run(run) => run.get(lane)?.triangle(),
            Corners::Gathered(tris) => *tris.get(lane)?,
        };
        Some((*self.ids.get(lane)?, corners))
    }
}

/// Calls `each` on the leaf's triangles in batches of up to four, in slot order, until it
/// breaks. Triangles the source does not have are skipped.
#[inline(always)]
pub(crate) fn for_each_batch<S: LeafTriangles + ?Sized>(
    source: &S,
    mut tris: LeafTriangleIds<'_>,
    mut each: impl FnMut(&Batch<'_>) -> ControlFlow<()>,
) -> ControlFlow<()> {
    if let Some(run) = source.run(tris.first_slot(), tris.entries()) {
        for chunk in run.chunks(4) {
            let (ids, used) = tris.next_four(chunk.len());
            if used == 0 {
                continue;
            }
            if let Some(lanes) = TriangleLanes::from_packed(chunk) {
                each(&Batch {
                    lanes,
                    used,
                    ids,
                    corners: Corners::Run(chunk),
                })?;
            }
        }
        return ControlFlow::Continue(());
    }
    loop {
        let mut ids = [0u32; 4];
        let mut corners = [Triangle::new(Vec3::ZERO, Vec3::ZERO, Vec3::ZERO); 4];
        let mut n = 0usize;
        for (slot, tri) in &mut tris {
            if let (Some(t), Some(id), Some(c)) = (
                source.corners(slot, tri),
                ids.get_mut(n),
                corners.get_mut(n),
            ) {
                (*id, *c) = (tri, t);
                n += 1;
                if n == 4 {
                    break;
                }
            }
        }
        if n == 0 {
            return ControlFlow::Continue(());
        }
        // Unused lanes repeat the first triangle: real numbers, ignored through `used`.
        let [first, ..] = corners;
        let filled =
            core::array::from_fn(|i| corners.get(i).filter(|_| i < n).copied().unwrap_or(first));
        each(&Batch {
            lanes: TriangleLanes::new(&filled),
            used: (1 << n) - 1,
            ids,
            corners: Corners::Gathered(corners),
        })?;
        if n < 4 {
            return ControlFlow::Continue(());
        }
    }
}
