//! The golden parity file `tests/golden/parity.txt`, which the WebAssembly tests and the
//! firmware check too.
//!
//! For every bundled mesh the parity run ([`meshq_workload::parity`]) is answered by a
//! brute-force scan over all triangles; the in-memory BVH, its four-wide collapse and blob
//! views in every mesh layout must give the same digest, and the file must record exactly that
//! digest. After an intended change of results, rewrite the file with
//! `MESHQ_BLESS_GOLDEN=1 cargo test -p meshq-tests --test integration parity_golden::`.

use std::fmt::Write as _;
use std::path::PathBuf;

use glam::Vec3;
use meshq::MeshBvh;
use meshq::advanced::WideNode;
use meshq::blob::{BlobView, MeshLayout};
use meshq::bvh::{BuildConfig, Bvh, SpatialSplits};
use meshq::math::{ClosestPoint, Ray, RayHit};
use meshq::mesh::ValidMesh;
use meshq::owned::{MeshIndex, StructureKind};
use meshq::query::RayOptions;
use meshq::wide::WideBvh;
use meshq::{MeshQuery, Traverse};
use meshq_tests::oracle::BruteForce;
use meshq_tests::{MESHES, bake, checked_bvh, load_mesh};
use meshq_workload::{GoldenEntry, ParitySpec, ParityTarget, find_golden, run_parity};

struct Brute(BruteForce);

impl ParityTarget for Brute {
    fn raycast(&mut self, ray: &Ray) -> Option<RayHit> {
        self.0.raycast(ray, &RayOptions::default())
    }
    fn raycast_any(&mut self, ray: &Ray) -> bool {
        self.0.raycast(ray, &RayOptions::default()).is_some()
    }
    fn closest_point(&mut self, point: Vec3) -> Option<ClosestPoint> {
        self.0.closest_point(point, f32::INFINITY)
    }
}

struct Owned(MeshIndex);

impl ParityTarget for Owned {
    fn raycast(&mut self, ray: &Ray) -> Option<RayHit> {
        self.0.raycast(ray)
    }
    fn raycast_any(&mut self, ray: &Ray) -> bool {
        self.0.raycast_any(ray)
    }
    fn closest_point(&mut self, point: Vec3) -> Option<ClosestPoint> {
        self.0.closest_point(point, f32::INFINITY)
    }
}

struct InMemory<'a> {
    bvh: Bvh<'a>,
    mesh: ValidMesh<'a>,
}

impl ParityTarget for InMemory<'_> {
    fn raycast(&mut self, ray: &Ray) -> Option<RayHit> {
        self.bvh.with(&self.mesh).raycast(ray)
    }
    fn raycast_any(&mut self, ray: &Ray) -> bool {
        self.bvh.with(&self.mesh).raycast_any(ray)
    }
    fn closest_point(&mut self, point: Vec3) -> Option<ClosestPoint> {
        self.bvh
            .with(&self.mesh)
            .closest_point(point, f32::INFINITY)
    }
}

struct Wide<'a> {
    wide: WideBvh<'a>,
    mesh: ValidMesh<'a>,
}

impl ParityTarget for Wide<'_> {
    fn raycast(&mut self, ray: &Ray) -> Option<RayHit> {
        self.wide.with(&self.mesh).raycast(ray)
    }
    fn raycast_any(&mut self, ray: &Ray) -> bool {
        self.wide.with(&self.mesh).raycast_any(ray)
    }
    fn closest_point(&mut self, point: Vec3) -> Option<ClosestPoint> {
        self.wide
            .with(&self.mesh)
            .closest_point(point, f32::INFINITY)
    }
}

struct FromBlob<'a>(BlobView<'a>);

impl ParityTarget for FromBlob<'_> {
    fn raycast(&mut self, ray: &Ray) -> Option<RayHit> {
        self.0.raycast(ray)
    }
    fn raycast_any(&mut self, ray: &Ray) -> bool {
        self.0.raycast_any(ray)
    }
    fn closest_point(&mut self, point: Vec3) -> Option<ClosestPoint> {
        self.0.closest_point(point, f32::INFINITY)
    }
}

fn golden_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("golden/parity.txt")
}

