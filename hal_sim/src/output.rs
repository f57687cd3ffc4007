//! Output files, written so that a failure leaves nothing half written
//! and no link is ever followed.

#[allow(unused_imports)] // EXIT_IO: named in the docs
use crate::error::{io, CliError, EXIT_IO};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Tries at most this many temporary names before giving up.
const TEMP_TRIES: u32 = 1000;

/// What a path that exists is, when it is not a regular file.
fn special_kind(t: std::fs::FileType) -> Option<&'static str> {
    if t.is_file() {
        return None;
    }
    if t.is_symlink() {
        return Some("a symbolic link");
    }
    if t.is_dir() {
        return Some("a directory");
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_char_device() {
            return Some("a character device");
        }
        if t.is_block_device() {
            return Some("a block device");
        }
        if t.is_fifo() {
            return Some("a fifo");
        }
        if t.is_socket() {
            return Some("a socket");
        }
    }
    Some("not a regular file")
}

/// Creates a new temporary file next to `path`, named
/// `.NAME.PID.N.tmp`: `create_new` never follows a link or opens a file
/// that is already there, so a name that is taken (by anything, a planted
/// link too) is skipped for the next `N`.
fn create_temp(path: &Path) -> Result<(std::fs::File, PathBuf), CliError> {
    let name = path
        .file_name()
        .ok_or_else(|| io(path, "not a file name"))?;
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    // The name only helps to recognise a leftover: a readable part is
    // enough, and keeps the temporary name within the system's limit.
    let stem: String = name.to_string_lossy().chars().take(64).collect();
    let pid = std::process::id();
    for n in 0..TEMP_TRIES {
        let tmp = dir.join(format!(".{stem}.{pid}.{n}.tmp"));
        match std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)
        {
            Ok(f) => return Ok((f, tmp)),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(io(path, e)),
        }
    }
    Err(io(
        path,
        format_args!("no free temporary name after {TEMP_TRIES} tries"),
    ))
}

/// The permissions a file that replaces one with `old` gets: its access
/// bits (read, write, execute for owner, group and others), not the
/// set-user-ID, set-group-ID or sticky bits.
fn kept_permissions(old: std::fs::Permissions) -> std::fs::Permissions {
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::Permissions::from_mode(old.mode() & 0o777)
    }
    #[cfg(not(unix))]
    {
        old
    }
}

/// Writes `bytes` to `path`, safely: into a new temporary file next to it,
/// then renamed over it, so that a failed write leaves no partial output
/// and no link is ever followed. A destination that exists and is not a
/// regular file (a symbolic link to anything, a directory, a device, a
/// fifo) is refused and left as it is. A regular file that is replaced
/// keeps its access mode (a file of mode 600 stays 600): the temporary
/// file gets it before anything is written into it. Every failure is an
/// [`EXIT_IO`] error naming `path`; the temporary file is removed.
pub(crate) fn write_output(path: &Path, bytes: &[u8]) -> Result<(), CliError> {
    let mut keep = None;
    match std::fs::symlink_metadata(path) {
        Ok(m) => {
            if let Some(kind) = special_kind(m.file_type()) {
                return Err(io(
                    path,
                    format_args!("is {kind}, not a regular file; refusing to replace it"),
                ));
            }
            keep = Some(kept_permissions(m.permissions()));
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
        Err(e) => return Err(io(path, e)),
    }
    let (mut file, tmp) = create_temp(path)?;
    let written = match keep {
        Some(mode) => file.set_permissions(mode),
        None => Ok(()),
    }
    .and_then(|()| file.write_all(bytes))
    .and_then(|()| file.sync_all());
    drop(file);
    // `rename` replaces the name `path`: were a link put there meanwhile,
    // the link would be replaced, not followed.
    written
        .and_then(|()| std::fs::rename(&tmp, path))
        .map_err(|e| {
            let _ = std::fs::remove_file(&tmp);
            io(path, e)
        })
}
