//! Handing a cell's triangles to a query, once per triangle where the query allows.

use core::ops::ControlFlow;

use super::Mailbox;
use crate::query::{Cell, LeafTriangleIds, Visitor};

/// The leaf side of one traversal: a mailbox when the visitor lets repeats be skipped.
pub(crate) struct Offer {
    mailbox: Option<Mailbox>,
}

impl Offer {
    /// For one traversal with `visitor`.
    #[inline(always)]
    pub(crate) fn new<V: Visitor + ?Sized>(visitor: &V) -> Self {
        Self {
            mailbox: visitor.hints().skips_repeats.then(Mailbox::new),
        }
    }

    /// Offers the references `ids` of `cell` (when tracked) to `visitor` (nothing for an empty
    /// cell).
    #[inline(always)]
    pub(crate) fn cell<V: Visitor + ?Sized>(
        &mut self,
        visitor: &mut V,
        ids: LeafTriangleIds<'_>,
        cell: Option<Cell>,
    ) -> ControlFlow<()> {
        if ids.entries() == 0 {
            return ControlFlow::Continue(());
        }
        let ids = match cell {
            Some(cell) => ids.with_cell(cell),
            None => ids,
        };
        match &mut self.mailbox {
            Some(mailbox) => visitor.leaf(mailbox.filter(ids)),
            None => visitor.leaf(ids),
        }
    }
}
