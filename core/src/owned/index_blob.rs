//! [`MeshIndex`] and the owned cell structures to and from blobs (features `alloc` and
//! `blob`).

use alloc::vec;
use alloc::vec::Vec;

use super::blob::unshared_mesh;
use super::cell_scene::CellScene;
use super::mesh_cells::{GridArrays, TreeArrays};
use super::{CellKind, MeshBvh, MeshCells, MeshIndex};
use crate::blob::{
    BlobHeader, BlobSource, BlobStructure, BlobView, BvhSections, MeshLayout, StructureConfig,
    encode_structure_into, structure_encoded_len,
};
use crate::cells::Words;
use crate::error::BlobError;
use crate::grid::GridLayout;
use crate::math::PackedTriangle;
use crate::mesh::ValidMesh;
use crate::query::LeafTriangles;
use crate::structure_kind::StructureKind;

impl MeshIndex {
    /// Validates a self-contained blob of any kind with every check of [`BlobView::parse`]
    /// (as [`MeshBvh::from_blob`] does for a BVH) and decodes it into owned buffers, so it
    /// queries as a built structure does and answers the same, bit for bit. The config is the
    /// one the blob records.
    ///
    /// A blob baked with [`MeshLayout::Packed`] stores corners, not the indexed mesh: the mesh
    /// becomes three vertices of its own per triangle, in triangle order (same triangles, same
    /// indices, same answers).
    ///
    /// # Errors
    /// What [`BlobView::parse`] reports ([`BlobError::MeshNotIncluded`] for a blob baked
    /// without its mesh: use [`MeshIndex::from_blob_with_mesh`]), and
    /// [`BlobError::RepeatedTriangle`] for a BVH order that names a triangle twice.
    pub fn from_blob(bytes: &[u8]) -> Result<Self, BlobError> {
        // A BVH blob (or bytes without a readable header, which fail there as in `parse`)
        // loads as `MeshBvh::from_blob` loads it; a cell structure is validated, then decoded.
        match BlobHeader::read(bytes) {
            Ok(header) if header.kind != StructureKind::Bvh => {
                Self::decode(&BlobView::parse(bytes)?)
            }
            _ => MeshBvh::from_blob(bytes).map(Self::Bvh),
        }
    }

    /// [`MeshIndex::from_blob`] for any blob, with the mesh it was baked from
    /// ([`BlobView::parse_with_mesh`]): needed for a blob baked without its mesh.
    ///
    /// # Errors
    /// What [`BlobView::parse_with_mesh`] reports, and [`BlobError::RepeatedTriangle`].
    pub fn from_blob_with_mesh(bytes: &[u8], mesh: &ValidMesh<'_>) -> Result<Self, BlobError> {
        Self::decode(&BlobView::parse_with_mesh(bytes, *mesh)?)
    }

    fn decode(view: &BlobView<'_>) -> Result<Self, BlobError> {
        let config = view.header().config;
        Ok(match (*view.structure(), config) {
            (BlobStructure::Bvh(_), _) => Self::Bvh(MeshBvh::decode(view)?),
            (BlobStructure::KdTree(t), StructureConfig::KdTree(config)) => {
                let nodes = (0..t.node_count()).filter_map(|i| t.node(i)).collect();
                let items = words(t.items());
                Self::KdTree(MeshCells {
                    scene: scene_of(view, &items)?,
                    arrays: TreeArrays {
                        bounds: *t.bounds(),
                        nodes,
                        items,
                    },
                    config,
                })
            }
            (BlobStructure::Octree(t), StructureConfig::Octree(config)) => {
                let nodes = (0..t.node_count()).filter_map(|i| t.node(i)).collect();
                let items = words(t.items());
                Self::Octree(MeshCells {
                    scene: scene_of(view, &items)?,
                    arrays: TreeArrays {
                        bounds: *t.bounds(),
                        nodes,
                        items,
                    },
                    config,
                })
            }
            (BlobStructure::Grid(g), StructureConfig::Grid { config, .. }) => {
                let items = words(g.items());
                let layout: GridLayout = *g.layout();
                Self::Grid(MeshCells {
                    scene: scene_of(view, &items)?,
                    arrays: GridArrays {
                        layout,
                        offsets: words(g.offsets()),
                        items,
                    },
                    config,
                })
            }
            // A validated view's config always matches its structure.
            _ => return Err(BlobError::HeaderMismatch { field: "config" }),
        })
    }

    /// The exact size of [`MeshIndex::to_blob`]'s output for `layout`.
    ///
    /// # Errors
    /// [`BlobError::TooLarge`] when a count does not fit the format.
    pub fn encoded_len(&self, layout: MeshLayout) -> Result<usize, BlobError> {
        match self {
            Self::Bvh(s) => s.encoded_len(layout),
            _ => self.with_source(|source, mesh| structure_encoded_len(source, mesh, layout)),
        }
    }

