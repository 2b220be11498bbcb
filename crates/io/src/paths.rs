//! Paths the user names, checked before any work starts: an output file or directory must be
//! writable the way wingcheck writes it, and an input must be a regular file.
//!
//! The policy (docs/outputs.md, "Output paths"):
//! * An output is replaced by a rename (atomically), so an existing output must be what the
//!   rename would replace: a regular file for a file, a directory for a directory. A symbolic
//!   link is refused (the rename would replace the link, not what it points to; name the target
//!   itself), and so is a FIFO, a device, a socket: special files are never opened, read or
//!   replaced.
//! * The name must leave room for the hidden sibling the writer builds beside it (a staged
//!   directory is `.NAME.wingcheck-staging-PID-NANOS`, [`STAGED_NAME_OVERHEAD`] bytes more):
//!   at most [`NAME_MAX`] bytes in all.
//! * Inputs are read only from regular files (a symlink to one is fine), opened without
//!   blocking, at most a given size.
//!
//! Paths stay `OsStr` throughout: a name that is not UTF-8 is written and read as given, and
//! shown lossily only in messages.

use std::ffi::OsStr;
use std::fs::FileType;
use std::io::Read;
use std::path::{Path, PathBuf};

use crate::IoError;

/// The longest file name (bytes) wingcheck creates: Linux's `NAME_MAX` on its common file
/// systems (ext4, xfs, btrfs, tmpfs).
pub const NAME_MAX: usize = 255;

/// Bytes a staged directory's name adds to its target's ([`crate::StagingDir`]):
/// `.` + NAME + `.wingcheck-staging-` + pid (≤ 10 digits) + `-` + nanoseconds (≤ 9 digits).
pub const STAGED_NAME_OVERHEAD: usize = 1 + ".wingcheck-staging-".len() + 10 + 1 + 9;

/// What a path is, in words (`a FIFO`, `a directory`, …).
pub fn kind_of(t: FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "a FIFO (named pipe)";
        }
        if t.is_char_device() || t.is_block_device() {
            return "a device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    if t.is_symlink() {
        "a symbolic link"
    } else if t.is_dir() {
        "a directory"
    } else if t.is_file() {
        "a regular file"
    } else {
        "a special file"
    }
}

fn bad(path: &Path, reason: impl Into<String>) -> IoError {
    IoError::BadOutput { path: path.to_path_buf(), reason: reason.into() }
}

fn parent_of(p: &Path) -> PathBuf {
    match p.parent() {
        Some(q) if !q.as_os_str().is_empty() => q.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// The file name of an output, within [`NAME_MAX`] with `overhead` bytes of a sibling's name
/// (`sibling` says which, in words).
fn checked_name<'a>(path: &'a Path, overhead: usize, sibling: &str) -> Result<&'a OsStr, IoError> {
    let name = path.file_name().ok_or_else(|| bad(path, "it has no file name (it ends in `..` or is a root)"))?;
    let len = name.len();
    if len + overhead > NAME_MAX {
        let why = if overhead == 0 {
            format!("its name is {len} bytes long; file names have at most {NAME_MAX}")
        } else {
            format!(
                "its name is {len} bytes long; wingcheck writes {sibling}, whose name is {overhead} bytes longer, and \
                 file names have at most {NAME_MAX}: use a name of at most {} bytes",
                NAME_MAX - overhead
            )
        };
        return Err(bad(path, why));
    }
    Ok(name)
}

/// An existing output: `want_dir` a directory, else a regular file. A symlink is refused when
/// the output is replaced by a rename (`replaced`), else followed (a directory written into).
fn check_existing(path: &Path, want_dir: bool, replaced: bool) -> Result<(), IoError> {
    let inspect = |e| IoError::Io { action: "inspect", path: path.to_path_buf(), source: e };
    let m = match std::fs::symlink_metadata(path) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(e) => return Err(inspect(e)),
        Ok(m) if m.file_type().is_symlink() && !replaced => match std::fs::metadata(path) {
            Ok(target) => target,
            Err(e) => return Err(bad(path, format!("it is a symbolic link that cannot be followed: {e}"))),
        },
        Ok(m) => m,
    };
    let t = m.file_type();
    if t.is_symlink() {
        return Err(bad(
            path,
            "it is a symbolic link: wingcheck replaces outputs by renaming over them, which would replace the link, \
             not what it points to; name the target itself",
        ));
    }
    if want_dir && !t.is_dir() {
        return Err(bad(path, format!("it exists and is {}, not a directory", kind_of(t))));
    }
    if !want_dir && !t.is_file() {
        return Err(bad(path, format!("it exists and is {}; wingcheck writes regular files only", kind_of(t))));
    }
    Ok(())
}

