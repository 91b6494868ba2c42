//! Writing a blob: sizing first, then encoding into the caller's buffer.

use postcard::ser_flavors::{Size, Slice};
use serde::ser::{Serialize, SerializeTupleVariant, Serializer};

use super::checksum::mesh_checksum;
use super::format::{
    BASE_VERSION, CHECKSUM_BYTES, FixedU32, HeaderCounts, HeaderSeal, MAGIC, MeshLayout,
    NodeRecord, PLANNED_VERSION, SPATIAL_VERSION, TriangleRecord, WINDING_VERSION, WindingRecord,
};
use super::source::{BlobSource, BvhSections};
use super::structure_config::WireConfig;
use crate::advanced::CollapseRoles;
use crate::bvh::{BuildConfig, Bvh};
use crate::cells::TwoWordNode;
use crate::error::{BlobError, BlobSection};
use crate::inside::WindingNode;
use crate::math::PackedTriangle;
use crate::mesh::ValidMesh;
use crate::query::SplitRefs;

/// What to put in a blob besides the tree.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct EncodeOptions<'r> {
    /// How to store the mesh (indexed by default; packed for the fastest in-place queries;
    /// omitted when the reader already has the mesh).
    pub mesh: MeshLayout,
    /// The config the tree was built with, recorded in the header for tools to show. It does not
    /// affect queries.
    pub config: BuildConfig,
    /// The roles of the tree's nodes in its eight-wide collapse
    /// ([`CollapsePlan::write_roles`](crate::advanced::CollapsePlan::write_roles) of a
    /// `CollapsePlan::<8>`), stored (format version 5) so that loaders collapse the tree without
    /// planning it. `None` (the default) writes the blob at an older version, whose loaders plan
    /// the collapse themselves. Queries answer the same either way.
    pub collapse_roles: Option<CollapseRoles<'r>>,
    /// The tree's winding-number expansions, one per node, exactly as
    /// [`WindingTree::build`](crate::inside::WindingTree::build) wrote them for this tree and
    /// mesh (checked), stored (format version 6) so that a view answers winding numbers,
    /// containment and signed distance in place
    /// (`BlobView::winding_tree`, feature `blob-winding`). 112 bytes per node.
    /// `None` (the default) writes no expansions.
    pub winding: Option<&'r [WindingNode]>,
}

impl<'r> EncodeOptions<'r> {
    /// The optional BVH sections these options ask for.
    const fn sections(&self) -> BvhSections<'r> {
        BvhSections {
            collapse_roles: self.collapse_roles,
            winding: self.winding,
        }
    }
}

/// The exact number of bytes [`encode_into`] writes for this tree, mesh and options.
///
/// # Errors
/// [`BlobError::TooLarge`] when a count does not fit the format.
pub fn encoded_len(
    bvh: &Bvh<'_>,
    mesh: &ValidMesh<'_>,
    options: &EncodeOptions,
) -> Result<usize, BlobError> {
    structure_encoded_len(
        &BlobSource::Bvh(bvh, options.config, options.sections()),
        mesh,
        options.mesh,
    )
}

/// Encodes `bvh`, built from `mesh`, into the front of `out` and returns the number of bytes
/// written ([`encoded_len`]): [`encode_structure_into`] for a BVH.
///
/// # Errors
/// As [`encode_structure_into`].
pub fn encode_into(
    bvh: &Bvh<'_>,
    mesh: &ValidMesh<'_>,
    options: &EncodeOptions,
    out: &mut [u8],
) -> Result<usize, BlobError> {
    encode_structure_into(
        &BlobSource::Bvh(bvh, options.config, options.sections()),
        mesh,
        options.mesh,
        out,
    )
}

/// The exact number of bytes [`encode_structure_into`] writes for this structure, mesh and
/// layout.
///
/// # Errors
/// [`BlobError::TooLarge`] when a count does not fit the format.
pub fn structure_encoded_len(
    source: &BlobSource<'_>,
    mesh: &ValidMesh<'_>,
    layout: MeshLayout,
) -> Result<usize, BlobError> {
    let payload = Payload {
        source,
        mesh,
        layout,
    };
    let payload_len = size_of_value(&payload)?;
    let header = header(source, mesh, layout, payload_len)?;
    size_of_value(&header)?
        .checked_add(payload_len)
        .ok_or(BlobError::TooLarge)
}

