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
