//! Output files that appear whole or not at all, and never over one of the run's inputs.
//!
//! Every file the command writes goes to a temporary file in the same directory, renamed over
//! the output path only once complete and synced: a run that fails, is killed, or meets a full
//! disk leaves any earlier file at that path as it was. An output path that already names
//! something other than a file or a directory — `/dev/null`, a named pipe, a terminal — is
//! written in place instead: a rename would put a plain file where the device or pipe was.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use tempfile::NamedTempFile;

/// Refuses `output` when it names the same file (device and inode) as one of `inputs`: writing
/// it would destroy an input. Paths that do not exist yet are never the same file.
pub fn refuse_inputs(output: &Path, inputs: &[&Path]) -> Result<()> {
    for input in inputs {
        if same_file(output, input) {
            bail!(
                "{}: the output is also an input ({}); write to another path",
                output.display(),
                input.display()
            );
        }
    }
    Ok(())
}

/// Whether `a` and `b` name one file: same device and inode, read from metadata, so a pipe
/// or device is never opened (opening a FIFO would wait for a writer).
#[cfg(unix)]
fn same_file(a: &Path, b: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (std::fs::metadata(a), std::fs::metadata(b)) {
        (Ok(x), Ok(y)) => x.dev() == y.dev() && x.ino() == y.ino(),
        _ => false,
    }
}

#[cfg(not(unix))]
fn same_file(a: &Path, b: &Path) -> bool {
    same_file::is_same_file(a, b).unwrap_or(false)
}

/// A file being written: it takes the output path's place only at [`AtomicFile::commit`];
/// dropped before that, it is deleted. A device or pipe is written in place.
pub struct AtomicFile {
    out: Sink,
    path: PathBuf,
}

enum Sink {
    /// A temporary file beside the output, renamed over it at the end.
    Temp(BufWriter<NamedTempFile>),
    /// A device, pipe or socket already at the output path, written as a stream.
    Stream(BufWriter<File>),
}

impl AtomicFile {
    /// Starts writing `path`, after refusing it if it is one of `inputs`.
    pub fn create(path: &Path, inputs: &[&Path]) -> Result<Self> {
        refuse_inputs(path, inputs)?;
        if is_stream(path) {
            let file = std::fs::OpenOptions::new()
                .write(true)
                .open(path)
                .with_context(|| format!("cannot open {}", path.display()))?;
            return Ok(Self {
                out: Sink::Stream(BufWriter::with_capacity(1 << 20, file)),
                path: path.to_owned(),
            });
        }
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        let prefix = partial_prefix(path);
        remove_stale_partials(dir, &prefix);
        let temp = tempfile::Builder::new()
            .prefix(&prefix)
            .suffix(PARTIAL_SUFFIX)
            .tempfile_in(dir)
            .with_context(|| format!("cannot create a file in {}", dir.display()))?;
        // Held until this process ends, however it ends: a later run tells a partial file
        // still being written from one a killed run left behind by trying this lock.
        let _ = temp.as_file().try_lock();
        Ok(Self {
            out: Sink::Temp(BufWriter::with_capacity(1 << 20, temp)),
            path: path.to_owned(),
        })
    }

    /// Flushes, syncs and renames the file over the output path (a stream: flushes it).
    pub fn commit(self) -> Result<()> {
        let path = self.path;
        let done = (|| -> Result<()> {
            match self.out {
                Sink::Temp(out) => {
                    let temp = out.into_inner().map_err(|e| e.into_error())?;
                    set_readable(temp.as_file())?;
                    temp.as_file().sync_all()?;
                    temp.persist(&path).map_err(|e| e.error)?;
                }
                Sink::Stream(mut out) => out.flush()?,
            }
            Ok(())
        })();
        done.with_context(|| format!("cannot write {}", path.display()))
    }

    fn writer(&mut self) -> &mut dyn Write {
        match &mut self.out {
            Sink::Temp(out) => out,
            Sink::Stream(out) => out,
        }
    }
}

/// How the temporary files of a run end.
const PARTIAL_SUFFIX: &str = ".partial";

/// How the temporary files of a run writing `path` start: `.meshq-NAME-`, so that the next run
/// writing the same output finds those a killed run left.
fn partial_prefix(path: &Path) -> String {
    let name = path
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    format!(".meshq-{name}-")
}

/// Removes the temporary files in `dir` starting with `prefix` that no running process holds
/// locked: what a killed run (`kill -9`, a power cut) left behind. Files another run is still
/// writing keep their lock and are left alone; failures only leave a file in place.
fn remove_stale_partials(dir: &Path, prefix: &str) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name();
        let name = name.to_string_lossy();
        let random = name
            .strip_prefix(prefix)
            .and_then(|rest| rest.strip_suffix(PARTIAL_SUFFIX));
        // tempfile's random part: six letters or digits, nothing else.
        if !random.is_some_and(|r| r.len() == 6 && r.chars().all(|c| c.is_ascii_alphanumeric())) {
            continue;
        }
        // Only regular files (not links, and not pipes, whose opening would block).
        if !entry.file_type().is_ok_and(|t| t.is_file()) {
            continue;
        }
        let path = entry.path();
        let unlocked = File::options()
            .write(true)
            .open(&path)
            .is_ok_and(|f| f.try_lock().is_ok());
        if unlocked {
            let _ = std::fs::remove_file(&path);
        }
    }
}

/// Whether `path` (followed through symbolic links, as `/dev/stdout` is) already names
/// something that is neither a regular file nor a directory.
fn is_stream(path: &Path) -> bool {
    std::fs::metadata(path).is_ok_and(|m| !m.is_file() && !m.is_dir())
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.writer().write(buf)
    }

    fn write_all(&mut self, buf: &[u8]) -> std::io::Result<()> {
        self.writer().write_all(buf)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.writer().flush()
    }
}

/// Temporary files are private (0600); an output gets the usual 0644.
#[cfg(unix)]
fn set_readable(file: &std::fs::File) -> std::io::Result<()> {
    use std::os::unix::fs::PermissionsExt;
    file.set_permissions(std::fs::Permissions::from_mode(0o644))
}

#[cfg(not(unix))]
fn set_readable(_: &std::fs::File) -> std::io::Result<()> {
    Ok(())
}
