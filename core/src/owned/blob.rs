//! [`MeshBvh`] to and from blobs (features `alloc` and `blob`).

use alloc::vec;
use alloc::vec::Vec;

use super::MeshBvh;
use crate::advanced::CollapseRoles;
use crate::blob::{
    self, BlobHeader, BlobView, BoxesUnchecked, EncodeOptions, MeshLayout, same_bounds,
};
use crate::bvh::check::{CheckLevel, Extent, check};
use crate::bvh::split_coverage::check_split_coverage;
use crate::bvh::{BvhNode, TreeArrays};
use crate::error::{BlobError, BlobSection, BuildError};
#[cfg(feature = "blob-winding")]
use crate::inside::WindingNodes;
use crate::inside::WindingTree;
use crate::math::PackedTriangle;
use crate::mesh::ValidMesh;
use crate::query::{SplitRef, SplitRefs};
use crate::structure_kind::StructureKind;
use crate::wide::collapse::eight_wide_roles;

impl MeshBvh {
    /// Validates a self-contained blob with every check of [`BlobView::parse`] and decodes it
    /// into owned buffers, so it queries as a built one does and answers the same, bit for bit.
    /// The config is the one the blob records. The blob is read once: the box checks, which
    /// `parse` makes after all the others, run on the decoded copy, whose triangles sit
    /// packed in leaf order, in the same order over the same bits, so a refused blob gets the
    /// error `parse` gives it.
    ///
    /// A blob baked with [`MeshLayout::Packed`] stores corners, not the indexed mesh: the mesh
    /// becomes three vertices of its own per triangle, in triangle order (same triangles,
    /// same indices, same answers).
    ///
    /// # Errors
    /// What [`BlobView::parse`] reports ([`BlobError::MeshNotIncluded`] for a blob baked
    /// without its mesh: use [`MeshBvh::from_blob_with_mesh`];
    /// [`BlobError::UnsupportedStructure`] for a sound blob of another structure), and
    /// [`BlobError::RepeatedTriangle`] for an order that names a triangle twice.
    pub fn from_blob(bytes: &[u8]) -> Result<Self, BlobError> {
        if BlobHeader::read(bytes).is_ok_and(|h| h.kind != StructureKind::Bvh) {
            // Not a BVH: validated in full, so a damaged one is reported as `parse` reports
            // it, then refused.
            return Self::decode(&BlobView::parse(bytes)?);
        }
        // The eight-wide collapse walks the stored roles, checking them as it goes.
        let unchecked = BoxesUnchecked::parse(bytes, Self::EIGHT_WIDE_BY_DEFAULT)?;
        let header = *unchecked.view().header();
        let loaded = Self::decode_unreferenced(unchecked.view())?;
        // `parse`'s last checks, in its order, on the copy.
        let shape = check(
            &loaded.bvh(),
            Some(&loaded.packed()),
            CheckLevel::Full,
            Extent::Exact,
        )?;
        check_split_coverage(&loaded.bvh(), &loaded.packed())?;
        same_bounds(&loaded.bvh().bounds(), &header.bounds)?;
        if shape.depth != header.depth {
            return Err(BlobError::HeaderMismatch { field: "depth" });
        }
        check_references(&loaded.order, loaded.triangle_count(), &loaded.split_refs())?;
        // Last, as `parse` checks them last: stored expansions are the ones this tree gives.
        if let Some(nodes) = &loaded.winding {
            let (bvh, mesh) = (loaded.bvh(), loaded.mesh());
            if !WindingTree::expansions_match(&bvh, &mesh, &nodes.as_slice()) {
                return Err(BlobError::BadWindingNodes);
            }
        }
        Ok(loaded)
    }

    /// [`MeshBvh::from_blob`] for any blob, with the mesh it was baked from
    /// ([`BlobView::parse_with_mesh`]): needed for a blob baked without its mesh.
    ///
    /// # Errors
    /// What [`BlobView::parse_with_mesh`] reports, and [`BlobError::RepeatedTriangle`].
    pub fn from_blob_with_mesh(bytes: &[u8], mesh: &ValidMesh<'_>) -> Result<Self, BlobError> {
        Self::decode(&BlobView::parse_with_mesh(bytes, *mesh)?)
    }

    /// Decodes a validated view, then counts the order's references exactly.
    pub(super) fn decode(view: &BlobView<'_>) -> Result<Self, BlobError> {
        let loaded = Self::decode_unreferenced(view)?;
        check_references(&loaded.order, loaded.triangle_count(), &loaded.split_refs())?;
        Ok(loaded)
    }

