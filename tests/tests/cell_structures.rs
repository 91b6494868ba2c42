//! The structures that cut space into cells — grid, k-d tree, octree — against brute force on
//! every bundled mesh, their sizing passes and budgets, and the early-exit rule.

use meshq::Traverse;
use meshq::cells::TreeSizes;
use meshq::grid::{Grid, GridConfig};
use meshq::kdtree::{KdConfig, KdNode, KdTree};
use meshq::octree::{Octree, OctreeConfig, OctreeNode};
use meshq_tests::oracle::BruteForce;
use meshq_tests::suite::check_all;
use meshq_tests::{MESHES, load_mesh};

/// Measures with a work buffer of twice the triangle count, doubling it until the measured
/// tree is complete.
fn measure_fully(
    triangles: usize,
    measure: impl Fn(&mut [u32]) -> Result<TreeSizes, meshq::error::BuildError>,
) -> TreeSizes {
    let mut len = 2 * triangles.max(1);
    loop {
        let sizes = measure(&mut vec![0; len]).unwrap();
        if sizes.complete {
            assert!(sizes.work <= len && sizes.items <= sizes.work, "{sizes:?}");
            return sizes;
        }
        len *= 2;
    }
}

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
        let sizes = measure_fully(mesh.triangle_count(), |w| KdTree::measure(&mesh, &config, w));
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

#[test]
fn octree_answers_every_query_as_brute_force() {
    for name in MESHES {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        let brute = BruteForce::new(&mesh);
        let config = OctreeConfig::default();
        let sizes = measure_fully(mesh.triangle_count(), |w| Octree::measure(&mesh, &config, w));
        let mut nodes = vec![OctreeNode::default(); sizes.nodes];
        let mut items = vec![0; sizes.work];
        let tree = Octree::build(&mesh, &config, &mut nodes, &mut items).unwrap();
        assert_eq!((tree.node_count(), tree.items().len()), (sizes.nodes, sizes.items), "{name}");
        let checked = Octree::from_parts(*tree.root(), tree.nodes(), tree.items(), mesh.triangle_count()).unwrap();
        let stats = checked.stats(mesh.triangle_count());
        eprintln!("{name}: {stats:?} refs/tri {:.2}", stats.references_per_triangle());
        check_all(&checked.with(&mesh), &brute, &loaded, &format!("{name} octree"));
    }
}