/// Encodes a structure of any kind, built from `mesh`, with the mesh stored as `layout` says,
/// into the front of `out`; returns the number of bytes written
/// ([`structure_encoded_len`]).
///
/// The bytes depend only on the structure, its config, the mesh and the layout, never on the
/// host: every number is little-endian, so a deterministic build gives the same blob on every
/// target. The structure is validated against the mesh first, so an invalid blob is never
/// written.
///
/// # Errors
/// [`BlobError::BufferTooSmall`] (nothing written) when `out` is shorter than
/// [`structure_encoded_len`]; [`BlobError::InvalidNode`] when the structure does not validate
/// against `mesh`; [`BlobError::HeaderMismatch`] for an out-of-range config;
/// [`BlobError::TooLarge`].
pub fn encode_structure_into(
    source: &BlobSource<'_>,
    mesh: &ValidMesh<'_>,
    layout: MeshLayout,
    out: &mut [u8],
) -> Result<usize, BlobError> {
    if !source.config().is_valid() {
        return Err(BlobError::HeaderMismatch { field: "config" });
    }
    source.check(mesh)?;
    let payload = Payload {
        source,
        mesh,
        layout,
    };
    let payload_len = size_of_value(&payload)?;
    let header = header(source, mesh, layout, payload_len)?;
    let header_len = size_of_value(&header)?;
    let total = header_len
        .checked_add(payload_len)
        .ok_or(BlobError::TooLarge)?;
    let got = out.len();
    let out = out.get_mut(..total).ok_or(BlobError::BufferTooSmall {
        section: BlobSection::Header,
        needed: total,
        got,
    })?;
    let (head, body) = out.split_at_mut(header_len);
    write_value(&payload, body)?;
    write_value(&header, head)?;
    reseal(out)?;
    Ok(total)
}

/// Recomputes a blob's checksum in place (after the blob was edited deliberately, for example by
/// a test that corrupts it). Only the header is read; nothing else is validated.
///
/// # Errors
/// Whatever [`BlobHeader::read`](super::BlobHeader::read) reports.
pub fn reseal(blob: &mut [u8]) -> Result<(), BlobError> {
    let header = super::BlobHeader::read(blob)?;
    let crc = blob_checksum(blob, header.header_len);
    let at = header.header_len.saturating_sub(CHECKSUM_BYTES);
    if let Some(slot) = blob.get_mut(at..header.header_len) {
        slot.copy_from_slice(&crc.to_le_bytes());
    }
    Ok(())
}

/// The blob checksum: CRC-32 of every byte except the checksum itself (the last four header
/// bytes, ending at `header_len`).
pub(crate) fn blob_checksum(blob: &[u8], header_len: usize) -> u32 {
    let at = header_len.saturating_sub(CHECKSUM_BYTES);
    let head = blob.get(..at).unwrap_or_default();
    let payload = blob.get(header_len..).unwrap_or_default();
    super::checksum::crc_of_parts(head, payload)
}

/// The header as written: magic, version, fields, checksum (a placeholder until resealed).
#[derive(serde::Serialize)]
struct Header {
    magic: [u8; 4],
    version: u16,
    counts: HeaderCounts,
    config: WireConfig,
    seal: HeaderSeal,
    checksum: FixedU32,
}

fn header(
    source: &BlobSource<'_>,
    mesh: &ValidMesh<'_>,
    layout: MeshLayout,
    payload_len: usize,
) -> Result<Header, BlobError> {
    let count = |n: usize| u32::try_from(n).map_err(|_| BlobError::TooLarge);
    let bounds = source.bounds();
    let version = version_of(source, mesh);
    let split_refs = if version >= SPATIAL_VERSION {
        Some(count(spatial_table(source, mesh).map_or(0, |t| t.len()))?)
    } else {
        None
    };
    Ok(Header {
        magic: MAGIC,
        version,
        counts: HeaderCounts {
            kind: source.kind().tag(),
            mesh: layout.tag(),
            triangle_count: count(mesh.triangle_count())?,
            vertex_count: count(mesh.vertex_count())?,
            node_count: count(source.node_count())?,
            depth: source.depth(mesh.triangle_count()),
            bounds_min: bounds.min.to_array(),
            bounds_max: bounds.max.to_array(),
        },
        config: WireConfig {
            config: source.config(),
            references: count(source.order().len())?,
            split_refs,
        },
        seal: HeaderSeal {
            mesh_checksum: mesh_checksum(mesh),
            payload_len: u64::try_from(payload_len).map_err(|_| BlobError::TooLarge)?,
        },
        checksum: FixedU32(0),
    })
}

/// The version a blob of `source` is written at: the oldest that holds it.
fn version_of(source: &BlobSource<'_>, mesh: &ValidMesh<'_>) -> u16 {
    match source {
        BlobSource::Bvh(_, _, sections) if sections.winding.is_some() => WINDING_VERSION,
        BlobSource::Bvh(_, _, sections) if sections.collapse_roles.is_some() => PLANNED_VERSION,
        _ if spatial_table(source, mesh).is_some() => SPATIAL_VERSION,
        _ => BASE_VERSION,
    }
}

/// The split references of a BVH with spatial splits (more slots than triangles, or split
/// references), which need version 4 at least; `None` for every other structure.
fn spatial_table<'s>(source: &'s BlobSource<'_>, mesh: &ValidMesh<'_>) -> Option<SplitRefs<'s>> {
    match source {
        BlobSource::Bvh(bvh, ..) => {
            let table = bvh.split_refs();
            (!table.is_empty() || bvh.order().len() != mesh.triangle_count()).then_some(table)
        }
        _ => None,
    }
}

