//! Raw little-endian record files: streamed in chunks so files of any size use bounded memory.

use std::fs::File;
use std::io::{BufReader, Read, Write};
use std::path::Path;

use anyhow::{Context, Result, bail};

use crate::atomic::AtomicFile;

/// Reads a headerless file of `f32` records, `floats` per record, a chunk at a time. Regular
/// files are checked for a whole number of records up front; pipes and other streams
/// (`/dev/stdin`) are read to their end, and a partial record at the end is an error.
pub struct RecordReader {
    file: BufReader<File>,
    floats: usize,
    /// Records in the file, when its length is known before reading (a regular file).
    pub expected: Option<u64>,
    /// Records read so far: all of them once [`RecordReader::next_chunk`] has returned 0.
    pub count: u64,
    what: String,
    path: String,
    bytes: Vec<u8>,
}

impl RecordReader {
    /// Opens `path`; a regular file's length must be a whole number of records. `what` names
    /// the records in errors ("ray", "point").
    pub fn open(path: &Path, floats: usize, what: &str) -> Result<Self> {
        let file = File::open(path).with_context(|| format!("cannot open {}", path.display()))?;
        let meta = file.metadata()?;
        let record = 4 * floats as u64;
        let expected = if meta.is_file() {
            let len = meta.len();
            if len % record != 0 {
                bail!(
                    "bad {what} file length: {} is {len} bytes, not a multiple of {record} ({floats} float32 per {what})",
                    path.display()
                );
            }
            Some(len / record)
        } else {
            None
        };
        Ok(Self {
            file: BufReader::with_capacity(1 << 20, file),
            floats,
            expected,
            count: 0,
            what: what.to_owned(),
            path: path.display().to_string(),
            bytes: Vec::new(),
        })
    }

    /// Reads up to `max` records into `out` (cleared first); returns how many. 0 at the end.
    pub fn next_chunk(&mut self, max: usize, out: &mut Vec<f32>) -> Result<usize> {
        out.clear();
        let record = self.floats * 4;
        // A file of known length needs a buffer no larger than what is left of it (one record
        // more, so that a file that grew is still caught): a small file is not given a whole
        // chunk's zeroed megabytes.
        let left = self
            .expected
            .map_or(u64::MAX, |e| e.saturating_sub(self.count) + 1);
        let max = usize::try_from(left).map_or(max, |left| max.min(left));
        self.bytes.resize(max * record, 0);
        let mut filled = 0;
        while filled < self.bytes.len() {
            let n = match self.file.read(&mut self.bytes[filled..]) {
                Ok(n) => n,
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
                Err(e) => return Err(e).with_context(|| format!("cannot read {}", self.path)),
            };
            if n == 0 {
                break;
            }
            filled += n;
        }
        let whole = filled / record * record;
        if whole != filled {
            bail!(
                "{}: ends inside {} {} (after {} whole ones, {} bytes of the next)",
                self.path,
                if self.what.starts_with(['a', 'e', 'i', 'o', 'u']) {
                    "an"
                } else {
                    "a"
                },
                self.what,
                self.count + (whole / record) as u64,
                filled - whole
            );
        }
        let (words, _) = self.bytes[..whole].as_chunks::<4>();
        out.extend(words.iter().map(|w| f32::from_le_bytes(*w)));
        let records = whole / record;
        self.count += records as u64;
        if self.expected.is_some_and(|e| self.count > e) {
            bail!("{}: the file grew while being read", self.path);
        }
        Ok(records)
    }
}

/// Writes 8-byte result records: a little-endian `f32` then a little-endian `u32`, into a file
/// that replaces the output path only when [`ResultWriter::finish`] succeeds.
pub struct ResultWriter {
    file: AtomicFile,
}

impl ResultWriter {
    /// Starts the output `path`, refused when it is one of `inputs`.
    pub fn create(path: &Path, inputs: &[&Path]) -> Result<Self> {
        Ok(Self {
            file: AtomicFile::create(path, inputs)?,
        })
    }

    pub fn write(&mut self, value: f32, index: u32) -> Result<()> {
        self.file.write_all(&value.to_le_bytes())?;
        self.file.write_all(&index.to_le_bytes())?;
        Ok(())
    }

    /// Appends little-endian `f32`s (the extra fields of longer records).
    pub fn write_f32s(&mut self, values: &[f32]) -> Result<()> {
        for v in values {
            self.file.write_all(&v.to_le_bytes())?;
        }
        Ok(())
    }

    pub fn finish(self) -> Result<()> {
        self.file.commit()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A file of `n` records of two floats each, record `i` holding `(i, -i)`, in a fresh
    /// directory under the system's temporary one.
    fn records_file(name: &str, n: u32) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("meshq-records-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(name);
        let bytes: Vec<u8> = (0..n)
            .flat_map(|i| [i as f32, -(i as f32)])
            .flat_map(f32::to_le_bytes)
            .collect();
        std::fs::write(&path, bytes).unwrap();
        path
    }

    /// Every record comes back once, in order, whatever the chunk size against the file's
    /// length (smaller, equal, larger), and the buffer never outgrows what is left of the file.
    #[test]
    fn chunks_read_every_record_once() {
        for (n, chunk) in [(0, 4), (1, 4), (7, 3), (9, 3), (5, 100), (100, 100)] {
            let path = records_file(&format!("r{n}-{chunk}"), n);
            let mut reader = RecordReader::open(&path, 2, "pair").unwrap();
            assert_eq!(reader.expected, Some(u64::from(n)));
            let (mut floats, mut all) = (Vec::new(), Vec::new());
            loop {
                let got = reader.next_chunk(chunk, &mut floats).unwrap();
                assert!(got <= chunk);
                assert_eq!(floats.len(), 2 * got);
                assert!(reader.bytes.len() <= 8 * (n as usize + 1).min(chunk));
                if got == 0 {
                    break;
                }
                all.extend_from_slice(&floats);
            }
            let want: Vec<f32> = (0..n).flat_map(|i| [i as f32, -(i as f32)]).collect();
            assert_eq!(all, want, "{n} records in chunks of {chunk}");
            assert_eq!(reader.count, u64::from(n));
        }
    }

    #[test]
    fn a_partial_record_is_refused() {
        let path = records_file("partial", 3);
        let mut bytes = std::fs::read(&path).unwrap();
        bytes.pop();
        std::fs::write(&path, bytes).unwrap();
        let err = RecordReader::open(&path, 2, "pair").err().unwrap();
        assert!(err.to_string().contains("not a multiple of 8"), "{err}");
    }
}