    /// Decodes a view whose order may still name a triangle too often (a load counts them
    /// last, after the boxes, as [`BlobView::parse`] orders its checks).
    fn decode_unreferenced(view: &BlobView<'_>) -> Result<Self, BlobError> {
        let header = *view.header();
        let config = *header.config.bvh().ok_or(BlobError::UnsupportedStructure {
            kind: header.kind.tag(),
        })?;
        let (n, v) = (header.triangle_count as usize, header.vertex_count as usize);
        let slots = header.reference_count as usize;
        let mut nodes = vec![BvhNode::EMPTY; header.node_count as usize];
        let mut order = vec![0u32; slots];
        let depth = view.decode_tree(&mut nodes, &mut order)?.depth();
        let splits: Vec<SplitRef> = view
            .tree()
            .map(|t| t.split_refs().iter().collect())
            .unwrap_or_default();
        let (positions, triangles) = if header.mesh == MeshLayout::Packed {
            // Three vertices of its own per triangle: their indices must fit in `u32`.
            if header.triangle_count > u32::MAX / 3 {
                return Err(BlobError::TooLarge);
            }
            let mut packed = vec![PackedTriangle::EMPTY; slots];
            view.decode_packed(&mut packed)?;
            unshared_mesh(n, &order, &packed)
        } else {
            let mut positions = vec![[0.0f32; 3]; v];
            let mut triangles = vec![[0u32; 3]; n];
            // Checked by the view already: copied, not validated again.
            view.copy_mesh(&mut positions, &mut triangles)?;
            (positions, triangles)
        };
        let roles = view.tree().and_then(|t| t.collapse_roles());
        let mut loaded = Self::assemble(
            positions, triangles, nodes, order, depth, config, false, roles,
        )
        .map_err(|e| match e {
            // Stored roles a load left to the collapse, which walks them (`BoxesUnchecked`).
            BuildError::InvalidConfig { field: "roles" } => BlobError::BadCollapsePlan,
            // Unreachable: the buffers are sized from the validated blob's own counts.
            _ => BlobError::BufferTooSmall {
                section: BlobSection::PackedTriangles,
                needed: slots,
                got: 0,
            },
        })?;
        loaded.splits = splits;
        // Copied as stored; a validated view checked them, `from_blob` checks them last.
        #[cfg(feature = "blob-winding")]
        {
            loaded.winding = view.tree().and_then(|t| t.winding_nodes()).map(|nodes| {
                (0..nodes.count())
                    .filter_map(|i| nodes.expansion(i))
                    .collect()
            });
        }
        Ok(loaded)
    }

    /// The exact size of [`MeshBvh::to_blob`]'s output for `layout`.
    ///
    /// # Errors
    /// [`BlobError::TooLarge`] when a count does not fit the format.
    pub fn encoded_len(&self, layout: MeshLayout) -> Result<usize, BlobError> {
        // Only the roles' length counts here, not their values.
        let roles = vec![0u8; CollapseRoles::len_for(self.nodes.len())];
        let options = self.encode_options(layout, &roles);
        blob::encoded_len(&self.bvh(), &self.mesh(), &options)
    }

    /// Encodes the tree, the roles of its nodes in its eight-wide collapse (planned here, as
    /// every build plans it: format version 5, so loaders collapse it without planning), its
    /// winding-number expansions when they were prepared
    /// ([`MeshBvh::with_winding_numbers`]: format version 6, 112 bytes per node, so that a
    /// [`BlobView::winding_tree`] answers containment and signed distance in place) and (as
    /// `layout` says) the mesh as a blob, with this tree's config in its header: the bytes
    /// [`blob::encode_into`] writes, which depend only on the mesh, the tree and the layout, on
    /// every target.
    ///
    /// # Errors
    /// What [`blob::encode_into`] reports.
    pub fn to_blob(&self, layout: MeshLayout) -> Result<Vec<u8>, BlobError> {
        let bvh = self.bvh();
        let roles = eight_wide_roles(&bvh).map_err(|_| BlobError::BadCollapsePlan)?;
        let options = self.encode_options(layout, &roles);
        let mesh = self.mesh();
        let mut out = vec![0u8; blob::encoded_len(&bvh, &mesh, &options)?];
        let n = blob::encode_into(&bvh, &mesh, &options, &mut out)?;
        out.truncate(n);
        Ok(out)
    }

    fn encode_options<'r>(&'r self, layout: MeshLayout, roles: &'r [u8]) -> EncodeOptions<'r> {
        EncodeOptions {
            mesh: layout,
            config: self.config,
            collapse_roles: Some(CollapseRoles::new(roles)),
            winding: self.winding.as_deref(),
        }
    }
}

/// Refuses an order (entries below `n`, as the validated view ensures) that names a triangle
/// more often than once plus its split references beyond the first say, exactly: counted,
/// where the view compared fingerprints. With as many slots as the triangles and entries
/// allow, every triangle is then held exactly that often.
fn check_references(order: &[u32], n: usize, splits: &SplitRefs<'_>) -> Result<(), BlobError> {
    // Slots: one per triangle, and one more per entry after the first of its triangle's.
    let groups = splits
        .iter()
        .zip(splits.iter().skip(1))
        .filter(|(a, b)| a.tri != b.tri)
        .count()
        + usize::from(!splits.is_empty());
    if order.len() != n + splits.len() - groups {
        return Err(BlobError::OrderNotPermutation);
    }
    let mut seen = vec![0u32; n];
    for (slot, &tri) in (0u32..).zip(order) {
        let allowed = splits.range_of(tri).len().max(1);
        match seen.get_mut(tri as usize) {
            Some(s) if (*s as usize) < allowed => *s += 1,
            _ => return Err(BlobError::RepeatedTriangle { slot, tri }),
        }
    }
    Ok(())
}

