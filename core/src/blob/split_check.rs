//! Whether a BVH's leaf slots and split references agree: the checks a tree with spatial
//! splits needs instead of "the order is a permutation".

use super::BlobMesh;
use super::format::PACKED_BYTES;
use super::order_check::check_order_covers;
use crate::bvh::TreeArrays;
use crate::error::BlobError;

/// Checks `tree`'s order (`order`: its entries, already checked to be below `n`) and split
/// references against a mesh of `n` triangles (topology already validated):
/// - with no split references, the order is a permutation of `0..n`;
/// - otherwise every entry is in range, in strict `(triangle, slot)` order, names the triangle
///   its slot holds and carries the box of the leaf holding that slot, bit for bit; each
///   split triangle has two entries or more; and the order names each triangle once plus each
///   split triangle once per entry beyond its first (so no other triangle repeats).
///
/// # Errors
/// [`BlobError::BadSplitRef`] naming the first bad entry, or
/// [`BlobError::OrderNotPermutation`].
pub(crate) fn check_slots<A: TreeArrays + ?Sized>(
    tree: &A,
    order: impl Iterator<Item = u32>,
    n: usize,
) -> Result<(), BlobError> {
    let splits = tree.split_refs();
    let tri_at = |slot: usize| {
        tree.leaf_triangles(slot, 1)
            .and_then(|mut ids| ids.next())
            .map(|(_, t)| t)
    };
    if splits.is_empty() {
        return check_order_covers(order, n, core::iter::empty());
    }
    let bad = |i: usize| BlobError::BadSplitRef {
        entry: u32::try_from(i).unwrap_or(u32::MAX),
    };
    let mut previous: Option<(u32, u32)> = None;
    let mut group_len = 0usize;
    for (i, r) in splits.iter().enumerate() {
        let key = (r.tri, r.slot);
        let same_group = previous.is_some_and(|(t, _)| t == r.tri);
        if previous.is_some_and(|p| key <= p)
            || (!same_group && previous.is_some() && group_len < 2)
            || r.tri as usize >= n
            || tri_at(r.slot as usize) != Some(r.tri)
        {
            return Err(bad(i));
        }
        group_len = if same_group { group_len + 1 } else { 1 };
        previous = Some(key);
    }
    if group_len < 2 {
        return Err(bad(splits.len().saturating_sub(1)));
    }
    // Each slot of a split triangle has its entry, with its leaf's box.
    let mut matched = 0usize;
    for node in (0..tree.node_count()).filter_map(|i| tree.node(i)) {
        if !node.is_leaf() {
            continue;
        }
        let first = node.first as usize;
        let leaf_box = node.aabb();
        for slot in first..first.saturating_add(node.count as usize) {
            let Some(tri) = tri_at(slot) else {
                continue;
            };
            let range = splits.range_of(tri);
            if range.is_empty() {
                continue;
            }
            let entry = range
                .clone()
                .find(|&i| splits.get(i).is_some_and(|r| r.slot as usize == slot));
            let Some(i) = entry else {
                return Err(bad(range.end));
            };
            let same_box = splits.get(i).is_some_and(|r| {
                let bits = |v: glam::Vec3| v.to_array().map(f32::to_bits);
                bits(r.leaf_box.min) == bits(leaf_box.min)
                    && bits(r.leaf_box.max) == bits(leaf_box.max)
            });
            if !same_box {
                return Err(bad(i));
            }
            matched += 1;
        }
    }
    if matched != splits.len() {
        return Err(bad(splits.len()));
    }
    check_order_covers(order, n, splits.iter().map(|r| r.tri))
}

/// Refuses a packed mesh (corners per leaf slot) whose slots of one split triangle hold
/// different corners: a query would then meet another triangle in each leaf. Other layouts
/// read a triangle's corners through its index, the same from every slot.
///
/// # Errors
/// [`BlobError::BadSplitRef`] naming the first entry whose slot's corners differ from those
/// of its triangle's first entry.
pub(crate) fn check_repeated_corners<A: TreeArrays + ?Sized>(
    tree: &A,
    mesh: Option<&BlobMesh<'_>>,
) -> Result<(), BlobError> {
    let (Some(BlobMesh::Packed { corners }), splits) = (mesh, tree.split_refs()) else {
        return Ok(());
    };
    let mut first: Option<(u32, Option<&[u8; PACKED_BYTES]>)> = None;
    for (i, r) in splits.iter().enumerate() {
        let here = corners.get(r.slot as usize);
        match first {
            Some((tri, there)) if tri == r.tri => {
                if here.is_none() || here != there {
                    return Err(BlobError::BadSplitRef {
                        entry: u32::try_from(i).unwrap_or(u32::MAX),
                    });
                }
            }
            _ => first = Some((r.tri, here)),
        }
    }
    Ok(())
}
