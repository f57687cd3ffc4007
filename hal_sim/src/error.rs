//! The command-line program's failures: what to tell the user, and the
//! exit status. Shared by [`cli`](crate::cli) and [`demo`](crate::demo),
//! which both report through it.

use std::fmt;
use std::path::Path;

/// Exit status for bad input (a scene that cannot be read or rendered).
pub const EXIT_INPUT: u8 = 1;
/// Exit status for a bad command line.
pub const EXIT_USAGE: u8 = 2;
/// Exit status for a failure to write the output.
pub const EXIT_IO: u8 = 3;

/// A failure of the program, with its exit status.
#[derive(Debug)]
pub struct CliError {
    /// Exit status.
    pub status: u8,
    /// What to tell the user.
    pub message: String,
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

/// A path as it may be shown on a terminal: every character that is not
/// printable escaped.
pub(crate) fn shown(path: &Path) -> String {
    crate::text::escape_for_terminal(&path.display().to_string())
}

/// Bad input at `path`: [`EXIT_INPUT`], the message after the file name.
pub(crate) fn input(path: &Path, msg: impl fmt::Display) -> CliError {
    CliError {
        status: EXIT_INPUT,
        message: format!("{}: {msg}", shown(path)),
    }
}

/// A failure to read or write `path`: [`EXIT_IO`].
pub(crate) fn io(path: &Path, e: impl fmt::Display) -> CliError {
    CliError {
        status: EXIT_IO,
        message: format!("{}: {e}", shown(path)),
    }
}
