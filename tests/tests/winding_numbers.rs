//! Winding numbers, containment and signed distance ([`meshq::inside`]) against `f64` brute
//! force, on closed, open (holes cut), non-manifold and self-intersecting meshes.

use glam::{DVec3, Vec3};
use meshq::MeshBvh;
use meshq::bvh::{BuildConfig, SpatialSplits};
use meshq::inside::{WindingAccuracy, WindingTree};
use meshq::mesh::MeshRef;
use meshq::query::{MeshQuery, Traverse};
use meshq_tests::hard_inputs::{self, Mesh};
use meshq_tests::winding_oracle::{odd_crossings_f64, winding_number_f64};
use meshq_tests::{load_mesh, workload};

/// A mesh by name with its kind, for messages.
struct Case {
    name: &'static str,
    mesh: Mesh,
}

fn bundled(name: &str) -> Mesh {
    let m = load_mesh(name);
    (m.positions, m.triangles)
}

/// Spot with every triangle whose centroid lies above a plane across its back removed: open,
/// with one large hole.
fn spot_with_a_hole() -> Mesh {
    let (positions, triangles) = bundled("spot");
    let top = positions.iter().map(|p| p[1]).fold(f32::MIN, f32::max);
    let kept = triangles
        .into_iter()
        .filter(|t| t.iter().map(|&i| positions[i as usize][1]).sum::<f32>() / 3.0 < 0.8 * top)
        .collect();
    (positions, kept)
}

/// Spot and a copy moved a third of its size along x: two closed surfaces that cross (winding
/// number 2 where they overlap).
fn two_crossing_spots() -> Mesh {
    let (mut positions, mut triangles) = bundled("spot");
    let n = positions.len() as u32;
    let shift = size(&positions) / 3.0;
    let copy: Vec<[f32; 3]> = positions
        .iter()
        .map(|p| [p[0] + shift, p[1], p[2]])
        .collect();
    positions.extend(copy);
    let moved: Vec<[u32; 3]> = triangles.iter().map(|t| t.map(|i| i + n)).collect();
    triangles.extend(moved);
    (positions, triangles)
}

/// Two cubes sharing one edge (four triangles on it) and a fin: a triangle standing on one
/// face's edge, out into space.
fn non_manifold_cubes() -> Mesh {
    let (mut positions, mut triangles) = hard_inputs::cuboid(1.0, 1.0, 1.0);
    let n = positions.len() as u32;
    // The second cube touches the first along the edge where both of their x and y extremes meet.
    let lo = positions.iter().fold([f32::MAX; 3], |m, p| {
        [m[0].min(p[0]), m[1].min(p[1]), m[2].min(p[2])]
    });
    let hi = positions.iter().fold([f32::MIN; 3], |m, p| {
        [m[0].max(p[0]), m[1].max(p[1]), m[2].max(p[2])]
    });
    let (wx, wy) = (hi[0] - lo[0], hi[1] - lo[1]);
    let copy: Vec<[f32; 3]> = positions
        .iter()
        .map(|p| [p[0] + wx, p[1] + wy, p[2]])
        .collect();
    positions.extend(copy);
    let moved: Vec<[u32; 3]> = triangles.iter().map(|t| t.map(|i| i + n)).collect();
    triangles.extend(moved);
    let [a, b, _] = triangles[0];
    let apex = positions.len() as u32;
    positions.push([lo[0] - wx, lo[1] - wy, lo[2] - 0.5 * (hi[2] - lo[2])]);
    triangles.push([a, b, apex]);
    (positions, triangles)
}

fn size(positions: &[[f32; 3]]) -> f32 {
    let (c, r) = {
        let (lo, hi) = positions.iter().fold(
            (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
            |(lo, hi), p| (lo.min(Vec3::from_array(*p)), hi.max(Vec3::from_array(*p))),
        );
        ((lo + hi) * 0.5, (hi - lo).length())
    };
    let _ = c;
    r
}

fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "spot (closed)",
            mesh: bundled("spot"),
        },
        Case {
            name: "fandisk (closed, creases)",
            mesh: bundled("fandisk"),
        },
        Case {
            name: "stanford-bunny (open)",
            mesh: bundled("stanford-bunny"),
        },
        Case {
            name: "spot with a hole",
            mesh: spot_with_a_hole(),
        },
        Case {
            name: "two crossing spots",
            mesh: two_crossing_spots(),
        },
        Case {
            name: "non-manifold cubes",
            mesh: non_manifold_cubes(),
        },
    ]
}

