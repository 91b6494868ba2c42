//! How much work a walk over triangle pairs may do: the cap that keeps mesh–mesh and
//! self-intersection queries bounded when boxes cannot tell triangles apart.

use core::ops::ControlFlow;

use super::Found;
use crate::bvh::{BvhNode, TreeArrays};
use crate::error::PairBudgetSpent;
use crate::query::LeafTriangleIds;

/// The most triangle pairs a mesh–mesh or self-intersection query may consider before it
/// stops with [`PairBudgetSpent`]. (The sampled distance of a remeshed mesh,
/// `owned::Remeshed::distance_to` with the `alloc` feature, takes one too: there a pair is a
/// sample point and a triangle its closest-point query loads.)
///
/// On ordinary meshes the boxes rule out all but a few pairs per triangle, so a walk
/// considers a small multiple of the triangle count. When many triangles share one place —
/// copies of one triangle, all corners at one point, long slivers that all cross one spot —
/// no box separates them and the pairs grow with the square of the count; the budget turns
/// that into an error instead of minutes of work.
///
/// The walk counts, for every pair of leaves whose boxes overlap, the triangle pairs the two
/// leaves hold (`a × b`, or `n (n − 1) / 2` for a leaf with itself, at least 1) *before* it
/// tests them, and stops before the pair of leaves that would take that count past
/// [`max_tests`](Self::max_tests). So [`Found::tested`] never exceeds it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PairBudget {
    /// The most triangle pairs the walk may consider (see above).
    pub max_tests: usize,
}

impl PairBudget {
    /// No cap: the walk goes on however long it takes.
    pub const UNLIMITED: Self = Self {
        max_tests: usize::MAX,
    };

    /// Pairs allowed per triangle of the two meshes by [`for_triangles`](Self::for_triangles).
    pub const TESTS_PER_TRIANGLE: usize = 256;

    /// Pairs allowed by [`for_triangles`](Self::for_triangles) whatever the triangle count, so
    /// that small meshes with a dense spot still get an answer.
    pub const LEAST_TESTS: usize = 1 << 20;

    /// The default budget for meshes of `a` and `b` triangles (for a self-intersection, pass
    /// the count twice): [`LEAST_TESTS`](Self::LEAST_TESTS) +
    /// [`TESTS_PER_TRIANGLE`](Self::TESTS_PER_TRIANGLE) × (`a` + `b`), saturating. Linear in
    /// the meshes' size, and well above what well-shaped meshes need.
    #[must_use]
    pub const fn for_triangles(a: usize, b: usize) -> Self {
        let per_triangle = Self::TESTS_PER_TRIANGLE.saturating_mul(a.saturating_add(b));
        Self {
            max_tests: Self::LEAST_TESTS.saturating_add(per_triangle),
        }
    }
}

/// A walk's running count against its budget.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Tally {
    budget: PairBudget,
    considered: usize,
    stopped: bool,
}

impl Tally {
    pub(crate) const fn new(budget: PairBudget) -> Self {
        Self {
            budget,
            considered: 0,
            stopped: false,
        }
    }

    /// Takes `pairs` (at least 1) from the budget; `false`, and the tally marked stopped,
    /// when they do not fit.
    pub(crate) fn take(&mut self, pairs: usize) -> bool {
        let next = self.considered.saturating_add(pairs.max(1));
        if next > self.budget.max_tests {
            self.stopped = true;
            return false;
        }
        self.considered = next;
        true
    }

    /// The triangles of a pair of leaves, after taking their pairs from the budget: `Break`
    /// when the budget refuses them (the walk stops), `Continue(None)` when a tree does not
    /// hold a leaf's range (which validation rules out; the pair is skipped).
    pub(crate) fn take_leaves<'t, A, B>(
        &mut self,
        a: &'t A,
        b: &'t B,
        leaf_a: &BvhNode,
        leaf_b: &BvhNode,
    ) -> ControlFlow<(), Option<(LeafTriangleIds<'t>, LeafTriangleIds<'t>)>>
    where
        A: TreeArrays + ?Sized,
        B: TreeArrays + ?Sized,
    {
        let pairs = (leaf_a.count as usize).saturating_mul(leaf_b.count as usize);
        if !self.take(pairs) {
            return ControlFlow::Break(());
        }
        ControlFlow::Continue(
            a.leaf_triangles(leaf_a.first as usize, leaf_a.count as usize)
                .zip(b.leaf_triangles(leaf_b.first as usize, leaf_b.count as usize)),
        )
    }

    /// The answer of a yes/no walk that tested `tested` pairs: yes when it `met` a pair (an
    /// answer, whether or not the budget ran out after), no when it went to its end, the
    /// error otherwise.
    pub(crate) const fn yes_or_no(
        &self,
        met: bool,
        tested: usize,
    ) -> Result<bool, PairBudgetSpent> {
        if met {
            return Ok(true);
        }
        match self.finish(Found {
            total: 0,
            written: 0,
            tested,
        }) {
            Ok(_) => Ok(false),
            Err(spent) => Err(spent),
        }
    }

    /// `found` when the walk went to its end, the error with what was found before it
    /// stopped otherwise.
    pub(crate) const fn finish(&self, found: Found) -> Result<Found, PairBudgetSpent> {
        if self.stopped {
            Err(PairBudgetSpent {
                max_tests: self.budget.max_tests,
                tested: found.tested,
                total: found.total,
                written: found.written,
            })
        } else {
            Ok(found)
        }
    }
}
