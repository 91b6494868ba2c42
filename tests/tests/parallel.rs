//! Feature `parallel`. Batches over a thread pool (`meshq::parallel`) answer every query
//! exactly as a brute-force scan does — the same bits — on pools of 1, 2 and 3 threads, for
//! every structure and for a blob read in place, with batches that are not a whole number of
//! runs, and a short output buffer is refused before anything is written. The parallel BVH
//! build gives the sequential build's nodes, order, depth and blob bytes, bit for bit, for
//! every preset, on meshes large enough to be split in parallel.

use meshq::MeshBvh;
use meshq::MeshQuery;
use meshq::advanced::PackedTriangle;
use meshq::advanced::{BvhNode, PrimRef};
use meshq::blob::{BlobView, MeshLayout};
use meshq::bvh::BuildConfig;
use meshq::bvh::Bvh;
use meshq::error::{BatchBuffer, BatchError};
use meshq::math::{ClosestPoint, RayHit};
use meshq::owned::{MeshIndex, StructureKind};
use meshq::parallel::{self, RUN};
use meshq::query::RayOptions;
use meshq_tests::oracle::BruteForce;
use meshq_tests::{bake, in_stadium, load_mesh, subdivided, workload};

fn ray_bits(h: Option<RayHit>) -> Option<(u32, u32, u32, u32)> {
    h.map(|h| (h.t.to_bits(), h.tri, h.u.to_bits(), h.v.to_bits()))
}

fn point_bits(c: Option<ClosestPoint>) -> Option<(u32, u32, [u32; 3])> {
    c.map(|c| {
        (
            c.distance_squared.to_bits(),
            c.tri,
            c.point.to_array().map(f32::to_bits),
        )
    })
}

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool")
}

/// Every parallel batch on `query` equals the oracle's answers.
fn check<Q: MeshQuery + Sync + ?Sized>(query: &Q, brute: &BruteForce, mesh_name: &str, what: &str) {
    let loaded = load_mesh(mesh_name);
    // Two and a half runs: the last run is short.
    let n = 2 * RUN + RUN / 2;
    let mut rays = workload::random_rays(&loaded.positions, n - 1024, 7);
    rays.extend(workload::camera_rays(&loaded.positions, 32, 32));
    let points = workload::closest_points(&loaded.positions, n, 11);
    let options = RayOptions::default();
    let want_hits: Vec<_> = rays
        .iter()
        .map(|r| ray_bits(brute.raycast(r, &options)))
        .collect();
    let bounded = brute
        .closest_point(points[0], f32::INFINITY)
        .map_or(0.0, |c| c.distance_squared.sqrt())
        * 2.0;
    let want_points: Vec<_> = points
        .iter()
        .map(|&p| point_bits(brute.closest_point(p, bounded)))
        .collect();
    assert!(
        want_hits.iter().filter(|h| h.is_some()).count() > n / 10,
        "{what}: rays hit"
    );
    for threads in [1, 2, 3] {
        pool(threads).install(|| {
            let mut hits = vec![None; n];
            parallel::raycast_batch(query, &rays, &options, &mut hits).expect("batch");
            let got: Vec<_> = hits.into_iter().map(ray_bits).collect();
            assert_eq!(got, want_hits, "{what}: closest hit on {threads} threads");

            let mut any = vec![false; n];
            parallel::raycast_any_batch(query, &rays, &options, &mut any).expect("batch");
            let want_any: Vec<bool> = want_hits.iter().map(Option::is_some).collect();
            assert_eq!(any, want_any, "{what}: any hit on {threads} threads");

            let mut near = vec![None; n + 3];
            parallel::closest_points(query, &points, bounded, &mut near).expect("batch");
            let got: Vec<_> = near[..n].iter().copied().map(point_bits).collect();
            assert_eq!(
                got, want_points,
                "{what}: closest points on {threads} threads"
            );
            assert!(
                near[n..].iter().all(Option::is_none),
                "{what}: past the points untouched"
            );
        });
    }
    // Too short an output: refused, nothing written.
    let mut short = vec![
        Some(RayHit {
            t: 1.0,
            tri: 9,
            u: 0.0,
            v: 0.0
        });
        n - 1
    ];
    assert_eq!(
        parallel::raycast_batch(query, &rays, &options, &mut short),
        Err(BatchError::BufferTooSmall {
            buffer: BatchBuffer::Results,
            needed: n,
            got: n - 1
        })
    );
    assert!(
        short.iter().all(|h| h.is_some_and(|h| h.tri == 9)),
        "{what}: untouched"
    );
}

