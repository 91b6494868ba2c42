//! Proof that a cell structure read from outside answers as a fresh build of its mesh: every
//! cell a triangle touches lists it.
//!
//! A query only meets a triangle through the cells that list it, so a structure whose cells
//! miss a triangle they touch answers wrongly, however sound its nodes. The builders hand a
//! triangle to every child cell it touches ([`ReferencePad::touches`]), starting from the root,
//! which holds them all; the check walks each triangle down the same way and looks it up in
//! every cell it reaches. Extra references (a cell listing a triangle it does not touch) cost
//! time, never an answer, and are not refused.

use super::{CellNode, CellTree, ReferencePad, Words};
use crate::math::{Triangle, Vec3};

/// Whether references `first..end` of `items`, in ascending order as builds write them, hold
/// `tri` (a binary search: a range out of order may be judged not to).
pub(crate) fn lists<W: Words>(items: W, first: usize, end: usize, tri: u32) -> bool {
    let (mut lo, mut hi) = (first, end);
    while lo < hi {
        let mid = lo + (hi - lo) / 2;
        match items.word(mid) {
            Some(w) if w == tri => return true,
            Some(w) if w < tri => lo = mid + 1,
            Some(_) => hi = mid,
            None => return false,
        }
    }
    false
}

/// Where references `first..end` of `items`, in ascending order as builds write them, hold
/// `tri` (a binary search, as [`lists`]).
pub(crate) fn find<W: Words>(items: W, first: usize, end: usize, tri: u32) -> Option<usize> {
    let (mut lo, mut hi) = (first, end);
    while lo < hi {
        let mid = lo + (hi - lo) / 2;
        match items.word(mid) {
            Some(w) if w == tri => return Some(mid),
            Some(w) if w < tri => lo = mid + 1,
            Some(_) => hi = mid,
            None => return None,
        }
    }
    None
}

/// The first subject of `coverage` (for `triangles` triangles) that reaches a leaf of `tree`
/// not holding it, walked down from the root into the children whose cells its corners touch
/// (padded by `pad`), as the builds hand a triangle down. `STACK` bounds the deferred children
/// as in [`for_each_cell`](super::for_each_cell).
pub(crate) fn first_uncovered_in_tree<T, W, const STACK: usize>(
    tree: &T,
    pad: ReferencePad,
    coverage: &mut Coverage<'_, W>,
    triangles: usize,
) -> Option<u32>
where
    T: CellTree + ?Sized,
    W: Words,
{
    // One stack for every walk: filling a fresh one per triangle cost more than the walk on
    // small trees.
    let mut stack = [(0u32, tree.root_cell(), 0u32); STACK];
    let subjects = coverage.subjects(triangles);
    (0..u32::try_from(subjects).unwrap_or(u32::MAX)).find(|&i| {
        let Some((tri, t)) = coverage.subject(i) else {
            return true;
        };
        let bounds = t.bounds();
        let Some(root) = stack.first_mut() else {
            return true;
        };
        *root = (0, tree.root_cell(), 0);
        let mut top = 1usize;
        while let Some((node, cell, depth)) = top.checked_sub(1).and_then(|i| stack.get(i).copied())
        {
            top -= 1;
            match tree.cell_node(node) {
                Some(CellNode::Leaf { first, count }) => {
                    let (first, end) = (first as usize, first as usize + count as usize);
                    match coverage.holds(i, tri, first, end) {
                        Held::Yes => {}
                        Held::AsEarlier => return false,
                        Held::No => return true,
                    }
                }
                Some(CellNode::Inner) => tree.children(node, &cell, depth, |child, c| {
                    // Boxes apart rule a child out before the exact test: most children of a
                    // cell hold none of a small triangle.
                    if pad.grow(c.aabb()).overlaps(&bounds)
                        && pad.touches(&t, c.aabb())
                        && let Some(slot) = stack.get_mut(top)
                    {
                        *slot = (child, c, depth + 1);
                        top += 1;
                    }
                }),
                None => return true,
            }
        }
        false
    })
}

/// What a cell's references say of a coverage subject (see [`Coverage::holds`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Held {
    /// Not listed, or (packed) listed with other corners: the structure misses the subject.
    No,
    /// Listed.
    Yes,
    /// Packed: listed by an earlier slot with the same corners. That slot's walk, already
    /// proved, goes through exactly the cells this subject's would, so the subject is
    /// covered and its walk can stop: walking every slot of a triangle that many cells list
    /// in full would cost the square of their number.
    AsEarlier,
}

