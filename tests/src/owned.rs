//! A BVH with owned buffers, for std code.

use meshq::blob::{self, EncodeOptions, MeshLayout};
use meshq::bvh::{self, BuildConfig, Bvh, BvhNode, PrimRef};
use meshq::error::{BlobError, BuildError, StructureError};
use meshq::mesh::ValidMesh;

/// Node and order buffers sized for a mesh, plus the depth of the built tree.
#[derive(Clone, Debug)]
pub struct OwnedBvh {
    /// The used nodes.
    pub nodes: Vec<BvhNode>,
    /// The triangle order.
    pub order: Vec<u32>,
}

impl OwnedBvh {
    /// Builds a BVH of `mesh` into freshly allocated, exactly sized buffers.
    ///
    /// # Errors
    /// The builder's error.
    pub fn build(mesh: &ValidMesh<'_>, config: &BuildConfig) -> Result<Self, BuildError> {
        let n = mesh.triangle_count();
        let mut nodes = vec![BvhNode::EMPTY; bvh::node_capacity(n)];
        let mut order = vec![0u32; n];
        let mut scratch = vec![PrimRef::EMPTY; n];
        let used = Bvh::build(mesh, config, &mut nodes, &mut order, &mut scratch)?
            .nodes()
            .len();
        nodes.truncate(used);
        Ok(Self { nodes, order })
    }

    /// The validated view.
    ///
    /// # Errors
    /// The validator's error.
    pub fn view<'a>(&'a self, mesh: &ValidMesh<'_>) -> Result<Bvh<'a>, StructureError> {
        Bvh::from_parts(&self.nodes, &self.order, mesh)
    }
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
    let owned = OwnedBvh::build(mesh, config).map_err(|e| e.to_string())?;
    let bvh = owned.view(mesh).map_err(|e| e.to_string())?;
    encode(&bvh, mesh, config, layout).map_err(|e| e.to_string())
}

/// Encodes a built BVH into an exactly sized vector.
///
/// # Errors
/// The encoder's error.
pub fn encode(
    bvh: &Bvh<'_>,
    mesh: &ValidMesh<'_>,
    config: &BuildConfig,
    layout: MeshLayout,
) -> Result<Vec<u8>, BlobError> {
    let options = EncodeOptions {
        mesh: layout,
        config: *config,
    };
    let mut out = vec![0u8; blob::encoded_len(bvh, mesh, &options)?];
    let n = blob::encode_into(bvh, mesh, &options, &mut out)?;
    out.truncate(n);
    Ok(out)
}
