//! Shared helpers for meshq's integration tests and benchmarks: the bundled meshes, the
//! workloads of DESIGN.md (random rays, camera rays, closest-point queries) from a seeded
//! integer generator, blob baking and full validation over the owned [`MeshBvh`], and
//! brute-force oracles that scan every triangle with the public primitive tests.

pub mod assets;
pub mod distance_oracle;
pub mod hard_inputs;
pub mod oracle;
pub mod suite;
pub mod topology;
pub mod winding_oracle;
pub mod workload;

pub use assets::{
    LoadedMesh, MESHES, assets_dir, in_stadium, load_mesh, load_obj, spot_patch, sticks, subdivided,
};
pub use meshq_workload::SplitMix64;
pub use topology::Topology;

use meshq::MeshBvh;
use meshq::advanced::BvhNode;
use meshq::blob::MeshLayout;
use meshq::bvh::{BuildConfig, Bvh};
use meshq::error::StructureError;
use meshq::mesh::ValidMesh;

/// The binary tree of `owned`, checked in full against `mesh` ([`Bvh::from_parts`]): every
/// test runs the validator on the trees it queries.
///
/// # Errors
/// The validator's error (for instance when `mesh` is not the mesh the tree was built from).
pub fn checked_bvh<'a>(
    owned: &'a MeshBvh,
    mesh: &ValidMesh<'_>,
) -> Result<Bvh<'a>, StructureError> {
    let bvh = owned.bvh();
    Bvh::from_parts(bvh.nodes(), bvh.order(), mesh)
}

/// Builds a BVH of `mesh` with `config` and encodes it as a blob with the given mesh layout.
///
/// # Errors
/// The builder's or the encoder's error, as text.
pub fn bake(
    mesh: &ValidMesh<'_>,
    config: &BuildConfig,
    layout: MeshLayout,
) -> Result<Vec<u8>, String> {
    let owned = MeshBvh::build(mesh, config).map_err(|e| e.to_string())?;
    owned.to_blob(layout).map_err(|e| e.to_string())
}

/// The blob bytes of a fuzz finding kept in `tests/fixtures/` (`name`): the input's first byte
/// is the `blob_parse` target's mode, and an odd mode means "reseal the checksum first", as
/// the target does.
///
/// # Panics
/// When the fixture cannot be read or is empty (a test setup error).
#[must_use]
pub fn fuzz_blob(name: &str) -> Vec<u8> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures")
        .join(name);
    let input = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let (&mode, rest) = input
        .split_first()
        .expect("a fuzz input starts with its mode byte");
    let mut bytes = rest.to_vec();
    if mode & 1 == 1 {
        // A blob too short to reseal stays as it is, as the target leaves it.
        let _ = meshq::advanced::reseal(&mut bytes);
    }
    bytes
}

/// The arrays of a built tree copied out, for tests that corrupt or refit them.
#[derive(Clone, Debug, PartialEq)]
pub struct TreeParts {
    /// The used nodes.
    pub nodes: Vec<BvhNode>,
    /// The triangle order.
    pub order: Vec<u32>,
}

impl TreeParts {
    /// Copies the binary tree of `owned`.
    #[must_use]
    pub fn of(owned: &MeshBvh) -> Self {
        let bvh = owned.bvh();
        Self {
            nodes: bvh.nodes().to_vec(),
            order: bvh.order().to_vec(),
        }
    }
}