/// Checks an output file before any work: a name within [`NAME_MAX`], an existing directory to
/// hold it, and nothing there but a regular file (no symlink, FIFO, device or directory).
pub fn check_output_file(path: &Path) -> Result<(), IoError> {
    check_output_file_with(path, None)
}

/// [`check_output_file`] for a file written with a sidecar beside it named NAME + `suffix`
/// (`.provenance.json`): the sidecar is checked too, and its name counts against the limit.
pub fn check_output_file_with(path: &Path, sidecar_suffix: Option<&str>) -> Result<(), IoError> {
    match sidecar_suffix {
        Some(suffix) => {
            checked_name(path, suffix.len(), &format!("its sidecar NAME{suffix} beside it"))?;
            let mut side = path.file_name().unwrap_or_default().to_os_string();
            side.push(suffix);
            check_existing(&path.with_file_name(side), false, true)?;
        }
        None => {
            checked_name(path, 0, "")?;
        }
    }
    let dir = parent_of(path);
    match std::fs::metadata(&dir) {
        Err(e) => return Err(bad(path, format!("its directory {}: {e}", dir.display()))),
        Ok(m) if !m.is_dir() => return Err(bad(path, format!("{} is not a directory", dir.display()))),
        Ok(m) if m.permissions().readonly() => {
            return Err(bad(path, format!("its directory {} is read-only", dir.display())))
        }
        Ok(_) => {}
    }
    check_existing(path, false, true)
}

/// Checks an output directory before any work: a name within [`NAME_MAX`] (with
/// [`STAGED_NAME_OVERHEAD`] when `staged`: the directory is built beside its target and swapped
/// in), nothing there but a directory (no file or special file; a symlink is refused for a
/// staged directory, which the swap would replace, and followed to a directory otherwise — a
/// search directory is written into), and a parent that is a directory where it exists
/// (missing parents are created by the writer).
pub fn check_output_dir(path: &Path, staged: bool) -> Result<(), IoError> {
    checked_name(path, if staged { STAGED_NAME_OVERHEAD } else { 0 }, "it into a hidden directory beside it")?;
    let mut dir = parent_of(path);
    // the nearest existing ancestor must be a directory
    loop {
        match std::fs::metadata(&dir) {
            Ok(m) if m.is_dir() => break,
            Ok(m) => {
                return Err(bad(path, format!("{} is {}, not a directory", dir.display(), kind_of(m.file_type()))))
            }
            Err(_) => match dir.parent() {
                Some(p) if !p.as_os_str().is_empty() => dir = p.to_path_buf(),
                _ => break,
            },
        }
    }
    check_existing(path, true, staged)
}

/// Refuses to replace `path` unless it is missing or a regular file: the writers' last check,
/// right before the rename (the pre-work check may be minutes old).
pub fn check_replaceable_file(path: &Path) -> Result<(), IoError> {
    check_existing(path, false, true)
}

/// Errors of [`read_regular`].
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    /// The file could not be opened or read.
    #[error("{0}")]
    Io(#[from] std::io::Error),
    /// Not a regular file (never opened, so a FIFO cannot block).
    #[error("it is {0}, not a regular file")]
    NotRegular(&'static str),
    /// Larger than the limit.
    #[error("it is larger than {0} bytes")]
    TooLarge(u64),
}

/// Reads a regular file (a symlink to one is followed) of at most `max_bytes`: anything else —
/// a FIFO, a device, a directory — is refused without being opened for reading (on Linux the
/// file is opened non-blocking and checked again, so a FIFO swapped in meanwhile cannot block).
pub fn read_regular(path: &Path, max_bytes: u64) -> Result<Vec<u8>, ReadError> {
    let t = std::fs::metadata(path)?.file_type();
    if !t.is_file() {
        return Err(ReadError::NotRegular(kind_of(t)));
    }
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(target_os = "linux")]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(rustix::fs::OFlags::NONBLOCK.bits() as i32);
    }
    let f = options.open(path)?;
    let t = f.metadata()?.file_type();
    if !t.is_file() {
        return Err(ReadError::NotRegular(kind_of(t)));
    }
    let mut bytes = Vec::new();
    f.take(max_bytes + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > max_bytes {
        return Err(ReadError::TooLarge(max_bytes));
    }
    Ok(bytes)
}
