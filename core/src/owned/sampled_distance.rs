//! The two-sided sampled distance between two meshes, within a budget of point–triangle tests.

use core::cell::Cell;

use super::MeshBvh;
use crate::bvh::BuildConfig;
use crate::collide::PairBudget;
use crate::error::RemeshError;
use crate::math::{PackedTriangle, Triangle};
use crate::mesh::ValidMesh;
use crate::query::{LeafTriangles, MeshQuery, Traverse};

/// The largest closest-point distance from sample points of each of two meshes to the other's
/// surface: every vertex and triangle centroid of both, or as many as a [`PairBudget`] allowed.
///
/// The largest over any set of samples is a lower bound of the Hausdorff distance (points
/// between samples may lie farther), so a run the budget stopped still gives one, from fewer
/// samples: [`measured`](Self::measured) says how many.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct SampledDistance {
    /// The largest distance found, divided by the length of the first mesh's bounds diagonal
    /// (0 for a mesh with a single point's bounds). `+∞` when a sample found no triangle: the
    /// other mesh has none.
    pub relative: f32,
    /// The samples whose distance was measured, at most [`samples`](Self::samples).
    pub measured: u64,
    /// The samples of both meshes: four per triangle (its corners and its centroid).
    pub samples: u64,
    /// The point–triangle tests made, at most the budget's
    /// [`max_tests`](PairBudget::max_tests).
    pub tested: u64,
}

impl SampledDistance {
    /// Whether every sample was measured (the budget was not spent).
    #[must_use]
    pub const fn is_complete(&self) -> bool {
        self.measured == self.samples
    }
}

/// Samples in this order so that a run the budget stops has spread its measured samples over
/// both meshes and all of each (a prime: coprime with every count it does not divide).
const STRIDES: [u64; 3] = [1_000_003, 999_983, 65_537];

/// [`SampledDistance`] between `first` (whose bounds scale the result) and `second`: samples
/// visited in a fixed stride order over both meshes, each a closest-point query on a BVH of
/// the other mesh; the query that would take the tests past `budget` is abandoned and the run
/// stops there. The same meshes and budget give the same answer on every target. A budget of
/// no tests measures no sample and builds no BVH.
///
/// # Errors
/// [`RemeshError::ReferenceBvh`] when a BVH of either mesh cannot be built.
pub(crate) fn sampled_distance(
    first: &ValidMesh<'_>,
    second: &ValidMesh<'_>,
    budget: PairBudget,
) -> Result<SampledDistance, RemeshError> {
    let bvh = |m: &ValidMesh<'_>| {
        MeshBvh::build(m, &BuildConfig::default())
            .map_err(|error| RemeshError::ReferenceBvh { error })
    };
    let first_samples = 4 * first.triangle_count() as u64;
    let samples = first_samples + 4 * second.triangle_count() as u64;
    if budget.max_tests == 0 {
        return Ok(SampledDistance {
            relative: 0.0,
            measured: 0,
            samples,
            tested: 0,
        });
    }
    let (to_first, to_second) = (bvh(first)?, bvh(second)?);
    let stride = STRIDES
        .iter()
        .copied()
        .find(|&p| !samples.is_multiple_of(p))
        .unwrap_or(1)
        % samples.max(1);
    let tally = TestTally::new(budget.max_tests as u64);
    let (mut farthest, mut measured) = (0.0f32, 0u64);
    let mut at = 0u64;
    for _ in 0..samples {
        let (from, to, index) = if at < first_samples {
            (first, &to_second, at)
        } else {
            (second, &to_first, at - first_samples)
        };
        at += stride;
        if at >= samples {
            at -= samples;
        }
        let Some(point) = sample(from, index) else {
            continue;
        };
        let counted = Counted {
            packed: to.packed(),
            tally: &tally,
        };
        let found = to.with(&counted).closest_point(point, f32::INFINITY);
        if tally.spent.get() {
            break;
        }
        measured += 1;
        let distance = found.map_or(f32::INFINITY, |c| c.distance_from(point));
        farthest = farthest.max(distance);
    }
    let bounds = first.bounds();
    let diagonal = (bounds.max - bounds.min).length();
    Ok(SampledDistance {
        relative: if diagonal > 0.0 {
            farthest / diagonal
        } else if farthest > 0.0 {
            f32::INFINITY
        } else {
            0.0
        },
        measured,
        samples,
        tested: tally.tested.get(),
    })
}

/// Sample `index` of `mesh`: corner `index % 4` of triangle `index / 4`, or its centroid for 3.
fn sample(mesh: &ValidMesh<'_>, index: u64) -> Option<glam::Vec3> {
    let tri: Triangle = mesh.triangle(u32::try_from(index / 4).ok()?)?;
    Some(match index % 4 {
        0 => tri.a,
        1 => tri.b,
        2 => tri.c,
        _ => (tri.a + tri.b + tri.c) / 3.0,
    })
}

/// The point–triangle tests of a distance run against its budget.
struct TestTally {
    max_tests: u64,
    tested: Cell<u64>,
    /// Set by the first triangle the budget could not pay for; the query it belongs to skipped
    /// it, so its answer is discarded.
    spent: Cell<bool>,
}

impl TestTally {
    const fn new(max_tests: u64) -> Self {
        Self {
            max_tests,
            tested: Cell::new(0),
            spent: Cell::new(false),
        }
    }

    /// Pays for `count` tests; `false` (and spent) when they do not fit.
    fn take(&self, count: usize) -> bool {
        let next = self.tested.get().saturating_add(count as u64);
        if self.spent.get() || next > self.max_tests {
            self.spent.set(true);
            return false;
        }
        self.tested.set(next);
        true
    }
}

/// A BVH's packed triangles, handed to a query only while the tally can pay for them: a query
/// loads a leaf's triangles through here before it tests them, so the count is the tests made.
struct Counted<'a> {
    packed: crate::query::PackedTriangles<'a>,
    tally: &'a TestTally,
}

impl LeafTriangles for Counted<'_> {
    #[inline(always)]
    fn corners(&self, slot: usize, tri: u32) -> Option<Triangle> {
        if self.tally.take(1) {
            self.packed.corners(slot, tri)
        } else {
            None
        }
    }

    #[inline(always)]
    fn run(&self, first: usize, count: usize) -> Option<&[PackedTriangle]> {
        // A refused run falls back to `corners`, which refuses each triangle in turn.
        if self.tally.take(count) {
            self.packed.run(first, count)
        } else {
            None
        }
    }
}
