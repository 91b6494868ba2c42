//! [`MeshBvh`] to and from blobs (features `alloc` and `blob`).

use alloc::vec;
use alloc::vec::Vec;

use super::MeshBvh;
use crate::advanced::CollapseRoles;
use crate::blob::{self, BlobView, BoxesUnchecked, EncodeOptions, MeshLayout};
use crate::bvh::check::{CheckLevel, Extent, check};
use crate::bvh::split_coverage::check_split_coverage;
use crate::bvh::{BvhNode, TreeArrays};
use crate::error::{BlobError, BlobSection};
use crate::math::PackedTriangle;
use crate::mesh::ValidMesh;
use crate::query::{SplitRef, SplitRefs};
use crate::wide::collapse::eight_wide_roles;

impl MeshBvh {
    /// Validates a self-contained blob with every check of [`BlobView::parse`] and decodes it
    /// into owned buffers, so it queries as a built one does and answers the same, bit for bit.
    /// The config is the one the blob records. The boxes are checked on the decoded copy; a
    /// blob refused there is parsed again, so the error is the one `parse` reports.
    ///
    /// A blob baked with [`MeshLayout::Packed`] stores corners, not the indexed mesh: the mesh
    /// becomes three vertices of its own per triangle, in triangle order (same triangles,
    /// same indices, same answers).
    ///
    /// # Errors
    /// What [`BlobView::parse`] reports ([`BlobError::MeshNotIncluded`] for a blob baked
    /// without its mesh: use [`MeshBvh::from_blob_with_mesh`]), and
    /// [`BlobError::RepeatedTriangle`] for an order that names a triangle twice.
    pub fn from_blob(bytes: &[u8]) -> Result<Self, BlobError> {
        // Sound blobs take the quicker path; anything it refuses is loaded again the checked
        // way, so every error is the one `BlobView::parse` (then `decode`) reports.
        Self::decode_then_check_boxes(bytes)
            .or_else(|_| BlobView::parse(bytes).and_then(|view| Self::decode(&view)))
    }

    /// [`MeshBvh::from_blob`] for a sound BVH blob, with the leaf and node boxes checked on the
    /// decoded copy, whose triangles are packed in leaf order, instead of on the bytes: the
    /// same checks over the same bits, without gathering every triangle through the blob's
    /// indices a second time.
    pub(super) fn decode_then_check_boxes(bytes: &[u8]) -> Result<Self, BlobError> {
        let unchecked = BoxesUnchecked::parse(bytes)?;
        let loaded = Self::decode(unchecked.view())?;
        let shape = check(
            &loaded.bvh(),
            Some(&loaded.packed()),
            CheckLevel::Full,
            Extent::Exact,
        )?;
        if shape.depth != loaded.depth {
            return Err(BlobError::HeaderMismatch { field: "depth" });
        }
        // The split references were checked against the blob's tree, whose boxes the decoded
        // copy repeats: the last check `BlobView::parse` makes, here on the copy.
        check_split_coverage(&loaded.bvh(), &loaded.packed())?;
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

    pub(super) fn decode(view: &BlobView<'_>) -> Result<Self, BlobError> {
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
        check_references(&order, n, &SplitRefs::new(&splits))?;
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
        .map_err(|_| {
            // Unreachable: the buffers are sized from the validated blob's own counts, and
            // the roles were checked against this very tree.
            BlobError::BufferTooSmall {
                section: BlobSection::PackedTriangles,
                needed: slots,
                got: 0,
            }
        })?;
        loaded.splits = splits;
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
    /// every build plans it: format version 5, so loaders collapse it without planning) and (as
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

    fn encode_options<'r>(&self, layout: MeshLayout, roles: &'r [u8]) -> EncodeOptions<'r> {
        EncodeOptions {
            mesh: layout,
            config: self.config,
            collapse_roles: Some(CollapseRoles::new(roles)),
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
    fn sound_blobs_take_the_quick_path_and_damaged_boxes_are_refused_there_too() {
        let (positions, triangles) = sheet(12);
        let mesh = MeshRef::new(&positions, &triangles).validate().unwrap();
        let built = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
        for layout in [MeshLayout::Indexed, MeshLayout::Packed] {
            let bytes = built.to_blob(layout).unwrap();
            // The quick path accepts a sound blob (or every load would silently take the
            // slower one) and gives what the checked path gives.
            let quick = MeshBvh::decode_then_check_boxes(&bytes).unwrap();
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
                assert!(
                    MeshBvh::decode_then_check_boxes(&damaged).is_err(),
                    "node {node}"
                );
                assert_eq!(MeshBvh::from_blob(&damaged).err(), Some(expected));
                refused += 1;
            }
            assert_eq!(refused, count);
        }
    }
}