fn prepared(mesh: &Mesh) -> MeshBvh {
    let valid = MeshRef::new(&mesh.0, &mesh.1).validate().unwrap();
    MeshBvh::build(&valid, &BuildConfig::default())
        .unwrap()
        .with_winding_numbers()
        .unwrap()
}

/// `count` points in the mesh's box grown by 10 % that lie farther than `gap` × its diagonal
/// from the surface (near the surface an `f32` point is off by more than the angle can bear).
fn points_away(scene: &MeshBvh, mesh: &Mesh, count: usize, gap: f32) -> Vec<Vec3> {
    let limit = gap * size(&mesh.0);
    workload::closest_points(&mesh.0, count * 2, 7)
        .into_iter()
        .filter(|&p| scene.closest_point(p, limit).is_none())
        .take(count)
        .collect()
}

/// The `f64` oracle at each point.
fn oracle(mesh: &Mesh, points: &[Vec3]) -> Vec<f64> {
    points
        .iter()
        .map(|&p| winding_number_f64(&mesh.0, &mesh.1, p))
        .collect()
}

/// The largest difference from `exact` (the oracle at each point) at `accuracy`.
fn largest_difference(
    tree: &WindingTree<'_>,
    points: &[Vec3],
    exact: &[f64],
    accuracy: WindingAccuracy,
) -> f64 {
    points
        .iter()
        .zip(exact)
        .map(|(&p, &w)| (f64::from(tree.winding_number(p, accuracy)) - w).abs())
        .fold(0.0, f64::max)
}

/// The largest difference from the `f64` oracle at `accuracy` over `points`.
fn largest_error(
    tree: &WindingTree<'_>,
    mesh: &Mesh,
    points: &[Vec3],
    accuracy: WindingAccuracy,
) -> f64 {
    largest_difference(tree, points, &oracle(mesh, points), accuracy)
}

/// The largest error the documentation states for each far ratio (`docs/inside.md`), at
/// points anywhere off the surface.
const STATED: [(f32, f64); 6] = [
    (1.5, 5e-2),
    (2.0, 1e-2),
    (2.5, 4e-3),
    (3.0, 2e-3),
    (5.0, 2e-4),
    (f32::INFINITY, 1e-4),
];

/// Points off the centroids of every `stride`-th triangle, `gap` × the diagonal along its unit
/// normal, on both sides.
fn points_near(mesh: &Mesh, stride: usize, gap: f32) -> Vec<Vec3> {
    let step = gap * size(&mesh.0);
    let corner = |i: u32| Vec3::from_array(mesh.0[i as usize]);
    mesh.1
        .iter()
        .step_by(stride)
        .filter_map(|&[a, b, c]| {
            let (a, b, c) = (corner(a), corner(b), corner(c));
            let n = (b - a).cross(c - a).try_normalize()?;
            let centroid = (a + b + c) / 3.0;
            Some([centroid + n * step, centroid - n * step])
        })
        .flatten()
        .collect()
}

/// Points in the box away from the surface and points a hundredth to a hundred-thousandth of
/// the diagonal off it, both sides.
fn probe_points(scene: &MeshBvh, mesh: &Mesh) -> Vec<Vec3> {
    let mut points = points_away(scene, mesh, 400, 1e-3);
    for gap in [1e-2f32, 1e-3, 1e-4, 1e-5] {
        points.extend(points_near(mesh, mesh.1.len() / 100 + 1, gap));
    }
    points
}

#[test]
fn winding_numbers_are_within_the_stated_error_of_f64_brute_force() {
    for case in cases() {
        let scene = prepared(&case.mesh);
        let tree = scene.winding().unwrap();
        let points = probe_points(&scene, &case.mesh);
        let exact = oracle(&case.mesh, &points);
        let mut last = f64::INFINITY;
        let mut line = format!("{}, {} points:", case.name, points.len());
        for (ratio, stated) in STATED {
            let accuracy = WindingAccuracy::new(ratio).unwrap();
            let error = largest_difference(&tree, &points, &exact, accuracy);
            line += &format!(" {ratio}: {error:.2e}");
            assert!(
                error <= stated,
                "{} at ratio {ratio}: {error:e} > {stated:e}",
                case.name
            );
            if ratio.is_finite() {
                // A larger ratio sums more triangles exactly: the error must fall.
                assert!(
                    error < last,
                    "{} at ratio {ratio}: {error:e} ≥ {last:e}",
                    case.name
                );
                last = error;
            }
        }
        println!("{line}");
    }
}

