//! Why a mesh–mesh or self-intersection query stopped before its end.

use core::fmt;

/// A mesh–mesh or self-intersection walk considered as many triangle pairs as its
/// [`PairBudget`](crate::collide::PairBudget) allows and stopped, its answer unknown.
///
/// This happens when many triangles sit in one place, where no box separates them: copies of
/// one triangle, triangles collapsed to a point, slivers all crossing one spot. Fix: clean the
/// mesh (weld, drop duplicate and zero-area triangles), or pass a larger budget, up to
/// [`PairBudget::UNLIMITED`](crate::collide::PairBudget::UNLIMITED), accepting work that grows
/// with the square of the triangles in that place.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PairBudgetSpent {
    /// The budget that was spent ([`PairBudget::max_tests`](crate::collide::PairBudget::max_tests)).
    pub max_tests: usize,
    /// Triangle pairs tested before the walk stopped (at most `max_tests`).
    pub tested: usize,
    /// Results found before the walk stopped: a lower bound of the true count.
    pub total: usize,
    /// Of those, results written to the front of the caller's buffer, the first ones in walk
    /// order as in a complete walk.
    pub written: usize,
}

impl fmt::Display for PairBudgetSpent {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "stopped after {} triangle pair tests ({} meeting pairs so far): the budget of {} \
             pairs is spent; many triangles sit in one place (duplicates, zero-area or \
             crossing slivers), so clean the mesh or raise the budget",
            self.tested, self.total, self.max_tests
        )
    }
}

impl core::error::Error for PairBudgetSpent {}
