//! The structures that cut space into cells — grid, k-d tree, octree — against brute force on
//! every bundled mesh, their sizing passes and budgets, and the early-exit rule.

use meshq::advanced::{KdNode, OctreeNode};
use meshq::cells::TreeSizes;
use meshq::error::{BufferKind, BuildError};
use meshq::grid::{Grid, GridConfig};
use meshq::kdtree::{KdConfig, KdTree};
use meshq::math::{Ray, Vec3};
use meshq::mesh::ValidMesh;
use meshq::octree::{Octree, OctreeConfig};
use meshq::owned::{MeshGrid, MeshIndex, StructureKind};
use meshq::query::RayOptions;
use meshq::{MeshQuery, Traverse};
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
            // The owned grid finds its arrays in one pass of its own: the same arrays.
            let owned = MeshGrid::build(&mesh, &config).unwrap();
            assert_eq!(
                owned.structure().layout(),
                grid.layout(),
                "{name} λ={lambda}"
            );
            assert_eq!(
                owned.structure().offsets(),
                grid.offsets(),
                "{name} λ={lambda}"
            );
            assert_eq!(owned.structure().items(), grid.items(), "{name} λ={lambda}");
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
        let sizes = measure_fully(mesh.triangle_count(), |w| {
            KdTree::measure(&mesh, &config, w)
        });
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
        let sizes = measure_fully(mesh.triangle_count(), |w| {
            Octree::measure(&mesh, &config, w)
        });
        let mut nodes = vec![OctreeNode::default(); sizes.nodes];
        let mut items = vec![0; sizes.work];
        let tree = Octree::build(&mesh, &config, &mut nodes, &mut items).unwrap();
        assert_eq!(
            (tree.node_count(), tree.items().len()),
            (sizes.nodes, sizes.items),
            "{name}"
        );
        let checked = Octree::from_parts(
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
            &format!("{name} octree"),
        );
    }
}

/// Every cell structure of `mesh`, built at full size through its measuring pass, each checked
/// by its validator.
struct Built {
    grid: (meshq::advanced::GridLayout, Vec<u32>, Vec<u32>),
    kd: (meshq::math::Aabb, Vec<KdNode>, Vec<u32>),
    oct: (meshq::math::Aabb, Vec<OctreeNode>, Vec<u32>),
}

impl Built {
    fn new(mesh: &ValidMesh<'_>) -> Self {
        let n = mesh.triangle_count();
        let sizes = Grid::measure(mesh, &GridConfig::default()).unwrap();
        let (mut offsets, mut items) = (vec![0; sizes.offsets], vec![0; sizes.items]);
        let grid = Grid::build(mesh, &GridConfig::default(), &mut offsets, &mut items).unwrap();
        let layout = *grid.layout();
        let sizes = measure_fully(n, |w| KdTree::measure(mesh, &KdConfig::default(), w));
        let (mut nodes, mut kd_items) = (vec![KdNode::default(); sizes.nodes], vec![0; sizes.work]);
        let kd = KdTree::build(mesh, &KdConfig::default(), &mut nodes, &mut kd_items).unwrap();
        let kd_bounds = *kd.bounds();
        kd_items.truncate(sizes.items);
        let sizes = measure_fully(n, |w| Octree::measure(mesh, &OctreeConfig::default(), w));
        let (mut onodes, mut oitems) = (
            vec![OctreeNode::default(); sizes.nodes],
            vec![0; sizes.work],
        );
        let oct = Octree::build(mesh, &OctreeConfig::default(), &mut onodes, &mut oitems).unwrap();
        let root = *oct.bounds();
        oitems.truncate(sizes.items);
        Self {
            grid: (layout, offsets, items),
            kd: (kd_bounds, nodes, kd_items),
            oct: (root, onodes, oitems),
        }
    }

    /// Runs the brute-force suite on all three.
    fn check(&self, mesh: &ValidMesh<'_>, loaded: &meshq_tests::LoadedMesh, brute: &BruteForce) {
        let n = mesh.triangle_count();
        let grid = Grid::from_parts(self.grid.0, &self.grid.1[..], &self.grid.2[..], n).unwrap();
        check_all(
            &grid.with(mesh),
            brute,
            loaded,
            &format!("{} grid", loaded.name),
        );
        let kd = KdTree::from_parts(self.kd.0, &self.kd.1[..], &self.kd.2[..], n).unwrap();
        check_all(
            &kd.with(mesh),
            brute,
            loaded,
            &format!("{} kd-tree", loaded.name),
        );
        let oct = Octree::from_parts(self.oct.0, &self.oct.1[..], &self.oct.2[..], n).unwrap();
        check_all(
            &oct.with(mesh),
            brute,
            loaded,
            &format!("{} octree", loaded.name),
        );
    }
}

