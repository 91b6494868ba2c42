//! Raw little-endian record files: streamed in chunks so files of any size use bounded memory.

use std::fs::File;
use std::io::{BufReader, BufWriter, Read, Write};
use std::path::Path;

use anyhow::{Context, Result, bail};

/// Reads a headerless file of `f32` records, `floats` per record, a chunk at a time.
pub struct RecordReader {
    file: BufReader<File>,
    floats: usize,
    /// Records in the file.
    pub count: u64,
    bytes: Vec<u8>,
}

impl RecordReader {
    /// Opens `path` and checks its length is a whole number of records. `what` names the
    /// records in errors ("ray", "point").
    pub fn open(path: &Path, floats: usize, what: &str) -> Result<Self> {
        let file = File::open(path).with_context(|| format!("cannot open {}", path.display()))?;
        let len = file.metadata()?.len();
        let record = 4 * floats as u64;
        if len % record != 0 {
            bail!(
                "bad {what} file length: {} is {len} bytes, not a multiple of {record} ({floats} float32 per {what})",
                path.display()
            );
        }
        Ok(Self {
            file: BufReader::with_capacity(1 << 20, file),
            floats,
            count: len / record,
            bytes: Vec::new(),
        })
    }

    /// Reads up to `max` records into `out` (cleared first); returns how many. 0 at the end.
    pub fn next_chunk(&mut self, max: usize, out: &mut Vec<f32>) -> Result<usize> {
        out.clear();
        self.bytes.resize(max * self.floats * 4, 0);
        let mut filled = 0;
        while filled < self.bytes.len() {
            let n = self.file.read(&mut self.bytes[filled..])?;
            if n == 0 {
                break;
            }
            filled += n;
        }
        let whole = filled / (self.floats * 4) * self.floats * 4;
        if whole != filled {
            bail!("the file changed length while being read");
        }
        let (words, _) = self.bytes[..whole].as_chunks::<4>();
        out.extend(words.iter().map(|w| f32::from_le_bytes(*w)));
        Ok(whole / (self.floats * 4))
    }
}

/// Writes 8-byte result records: a little-endian `f32` then a little-endian `u32`.
pub struct ResultWriter {
    file: BufWriter<File>,
}

impl ResultWriter {
    pub fn create(path: &Path) -> Result<Self> {
        let file =
            File::create(path).with_context(|| format!("cannot create {}", path.display()))?;
        Ok(Self {
            file: BufWriter::with_capacity(1 << 20, file),
        })
    }

    pub fn write(&mut self, value: f32, index: u32) -> Result<()> {
        self.file.write_all(&value.to_le_bytes())?;
        self.file.write_all(&index.to_le_bytes())?;
        Ok(())
    }

    pub fn finish(mut self) -> Result<()> {
        self.file.flush()?;
        Ok(())
    }
}
