//! A cursor over blob bytes that reports where decoding stopped.

use serde::Deserialize;

use crate::error::{BlobError, BlobSection};

/// Reads postcard values and fixed-size record arrays front to back.
pub(crate) struct Reader<'a> {
    rest: &'a [u8],
    offset: usize,
}

impl<'a> Reader<'a> {
    pub(crate) const fn new(bytes: &'a [u8]) -> Self {
        Self {
            rest: bytes,
            offset: 0,
        }
    }

    /// Bytes consumed so far.
    pub(crate) const fn offset(&self) -> usize {
        self.offset
    }

    /// The bytes not yet consumed.
    pub(crate) const fn rest(&self) -> &'a [u8] {
        self.rest
    }

    /// The next `n` bytes as they are.
    pub(crate) fn bytes(&mut self, n: usize, section: BlobSection) -> Result<&'a [u8], BlobError> {
        if n > self.rest.len() {
            return Err(BlobError::Truncated {
                offset: self.offset.saturating_add(self.rest.len()),
                section,
            });
        }
        let (head, tail) = self.rest.split_at(n);
        self.rest = tail;
        self.offset = self.offset.saturating_add(n);
        Ok(head)
    }

    /// One postcard value.
    pub(crate) fn value<T: Deserialize<'a>>(
        &mut self,
        section: BlobSection,
    ) -> Result<T, BlobError> {
        match postcard::take_from_bytes::<T>(self.rest) {
            Ok((value, tail)) => {
                let used = self.rest.len().saturating_sub(tail.len());
                self.rest = tail;
                self.offset = self.offset.saturating_add(used);
                Ok(value)
            }
            Err(postcard::Error::DeserializeUnexpectedEnd) => Err(BlobError::Truncated {
                offset: self.offset.saturating_add(self.rest.len()),
                section,
            }),
            Err(_) => Err(BlobError::Malformed {
                offset: self.offset,
                section,
            }),
        }
    }

    /// A postcard sequence of `N`-byte records whose length must be `expected`, returned in
    /// place.
    #[inline(always)]
    pub(crate) fn records<const N: usize>(
        &mut self,
        expected: u32,
        section: BlobSection,
    ) -> Result<&'a [[u8; N]], BlobError> {
        let (records, _) = self
            .record_bytes(expected, N, false, section)?
            .as_chunks::<N>();
        Ok(records)
    }

    /// [`records`](Self::records), where an `optional` sequence may also be empty.
    #[inline(always)]
    pub(crate) fn records_maybe<const N: usize>(
        &mut self,
        expected: u32,
        optional: bool,
        section: BlobSection,
    ) -> Result<&'a [[u8; N]], BlobError> {
        let (records, _) = self
            .record_bytes(expected, N, optional, section)?
            .as_chunks::<N>();
        Ok(records)
    }

    /// The bytes of [`records`](Self::records) (`expected` records of `size` bytes): one body
    /// for every record size, which keeps the firmware's code small.
    #[inline(never)]
    fn record_bytes(
        &mut self,
        expected: u32,
        size: usize,
        optional: bool,
        section: BlobSection,
    ) -> Result<&'a [u8], BlobError> {
        let found: u32 = self.value(section)?;
        if found != expected && !(optional && found == 0) {
            return Err(BlobError::CountMismatch {
                section,
                expected: expected.into(),
                found: found.into(),
            });
        }
        let len = usize::try_from(found)
            .ok()
            .and_then(|n| n.checked_mul(size))
            .ok_or(BlobError::TooLarge)?;
        self.bytes(len, section)
    }
}