/// The uneven scene (a mesh on a ground a hundred times wider) through every structure.
#[test]
fn every_structure_answers_as_brute_force_in_the_stadium() {
    for name in ["spot", "teapot"] {
        let loaded = meshq_tests::in_stadium(&load_mesh(name));
        let mesh = loaded.valid();
        Built::new(&mesh).check(&mesh, &loaded, &BruteForce::new(&mesh));
    }
}

/// A long slope crossing many cells is hit only far behind the first of a row of walls: a walk
/// that stopped at the first cell with any hit (not one inside the cell) would return the
/// slope. Rays fan out over the walls from the slope's side.
#[test]
fn a_hit_beyond_the_current_cell_does_not_end_the_walk() {
    let mut positions = vec![
        [-1.0, -100.0, 0.71],
        [200.0, -100.0, -1.29],
        [-1.0, 100.0, 0.71],
    ];
    let mut triangles = vec![[0u32, 1, 2]];
    for i in 0..21 {
        let x = 10.5 + i as f32;
        let v = positions.len() as u32;
        positions.extend([[x, 0.0, 0.0], [x, 1.0, 0.0], [x, 1.0, 1.0], [x, 0.0, 1.0]]);
        triangles.extend([[v, v + 1, v + 2], [v, v + 2, v + 3]]);
    }
    let loaded = meshq_tests::LoadedMesh {
        name: "slope-and-walls".into(),
        positions,
        triangles,
    };
    let mesh = loaded.valid();
    let brute = BruteForce::new(&mesh);
    let built = Built::new(&mesh);
    built.check(&mesh, &loaded, &brute);
    let n = mesh.triangle_count();
    let kd = KdTree::from_parts(built.kd.0, &built.kd.1[..], &built.kd.2[..], n).unwrap();
    for k in 0..50 {
        let (y, z) = (0.02 + 0.0192 * k as f32, 0.5 + 0.009 * (k % 7) as f32);
        let ray = Ray::new(Vec3::new(0.0, y, z), Vec3::X);
        let want = brute.raycast(&ray, &RayOptions::default());
        assert_eq!(kd.with(&mesh).raycast(&ray), want, "ray {k}");
        assert_ne!(
            want.map(|h| h.tri),
            Some(0),
            "ray {k} must hit a wall first"
        );
    }
}

/// Short buffers give coarser structures, never errors (down to what the root needs), and the
/// coarser structures still answer exactly; the result depends only on the lengths.
#[test]
fn short_buffers_give_coarser_structures_that_still_answer_exactly() {
    let loaded = load_mesh("spot");
    let mesh = loaded.valid();
    let brute = BruteForce::new(&mesh);
    let n = mesh.triangle_count();
    let full = Grid::measure(&mesh, &GridConfig::default()).unwrap();
    for (offsets_len, items_len) in [
        (full.offsets, full.items / 2),
        (full.offsets / 5, full.items),
        (2, n),
    ] {
        let (mut offsets, mut items) = (vec![0; offsets_len], vec![0; items_len]);
        let grid = Grid::build(&mesh, &GridConfig::default(), &mut offsets, &mut items).unwrap();
        assert!(grid.offsets().len() <= offsets_len && grid.items().len() <= items_len);
        let (layout, used) = (*grid.layout(), grid.items().len());
        let (mut o2, mut i2) = (vec![0; offsets_len], vec![0; items_len]);
        let again = Grid::build(&mesh, &GridConfig::default(), &mut o2, &mut i2).unwrap();
        assert_eq!(
            (again.layout(), again.items().len()),
            (&layout, used),
            "deterministic"
        );
        let grid = Grid::from_parts(
            layout,
            &offsets[..layout.cell_count().unwrap() + 1],
            &items[..used],
            n,
        )
        .unwrap();
        check_all(
            &grid.with(&mesh),
            &brute,
            &loaded,
            &format!("grid in {offsets_len}/{items_len}"),
        );
    }
    let full = measure_fully(n, |w| KdTree::measure(&mesh, &KdConfig::default(), w));
    for (nodes_len, items_len) in [
        (full.nodes / 3, full.work),
        (full.nodes, full.work * 2 / 3),
        (1, n),
    ] {
        let (mut nodes, mut items) = (vec![KdNode::default(); nodes_len], vec![0; items_len]);
        let tree = KdTree::build(&mesh, &KdConfig::default(), &mut nodes, &mut items).unwrap();
        assert!(tree.node_count() <= nodes_len && tree.items().len() <= items_len);
        let (count, refs) = (tree.node_count(), tree.items().len());
        let sizes = KdTree::measure(&mesh, &KdConfig::default(), &mut vec![0; items_len]).unwrap();
        if nodes_len >= full.nodes {
            assert_eq!(
                (sizes.nodes, sizes.items),
                (count, refs),
                "measure matches the build"
            );
            assert!(!sizes.complete);
        }
        let tree = KdTree::from_parts(mesh.bounds(), &nodes[..count], &items[..refs], n).unwrap();
        check_all(
            &tree.with(&mesh),
            &brute,
            &loaded,
            &format!("kd-tree in {nodes_len}/{items_len}"),
        );
    }
    let full = measure_fully(n, |w| Octree::measure(&mesh, &OctreeConfig::default(), w));
    for (nodes_len, items_len) in [
        (full.nodes / 3, full.work),
        (full.nodes, full.work * 2 / 3),
        (1, n),
    ] {
        let (mut nodes, mut items) = (vec![OctreeNode::default(); nodes_len], vec![0; items_len]);
        let tree = Octree::build(&mesh, &OctreeConfig::default(), &mut nodes, &mut items).unwrap();
        let (root, count, refs) = (*tree.bounds(), tree.node_count(), tree.items().len());
        assert!(count <= nodes_len && refs <= items_len);
        let tree = Octree::from_parts(root, &nodes[..count], &items[..refs], n).unwrap();
        check_all(
            &tree.with(&mesh),
            &brute,
            &loaded,
            &format!("octree in {nodes_len}/{items_len}"),
        );
    }
}

