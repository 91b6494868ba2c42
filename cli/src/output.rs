//! Printing results: every write to standard output is checked, so a closed pipe or a full
//! disk becomes an error the command reports (see `main`), never a panic.

use anyhow::Result;
use serde::Serialize;

/// Like `println!`, but a failed write returns the error (tagged as standard output's) from
/// the enclosing function, which must return `anyhow::Result`.
macro_rules! say {
    () => {
        $crate::output::checked(::std::io::Write::write_all(&mut ::std::io::stdout().lock(), b"\n"))?
    };
    ($($arg:tt)*) => {
        $crate::output::checked(::std::io::Write::write_fmt(
            &mut ::std::io::stdout().lock(),
            format_args!("{}\n", format_args!($($arg)*)),
        ))?
    };
}
pub(crate) use say;

/// A write to standard output failed.
#[derive(Debug)]
pub struct StdoutError(pub std::io::Error);

impl std::fmt::Display for StdoutError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "cannot write to standard output: {}", self.0)
    }
}

impl std::error::Error for StdoutError {}

/// `result` with its error marked as standard output's.
pub fn checked(result: std::io::Result<()>) -> Result<(), StdoutError> {
    result.map_err(StdoutError)
}

/// Prints `value` as one line of JSON on stdout.
pub fn json<T: Serialize>(value: &T) -> Result<()> {
    say!("{}", serde_json::to_string(value)?);
    Ok(())
}