#[test]
fn contains_agrees_with_ray_parity_on_closed_meshes() {
    // Three rays in unrelated directions vote; points within 10⁻³ of the diagonal from the
    // surface are left out (there a ray may graze an edge in f64 too).
    let directions = [
        DVec3::new(0.267, 0.534, 0.801),
        DVec3::new(-0.723, 0.123, 0.678),
        DVec3::new(0.301, -0.905, -0.301),
    ];
    let closed = ["spot", "fandisk", "cow", "uv-sphere"];
    for name in closed {
        let mesh = bundled(name);
        let scene = prepared(&mesh);
        let tree = scene.winding().unwrap();
        let points = points_away(&scene, &mesh, 1500, 1e-3);
        let mut inside = 0;
        for &p in &points {
            let votes = directions
                .iter()
                .filter(|&&d| odd_crossings_f64(&mesh.0, &mesh.1, p, d))
                .count();
            let parity = votes >= 2;
            assert_eq!(
                tree.contains(p, WindingAccuracy::DEFAULT),
                parity,
                "{name} at {p}"
            );
            inside += usize::from(parity);
        }
        // The check means something only if both answers occur.
        assert!(
            inside > 20 && inside < points.len() - 20,
            "{name}: {inside} inside"
        );
    }
}

#[test]
fn signed_distance_is_the_closest_point_with_the_oracle_sign() {
    for case in cases() {
        let scene = prepared(&case.mesh);
        let tree = scene.winding().unwrap();
        let mut points = points_away(&scene, &case.mesh, 300, 1e-3);
        points.extend(points_near(&case.mesh, case.mesh.1.len() / 100 + 1, 1e-4));
        let (mut negative, mut checked) = (0, 0);
        for &p in &points {
            let signed = tree
                .signed_distance(p, f32::INFINITY, WindingAccuracy::DEFAULT)
                .unwrap();
            let closest = scene.closest_point(p, f32::INFINITY).unwrap();
            assert_eq!(signed.closest, closest, "{} at {p}", case.name);
            assert_eq!(
                signed.distance.abs().to_bits(),
                closest.distance_from(p).to_bits(),
                "{} at {p}",
                case.name
            );
            let w = winding_number_f64(&case.mesh.0, &case.mesh.1, p);
            // Where the true number sits near 1/2 the side is a matter of rounding.
            if (w.abs() - 0.5).abs() > 0.01 {
                checked += 1;
                assert_eq!(
                    signed.distance < 0.0,
                    w.abs() >= 0.5,
                    "{} at {p}: w {w}",
                    case.name
                );
                negative += usize::from(signed.distance < 0.0);
            }
        }
        assert!(
            checked > points.len() * 9 / 10,
            "{}: {checked} checked",
            case.name
        );
        assert!(negative > 10, "{}: {negative} inside", case.name);
    }
}

#[test]
fn batches_and_threads_give_the_single_answers() {
    let mesh = bundled("stanford-bunny");
    let scene = prepared(&mesh);
    let tree = scene.winding().unwrap();
    let points = workload::closest_points(&mesh.0, 10_000, 3);
    let accuracy = WindingAccuracy::DEFAULT;
    let single: Vec<u32> = points
        .iter()
        .map(|&p| tree.winding_number(p, accuracy).to_bits())
        .collect();
    let mut batch = vec![0.0f32; points.len()];
    let mut keys = vec![0u64; points.len()];
    tree.winding_numbers(&points, accuracy, &mut keys, &mut batch)
        .unwrap();
    assert_eq!(
        batch.iter().map(|w| w.to_bits()).collect::<Vec<_>>(),
        single
    );
    let mut threaded = vec![0.0f32; points.len()];
    meshq::parallel::winding_numbers(&tree, &points, accuracy, &mut threaded).unwrap();
    assert_eq!(
        threaded.iter().map(|w| w.to_bits()).collect::<Vec<_>>(),
        single
    );
    let mut signed = vec![None; points.len()];
    meshq::parallel::signed_distances(&tree, &scene, &points, 0.05, accuracy, &mut signed).unwrap();
    for (s, &p) in signed.iter().zip(&points) {
        assert_eq!(*s, tree.signed_distance(p, 0.05, accuracy));
    }
    assert!(signed.iter().any(Option::is_none) && signed.iter().any(Option::is_some));
    let mut alone = vec![None; points.len()];
    tree.signed_distances(
        &tree.bvh().with(&tree.mesh()),
        &points,
        0.05,
        accuracy,
        &mut keys,
        &mut alone,
    )
    .unwrap();
    assert_eq!(alone, signed);
    let mut short = vec![0.0f32; 3];
    assert!(
        tree.winding_numbers(&points, accuracy, &mut keys, &mut short)
            .is_err()
    );
    assert_eq!(short, [0.0; 3]);
}

