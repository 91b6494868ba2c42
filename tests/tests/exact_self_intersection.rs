//! Self-intersection decided exactly: on meshes whose corners sit on a coarse grid (so that
//! exact touches, shared planes and folds are common), the pairs `self_intersecting_pairs`
//! reports are exactly those an independent exact oracle finds: a separating-axis test in
//! 128-bit integers on the grid coordinates, with the rule for neighbours (meeting beyond
//! what they share) written out on its own.

use std::collections::BTreeSet;

use meshq::bvh::BuildConfig;
use meshq::collide::{PairBudget, TrianglePair, self_intersecting_pairs};
use meshq::mesh::MeshRef;
use meshq::owned::MeshBvh;
use meshq_tests::{SplitMix64, load_mesh};

type P = [i128; 3];

fn sub(a: P, b: P) -> P {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn cross(a: P, b: P) -> P {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn dot(a: P, b: P) -> i128 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Whether two convex point sets (a triangle's corners, a segment's ends) are separated along
/// one of `axes` (strictly: touching is not separated).
fn separated(one: &[P], two: &[P], axes: &[P]) -> bool {
    axes.iter().filter(|a| **a != [0; 3]).any(|&axis| {
        let span = |pts: &[P]| {
            let d = pts.iter().map(|&p| dot(axis, p));
            (d.clone().min().unwrap(), d.max().unwrap())
        };
        let ((lo1, hi1), (lo2, hi2)) = (span(one), span(two));
        hi1 < lo2 || hi2 < lo1
    })
}

/// The edge directions of a convex set's corners (all pairs).
fn edges(pts: &[P]) -> Vec<P> {
    let mut out = Vec::new();
    for i in 0..pts.len() {
        for j in i + 1..pts.len() {
            out.push(sub(pts[j], pts[i]));
        }
    }
    out
}

/// Whether the closed convex hulls of `one` and `two` (each a triangle with area or a
/// segment) share a point: no separating axis among the normals, the cross products of edge
/// pairs and the in-plane edge normals, which covers crossing and coplanar cases alike.
fn hulls_meet(one: &[P], two: &[P]) -> bool {
    let (e1, e2) = (edges(one), edges(two));
    let mut axes = Vec::new();
    let mut normals = Vec::new();
    for e in [&e1, &e2] {
        if e.len() == 3 {
            normals.push(cross(e[0], e[1]));
        }
    }
    for &n in &normals {
        axes.push(n);
        for e in e1.iter().chain(&e2) {
            axes.push(cross(n, *e));
        }
    }
    for a in &e1 {
        for b in &e2 {
            axes.push(cross(*a, *b));
        }
    }
    !separated(one, two, &axes)
}

/// The oracle's rule for two triangles of one mesh, given by grid corners and vertex indices.
fn meet_beyond_shared(t1: [P; 3], t2: [P; 3], i1: [u32; 3], i2: [u32; 3]) -> bool {
    let area = |t: [P; 3]| cross(sub(t[1], t[0]), sub(t[2], t[0])) != [0; 3];
    if !area(t1) || !area(t2) {
        return false;
    }
    let same = |k1: usize, k2: usize| i1[k1] == i2[k2] || t1[k1] == t2[k2];
    let pairs: Vec<(usize, usize)> = (0..3)
        .flat_map(|k1| (0..3).map(move |k2| (k1, k2)))
        .filter(|&(k1, k2)| same(k1, k2))
        .collect();
    match pairs.len() {
        0 => hulls_meet(&t1, &t2),
        1 => {
            let (k1, k2) = pairs[0];
            let other = |t: [P; 3], k: usize| [t[(k + 1) % 3], t[(k + 2) % 3]];
            hulls_meet(&other(t1, k1), &t2) || hulls_meet(&other(t2, k2), &t1)
        }
        2 => {
            let free1 = (0..3).find(|k| pairs.iter().all(|p| p.0 != *k)).unwrap();
            let free2 = (0..3).find(|k| pairs.iter().all(|p| p.1 != *k)).unwrap();
            let (p, q) = (t1[(free1 + 1) % 3], t1[(free1 + 2) % 3]);
            let (r1, r2) = (t1[free1], t2[free2]);
            let n1 = cross(sub(q, p), sub(r1, p));
            // Coplanar, with both free corners on one side of the shared edge.
            dot(n1, sub(r2, p)) == 0 && dot(n1, cross(sub(q, p), sub(r2, p))) > 0
        }
        _ => true,
    }
}

/// A bundled mesh moved onto a grid of 2⁻⁸ steps (about 500 across) and displaced there by
/// up to `jitter` steps per coordinate: grid corners, exactly representable as `f32`, that
/// the displacement folds and crosses.
fn grid_mesh(name: &str, jitter: i64, seed: u64) -> (Vec<[f32; 3]>, Vec<[u32; 3]>, Vec<P>) {
    let loaded = load_mesh(name);
    let (lo, hi) = loaded.positions.iter().fold(
        ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]),
        |(lo, hi), p| {
            (
                std::array::from_fn(|k| lo[k].min(p[k])),
                std::array::from_fn(|k| hi[k].max(p[k])),
            )
        },
    );
    let size = (0..3).map(|k| hi[k] - lo[k]).fold(0.0f32, f32::max);
    let mut rng = SplitMix64::new(seed);
    let grid: Vec<P> = loaded
        .positions
        .iter()
        .map(|p| {
            std::array::from_fn(|k| {
                let cell = ((p[k] - lo[k]) / size * 512.0).round() as i64;
                let step = (rng.next_u64() % (2 * jitter as u64 + 1)) as i64 - jitter;
                i128::from(cell + step)
            })
        })
        .collect();
    let positions = grid.iter().map(|g| g.map(|c| c as f32 / 256.0)).collect();
    (positions, loaded.triangles.clone(), grid)
}

