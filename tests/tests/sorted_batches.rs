//! A large batch of rays from many origins on a large structure is answered in sorted order
//! (`MeshQuery::raycast_batch`): the order taken is a sorted permutation of the rays, and
//! every answer is still the ray's own — the single call's bits and a brute-force scan's — on
//! one thread and on a pool, for the owned BVH, a `MeshIndex` and a blob read in place.
//! Invalid rays and runs of rays from one origin inside the batch are answered as alone.

use meshq::blob::{BlobView, MeshLayout};
use meshq::bvh::BuildConfig;
use meshq::math::{Ray, RayHit, Vec3};
use meshq::owned::{MeshIndex, StructureKind};
use meshq::parallel;
use meshq::query::{RayOptions, sorts_ray_batch, sorts_ray_batches_of};
use meshq::{MeshBvh, MeshQuery};
use meshq_tests::oracle::BruteForce;
use meshq_tests::{bake, load_mesh, subdivided, workload};

/// The least a batch and a structure must hold to be sorted (`MeshQuery::raycast_batch`).
const SORT_MIN_RAYS: usize = 65_536;
const SORT_MIN_TRIANGLES: usize = 131_072;

fn bits(h: Option<RayHit>) -> Option<(u32, u32, u32, u32)> {
    h.map(|h| (h.t.to_bits(), h.tri, h.u.to_bits(), h.v.to_bits()))
}

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool")
}

/// Random rays, with a camera's run of rays from one origin, invalid rays and rays that miss
/// the mesh's box mixed in.
fn batch(positions: &[[f32; 3]]) -> Vec<Ray> {
    let mut rays = workload::random_rays(positions, SORT_MIN_RAYS + 1_500, 0x5EED_0042);
    let camera = workload::camera_rays(positions, 16, 16);
    let at = rays.len() / 3;
    rays.splice(at..at, camera);
    rays.push(Ray::new(Vec3::new(f32::NAN, 0.0, 0.0), Vec3::X));
    rays.push(Ray::new(Vec3::ZERO, Vec3::ZERO));
    let away = rays[7];
    rays.push(Ray::new(away.origin, -away.dir));
    rays
}

/// `query`'s batch answers, the order it took, and the same on pools, against `want`.
fn check<Q: MeshQuery + Sync>(query: &Q, rays: &[Ray], want: &[Option<RayHit>], what: &str) {
    let options = RayOptions::default();
    let n = rays.len();
    let mut keys = vec![0u64; n];
    let mut out = vec![None; n];
    query
        .raycast_batch(rays, &options, &mut keys, &mut out)
        .expect("batch");
    assert!(
        out.iter()
            .map(|&h| bits(h))
            .eq(want.iter().map(|&h| bits(h))),
        "{what}: batch answers"
    );
    // `keys` holds the order taken: ascending keys whose low halves are every ray's index
    // once, not the given order.
    assert!(keys.windows(2).all(|w| w[0] <= w[1]), "{what}: sorted");
    let mut seen = vec![false; n];
    for &k in &keys {
        let i = (k & 0xFFFF_FFFF) as usize;
        assert!(!std::mem::replace(&mut seen[i], true), "{what}: {i} twice");
    }
    assert!(
        keys.iter()
            .enumerate()
            .any(|(i, &k)| (k & 0xFFFF_FFFF) as usize != i),
        "{what}: the given order"
    );
    let mut any = vec![false; n];
    query
        .raycast_any_batch(rays, &options, &mut keys, &mut any)
        .expect("any-hit batch");
    let want_any: Vec<bool> = want.iter().map(Option::is_some).collect();
    assert_eq!(any, want_any, "{what}: any-hit batch");
    for threads in [1, 2] {
        pool(threads).install(|| {
            let mut hits = vec![None; n];
            parallel::raycast_batch(query, rays, &options, &mut hits).expect("batch");
            assert!(
                hits.iter()
                    .map(|&h| bits(h))
                    .eq(want.iter().map(|&h| bits(h))),
                "{what}: {threads} threads"
            );
            let mut any = vec![false; n];
            parallel::raycast_any_batch(query, rays, &options, &mut any).expect("batch");
            assert_eq!(any, want_any, "{what}: any hit on {threads} threads");
        });
    }
}

#[test]
fn large_batches_are_sorted_and_answer_each_ray_as_alone() {
    let loaded = subdivided(&load_mesh("stanford-bunny"));
    let mesh = loaded.valid();
    assert!(mesh.triangle_count() >= SORT_MIN_TRIANGLES);
    let owned = MeshBvh::build(&mesh, &BuildConfig::default()).expect("build");
    let rays = batch(&loaded.positions);
    let options = RayOptions::default();
    let want: Vec<_> = rays
        .iter()
        .map(|r| owned.raycast_with(r, &options))
        .collect();
    assert!(
        want.iter().filter(|h| h.is_some()).count() > rays.len() / 5,
        "rays hit"
    );
    // The single calls themselves, against a scan of every triangle, on every 16th ray.
    let brute = BruteForce::new(&mesh);
    for (i, ray) in rays.iter().enumerate().step_by(16) {
        assert_eq!(
            bits(want[i]),
            bits(brute.raycast(ray, &options)),
            "ray {i} against the scan"
        );
    }
    check(&owned, &rays, &want, "owned BVH");
    let index = MeshIndex::build(&mesh, StructureKind::Bvh).expect("build");
    check(&index, &rays, &want, "MeshIndex");
    let blob = bake(&mesh, &BuildConfig::default(), MeshLayout::Packed).expect("baked");
    let view = BlobView::parse(&blob).expect("a valid blob");
    check(&view, &rays, &want, "blob view");
}