#[test]
fn trees_with_spatial_splits_count_each_triangle_once() {
    let mesh = two_crossing_spots();
    let valid = MeshRef::new(&mesh.0, &mesh.1).validate().unwrap();
    let split = MeshBvh::build_spatial(&valid, &BuildConfig::default(), &SpatialSplits::default())
        .unwrap()
        .with_winding_numbers()
        .unwrap();
    assert!(!split.split_refs().is_empty(), "the mesh must make splits");
    let tree = split.winding().unwrap();
    let points = probe_points(&split, &mesh);
    for (ratio, stated) in [STATED[1], STATED[5]] {
        let error = largest_error(&tree, &mesh, &points, WindingAccuracy::new(ratio).unwrap());
        assert!(error <= stated, "ratio {ratio}: {error:e}");
    }
}

#[test]
fn degenerate_meshes_give_bounded_answers() {
    let accuracy = WindingAccuracy::DEFAULT;
    // Every triangle at one point: no area, so no angle anywhere, also at the point itself.
    let mesh = hard_inputs::point(1000);
    let scene = prepared(&mesh);
    let tree = scene.winding().unwrap();
    for p in [
        Vec3::new(0.25, 0.5, 0.75),
        Vec3::new(0.25, 0.5, 0.7500001),
        Vec3::ZERO,
    ] {
        assert_eq!(tree.winding_number(p, accuracy), 0.0);
    }
    // 200,000 copies of one triangle: the winding number is the copies' sum, in bounded time,
    // within the worst case of summing that many terms in f32 ((n − 1)·2⁻²⁴ of the sum).
    let mesh = hard_inputs::same(200_000);
    let scene = prepared(&mesh);
    let tree = scene.winding().unwrap();
    let p = Vec3::new(0.2, 0.2, 0.5);
    let w = f64::from(tree.winding_number(p, accuracy));
    let one = winding_number_f64(&mesh.0, &mesh.1[..1], p);
    let sum = 200_000.0 * one;
    let rounding = 199_999.0 * f64::from(f32::EPSILON) / 2.0;
    assert!((w - sum).abs() <= rounding * sum.abs(), "{w} vs {sum}");
    // Sizes at both ends of the valid range (coordinates up to 2⁵⁰, and tiny ones): the
    // numbers do not change with scale, so they match the f64 oracle as at size 1.
    let spot = bundled("spot");
    let reference = prepared(&spot);
    let points = points_away(&reference, &spot, 100, 1e-3);
    for factor in [1e15f32 / size(&spot.0), 1e-15] {
        let scaled: Vec<[f32; 3]> = spot.0.iter().map(|p| p.map(|x| x * factor)).collect();
        let mesh = (scaled, spot.1.clone());
        let scene = prepared(&mesh);
        let tree = scene.winding().unwrap();
        let moved: Vec<Vec3> = points.iter().map(|&p| p * factor).collect();
        let error = largest_error(&tree, &mesh, &moved, accuracy);
        assert!(error <= STATED[1].1, "scaled by {factor:e}: {error:e}");
        assert!(
            tree.signed_distance(moved[0], f32::INFINITY, accuracy)
                .is_some()
        );
    }
    let tree = reference.winding().unwrap();
    // Not finite points: NaN, no sign, no panic.
    assert!(tree.winding_number(Vec3::NAN, accuracy).is_nan());
    assert!(!tree.contains(Vec3::INFINITY, accuracy));
    // An empty mesh: 0 everywhere.
    let empty: Mesh = (vec![], vec![]);
    let scene = prepared(&empty);
    assert_eq!(
        scene.winding().unwrap().winding_number(Vec3::ONE, accuracy),
        0.0
    );
}

