//! Walking a k-d tree: rays front to back through the cells they cross, other queries nearest
//! cell first.

use core::ops::ControlFlow;

use super::{KdConfig, KdKind, KdTree};
use crate::cells::{Offer, Region, Untracked, Words};
use crate::geom::SlabRay;
use crate::math::Ray;
use crate::query::{Cell, Traverse, Visitor};

/// Relative slack on ray parameters, as the query layer's box tests use: a cell is entered when
/// the ray might reach it within rounding.
const MARGIN: f32 = 1.0 / 65_536.0;

/// Deferred cells: one per level at most.
const STACK: usize = KdConfig::MAX_DEPTH as usize + 2;

impl<N: Words, W: Words> Traverse for KdTree<N, W> {
    fn traverse<V: Visitor + ?Sized>(&self, visitor: &mut V) {
        let mut offer = Offer::new(visitor);
        match visitor.ray().copied() {
            // Ray queries rarely read cells: only work them out for a visitor that does.
            Some(ray) if visitor.hints().needs_cells => {
                self.march::<V, Cell, false>(&ray, visitor, &mut offer);
            }
            Some(ray) => self.march::<V, Untracked, false>(&ray, visitor, &mut offer),
            None => self.descend(visitor, &mut offer),
        }
    }
}

/// Component `axis` (0, 1, anything else 2) of `v`.
#[inline(always)]
fn component(v: [f32; 3], axis: usize) -> f32 {
    let [x, y, z] = v;
    match axis {
        0 => x,
        1 => y,
        _ => z,
    }
}

impl<N: Words, W: Words> KdTree<N, W> {
    /// Offers a leaf's references; `Break` when the visitor ends the walk.
    #[inline(always)]
    fn visit<V: Visitor + ?Sized>(
        &self,
        first: u32,
        count: u32,
        cell: Option<Cell>,
        visitor: &mut V,
        offer: &mut Offer,
    ) -> ControlFlow<()> {
        match self.items.ids(first as usize, count as usize) {
            Some(ids) => offer.cell(visitor, ids, cell),
            None => ControlFlow::Continue(()),
        }
    }

    /// Front to back along `ray`: at each plane the span `(t_near, t_far)` is cut where the ray
    /// crosses it; the near side is walked now, the far side deferred with its own span. After
    /// a leaf, the next deferred cell is entered only if the visitor's answer does not already
    /// lie before it (`revisit` of its `t_near`): a hit inside the current cell ends the walk,
    /// one beyond it does not. `R` is what is kept of each cell (the cell, or nothing).
    ///
    /// Plane crossings are found with the slab test's padded reciprocal direction and widened
    /// by [`MARGIN`], so a span never loses a point the ray reaches within rounding.
    ///
    /// `EXIT_ON_ANY_HIT` replaces that rule by "stop once anything was hit" — wrong, kept only
    /// so a test can show the suites catch it.
    pub(super) fn march<V: Visitor + ?Sized, R: Region, const EXIT_ON_ANY_HIT: bool>(
        &self,
        ray: &Ray,
        visitor: &mut V,
        offer: &mut Offer,
    ) {
        let b = self.bounds;
        let slab = SlabRay::new(ray);
        let (entry, exit) = slab.clip(b.min.to_array(), b.max.to_array());
        let (t0, t1) = (entry - entry.abs() * MARGIN, exit + exit.abs() * MARGIN);
        if !(t0 <= t1) {
            return;
        }
        let (o, d, inv) = (
            ray.origin.to_array(),
            ray.dir.to_array(),
            slab.inv_dir.to_array(),
        );
        let root = R::root(b);
        let Some(root_node) = self.node(0) else {
            return;
        };
        let mut stack = [(root_node, t0, t1, root); STACK];
        let mut top = 0usize;
        let mut current = Some((root_node, t0, t1, root));
        loop {
            let Some((mut node, near_t, mut far_t, mut cell)) = current.take().or_else(|| {
                top = top.checked_sub(1)?;
                stack.get(top).copied()
            }) else {
                return;
            };
            if !visitor.revisit(near_t) {
                // Deferred cells come off the stack nearest first: none further can help.
                return;
            }
            loop {
                match node.kind() {
                    KdKind::Leaf { first, count } => {
                        if self
                            .visit(first, count, cell.cell(), visitor, offer)
                            .is_break()
                        {
                            return;
                        }
                        if EXIT_ON_ANY_HIT && !visitor.revisit(f32::MAX) {
                            return;
                        }
                        break;
                    }
                    KdKind::Inner {
                        axis,
                        split,
                        first_child,
                    } => {
                        // Both children are read before the ray decides between them: they
                        // share a cache line, and the loads overlap the arithmetic.
                        let (Some(lower), Some(upper)) = (
                            self.node(first_child as usize),
                            self.node(first_child as usize + 1),
                        ) else {
                            break;
                        };
                        let (oa, da) = (component(o, axis), component(d, axis));
                        let low_first = oa < split || (oa == split && da <= 0.0);
                        let (visit_near, visit_far, cut_lo, cut_hi) = if da == 0.0 {
                            // Parallel to the plane: only the origin's side, or both when the
                            // ray lies in the plane.
                            (true, oa == split, near_t, far_t)
                        } else {
                            // The plane lies ahead when the ray moves toward the far side;
                            // behind the origin, only the near side is reached.
                            let ahead = (da < 0.0) != low_first;
                            let ts = (split - oa) * component(inv, axis);
                            let slack = ts.abs() * MARGIN;
                            (
                                !ahead || ts + slack >= near_t,
                                ahead && ts - slack <= far_t,
                                ts - slack,
                                ts + slack,
                            )
                        };
                        let (below, above) = cell.split(axis, split);
                        let (near, far) = if low_first {
                            ((lower, below), (upper, above))
                        } else {
                            ((upper, above), (lower, below))
                        };
                        // Written without branching on which sides are visited (the ray's
                        // path is unpredictable): the far side is always stored and kept only
                        // when both are visited.
                        let both = visit_near && visit_far;
                        if let Some(slot) = stack.get_mut(top) {
                            *slot = (far.0, near_t.max(cut_lo), far_t, far.1);
                            top += usize::from(both);
                        }
                        (node, cell) = if visit_near { near } else { far };
                        far_t = if both { far_t.min(cut_hi) } else { far_t };
                    }
                }
            }
        }
    }

