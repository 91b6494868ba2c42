//! The structures that cut space into cells — grid, k-d tree, octree — against brute force on
//! every bundled mesh, their sizing passes and budgets, and the early-exit rule.

use meshq::Traverse;
use meshq::grid::{Grid, GridConfig};
use meshq::kdtree::{KdConfig, KdNode, KdTree};
use meshq_tests::oracle::BruteForce;
use meshq_tests::suite::check_all;
use meshq_tests::{MESHES, load_mesh};

#[test]
fn grid_answers_every_query_as_brute_force() {
    for name in MESHES {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        let brute = BruteForce::new(&mesh);
        for lambda in [GridConfig::DEFAULT_CELLS_PER_TRIANGLE, 0.05] {
            let config = GridConfig {
                cells_per_triangle: lambda,
                ..GridConfig::default()
            };
            let sizes = Grid::measure(&mesh, &config).unwrap();
            let (mut offsets, mut items) = (vec![0; sizes.offsets], vec![0; sizes.items]);
            let grid = Grid::build(&mesh, &config, &mut offsets, &mut items).unwrap();
            assert_eq!(grid.items().len(), sizes.items, "{name}: measured exactly");
            let checked = Grid::from_parts(
                *grid.layout(),
                grid.offsets(),
                grid.items(),
                mesh.triangle_count(),
            )
            .unwrap();
            check_all(
                &checked.with(&mesh),
                &brute,
                &loaded,
                &format!("{name} grid λ={lambda}"),
            );
        }
    }
}

#[test]
fn kdtree_answers_every_query_as_brute_force() {
    for name in MESHES {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        let brute = BruteForce::new(&mesh);
        let config = KdConfig::default();
        let mut work = vec![0; 8 * mesh.triangle_count()];
        let sizes = KdTree::measure(&mesh, &config, &mut work).unwrap();
        assert!(sizes.complete, "{name}: {sizes:?}");
        let mut nodes = vec![KdNode::default(); sizes.nodes];
        let mut items = vec![0; sizes.work];
        let tree = KdTree::build(&mesh, &config, &mut nodes, &mut items).unwrap();
        assert_eq!(
            (tree.node_count(), tree.items().len()),
            (sizes.nodes, sizes.items),
            "{name}"
        );
        let checked = KdTree::from_parts(
            *tree.bounds(),
            tree.nodes(),
            tree.items(),
            mesh.triangle_count(),
        )
        .unwrap();
        let stats = checked.stats(mesh.triangle_count());
        eprintln!(
            "{name}: {stats:?} refs/tri {:.2}",
            stats.references_per_triangle()
        );
        check_all(
            &checked.with(&mesh),
            &brute,
            &loaded,
            &format!("{name} kd-tree"),
        );
    }
}