/// The golden line of one mesh, after checking every structure against brute force.
fn computed_line(name: &str) -> String {
    let loaded = load_mesh(name);
    let mesh = loaded.valid();
    let spec = ParitySpec::DEFAULT;
    let config = BuildConfig::default();
    let owned = MeshBvh::build(&mesh, &config).unwrap();
    let bvh = checked_bvh(&owned, &mesh).unwrap();
    // The queries are placed around the root box a blob header records.
    let bounds = bvh.bounds();

    let expected = run_parity(&spec, bounds, &mut Brute(BruteForce::new(&mesh)));
    assert!(
        expected.hits > spec.rays / 4 && expected.any_hits > spec.any_rays / 4,
        "{name}: the parity rays should hit often: {expected:?}"
    );
    assert_eq!(
        expected.points_found, spec.points,
        "{name}: unbounded closest point"
    );

    let in_memory = run_parity(&spec, bounds, &mut InMemory { bvh, mesh });
    assert_eq!(
        in_memory, expected,
        "{name}: in-memory BVH against brute force"
    );
    let sizes = WideBvh::<WideNode>::measure(&bvh);
    let mut plan_entries = vec![meshq::advanced::PlanEntry::EMPTY; sizes.plan];
    let mut wide_nodes = vec![WideNode::EMPTY; sizes.nodes];
    let wide = WideBvh::build(&bvh, &mut plan_entries, &mut wide_nodes).unwrap();
    // The root's child boxes are padded around their own triangles: inside the root's box.
    assert!(bounds.contains_aabb(&wide.bounds()), "{name}: wide bounds");
    let from_wide = run_parity(&spec, bounds, &mut Wide { wide, mesh });
    assert_eq!(from_wide, expected, "{name}: wide BVH against brute force");

    // Every structure gives the same digest: the k-d tree, the octree and the grid too.
    // Their blobs, queried in place, give it as well.
    for kind in StructureKind::ALL {
        let index = MeshIndex::build(&mesh, kind).unwrap();
        for layout in [MeshLayout::Indexed, MeshLayout::Packed] {
            let blob = index.to_blob(layout).unwrap();
            let view = BlobView::parse(&blob).unwrap();
            let from_blob = run_parity(&spec, bounds, &mut FromBlob(view));
            assert_eq!(from_blob, expected, "{name}: {kind} blob ({layout:?})");
        }
        let from_index = run_parity(&spec, bounds, &mut Owned(index));
        assert_eq!(from_index, expected, "{name}: {kind} against brute force");
    }

    let layouts = [MeshLayout::Indexed, MeshLayout::Packed, MeshLayout::Omitted];
    for layout in layouts {
        let blob = bake(&mesh, &config, layout).unwrap();
        let view = match layout {
            MeshLayout::Omitted => BlobView::parse_with_mesh(&blob, mesh),
            _ => BlobView::parse(&blob),
        }
        .unwrap();
        assert_eq!(view.bounds(), bounds, "{name}: header bounds, {layout:?}");
        let from_blob = run_parity(&spec, view.bounds(), &mut FromBlob(view));
        assert_eq!(
            from_blob, expected,
            "{name}: blob view ({layout:?}) against brute force"
        );
    }

    let entry = GoldenEntry {
        mesh: name,
        triangles: u32::try_from(mesh.triangle_count()).unwrap(),
        spec,
        bounds_bits: GoldenEntry::bits_of(&bounds),
        report: expected,
    };
    entry.to_string()
}

const HEADER: &str = "\
# meshq parity golden file: one line per bundled mesh, checked by the native tests
# (tests/tests/parity_golden.rs, from brute-force answers), the WebAssembly tests and the
# firmware under QEMU. digest = CRC-64/XZ over every result bit of the parity run (see
# meshq_workload::parity). Rewrite with MESHQ_BLESS_GOLDEN=1 only after an intended change.
";