#[test]
fn parallel_batches_equal_brute_force_on_every_structure() {
    for name in ["spot", "fandisk"] {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        let brute = BruteForce::new(&mesh);
        for kind in [
            StructureKind::Bvh,
            StructureKind::KdTree,
            StructureKind::Octree,
            StructureKind::Grid,
        ] {
            let index = MeshIndex::build(&mesh, kind).expect("build");
            check(&index, &brute, name, &format!("{name} {kind:?}"));
        }
        let blob = bake(&mesh, &BuildConfig::default(), MeshLayout::Packed).expect("baked");
        let view = BlobView::parse(&blob).expect("a valid blob");
        check(&view, &brute, name, &format!("{name} blob view"));
    }
}

/// Every coordinate's bits, slot by slot.
fn bits(packed: &[PackedTriangle]) -> Vec<u32> {
    packed
        .iter()
        .flat_map(|t| [t.a, t.b, t.c])
        .flatten()
        .map(f32::to_bits)
        .collect()
}

#[test]
fn the_parallel_build_is_the_sequential_build() {
    let bunny = load_mesh("stanford-bunny");
    // 277,804 triangles: well past the size the parallel build splits in parallel.
    let meshes = [in_stadium(&bunny), subdivided(&bunny), bunny];
    for (m, loaded) in meshes.iter().enumerate() {
        let mesh = loaded.valid();
        let n = mesh.triangle_count();
        for config in [
            BuildConfig::fast(),
            BuildConfig::balanced(),
            BuildConfig::high_quality(),
            BuildConfig {
                split: meshq::bvh::SplitStrategy::Sweep { step: 32 },
                ..BuildConfig::balanced()
            },
        ] {
            let mut nodes = vec![BvhNode::EMPTY; Bvh::measure(n, None).nodes];
            let mut order = vec![0u32; n];
            let mut scratch = vec![PrimRef::EMPTY; n];
            let sequential =
                Bvh::build(&mesh, &config, &mut nodes, &mut order, &mut scratch).expect("build");
            let want = (
                sequential.nodes().to_vec(),
                sequential.order().to_vec(),
                sequential.depth(),
            );
            for threads in [1, 2, 3] {
                let mut nodes = vec![BvhNode::EMPTY; Bvh::measure(n, None).nodes];
                let mut order = vec![0u32; n];
                let mut scratch = vec![PrimRef::EMPTY; n];
                let parallel = pool(threads).install(|| {
                    Bvh::build_parallel(&mesh, &config, &mut nodes, &mut order, &mut scratch)
                        .expect("build")
                });
                parallel.check(&mesh).expect("a valid tree");
                let got = (
                    parallel.nodes().to_vec(),
                    parallel.order().to_vec(),
                    parallel.depth(),
                );
                assert!(
                    got == want,
                    "mesh {m} ({n} triangles), {config:?}, {threads} threads: another tree"
                );
                // Packing on the pool copies the same corners into the same slots.
                let mut one = vec![PackedTriangle::EMPTY; n];
                let mut many = vec![PackedTriangle::EMPTY; n];
                sequential.pack_triangles(&mesh, &mut one).expect("pack");
                pool(threads)
                    .install(|| parallel.pack_triangles_parallel(&mesh, &mut many))
                    .expect("pack");
                assert!(
                    bits(&one) == bits(&many),
                    "mesh {m}, {threads} threads: packing"
                );
                assert!(
                    parallel
                        .pack_triangles_parallel(&mesh, &mut many[1..])
                        .is_err()
                );
            }
        }
        // The owned form, down to the blob bytes, the packed triangles and the wide nodes
        // queries walk (packed and collapsed on the pool too).
        let config = BuildConfig::default();
        let a = MeshBvh::build(&mesh, &config).expect("build");
        for threads in [2, 3] {
            let b =
                pool(threads).install(|| MeshBvh::build_parallel(&mesh, &config).expect("build"));
            assert_eq!(
                a.to_blob(MeshLayout::Indexed).expect("blob"),
                b.to_blob(MeshLayout::Indexed).expect("blob"),
                "mesh {m}, {threads} threads: blob bytes"
            );
            assert!(
                bits(a.packed().as_slice()) == bits(b.packed().as_slice()),
                "mesh {m}, {threads} threads: packed triangles"
            );
            let same_wide = match (a.wide(), b.wide(), a.eight_wide(), b.eight_wide()) {
                (Some(a), Some(b), None, None) => {
                    a.nodes().len() == b.nodes().len()
                        && a.nodes().iter().zip(b.nodes()).all(|(x, y)| x.same_bits(y))
                }
                (None, None, Some(a), Some(b)) => {
                    a.nodes().len() == b.nodes().len()
                        && a.nodes().iter().zip(b.nodes()).all(|(x, y)| x.same_bits(y))
                }
                _ => false,
            };
            assert!(same_wide, "mesh {m}, {threads} threads: wide nodes");
        }
    }
    // Too short a buffer: refused before anything is written, as the sequential build does.
    let loaded = load_mesh("spot");
    let mesh = loaded.valid();
    let n = mesh.triangle_count();
    let mut nodes = vec![BvhNode::EMPTY; Bvh::measure(n, None).nodes - 1];
    let (mut order, mut scratch) = (vec![7u32; n], vec![PrimRef::EMPTY; n]);
    assert!(
        Bvh::build_parallel(
            &mesh,
            &BuildConfig::default(),
            &mut nodes,
            &mut order,
            &mut scratch
        )
        .is_err()
    );
    assert!(order.iter().all(|&o| o == 7));
}