#[test]
fn a_winding_tree_needs_one_expansion_per_node() {
    let mesh = bundled("spot");
    let valid = MeshRef::new(&mesh.0, &mesh.1).validate().unwrap();
    let scene = MeshBvh::build(&valid, &BuildConfig::default()).unwrap();
    assert!(scene.winding().is_none(), "not prepared yet");
    let needed = scene.bvh().nodes().len();
    let mut nodes = vec![meshq::inside::WindingNode::EMPTY; needed - 1];
    let err = WindingTree::build(scene.bvh(), scene.mesh(), &mut nodes).unwrap_err();
    assert_eq!(
        err,
        meshq::error::BuildError::BufferTooSmall {
            buffer: meshq::error::BufferKind::WindingNodes,
            needed,
            got: needed - 1
        }
    );
    assert!(
        nodes
            .iter()
            .all(|n| *n == meshq::inside::WindingNode::EMPTY)
    );
    assert!(WindingTree::from_parts(scene.bvh(), scene.mesh(), &nodes).is_err());
}

/// The points of the golden winding-number file around `positions`.
fn golden_points(positions: &[[f32; 3]]) -> Vec<Vec3> {
    let bounds = meshq_workload::centre_radius(positions).2;
    meshq_workload::QueryPoints::new(bounds, meshq_workload::WINDING_SEED)
        .take(2000)
        .collect()
}

#[test]
fn the_golden_winding_file_holds_every_bundled_mesh() {
    // The WebAssembly tests check the same digests (wasm/tests/parity.rs); each number is
    // checked here against the f64 oracle within the stated error first.
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("golden/winding.txt");
    let mut file = String::from(
        "# meshq winding-number golden file: see meshq_workload::winding_golden. Rewrite with\n\
         # MESHQ_BLESS_GOLDEN=1 cargo test -p meshq-tests --test integration winding_numbers::\n",
    );
    let recorded = std::fs::read_to_string(&path).unwrap_or_default();
    for name in meshq_tests::MESHES {
        let mesh = bundled(name);
        let scene = prepared(&mesh);
        let tree = scene.winding().unwrap();
        let points = golden_points(&mesh.0);
        let mut numbers = vec![0.0f32; points.len()];
        let mut keys = vec![0u64; points.len()];
        tree.winding_numbers(&points, WindingAccuracy::DEFAULT, &mut keys, &mut numbers)
            .unwrap();
        let exact = oracle(&mesh, &points);
        for ((&w, &e), &p) in numbers.iter().zip(&exact).zip(&points) {
            assert!(
                (f64::from(w) - e).abs() <= STATED[1].1,
                "{name} at {p}: {w} vs {e}"
            );
        }
        // Signed distances, each the closest point's distance with the number's sign.
        let signed: Vec<f32> = points
            .iter()
            .zip(&numbers)
            .map(|(&p, &w)| {
                let s = tree
                    .signed_distance(p, f32::INFINITY, WindingAccuracy::DEFAULT)
                    .unwrap();
                let closest = scene.closest_point(p, f32::INFINITY).unwrap();
                assert_eq!(s.distance.abs(), closest.distance_from(p), "{name} at {p}");
                assert_eq!(s.distance < 0.0, w.abs() >= 0.5, "{name} at {p}");
                s.distance
            })
            .collect();
        let digest = meshq_workload::WindingDigest::of(&numbers, &signed);
        file += &format!("{name} {digest}\n");
        if std::env::var_os("MESHQ_BLESS_GOLDEN").is_none() {
            let golden = meshq_workload::find_winding_golden(&recorded, name)
                .unwrap_or_else(|e| panic!("{name}: {e}; bless with MESHQ_BLESS_GOLDEN=1"));
            assert_eq!(
                digest, golden,
                "{name}: numbers changed; bless on purpose only"
            );
        }
    }
    if std::env::var_os("MESHQ_BLESS_GOLDEN").is_some() {
        std::fs::write(&path, file).unwrap();
    }
}

