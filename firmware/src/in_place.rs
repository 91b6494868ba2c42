//! The parity queries answered straight from the blob bytes in flash.

use glam::Vec3;
use meshq::MeshQuery;
use meshq::blob::BlobView;
use meshq::math::{ClosestPoint, Ray, RayHit};
use meshq_workload::ParityTarget;

/// A blob view as a parity target: closest hit, any hit and unbounded closest point, all with
/// the default options (watertight test, both faces).
///
/// Each query stays out of line: inlined into one caller, the traversal stacks of all three
/// would share that caller's frame and add up, where apart only the deepest one counts.
pub struct InPlace<'a, 'b>(pub &'a BlobView<'b>);

impl ParityTarget for InPlace<'_, '_> {
    #[inline(never)]
    fn raycast(&mut self, ray: &Ray) -> Option<RayHit> {
        self.0.raycast(ray)
    }

    #[inline(never)]
    fn raycast_any(&mut self, ray: &Ray) -> bool {
        self.0.raycast_any(ray)
    }

    #[inline(never)]
    fn closest_point(&mut self, point: Vec3) -> Option<ClosestPoint> {
        self.0.closest_point(point, f32::INFINITY)
    }
}