/// A batch large enough for one sorted piece per thread (`parallel::SORTED_PIECE` rays each)
/// is cut into such pieces on the pool: every answer is still the single call's, on one
/// thread (one piece), on two (two uneven pieces, one holding a camera's run and invalid rays)
/// and on three (three pieces of fewer than `SORTED_PIECE` rays: the batch is sorted whole).
#[test]
fn batches_in_sorted_pieces_per_thread_answer_each_ray_as_alone() {
    let loaded = subdivided(&load_mesh("stanford-bunny"));
    let mesh = loaded.valid();
    let owned = MeshBvh::build(&mesh, &BuildConfig::default()).expect("build");
    let mut rays = workload::random_rays(&loaded.positions, 2 * parallel::SORTED_PIECE + 777, 9);
    let camera = workload::camera_rays(&loaded.positions, 16, 16);
    let at = rays.len() - 5_000;
    rays.splice(at..at, camera);
    rays.insert(at, Ray::new(Vec3::new(0.0, f32::INFINITY, 0.0), Vec3::Y));
    let options = RayOptions::default();
    let want: Vec<_> = rays
        .iter()
        .map(|r| owned.raycast_with(r, &options))
        .collect();
    let brute = BruteForce::new(&mesh);
    for (i, ray) in rays.iter().enumerate().step_by(4096) {
        assert_eq!(
            bits(want[i]),
            bits(brute.raycast(ray, &options)),
            "ray {i} against the scan"
        );
    }
    let want_any: Vec<bool> = want.iter().map(Option::is_some).collect();
    for threads in [1, 2, 3] {
        pool(threads).install(|| {
            let mut hits = vec![None; rays.len()];
            parallel::raycast_batch(&owned, &rays, &options, &mut hits).expect("batch");
            assert!(
                hits.iter()
                    .map(|&h| bits(h))
                    .eq(want.iter().map(|&h| bits(h))),
                "{threads} threads"
            );
            let mut any = vec![false; rays.len()];
            parallel::raycast_any_batch(&owned, &rays, &options, &mut any).expect("batch");
            assert_eq!(any, want_any, "any hit on {threads} threads");
        });
    }
}

/// Below either threshold a batch keeps the given order (and the same answers).
#[test]
fn small_batches_and_small_meshes_keep_the_given_order() {
    let loaded = load_mesh("stanford-bunny");
    let mesh = loaded.valid();
    assert!(mesh.triangle_count() < SORT_MIN_TRIANGLES);
    let owned = MeshBvh::build(&mesh, &BuildConfig::default()).expect("build");
    let rays = batch(&loaded.positions);
    let options = RayOptions::default();
    let mut keys = vec![0u64; rays.len()];
    let mut out = vec![None; rays.len()];
    owned
        .raycast_batch(&rays, &options, &mut keys, &mut out)
        .expect("batch");
    assert!(keys.iter().enumerate().all(|(i, &k)| k == i as u64));
    for (ray, &got) in rays.iter().zip(&out) {
        assert_eq!(bits(got), bits(owned.raycast_with(ray, &options)));
    }
    let large = subdivided(&loaded);
    let owned = MeshBvh::build(&large.valid(), &BuildConfig::default()).expect("build");
    let few = &rays[..SORT_MIN_RAYS - 1];
    owned
        .raycast_batch(few, &options, &mut keys, &mut out)
        .expect("batch");
    assert!(
        keys[..few.len()]
            .iter()
            .enumerate()
            .all(|(i, &k)| k == i as u64)
    );
}

/// `sorts_ray_batches_of` (a batch's length, before its rays are read) agrees with
/// `sorts_ray_batch` on batches from many origins, and with the order the batch call takes.
#[test]
fn the_length_alone_tells_whether_a_batch_from_many_origins_is_sorted() {
    let small = load_mesh("stanford-bunny");
    let large = subdivided(&small);
    let options = RayOptions::default();
    for (loaded, sorts) in [(&small, false), (&large, true)] {
        let owned = MeshBvh::build(&loaded.valid(), &BuildConfig::default()).expect("build");
        for n in [SORT_MIN_RAYS - 1, SORT_MIN_RAYS, SORT_MIN_RAYS + 100] {
            let rays = workload::random_rays(&loaded.positions, n, 3);
            let want = sorts && n >= SORT_MIN_RAYS;
            assert_eq!(sorts_ray_batches_of(&owned, n), want, "{n} rays");
            assert_eq!(sorts_ray_batch(&owned, &rays), want, "{n} rays");
            let (mut keys, mut out) = (vec![0u64; n], vec![None; n]);
            owned
                .raycast_batch(&rays, &options, &mut keys, &mut out)
                .expect("batch");
            let given = keys.iter().enumerate().all(|(i, &k)| k == i as u64);
            assert_eq!(!given, want, "{n} rays: the order taken");
        }
    }
}