#[test]
fn signed_distance_grids_hold_the_single_answers_and_their_band() {
    use meshq::inside::SampleGrid;
    let mesh = bundled("spot");
    let scene = prepared(&mesh);
    let tree = scene.winding().unwrap();
    let bounds = tree.mesh().bounds();
    let grid = SampleGrid::cubic(bounds, 24, 0.1).unwrap();
    let [nx, ny, nz] = grid.counts();
    assert_eq!(nx.max(ny).max(nz), 24);
    let spacing = grid.spacing();
    assert!(spacing.x == spacing.y && spacing.y == spacing.z && spacing.x > 0.0);
    let last = grid.point(grid.len() - 1);
    assert!(grid.min().cmple(bounds.min).all() && last.cmpge(bounds.max).all());
    let accuracy = WindingAccuracy::DEFAULT;
    let mut whole = vec![0.0f32; grid.len()];
    tree.signed_distance_grid(&scene, &grid, f32::INFINITY, accuracy, 0, &mut whole)
        .unwrap();
    let mut inside = 0;
    for (i, &v) in whole.iter().enumerate() {
        let p = grid.point(i);
        let single = tree.signed_distance(p, f32::INFINITY, accuracy).unwrap();
        assert_eq!(v.to_bits(), single.distance.to_bits(), "sample {i}");
        let w = winding_number_f64(&mesh.0, &mesh.1, p);
        if (w.abs() - 0.5).abs() > 0.01 {
            assert_eq!(v < 0.0, w.abs() >= 0.5, "sample {i}");
        }
        inside += usize::from(v < 0.0);
    }
    assert!(inside > 100 && inside < grid.len() / 2, "{inside} inside");
    // In slices, on the pool, through the binary tree: the same bits.
    let mut sliced = vec![0.0f32; grid.len()];
    for (k, chunk) in sliced.chunks_mut(1000).enumerate() {
        let own = tree.bvh();
        let own_mesh = tree.mesh();
        tree.signed_distance_grid(
            &own.with(&own_mesh),
            &grid,
            f32::INFINITY,
            accuracy,
            k * 1000,
            chunk,
        )
        .unwrap();
    }
    assert_eq!(sliced, whole);
    let mut pooled = vec![0.0f32; grid.len()];
    meshq::parallel::signed_distance_grid(
        &tree,
        &scene,
        &grid,
        f32::INFINITY,
        accuracy,
        &mut pooled,
    )
    .unwrap();
    assert_eq!(pooled, whole);
    // A narrow band: exact within it, ±band with the same sign beyond.
    let band = 4.0 * spacing.x;
    let mut banded = vec![0.0f32; grid.len()];
    tree.signed_distance_grid(&scene, &grid, band, accuracy, 0, &mut banded)
        .unwrap();
    for (i, (&b, &v)) in banded.iter().zip(&whole).enumerate() {
        if v.abs() <= band {
            assert_eq!(b.to_bits(), v.to_bits(), "sample {i}");
        } else {
            assert_eq!(b, band.copysign(v), "sample {i}");
        }
    }
    // Too long or empty an output: refused, untouched.
    let mut long = vec![7.0f32; grid.len() + 1];
    assert!(
        tree.signed_distance_grid(&scene, &grid, band, accuracy, 0, &mut long)
            .is_err()
    );
    assert!(long.iter().all(|&v| v == 7.0));
    assert!(SampleGrid::new(bounds, [0, 4, 4]).is_none());
    assert!(SampleGrid::cubic(bounds, 1, 0.1).is_none());
    assert!(SampleGrid::cubic(bounds, 8, f32::NAN).is_none());
}

