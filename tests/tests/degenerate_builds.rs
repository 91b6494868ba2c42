//! Cell structures on geometry no cut separates — copies of one triangle, slivers all crossing
//! one point, zero-area triangles at one point, triangles spanning the whole box — at 1k, 10k
//! and 50k triangles: references stay within
//! [`REFERENCES_PER_TRIANGLE`](meshq::cells::REFERENCES_PER_TRIANGLE) per triangle (so work and
//! memory grow linearly, counted, not timed), and every structure still answers rays and
//! closest points as brute force does.

use meshq::MeshQuery;
use meshq::Vec3;
use meshq::cells::REFERENCES_PER_TRIANGLE;
use meshq::grid::{Grid, GridConfig};
use meshq::math::Ray;
use meshq::mesh::MeshRef;
use meshq::owned::{MeshGrid, MeshKdTree, MeshOctree};
use meshq_tests::hard_inputs::{Mesh, crossing, overlap, point, same};
use meshq_tests::oracle::BruteForce;

type Family = (&'static str, fn(u32) -> Mesh);

const FAMILIES: [Family; 4] = [
    ("same", same),
    ("crossing", crossing),
    ("point", point),
    ("overlap", overlap),
];

fn rays(count: usize) -> Vec<Ray> {
    let mut state = 0x2545_F491u32;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        state as f32 / u32::MAX as f32 * 2.0 - 1.0
    };
    (0..count)
        .map(|_| {
            let origin = Vec3::new(next(), next(), next()) * 3.0;
            let towards = Vec3::new(next(), next(), next()) * 0.5;
            Ray::new(origin, (towards - origin).normalize())
        })
        .collect()
}

#[test]
fn cell_structures_stay_within_their_reference_bound_on_degenerate_geometry() {
    for (family, make) in FAMILIES {
        for n in [1_000u32, 10_000, 50_000] {
            let (positions, triangles) = make(n);
            let mesh = MeshRef::new(&positions, &triangles).validate().unwrap();
            let most = n as usize * REFERENCES_PER_TRIANGLE;
            let what = format!("{family} {n}");
            let kd = MeshKdTree::build(&mesh, &Default::default()).unwrap();
            let octree = MeshOctree::build(&mesh, &Default::default()).unwrap();
            let grid = MeshGrid::build(&mesh, &GridConfig::default()).unwrap();
            let counts = [
                ("k-d tree", kd.stats().references),
                ("octree", octree.stats().references),
                ("grid", grid.stats().references),
            ];
            for (kind, references) in counts {
                assert!(
                    references >= n as usize,
                    "{what} {kind}: every triangle referenced"
                );
                assert!(references <= most, "{what} {kind}: {references} references");
            }
            // The measured grid is the owned one.
            let sizes = Grid::measure(&mesh, &GridConfig::default()).unwrap();
            assert_eq!(sizes.items, grid.stats().references, "{what}");
            if n == 1_000 {
                let brute = BruteForce::new(&mesh);
                for ray in rays(200) {
                    let want = brute.raycast(&ray, &Default::default());
                    assert_eq!(kd.raycast(&ray), want, "{what} k-d tree");
                    assert_eq!(octree.raycast(&ray), want, "{what} octree");
                    assert_eq!(grid.raycast(&ray), want, "{what} grid");
                    let p = ray.origin;
                    let want = brute.closest_point(p, f32::INFINITY);
                    assert_eq!(kd.closest_point(p, f32::INFINITY), want, "{what} k-d tree");
                    assert_eq!(
                        octree.closest_point(p, f32::INFINITY),
                        want,
                        "{what} octree"
                    );
                    assert_eq!(grid.closest_point(p, f32::INFINITY), want, "{what} grid");
                }
            }
        }
    }
}