/// Everything after the header: a BVH's nodes and order (then, from version 4, its split
/// references, and from version 5 its collapse roles), or a cell structure's words and
/// references; then the mesh section.
struct Payload<'q, 'a> {
    source: &'q BlobSource<'q>,
    mesh: &'q ValidMesh<'a>,
    layout: MeshLayout,
}

impl Serialize for Payload<'_, '_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeTuple;
        let version = version_of(self.source, self.mesh);
        let splits = version >= SPATIAL_VERSION;
        let (roles, winding) = match self.source {
            BlobSource::Bvh(_, _, sections) => {
                (sections.collapse_roles.map(|r| r.bytes()), sections.winding)
            }
            _ => (None, None),
        };
        // Version 5 holds the roles; version 6 holds both sections, each possibly empty.
        let planned = version >= PLANNED_VERSION;
        let expansions = version >= WINDING_VERSION;
        let mut t = s.serialize_tuple(
            3 + usize::from(splits) + usize::from(planned) + usize::from(expansions),
        )?;
        match self.source {
            BlobSource::Bvh(bvh, ..) => {
                t.serialize_element(&Seq(bvh.nodes().iter().map(NodeRecord::from)))?;
            }
            BlobSource::KdTree(tree, _) => t.serialize_element(&node_words(tree.nodes()))?,
            BlobSource::Octree(tree, _) => t.serialize_element(&node_words(tree.nodes()))?,
            BlobSource::Grid(grid, _) => {
                t.serialize_element(&Seq(grid.offsets().iter().map(|&w| FixedU32(w))))?;
            }
        }
        let order = self.source.order();
        t.serialize_element(&Seq(order.iter().map(|&i| FixedU32(i))))?;
        if splits {
            let table = spatial_table(self.source, self.mesh).unwrap_or(SplitRefs::NONE);
            t.serialize_element(&Seq(table.iter().map(|r| r.to_le_bytes())))?;
        }
        if planned {
            t.serialize_element(&Seq(roles.unwrap_or_default().iter()))?;
        }
        if expansions {
            let nodes = winding.unwrap_or_default();
            t.serialize_element(&Seq(nodes.iter().map(WindingRecord)))?;
        }
        t.serialize_element(&MeshSection {
            order,
            mesh: self.mesh,
            layout: self.layout,
        })?;
        t.end()
    }
}

/// Two-word nodes as a sequence of fixed-width words.
fn node_words<N: TwoWordNode>(nodes: &[N]) -> Seq<impl Iterator<Item = FixedU32> + Clone + '_> {
    Seq(nodes.iter().flat_map(|n| n.words()).map(FixedU32))
}

/// The mesh section: an enum whose variant index is the [`MeshLayout`] tag. A packed mesh
/// holds one corner triple per entry of `order` (a BVH's leaf slots, a cell structure's
/// references).
struct MeshSection<'q, 'a> {
    order: &'q [u32],
    mesh: &'q ValidMesh<'a>,
    layout: MeshLayout,
}

impl Serialize for MeshSection<'_, '_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        const NAME: &str = "MeshSection";
        match self.layout {
            MeshLayout::Indexed => {
                let mut v = s.serialize_tuple_variant(NAME, 0, "Indexed", 2)?;
                v.serialize_field(&Seq(self.mesh.positions().iter()))?;
                v.serialize_field(&Seq(self
                    .mesh
                    .triangles()
                    .iter()
                    .map(|&[a, b, c]| TriangleRecord(a, b, c))))?;
                v.end()
            }
            MeshLayout::Packed => {
                let mesh = self.mesh;
                let mut v = s.serialize_tuple_variant(NAME, 1, "Packed", 1)?;
                v.serialize_field(&Seq(self.order.iter().map(|&tri| {
                    mesh.triangle(tri)
                        .map_or(PackedTriangle::EMPTY, |t| PackedTriangle {
                            a: t.a.to_array(),
                            b: t.b.to_array(),
                            c: t.c.to_array(),
                        })
                })))?;
                v.end()
            }
            MeshLayout::Omitted => s.serialize_unit_variant(NAME, 2, "Omitted"),
        }
    }
}

/// A sequence serialized from a cloneable, exactly sized iterator (postcard needs the length
/// up front).
struct Seq<I>(I);

impl<I> Serialize for Seq<I>
where
    I: Iterator + Clone,
    I::Item: Serialize,
{
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(self.0.clone())
    }
}

fn size_of_value<T: Serialize>(value: &T) -> Result<usize, BlobError> {
    postcard::serialize_with_flavor(value, Size::default()).map_err(|_| BlobError::TooLarge)
}

fn write_value<T: Serialize>(value: &T, out: &mut [u8]) -> Result<(), BlobError> {
    let got = out.len();
    postcard::serialize_with_flavor(value, Slice::new(out))
        .map(|_| ())
        .map_err(|_| BlobError::BufferTooSmall {
            section: BlobSection::Header,
            needed: got,
            got,
        })
}