/// Pseudo-normal signs: on the closed meshes, the sign the `f64` winding-number oracle gives,
/// with the closest point's magnitude bit for bit; open, non-manifold and inconsistently
/// oriented meshes refused, naming the edge.
#[test]
fn pseudo_normal_signs_agree_with_the_oracle_on_closed_meshes() {
    use meshq::inside::{PseudoNormalError, PseudoNormals};
    use meshq::owned::MeshPseudoNormals;
    let mut signed_cases = 0;
    for case in cases() {
        let valid = MeshRef::new(&case.mesh.0, &case.mesh.1).validate().unwrap();
        let normals = match MeshPseudoNormals::of(&valid) {
            Ok(n) => n,
            Err(e) => {
                let closed =
                    case.name.starts_with("spot (closed)") || case.name.starts_with("fandisk");
                assert!(!closed, "{}: refused ({e})", case.name);
                assert!(
                    matches!(
                        e,
                        PseudoNormalError::OpenEdge { .. }
                            | PseudoNormalError::NonManifoldEdge { .. }
                    ),
                    "{}: {e}",
                    case.name
                );
                continue;
            }
        };
        assert!(
            !case.name.contains("open")
                && !case.name.contains("hole")
                && !case.name.contains("non-manifold"),
            "{}: accepted",
            case.name
        );
        if case.name.contains("crossing") {
            // Closed and manifold, but crossing itself: between the surfaces the nearest one
            // need not say the side (the winding number's case, not the pseudo-normal's).
            continue;
        }
        let scene = prepared(&case.mesh);
        let mut points = points_away(&scene, &case.mesh, 300, 1e-3);
        points.extend(points_near(&case.mesh, case.mesh.1.len() / 100 + 1, 1e-4));
        let (mut checked, mut negative) = (0, 0);
        for &p in &points {
            let signed = normals
                .view()
                .signed_distance(&scene, &valid, p, f32::INFINITY)
                .unwrap();
            let closest = scene.closest_point(p, f32::INFINITY).unwrap();
            assert_eq!(signed.closest, closest);
            assert_eq!(
                signed.distance.abs().to_bits(),
                closest.distance_from(p).to_bits()
            );
            let w = winding_number_f64(&case.mesh.0, &case.mesh.1, p);
            if (w.abs() - 0.5).abs() > 0.01 {
                checked += 1;
                assert_eq!(
                    signed.distance < 0.0,
                    w.abs() >= 0.5,
                    "{} at {p}: w {w}",
                    case.name
                );
                negative += usize::from(signed.distance < 0.0);
            }
        }
        assert!(
            checked > points.len() * 9 / 10 && negative > 10,
            "{}: {checked} checked, {negative} inside",
            case.name
        );
        signed_cases += 1;
    }
    assert_eq!(signed_cases, 2, "spot and fandisk signed");
    // One triangle flipped: its edges run the same way as their neighbours'.
    let (positions, mut triangles) = hard_inputs::cuboid(1.0, 1.0, 1.0);
    triangles[3].swap(1, 2);
    let flipped = MeshRef::new(&positions, &triangles).validate().unwrap();
    assert!(matches!(
        MeshPseudoNormals::of(&flipped),
        Err(PseudoNormalError::InconsistentOrientation { .. })
    ));
    // Caller buffers: too small is an error; the right size gives the owned answers.
    let (positions, triangles) = hard_inputs::cuboid(1.0, 2.0, 3.0);
    let cube = MeshRef::new(&positions, &triangles).validate().unwrap();
    let (mut v, mut e, mut s) = (
        vec![Vec3::ZERO; 8],
        vec![[Vec3::ZERO; 3]; 12],
        vec![(0u64, 0u32); 35],
    );
    assert_eq!(
        PseudoNormals::build(&cube, &mut v, &mut e, &mut s).map(|_| ()),
        Err(PseudoNormalError::BufferTooSmall)
    );
    let mut s = vec![(0u64, 0u32); 36];
    let normals = PseudoNormals::build(&cube, &mut v, &mut e, &mut s).unwrap();
    let bvh = MeshBvh::build(&cube, &BuildConfig::default()).unwrap();
    let inside = normals
        .signed_distance(&bvh, &cube, Vec3::new(0.5, 1.0, 0.2), f32::INFINITY)
        .unwrap();
    assert!((inside.distance + 0.2).abs() < 1e-6, "{}", inside.distance);
    // Off a corner, the closest feature is the vertex: its pseudo-normal points out.
    let corner = normals
        .signed_distance(&bvh, &cube, Vec3::new(1.1, 2.1, 3.1), f32::INFINITY)
        .unwrap();
    assert!(corner.distance > 0.0);
    let inside_corner = normals
        .signed_distance(&bvh, &cube, Vec3::new(0.95, 1.96, 2.97), f32::INFINITY)
        .unwrap();
    assert!(inside_corner.distance < 0.0);
}