#[test]
fn self_intersection_pairs_are_the_exact_oracles_pairs() {
    for (name, jitter, seed) in [("cow", 2, 1), ("fandisk", 3, 2), ("spot", 4, 3)] {
        let (positions, triangles, grid) = grid_mesh(name, jitter, seed);
        let mesh = MeshRef::new(&positions, &triangles).validate().unwrap();
        let bvh = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
        let mut out = vec![TrianglePair::default(); 1 << 20];
        let found = self_intersecting_pairs(
            &bvh.bvh(),
            &mesh,
            PairBudget::for_triangles(triangles.len(), triangles.len()),
            &mut out,
        )
        .unwrap();
        assert!(!found.overflowed());
        let got: BTreeSet<(u32, u32)> = out[..found.written].iter().map(|p| (p.a, p.b)).collect();
        // Every pair whose grid boxes touch, through the oracle.
        let corners = |t: usize| triangles[t].map(|i| grid[i as usize]);
        let boxes: Vec<(P, P)> = (0..triangles.len())
            .map(|t| {
                let c = corners(t);
                (
                    std::array::from_fn(|k| c.iter().map(|p| p[k]).min().unwrap()),
                    std::array::from_fn(|k| c.iter().map(|p| p[k]).max().unwrap()),
                )
            })
            .collect();
        let mut want = BTreeSet::new();
        for i in 0..triangles.len() {
            for j in i + 1..triangles.len() {
                let ((lo1, hi1), (lo2, hi2)) = (boxes[i], boxes[j]);
                if (0..3).any(|k| hi1[k] < lo2[k] || hi2[k] < lo1[k]) {
                    continue;
                }
                if meet_beyond_shared(corners(i), corners(j), triangles[i], triangles[j]) {
                    want.insert((i as u32, j as u32));
                }
            }
        }
        assert!(
            want.len() > 20,
            "{name}: only {} pairs to compare",
            want.len()
        );
        assert_eq!(
            got.difference(&want).count() + want.difference(&got).count(),
            0,
            "{name}: meshq {} pairs, oracle {}; only meshq {:?}; only the oracle {:?}",
            got.len(),
            want.len(),
            got.difference(&want).take(5).collect::<Vec<_>>(),
            want.difference(&got).take(5).collect::<Vec<_>>()
        );
    }
}
