//! Loading a BVH blob into owned buffers with its boxes checked on the decoded copy.
//!
//! [`BlobView::parse`] checks each leaf's triangles against its box by gathering them from the
//! blob's bytes through the indices, the dearest step of a load. A loader that decodes the
//! blob anyway can check the boxes afterwards, on the copy, whose triangles sit packed in leaf
//! order: the same checks in the same order over the same bits. `parse` makes its box checks
//! after all the others, so [`BoxesUnchecked`], the blob with every check before them done,
//! and then the box checks on the copy, report the same first problem `parse` does.

use super::view::{RawStructure, check_before_boxes, check_mesh, sections};
use super::{BlobMesh, BlobStructure, BlobTree, BlobView};
use alloc::vec;

use super::split_check::check_slots;
use crate::bvh::TreeArrays;
use crate::bvh::check::{CheckLevel, Extent, check};
use crate::error::BlobError;

/// A self-contained BVH blob that passed every check [`BlobView::parse`] makes before the boxes
/// (which it makes last): not yet the boxes (finite, nested, holding their triangles), the
/// split references' coverage, the root box and depth against the header. Only for decoding
/// into buffers on which those checks then run, in that order.
pub(crate) struct BoxesUnchecked<'a>(BlobView<'a>);

impl<'a> BoxesUnchecked<'a> {
    /// [`BlobView::parse`] up to the box checks, for BVH blobs that store their mesh.
    ///
    /// # Errors
    /// The problem `parse` reports first, when it is found before the boxes;
    /// [`BlobError::UnsupportedStructure`] for another kind.
    ///
    /// With `collapse_checks_roles` (a loader whose collapse walks the stored roles, failing
    /// as [`BlobView::parse`]'s check of them does), the roles are left to it.
    pub(crate) fn parse(bytes: &'a [u8], collapse_checks_roles: bool) -> Result<Self, BlobError> {
        let s = sections(bytes)?;
        let mesh = s.mesh.ok_or(BlobError::MeshNotIncluded)?;
        check_mesh(&mesh)?;
        let header = s.header;
        let RawStructure::Bvh(mut tree) = s.structure else {
            return Err(BlobError::UnsupportedStructure {
                kind: header.kind.tag(),
            });
        };
        // The boxes wait for the decoded copy; so do stored roles the load's collapse walks.
        let roles_later = collapse_checks_roles && tree.collapse_roles().is_some();
        // The topology only: no box is read, and no corner.
        let topology = |t: &BlobTree<'_>| {
            check(
                t,
                None::<&BlobMesh<'_>>,
                CheckLevel::Topology,
                Extent::Exact,
            )
            .map(|shape| (shape, None))
        };
        let n = header.triangle_count as usize;
        let slots = |t: &BlobTree<'_>| counted_or_fingerprinted(t, n);
        check_before_boxes(
            &header,
            &mut tree,
            Some(&mesh),
            topology,
            slots,
            roles_later,
        )?;
        Ok(Self(BlobView {
            header,
            structure: BlobStructure::Bvh(tree),
            mesh,
        }))
    }

    /// The view, to decode from. Its boxes are unchecked: check the decoded tree in full
    /// before it answers anything.
    pub(crate) const fn view(&self) -> &BlobView<'a> {
        &self.0
    }
}

/// The order check of [`BlobView::parse`] for a loader, which has memory to spare: a tree
/// without split references must name every triangle once, so count that exactly, which is
/// cheaper than the fingerprint and passes only where it passes; when the count fails, the
/// fingerprint gives `parse`'s verdict (it may pass a crafted order, which the loader's exact
/// count after decoding then refuses, as before).
fn counted_or_fingerprinted(tree: &BlobTree<'_>, n: usize) -> Result<(), BlobError> {
    if tree.split_refs().is_empty() && tree.order.len() == n {
        let mut seen = vec![false; n];
        let once = tree
            .order_entries()
            .all(|tri| match seen.get_mut(tri as usize) {
                Some(s) if !*s => {
                    *s = true;
                    true
                }
                _ => false,
            });
        if once {
            return Ok(());
        }
    }
    check_slots(tree, tree.order_entries(), n)
}