    /// Encodes the structure and (as `layout` says) the mesh as a blob, with the structure's
    /// config in its header: the bytes
    /// [`encode_structure_into`] writes, which depend only on the mesh, the structure and the
    /// layout, on every target.
    ///
    /// # Errors
    /// What [`encode_structure_into`] reports.
    pub fn to_blob(&self, layout: MeshLayout) -> Result<Vec<u8>, BlobError> {
        match self {
            // With its collapse roles ([`MeshBvh::to_blob`]).
            Self::Bvh(s) => s.to_blob(layout),
            _ => self.with_source(|source, mesh| encode(source, mesh, layout)),
        }
    }

    /// Runs `f` on the structure as a [`BlobSource`] and the mesh (a BVH without its collapse
    /// roles: [`MeshBvh::to_blob`] adds them).
    fn with_source<T>(
        &self,
        f: impl FnOnce(&BlobSource<'_>, &ValidMesh<'_>) -> Result<T, BlobError>,
    ) -> Result<T, BlobError> {
        match self {
            Self::Bvh(s) => f(
                &BlobSource::Bvh(&s.bvh(), *s.config(), BvhSections::default()),
                &s.mesh(),
            ),
            Self::KdTree(s) => f(&BlobSource::KdTree(&s.structure(), s.config), &s.mesh()),
            Self::Octree(s) => f(&BlobSource::Octree(&s.structure(), s.config), &s.mesh()),
            Self::Grid(s) => f(&BlobSource::Grid(&s.structure(), s.config), &s.mesh()),
        }
    }
}

/// Words read into memory.
fn words<W: Words>(w: W) -> Vec<u32> {
    (0..w.len()).filter_map(|i| w.word(i)).collect()
}

/// The mesh of a cell structure's view, copied (an indexed or external mesh) or rebuilt from
/// the corners stored per reference (a packed blob), packed in `items` order.
fn scene_of(view: &BlobView<'_>, items: &[u32]) -> Result<CellScene, BlobError> {
    let header = view.header();
    let (n, v) = (header.triangle_count as usize, header.vertex_count as usize);
    let (positions, triangles) = if header.mesh == MeshLayout::Packed {
        // Three vertices of its own per triangle: their indices must fit in `u32`.
        if header.triangle_count > u32::MAX / 3 {
            return Err(BlobError::TooLarge);
        }
        let packed: Vec<PackedTriangle> = (0..items.len())
            .zip(items)
            .map(|(slot, &tri)| {
                view.mesh()
                    .corners(slot, tri)
                    .map_or(PackedTriangle::EMPTY, |t| PackedTriangle::new(&t))
            })
            .collect();
        check_one_corner_set(n, items, &packed)?;
        unshared_mesh(n, items, &packed)
    } else {
        let mut positions = vec![[0.0f32; 3]; v];
        let mut triangles = vec![[0u32; 3]; n];
        view.decode_mesh(&mut positions, &mut triangles)?;
        (positions, triangles)
    };
    let mut scene = CellScene {
        positions,
        triangles,
        packed: Vec::new(),
    };
    scene
        .pack(items)
        .map_err(|_| BlobError::HeaderMismatch { field: "mesh" })?;
    Ok(scene)
}

impl<K: CellKind> MeshCells<K> {
    /// [`MeshIndex::to_blob`] for a cell structure.
    ///
    /// # Errors
    /// What [`encode_structure_into`] reports.
    pub fn to_blob(&self, layout: MeshLayout) -> Result<Vec<u8>, BlobError> {
        let view = self.structure();
        encode(&K::source(&view, self.config), &self.mesh(), layout)
    }
}

/// The blob of `source` over `mesh`, in a buffer of its exact size.
fn encode(
    source: &BlobSource<'_>,
    mesh: &ValidMesh<'_>,
    layout: MeshLayout,
) -> Result<Vec<u8>, BlobError> {
    let mut out = vec![0u8; structure_encoded_len(source, mesh, layout)?];
    let n = encode_structure_into(source, mesh, layout, &mut out)?;
    out.truncate(n);
    Ok(out)
}

/// Refuses packed references that do not give each of `triangles` triangles exactly one set
/// of corners: exactly, with a mark per triangle, what the view checked by fingerprint.
fn check_one_corner_set(
    triangles: usize,
    items: &[u32],
    packed: &[PackedTriangle],
) -> Result<(), BlobError> {
    let mut first: Vec<Option<usize>> = vec![None; triangles];
    for (slot, &tri) in items.iter().enumerate() {
        match first.get_mut(tri as usize) {
            Some(Some(at)) => {
                let same = |p: Option<&PackedTriangle>| {
                    p.map(|t| [t.a, t.b, t.c].map(|v| v.map(f32::to_bits)))
                };
                if same(packed.get(*at)) != same(packed.get(slot)) {
                    return Err(BlobError::OrderNotPermutation);
                }
            }
            Some(unseen) => *unseen = Some(slot),
            None => return Err(BlobError::OrderNotPermutation),
        }
    }
    let named = first.iter().filter(|f| f.is_some()).count();
    if named == triangles {
        Ok(())
    } else {
        Err(BlobError::CountMismatch {
            section: crate::error::BlobSection::References,
            expected: triangles as u64,
            found: named as u64,
        })
    }
}
