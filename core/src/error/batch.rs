//! The error of batched queries.

use core::fmt;

/// Which caller buffer a [`BatchError::BufferTooSmall`] is about.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BatchBuffer {
    /// The answers, one per query.
    Results,
    /// The sort keys, one `u64` per query.
    SortKeys,
}

/// Why a batched query did not run. Nothing was written to any buffer.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BatchError {
    /// A caller buffer holds fewer elements than the batch has queries. Fix: give it at least
    /// one element per query.
    BufferTooSmall {
        /// Which buffer.
        buffer: BatchBuffer,
        /// Elements needed (the number of queries).
        needed: usize,
        /// Elements given.
        got: usize,
    },
    /// More than `u32::MAX` queries in one batch (their order is kept in 32 bits). Fix: split
    /// the batch.
    TooLarge,
}

impl fmt::Display for BatchError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::BufferTooSmall {
                buffer,
                needed,
                got,
            } => {
                let which = match buffer {
                    BatchBuffer::Results => "result",
                    BatchBuffer::SortKeys => "sort key",
                };
                write!(f, "{which} buffer too small: needed {needed}, got {got}")
            }
            Self::TooLarge => f.write_str("more than 2^32 - 1 queries in one batch"),
        }
    }
}

impl core::error::Error for BatchError {}