/// The spatial-split build on pools of 2 and 3 threads gives the sequential build's nodes,
/// order and split references, bit for bit, and the owned form the same blob bytes, on scenes
/// large enough to be split in parallel (the sticks repeat many triangles; the bunny few).
#[test]
fn the_parallel_spatial_build_is_the_sequential_one() {
    use meshq::bvh::SpatialSplits;
    let spatial = SpatialSplits::DEFAULT;
    let config = BuildConfig::default();
    for loaded in [meshq_tests::sticks(2500), load_mesh("stanford-bunny")] {
        let mesh = loaded.valid();
        let name = &loaded.name;
        let a = MeshBvh::build_spatial(&mesh, &config, &spatial).expect("build");
        assert!(
            a.reference_count() > 17 * 1024,
            "{name}: large enough for parallel pieces"
        );
        assert!(!a.split_refs().is_empty(), "{name}: split references");
        for threads in [2, 3] {
            let b = pool(threads)
                .install(|| MeshBvh::build_spatial_parallel(&mesh, &config, &spatial))
                .expect("build");
            assert_eq!(
                a.bvh().nodes(),
                b.bvh().nodes(),
                "{name}, {threads} threads: nodes"
            );
            assert_eq!(
                a.bvh().order(),
                b.bvh().order(),
                "{name}, {threads} threads: order"
            );
            assert!(
                a.split_refs() == b.split_refs(),
                "{name}, {threads} threads: split references"
            );
            assert_eq!(
                a.to_blob(MeshLayout::Indexed).expect("blob"),
                b.to_blob(MeshLayout::Indexed).expect("blob"),
                "{name}, {threads} threads: blob bytes"
            );
        }
    }
}
