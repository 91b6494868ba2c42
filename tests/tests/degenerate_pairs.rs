//! Mesh–mesh and self-intersection walks on geometry no box separates — copies of one
//! triangle, slivers all crossing one point, zero-area triangles at one point, triangles
//! spanning the whole box — at 1k and 10k triangles: the pairs tested never exceed the
//! [`PairBudget`] (so work grows linearly with the default budget, counted, not timed), a
//! spent budget is the typed error with what was found so far, and where the budget suffices
//! the answer is brute force's. At 10k the unbudgeted walks would face 50M pairs, eight times
//! the default budget: what a larger count adds is only more of the same walk, at a cost that
//! grows with the budget.

use meshq::Traverse;
use meshq::bvh::BuildConfig;
use meshq::collide::{
    PairBudget, TrianglePair, intersecting_pairs, meshes_intersect, self_intersecting_pairs,
    self_intersects,
};
use meshq::geom::triangles_meet;
use meshq::math::Triangle;
use meshq::mesh::{MeshRef, ValidMesh};
use meshq::owned::MeshBvh;
use meshq_tests::hard_inputs::{Mesh, crossing, overlap, point, same};

type Family = (&'static str, fn(u32) -> Mesh);

const FAMILIES: [Family; 4] = [
    ("same", same),
    ("crossing", crossing),
    ("point", point),
    ("overlap", overlap),
];

fn triangles(mesh: &ValidMesh<'_>) -> Vec<Triangle> {
    (0..mesh.triangle_count() as u32)
        .map(|t| mesh.triangle(t).unwrap())
        .collect()
}

/// Pairs `(i, j)`, `i < j`, of triangles that meet, by the self-intersection walk's exact
/// predicate over every pair: right for triangles sharing no corner by index or position
/// (`point` and `overlap`; `same` is counted apart, and `crossing`'s opposite slivers share
/// corners by position).
fn brute_self_pairs(tris: &[Triangle]) -> usize {
    let mut meeting = 0;
    for i in 0..tris.len() {
        for j in i + 1..tris.len() {
            if triangles_meet(&tris[i], &tris[j]) {
                meeting += 1;
            }
        }
    }
    meeting
}

fn brute_pairs(a: &[Triangle], b: &[Triangle]) -> usize {
    a.iter()
        .map(|ta| b.iter().filter(|tb| triangles_meet(ta, tb)).count())
        .sum()
}

#[test]
fn pair_walks_stay_within_their_budget_on_degenerate_geometry() {
    for (family, make) in FAMILIES {
        for n in [1_000u32, 10_000] {
            let (positions, tris) = make(n);
            let mesh = MeshRef::new(&positions, &tris).validate().unwrap();
            let bvh = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
            let tree = bvh.bvh();
            let what = format!("{family} {n}");
            let count = n as usize;
            let budget = PairBudget::for_triangles(count, count);
            // Triangle pairs this walk would face without a budget, when every leaf box
            // overlaps every other: the square of the count, far past the budget at 10k.
            let self_found = self_intersecting_pairs(&tree, &mesh, budget, &mut []);
            let tested = self_found.map_or_else(|spent| spent.tested, |found| found.tested);
            assert!(tested <= budget.max_tests, "{what}: {self_found:?}");
            let with = tree.with(&mesh);
            let other = intersecting_pairs(with, with, None, budget, &mut []);
            let tested = other.map_or_else(|spent| spent.tested, |found| found.tested);
            assert!(tested <= budget.max_tests, "{what}: {other:?}");
            match (family, n) {
                (_, 1_000) => {
                    let all = triangles(&mesh);
                    let self_found = self_found.unwrap();
                    let brute = brute_self_pairs(&all);
                    match family {
                        // Copies share all three corners and lie on each other with all
                        // their area: every pair folds over.
                        "same" => assert_eq!(self_found.total, count * (count - 1) / 2),
                        // Touching at a shared corner is left out, so at most brute force.
                        "crossing" => assert!(self_found.total <= brute, "{what}"),
                        _ => assert_eq!(self_found.total, brute, "{what}: self pairs"),
                    }
                    assert_eq!(
                        other.unwrap().total,
                        brute_pairs(&all, &all),
                        "{what}: mesh against itself"
                    );
                }
                ("same" | "point", 10_000) => {
                    // Nothing separates these: the budget runs out, as an error.
                    assert!(self_found.is_err(), "{what}: {self_found:?}");
                    assert!(other.is_err(), "{what}: {other:?}");
                }
                _ => {}
            }
            if (family, n) == ("point", 10_000) {
                // Zero-area triangles meet nothing: the yes/no walk finds no pair to stop
                // at, and the budget ends it.
                let spent = meshes_intersect(with, with, None, budget).unwrap_err();
                assert!(spent.tested <= budget.max_tests);
                assert_eq!(spent.max_tests, budget.max_tests);
                assert!(self_intersects(&tree, &mesh, budget).is_err());
            }
            if (family, n) == ("same", 10_000) {
                // A yes found before the budget runs out is an answer.
                assert_eq!(meshes_intersect(with, with, None, budget), Ok(true));
                assert_eq!(self_intersects(&tree, &mesh, budget), Ok(true));
            }
        }
    }
}

#[test]
fn a_small_budget_stops_the_walk_and_keeps_what_it_found() {
    let (positions, tris) = same(1_000);
    let mesh = MeshRef::new(&positions, &tris).validate().unwrap();
    let bvh = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
    let tree = bvh.bvh();
    let mut all = vec![TrianglePair::default(); 600_000];
    let full = self_intersecting_pairs(&tree, &mesh, PairBudget::UNLIMITED, &mut all).unwrap();
    assert!(full.tested > 10_000, "{full:?}");
    let small = PairBudget { max_tests: 10_000 };
    let mut first = vec![TrianglePair::default(); 600_000];
    let spent = self_intersecting_pairs(&tree, &mesh, small, &mut first).unwrap_err();
    assert_eq!(spent.max_tests, 10_000);
    assert!(spent.tested <= 10_000, "{spent:?}");
    // The walk tests each leaf pair whole; it stops before the one that does not fit, so at
    // most one leaf's worth of pairs short of the budget.
    assert!(spent.tested + 4 * 1_000 > 10_000, "{spent:?}");
    assert!(spent.total > 0 && spent.written == spent.total);
    // What it found is the start of the full walk, in the same order.
    assert_eq!(first[..spent.written], all[..spent.written]);
    // Exactly the full walk's pair count as a budget is enough.
    let enough = PairBudget {
        max_tests: full.tested.max(1) * 2,
    };
    assert_eq!(
        self_intersecting_pairs(&tree, &mesh, enough, &mut []).map(|f| f.total),
        Ok(full.total)
    );
}

#[test]
fn the_default_budget_grows_linearly_and_saturates() {
    let one = PairBudget::for_triangles(1_000, 1_000).max_tests;
    let ten = PairBudget::for_triangles(10_000, 10_000).max_tests;
    assert_eq!(
        ten - one,
        PairBudget::TESTS_PER_TRIANGLE * 18_000,
        "linear in the triangles"
    );
    assert_eq!(
        PairBudget::for_triangles(0, 0).max_tests,
        PairBudget::LEAST_TESTS
    );
    assert_eq!(
        PairBudget::for_triangles(usize::MAX, 1).max_tests,
        usize::MAX
    );
}