    /// Nearest cell first for queries without a ray: both children entered through their cell
    /// boxes, the one with the smaller key walked now, the other deferred.
    fn descend<V: Visitor + ?Sized>(&self, visitor: &mut V, offer: &mut Offer) {
        let root = Cell::root(self.bounds);
        let Some(key) = visitor.enter(root.aabb()) else {
            return;
        };
        let mut stack = [(0u32, 0.0f32, root); STACK];
        let mut top = 0usize;
        let mut current = Some((0u32, key, root));
        loop {
            let Some((mut node, key, mut cell)) = current.take().or_else(|| {
                top = top.checked_sub(1)?;
                stack.get(top).copied()
            }) else {
                return;
            };
            if !visitor.revisit(key) {
                continue;
            }
            loop {
                match self.node(node as usize).map(|n| n.kind()) {
                    Some(KdKind::Leaf { first, count }) => {
                        if self
                            .visit(first, count, Some(cell), visitor, offer)
                            .is_break()
                        {
                            return;
                        }
                        break;
                    }
                    Some(KdKind::Inner {
                        axis,
                        split,
                        first_child,
                    }) => {
                        let (below, above) = cell.split(axis, split);
                        let kb = visitor.enter(below.aabb());
                        let ka = visitor.enter(above.aabb());
                        let pick = match (kb, ka) {
                            (Some(b), Some(a)) => {
                                let (near, far) = if a < b {
                                    ((first_child + 1, above), (first_child, b, below))
                                } else {
                                    ((first_child, below), (first_child + 1, a, above))
                                };
                                if let Some(slot) = stack.get_mut(top) {
                                    *slot = far;
                                    top += 1;
                                }
                                Some(near)
                            }
                            (Some(_), None) => Some((first_child, below)),
                            (None, Some(_)) => Some((first_child + 1, above)),
                            (None, None) => None,
                        };
                        match pick {
                            Some(next) => (node, cell) = next,
                            None => break,
                        }
                    }
                    None => break,
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::kdtree::{KdConfig, KdNode};
    use crate::mesh::MeshRef;
    use crate::query::MeshQuery;

    /// The k-d tree walked with the wrong early exit: stop after the first leaf that produced
    /// any hit, wherever that hit lies.
    struct ExitOnAnyHit<'a>(KdTree<&'a [KdNode], &'a [u32]>);

    impl Traverse for ExitOnAnyHit<'_> {
        fn traverse<V: Visitor + ?Sized>(&self, visitor: &mut V) {
            let mut offer = Offer::new(visitor);
            if let Some(ray) = visitor.ray().copied() {
                self.0.march::<V, Cell, true>(&ray, visitor, &mut offer);
            }
        }
    }

    /// A ray along +x meets a long sloping triangle first in cells before a row of walls, but
    /// hits it only at x = 20, behind the first wall (x = 10.5). The hit found in the first
    /// cells lies outside them, so the walk must go on: the correct rule finds the wall, the
    /// mutant stops at the slope. (The integration suite runs this scene against brute force,
    /// so the mutant would fail it.)
    #[test]
    fn stopping_at_a_hit_outside_the_cell_gives_a_wrong_answer() {
        let mut positions = vec![
            [-1.0, -100.0, 0.71],
            [200.0, -100.0, -1.29],
            [-1.0, 100.0, 0.71],
        ];
        let mut triangles = vec![[0u32, 1, 2]];
        for i in 0..21 {
            let x = 10.5 + i as f32;
            let v = positions.len() as u32;
            positions.extend([[x, 0.0, 0.0], [x, 1.0, 0.0], [x, 1.0, 1.0], [x, 0.0, 1.0]]);
            triangles.extend([[v, v + 1, v + 2], [v, v + 2, v + 3]]);
        }
        let mesh = MeshRef::new(&positions, &triangles).validate().unwrap();
        let mut work = vec![0; 64 * triangles.len()];
        let sizes = KdTree::measure(&mesh, &KdConfig::default(), &mut work).unwrap();
        let mut nodes = vec![KdNode::default(); sizes.nodes];
        let mut items = vec![0; sizes.work];
        let tree = KdTree::build(&mesh, &KdConfig::default(), &mut nodes, &mut items).unwrap();
        assert!(
            tree.node_count() > 3,
            "the scene must be split into several cells"
        );
        let ray = crate::math::Ray::new(Vec3::new(0.0, 0.5, 0.5), Vec3::X);
        let right = tree.with(&mesh).raycast(&ray).unwrap();
        assert_eq!((right.t, right.tri), (10.5, 1));
        let wrong = ExitOnAnyHit(tree).with(&mesh).raycast(&ray).unwrap();
        assert_eq!(
            wrong.tri, 0,
            "the mutant stops at the slope, behind the wall"
        );
    }
}