/// Expansions stored in a blob (format version 6) answer in place — winding numbers,
/// containment, signed distances, single and batched — exactly as the tree built in memory,
/// for every mesh layout, on closed, open and self-crossing meshes; a loaded `MeshBvh` keeps
/// them; a blob without them has none; a blob whose expansions were altered is refused by
/// every loader.
#[test]
fn expansions_stored_in_blobs_answer_in_place() {
    use meshq::blob::{BlobView, MeshLayout};
    use meshq::error::BlobError;
    let accuracy = WindingAccuracy::DEFAULT;
    for (name, mesh) in [
        ("spot", bundled("spot")),
        ("spot with a hole", spot_with_a_hole()),
        ("two crossing spots", two_crossing_spots()),
    ] {
        let scene = prepared(&mesh);
        let tree = scene.winding().unwrap();
        let valid = MeshRef::new(&mesh.0, &mesh.1).validate().unwrap();
        let points = probe_points(&scene, &mesh);
        let mut want = vec![0.0f32; points.len()];
        let mut keys = vec![0u64; points.len()];
        tree.winding_numbers(&points, accuracy, &mut keys, &mut want)
            .unwrap();
        for layout in [MeshLayout::Indexed, MeshLayout::Packed, MeshLayout::Omitted] {
            let bytes = scene.to_blob(layout).unwrap();
            let view = match layout {
                MeshLayout::Omitted => BlobView::parse_with_mesh(&bytes, valid).unwrap(),
                _ => BlobView::parse(&bytes).unwrap(),
            };
            assert_eq!(view.header().version, 6, "{name} {layout:?}");
            let stored = view.winding_tree().unwrap();
            assert_eq!(stored.scale(), tree.scale());
            let mut got = vec![0.0f32; points.len()];
            stored
                .winding_numbers(&points, accuracy, &mut keys, &mut got)
                .unwrap();
            let bits = |v: &[f32]| v.iter().map(|w| w.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&got), bits(&want), "{name} {layout:?}: batch");
            for (k, &p) in points.iter().enumerate().step_by(7) {
                let w = stored.winding_number(p, accuracy);
                assert_eq!(w.to_bits(), want[k].to_bits(), "{name} {layout:?} at {p}");
                assert_eq!(stored.contains(p, accuracy), tree.contains(p, accuracy));
                assert_eq!(
                    stored.signed_distance(p, f32::INFINITY, accuracy),
                    tree.signed_distance(p, f32::INFINITY, accuracy),
                    "{name} {layout:?} at {p}"
                );
            }
            // Loaded into memory, the expansions come along, the same bits.
            let loaded = match layout {
                MeshLayout::Omitted => MeshBvh::from_blob_with_mesh(&bytes, &valid),
                _ => MeshBvh::from_blob(&bytes),
            }
            .unwrap();
            let again = loaded.winding().unwrap();
            assert!(
                again
                    .nodes()
                    .iter()
                    .zip(tree.nodes())
                    .all(|(a, b)| format!("{a:?}") == format!("{b:?}"))
                    && again.nodes().len() == tree.nodes().len()
            );
        }
        // Without expansions: version 5, and no winding tree from the view.
        let plain = MeshBvh::build(&valid, &BuildConfig::default()).unwrap();
        let bytes = plain.to_blob(MeshLayout::Indexed).unwrap();
        let view = BlobView::parse(&bytes).unwrap();
        assert_eq!(view.header().version, 5);
        assert!(view.winding_tree().is_none());
        assert!(MeshBvh::from_blob(&bytes).unwrap().winding().is_none());

        // One bit of one stored expansion changed (the last node's last float, just before
        // the omitted mesh's tag byte), the checksum made right again: refused.
        let mut bytes = scene.to_blob(MeshLayout::Omitted).unwrap();
        let at = bytes.len() - 1 - 4;
        bytes[at] ^= 1;
        meshq::advanced::reseal(&mut bytes).unwrap();
        assert_eq!(
            BlobView::parse_with_mesh(&bytes, valid).unwrap_err(),
            BlobError::BadWindingNodes,
            "{name}"
        );
        assert_eq!(
            MeshBvh::from_blob_with_mesh(&bytes, &valid).unwrap_err(),
            BlobError::BadWindingNodes
        );
        let mut bytes = scene.to_blob(MeshLayout::Indexed).unwrap();
        // In an indexed blob the mesh comes after the expansions: find the last node's record
        // by its bytes and change its radius.
        let last = tree.nodes().last().unwrap();
        let record: Vec<u8> = last.centre.iter().flat_map(|x| x.to_le_bytes()).collect();
        let at = bytes
            .windows(record.len())
            .rposition(|w| w == record.as_slice())
            .unwrap()
            + 12;
        bytes[at] ^= 1;
        meshq::advanced::reseal(&mut bytes).unwrap();
        assert_eq!(
            BlobView::parse(&bytes).unwrap_err(),
            BlobError::BadWindingNodes
        );
        assert_eq!(
            MeshBvh::from_blob(&bytes).unwrap_err(),
            BlobError::BadWindingNodes
        );
    }
}