/// The subjects and the leaf test that prove a cell structure's coverage: what
/// [`first_uncovered_in_tree`] (or a grid's walk over its cells) needs, for a blob's indexed
/// mesh or for its packed corners.
pub(crate) struct Coverage<'m, W: Words> {
    items: W,
    mesh: CoverageMesh<'m>,
    /// Packed corners: the walk so far (subject, its triangle, the smallest slot listing it),
    /// once a walk has begun.
    current: Option<(u32, u32, usize)>,
    /// Packed corners: how many slots were the smallest listing their triangle on their own
    /// walk, and each one's triangle handed to `named` (every triangle once, in a sound blob).
    firsts: usize,
    named: &'m mut dyn FnMut(u32),
}

/// Where the corners a coverage walk starts from come from.
pub(crate) enum CoverageMesh<'m> {
    /// Triangle `i` is subject `i`.
    Triangles(&'m dyn Fn(u32) -> Option<Triangle>),
    /// Slot `i` (naming `items[i]`) is subject `i`, walked with that slot's 36 bytes of
    /// corners, which every slot listing the same triangle on the way must repeat.
    Packed(&'m [[u8; 36]]),
}

impl<'m, W: Words> Coverage<'m, W> {
    /// The coverage proof of `items` over `mesh`; with packed corners, `named` is handed the
    /// triangle of every slot that stands for its triangle (see [`Coverage::named`]).
    pub(crate) fn new(items: W, mesh: CoverageMesh<'m>, named: &'m mut dyn FnMut(u32)) -> Self {
        Self {
            items,
            mesh,
            current: None,
            firsts: 0,
            named,
        }
    }

    /// How many subjects there are, for `triangles` triangles.
    pub(crate) fn subjects(&self, triangles: usize) -> usize {
        match self.mesh {
            CoverageMesh::Triangles(_) => triangles,
            CoverageMesh::Packed(corners) => corners.len(),
        }
    }

    /// Subject `i`: its triangle and corners.
    pub(crate) fn subject(&self, i: u32) -> Option<(u32, Triangle)> {
        match self.mesh {
            CoverageMesh::Triangles(triangle) => Some((i, triangle(i)?)),
            CoverageMesh::Packed(corners) => {
                let tri = self.items.word(i as usize)?;
                Some((tri, packed_triangle(corners.get(i as usize)?)))
            }
        }
    }

    /// Whether references `first..end` hold subject `i`, triangle `tri`: list it, and (packed)
    /// with the same corners, by this slot or an earlier one (see [`Held`]). Subjects are
    /// walked in order, each one's walk stopping at its first answer other than
    /// [`Held::Yes`].
    pub(crate) fn holds(&mut self, i: u32, tri: u32, first: usize, end: usize) -> Held {
        match self.mesh {
            CoverageMesh::Triangles(_) => {
                if lists(self.items, first, end, tri) {
                    Held::Yes
                } else {
                    Held::No
                }
            }
            CoverageMesh::Packed(corners) => {
                let Some(slot) = find(self.items, first, end, tri) else {
                    return Held::No;
                };
                match &mut self.current {
                    Some((subject, _, first)) if *subject == i => *first = (*first).min(slot),
                    _ => {
                        self.finish_walk();
                        self.current = Some((i, tri, slot));
                    }
                }
                let same =
                    corners.get(slot).is_some() && corners.get(slot) == corners.get(i as usize);
                match (same, slot < i as usize) {
                    (false, _) => Held::No,
                    (true, false) => Held::Yes,
                    (true, true) => Held::AsEarlier,
                }
            }
        }
    }

    /// After a walk over every subject that found no uncovered one: how many of `triangles`
    /// triangles the subjects named (indexed: all; packed: the slots that were the smallest
    /// slot listing their triangle on their own walk, one per triangle whose slots agree; a
    /// triangle given two sets of corners in cells apart counts twice, which the triangles
    /// handed to `named`, compared with `0..triangles`, tell).
    pub(crate) fn named(mut self, triangles: usize) -> usize {
        match self.mesh {
            CoverageMesh::Triangles(_) => triangles,
            CoverageMesh::Packed(_) => {
                self.finish_walk();
                self.firsts
            }
        }
    }

    fn finish_walk(&mut self) {
        // No sentinel values: on 32-bit targets `u32::MAX as usize` is `usize::MAX`.
        let Some((subject, tri, first)) = self.current else {
            return;
        };
        if subject as usize == first {
            self.firsts += 1;
            (self.named)(tri);
        }
    }
}

/// The triangle of 36 bytes of packed corners (three little-endian `f32` points).
fn packed_triangle(bytes: &[u8; 36]) -> Triangle {
    let mut w = [0.0f32; 9];
    for (x, word) in w.iter_mut().zip(bytes.chunks_exact(4)) {
        *x = f32::from_le_bytes(word.try_into().unwrap_or([0; 4]));
    }
    let [ax, ay, az, bx, by, bz, cx, cy, cz] = w;
    Triangle::new(
        Vec3::new(ax, ay, az),
        Vec3::new(bx, by, bz),
        Vec3::new(cx, cy, cz),
    )
}