/// Every buffer of every structure, one element short of what the root needs: a typed error
/// naming it, no structure.
#[test]
fn buffers_too_small_for_the_root_are_refused() {
    let loaded = load_mesh("cow");
    let mesh = loaded.valid();
    let n = mesh.triangle_count();
    let too_small = |r: Result<(), BuildError>, buffer: BufferKind, needed: usize| match r {
        Err(BuildError::BufferTooSmall {
            buffer: b,
            needed: nd,
            ..
        }) => {
            assert_eq!((b, nd), (buffer, needed));
        }
        other => panic!("{buffer:?}: {other:?}"),
    };
    let grid = |o: usize, i: usize| {
        Grid::build(
            &mesh,
            &GridConfig::default(),
            &mut vec![0; o],
            &mut vec![0; i],
        )
        .map(|_| ())
    };
    too_small(grid(1, n * 4), BufferKind::CellOffsets, 2);
    too_small(grid(1000, n - 1), BufferKind::References, n);
    let kd = |o: usize, i: usize| {
        KdTree::build(
            &mesh,
            &KdConfig::default(),
            &mut vec![KdNode::default(); o],
            &mut vec![0; i],
        )
        .map(|_| ())
    };
    too_small(kd(0, n * 4), BufferKind::Nodes, 1);
    too_small(kd(1000, n - 1), BufferKind::References, n);
    too_small(
        KdTree::measure(&mesh, &KdConfig::default(), &mut vec![0; n - 1]).map(|_| ()),
        BufferKind::References,
        n,
    );
    let oct = |o: usize, i: usize| {
        Octree::build(
            &mesh,
            &OctreeConfig::default(),
            &mut vec![OctreeNode::default(); o],
            &mut vec![0; i],
        )
        .map(|_| ())
    };
    too_small(oct(0, n * 4), BufferKind::Nodes, 1);
    too_small(oct(1000, n - 1), BufferKind::References, n);
    too_small(
        Octree::measure(&mesh, &OctreeConfig::default(), &mut vec![0; n - 1]).map(|_| ()),
        BufferKind::References,
        n,
    );
    let mut packed = vec![meshq::advanced::PackedTriangle::default(); 3];
    assert!(matches!(
        meshq::advanced::pack_references(&mesh, &[0, 1, 2, 3], &mut packed),
        Err(BuildError::BufferTooSmall {
            buffer: BufferKind::Packed,
            needed: 4,
            got: 3
        })
    ));
}

/// The owned structures read packed triangles per reference; they answer as the scan does.
#[test]
fn owned_structures_of_every_kind_answer_as_brute_force() {
    for name in ["cow", "fandisk"] {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        let brute = BruteForce::new(&mesh);
        for kind in StructureKind::ALL {
            let index = MeshIndex::build(&mesh, kind).unwrap();
            assert_eq!(index.kind(), kind);
            assert_eq!(kind.name().parse::<StructureKind>(), Ok(kind));
            check_all(&index, &brute, &loaded, &format!("{name} owned {kind}"));
        }
    }
    assert!("quadtree".parse::<StructureKind>().is_err());
}

type KdEdit<'a> = dyn Fn(&mut Vec<KdNode>, &mut Vec<u32>) + 'a;
type OctEdit<'a> = dyn Fn(&mut Vec<OctreeNode>, &mut Vec<u32>) + 'a;
type GridEdit<'a> = dyn Fn(&mut meshq::advanced::GridLayout, &mut Vec<u32>, &mut Vec<u32>) + 'a;