/// Positions and triangles of `triangles` triangles given by slot (`packed[slot]` is triangle
/// `order[slot]`; a BVH's leaf order, or a cell structure's references, where a triangle may
/// appear several times with the same corners): three vertices of their own per triangle, in
/// triangle order. A triangle no slot names (none does in a validated structure) sits at the
/// origin. The caller makes sure `3 · triangles` fits in `u32`.
pub(super) fn unshared_mesh(
    triangles: usize,
    order: &[u32],
    packed: &[PackedTriangle],
) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let mut positions = vec![[0.0f32; 3]; 3 * triangles];
    for (&tri, corners) in order.iter().zip(packed) {
        let at = 3 * tri as usize;
        if let Some(out) = positions.get_mut(at..at + 3) {
            out.copy_from_slice(&[corners.a, corners.b, corners.c]);
        }
    }
    let triangles = (0u32..)
        .step_by(3)
        .take(triangles)
        .map(|v| [v, v + 1, v + 2])
        .collect();
    (positions, triangles)
}

#[cfg(test)]
mod tests {
    use alloc::vec::Vec;

    use super::MeshBvh;
    use crate::advanced::CollapsePlan;
    use crate::blob::{BlobHeader, BlobView, MeshLayout};
    use crate::bvh::BuildConfig;
    use crate::mesh::MeshRef;
    use crate::wide::WideNode8;
    use crate::wide::collapse::collapse_planned_vec;

    /// A wavy sheet of `2·n²` triangles.
    fn sheet(n: u32) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
        let mut positions = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                let (x, y) = (i as f32 / n as f32, j as f32 / n as f32);
                positions.push([x, y, 0.1 * libm::sinf(7.0 * x) * libm::cosf(5.0 * y)]);
            }
        }
        let mut triangles = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let v = j * (n + 1) + i;
                triangles.push([v, v + 1, v + n + 2]);
                triangles.push([v, v + n + 2, v + n + 1]);
            }
        }
        (positions, triangles)
    }

    #[test]
    fn loads_check_boxes_on_the_copy_and_refuse_damaged_boxes_as_parse_does() {
        let (positions, triangles) = sheet(12);
        let mesh = MeshRef::new(&positions, &triangles).validate().unwrap();
        let built = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
        for layout in [MeshLayout::Indexed, MeshLayout::Packed] {
            let bytes = built.to_blob(layout).unwrap();
            // A load (boxes checked on the copy) gives what decoding a parsed view gives.
            let quick = MeshBvh::from_blob(&bytes).unwrap();
            let checked = MeshBvh::decode(&BlobView::parse(&bytes).unwrap()).unwrap();
            assert_eq!(quick.bvh().nodes(), checked.bvh().nodes());
            assert_eq!(quick.packed().as_slice(), checked.packed().as_slice());
            // The space reserved for the wide nodes made from the blob's roles is exactly
            // their count: nothing left over, nothing moved by a shrink.
            let roles = BlobView::parse(&bytes)
                .unwrap()
                .tree()
                .and_then(|t| t.collapse_roles())
                .unwrap();
            let plan = CollapsePlan::<8>::from_roles_unchecked(&quick.bvh(), roles);
            let wide = collapse_planned_vec::<WideNode8, 8>(&plan).unwrap();
            assert!(wide.len() > 1);
            assert_eq!(plan.node_bound(), wide.len());
            // Nodes are 32-byte records after the header and their count's varint: shrink
            // each node's box in turn, one coordinate pulled to its centre.
            let header = BlobHeader::read(&bytes).unwrap();
            let count = header.node_count as usize;
            let varint = (count.max(1).ilog2() / 7 + 1) as usize;
            let first = header.header_len + varint;
            let mut refused = 0;
            for node in 0..count {
                let at = first + 32 * node;
                let mut damaged = bytes.clone();
                let min = f32::from_le_bytes(damaged[at..at + 4].try_into().unwrap());
                let max = f32::from_le_bytes(damaged[at + 16..at + 20].try_into().unwrap());
                let mid = 0.5 * (min + max);
                damaged[at + 16..at + 20].copy_from_slice(&mid.to_le_bytes());
                crate::advanced::reseal(&mut damaged).unwrap();
                let expected = BlobView::parse(&damaged).unwrap_err();
                assert_eq!(
                    MeshBvh::from_blob(&damaged).err(),
                    Some(expected),
                    "node {node}"
                );
                refused += 1;
            }
            assert_eq!(refused, count);
        }
    }
}