#[test]
fn every_structure_and_the_golden_file_agree_with_brute_force() {
    let mut file = String::from(HEADER);
    let lines: Vec<String> = MESHES.iter().map(|name| computed_line(name)).collect();
    for line in &lines {
        writeln!(file, "{line}").unwrap();
    }
    if std::env::var_os("MESHQ_BLESS_GOLDEN").is_some() {
        std::fs::write(golden_path(), &file).unwrap();
        return;
    }
    let recorded = std::fs::read_to_string(golden_path()).unwrap();
    for (name, line) in MESHES.iter().zip(&lines) {
        let recorded_entry = find_golden(&recorded, name)
            .unwrap_or_else(|e| panic!("{name}: {e} (bless with MESHQ_BLESS_GOLDEN=1)"));
        let computed = find_golden(line, name).unwrap();
        assert_eq!(
            recorded_entry, computed,
            "{name}: the golden file disagrees with brute force; if results changed on purpose, \
             rewrite it with MESHQ_BLESS_GOLDEN=1"
        );
    }
}

const BLOBS_HEADER: &str = "\
# meshq blob golden file: length and header checksum (CRC-32 over every other byte) of each
# bundled mesh's blob with the indexed mesh layout, built with the default config (binned SAH)
# and, as `<mesh>-fast`, with the fast preset (centre splits), as `<mesh>-sweep` with sweep SAH
# (a cut weighed every 32 triangles, default costs); `<mesh>-kdtree`, `-octree` and
# `-grid` hold the other structures with their default configs; `<mesh>-spatial` the BVH with
# spatial splits (default config and room). BVH blobs are format version 5, with the roles of
# their nodes in the eight-wide collapse; the others version 3. Builds and plans are
# deterministic, so the WebAssembly build must produce these exact bytes too.
";

fn blobs_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("golden/blobs.txt")
}

#[test]
fn default_and_fast_blobs_match_the_golden_blob_file() {
    let mut file = String::from(BLOBS_HEADER);
    let sweep = BuildConfig {
        split: meshq::bvh::SplitStrategy::Sweep {
            step: meshq::bvh::SplitStrategy::SWEEP_STEP,
        },
        ..BuildConfig::default()
    };
    for (suffix, config) in [
        ("", BuildConfig::default()),
        ("-fast", BuildConfig::fast()),
        ("-sweep", sweep),
    ] {
        for name in MESHES {
            let loaded = load_mesh(name);
            let mesh = loaded.valid();
            let blob = bake(&mesh, &config, MeshLayout::Indexed).unwrap();
            // Deterministic: a second bake gives the same bytes.
            assert_eq!(bake(&mesh, &config, MeshLayout::Indexed).unwrap(), blob);
            let header = meshq::advanced::BlobHeader::read(&blob).unwrap();
            writeln!(
                file,
                "{name}{suffix} bytes={} checksum={:#010x}",
                blob.len(),
                header.checksum
            )
            .unwrap();
        }
    }
    for name in MESHES {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        let spatial = SpatialSplits::DEFAULT;
        let scene = MeshBvh::build_spatial(&mesh, &BuildConfig::default(), &spatial).unwrap();
        let blob = scene.to_blob(MeshLayout::Indexed).unwrap();
        let again = MeshBvh::build_spatial(&mesh, &BuildConfig::default(), &spatial).unwrap();
        assert_eq!(again.to_blob(MeshLayout::Indexed).unwrap(), blob, "{name}");
        let header = meshq::advanced::BlobHeader::read(&blob).unwrap();
        writeln!(
            file,
            "{name}-spatial bytes={} checksum={:#010x}",
            blob.len(),
            header.checksum
        )
        .unwrap();
    }
    for kind in &StructureKind::ALL[1..] {
        for name in MESHES {
            let loaded = load_mesh(name);
            let index = MeshIndex::build(&loaded.valid(), *kind).unwrap();
            let blob = index.to_blob(MeshLayout::Indexed).unwrap();
            let header = meshq::advanced::BlobHeader::read(&blob).unwrap();
            writeln!(
                file,
                "{name}-{kind} bytes={} checksum={:#010x}",
                blob.len(),
                header.checksum
            )
            .unwrap();
        }
    }
    if std::env::var_os("MESHQ_BLESS_GOLDEN").is_some() {
        std::fs::write(blobs_path(), &file).unwrap();
        return;
    }
    let recorded = std::fs::read_to_string(blobs_path()).unwrap();
    assert_eq!(
        recorded, file,
        "tests/golden/blobs.txt is stale; if blobs changed on purpose, rewrite it with \
         MESHQ_BLESS_GOLDEN=1"
    );
}