/// Arrays that do not form a structure are refused with a typed error, never a panic: each
/// corruption below breaks one rule the walks rely on.
#[test]
fn corrupted_arrays_are_refused() {
    let loaded = load_mesh("cow");
    let mesh = loaded.valid();
    let n = mesh.triangle_count();
    let built = Built::new(&mesh);

    let (bounds, nodes, items) = &built.kd;
    let inner = nodes.iter().position(|x| x.b & 3 != 3).unwrap();
    let leaf = nodes.iter().position(|x| x.b & 3 == 3).unwrap();
    let corrupt = |f: &KdEdit| {
        let (mut nodes, mut items) = (nodes.clone(), items.clone());
        f(&mut nodes, &mut items);
        KdTree::from_parts(*bounds, &nodes[..], &items[..], n).map(|_| ())
    };
    assert!(corrupt(&|_, _| {}).is_ok());
    let kd_cases: [(&str, &KdEdit<'_>); 6] = [
        ("child before parent", &|v, _| v[inner].b &= 3),
        ("child out of range", &|v, _| {
            v[inner].b = (u32::MAX >> 2) << 2
        }),
        ("plane not finite", &|v, _| v[inner].a = f32::NAN.to_bits()),
        ("plane outside cell", &|v, _| v[inner].a = 1e30f32.to_bits()),
        ("leaf past the references", &|v, i| {
            v[leaf] = KdNode::leaf(i.len() as u32, 5)
        }),
        ("reference past the mesh", &|_, i| i[0] = u32::MAX - 1),
    ];
    for (what, f) in kd_cases {
        assert!(corrupt(f).is_err(), "k-d tree: {what}");
    }

    let (root, onodes, oitems) = &built.oct;
    let inner = onodes
        .iter()
        .position(|x| x.first_child().is_some())
        .unwrap();
    let ocorrupt = |f: &OctEdit| {
        let (mut nodes, mut items) = (onodes.clone(), oitems.clone());
        f(&mut nodes, &mut items);
        Octree::from_parts(*root, &nodes[..], &items[..], n).map(|_| ())
    };
    assert!(ocorrupt(&|_, _| {}).is_ok());
    let last = onodes.len() as u32;
    let oct_cases: [(&str, &OctEdit<'_>); 4] = [
        ("child before parent", &|v, _| {
            v[inner] = OctreeNode::inner(0)
        }),
        ("children out of range", &|v, _| {
            v[inner] = OctreeNode::inner(last - 3)
        }),
        ("one node dropped", &|v, _| {
            v.pop();
        }),
        ("reference past the mesh", &|_, i| i[0] = n as u32),
    ];
    for (what, f) in oct_cases {
        assert!(ocorrupt(f).is_err(), "octree: {what}");
    }

    let (layout, offsets, items) = &built.grid;
    let gcorrupt = |f: &GridEdit| {
        let (mut l, mut o, mut i) = (*layout, offsets.clone(), items.clone());
        f(&mut l, &mut o, &mut i);
        Grid::from_parts(l, &o[..], &i[..], n).map(|_| ())
    };
    assert!(gcorrupt(&|_, _, _| {}).is_ok());
    let grid_cases: [(&str, &GridEdit<'_>); 5] = [
        ("resolution zero", &|l, _, _| l.resolution[0] = 0),
        ("resolution not matching offsets", &|l, _, _| {
            l.resolution[1] += 1
        }),
        ("offsets decreasing", &|_, o, _| o[1] = u32::MAX),
        ("offsets past the references", &|_, _, i| {
            i.pop();
        }),
        ("bounds not finite", &|l, _, _| {
            l.bounds.max.x = f32::INFINITY
        }),
    ];
    for (what, f) in grid_cases {
        assert!(gcorrupt(f).is_err(), "grid: {what}");
    }
}

/// A mesh without triangles builds every structure, and every query finds nothing.
#[test]
fn an_empty_mesh_builds_and_answers_nothing() {
    let positions = [[0.0f32, 0.0, 0.0]];
    let mesh = meshq::mesh::MeshRef::new(&positions, &[])
        .validate()
        .unwrap();
    for kind in StructureKind::ALL {
        let index = MeshIndex::build(&mesh, kind).unwrap();
        assert_eq!(
            index.raycast(&Ray::new(Vec3::new(0.0, 0.0, 1.0), -Vec3::Z)),
            None,
            "{kind}"
        );
        assert_eq!(
            index.closest_point(Vec3::ONE, f32::INFINITY),
            None,
            "{kind}"
        );
    }
}
