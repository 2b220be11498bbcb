//! Outputs that never lose the previous result: the one atomic file write and the one atomic
//! directory replacement of wingcheck, used by `report` and `certify`.
//!
//! * [`write_file_atomic`]: temp file in the destination's directory, `fsync`, rename over the
//!   destination, `fsync` of the directory; mode 0644. [`create_file_atomic`] creates a file
//!   that must not exist yet, [`FileSet`] commits several files; the same discipline
//!   (module `atomic`), used by `report`, `certify`, `simulate` and `search`.
//! * [`StagingDir`]: a directory is built beside its target (same parent, so no rename crosses
//!   file systems) and [`StagingDir::commit`] swaps it in. On Linux the swap is one
//!   `renameat2(RENAME_EXCHANGE)` (via rustix): at every instant the target holds either the
//!   complete old or the complete new directory. Elsewhere, or on file systems without
//!   exchange, the fallback renames the old directory aside, renames the new one in and deletes
//!   the old one; a crash between the two renames leaves the old directory under a hidden name,
//!   and the next [`StagingDir::new`] for the same target puts it back.
//! * An existing target is replaced only after the caller's ownership check (the tool never
//!   deletes files it did not write; see [`only_listed_files`]). Staging and set-aside
//!   directories of dead processes for the same target are removed (or restored) by
//!   [`StagingDir::new`]. A staging directory's writer is alive while it holds its lock in the
//!   parent directory ([`DirLock`], a file lock: no `/proc` look-up, no reused-pid confusion).

#![warn(missing_docs)]

mod allocator;
mod atomic;
pub mod clock;
mod lock;
pub mod marked;
mod number;
pub mod panics;
pub mod paths;
pub mod prose;
mod provenance;
mod table;

pub use allocator::{tune_allocator, HEAP_LIMITS};
use atomic::set_mode_0644;
pub use atomic::{create_file_atomic, is_temp, remove_stale_temps, write_file_atomic, FileSet, StagedFile};
pub use lock::{is_lock_file, lock_name, lock_owner, owner_alive, remove_stale_locks, DirLock};
pub use marked::{check_marked_replaceable, write_marked_dir};
pub use number::{number, push_number};
pub use panics::{catch, Panicked};
pub use paths::{check_output_dir, check_output_file, check_output_file_with, read_regular, ReadError};
pub use provenance::{
    build, set_build, sha256_hex, sidecar_path, BuildInfo, FileRecord, Provenance, TreeState, SCHEMA_VERSION,
    SIDECAR_SUFFIX,
};
pub use table::{column_name, csv_numbers, csv_record, csv_text, grid_number, is_column_name, key_column, CsvWriter};

use std::collections::BTreeSet;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::{SystemTime, UNIX_EPOCH};

/// Errors of atomic writes and directory replacement.
#[derive(Debug, thiserror::Error)]
pub enum IoError {
    /// A file-system operation failed.
    #[error("cannot {action} {path}: {source}")]
    Io {
        /// What was being done.
        action: &'static str,
        /// On which path.
        path: PathBuf,
        /// The OS error.
        source: std::io::Error,
    },
    /// The target holds files this tool did not write; nothing was replaced.
    #[error("refusing to replace {path}: it holds files wingcheck did not write ({files}); move them away or choose another --out")]
    Foreign {
        /// The target.
        path: PathBuf,
        /// Some of the foreign files (comma-separated).
        files: String,
    },
    /// The target is not a directory or has no usable file name.
    #[error("{path} cannot be used as an output directory: {reason}")]
    BadTarget {
        /// The target.
        path: PathBuf,
        /// Why.
        reason: String,
    },
    /// [`create_file_atomic`] found its destination already there (left untouched).
    #[error("{path} already exists")]
    Exists {
        /// The destination.
        path: PathBuf,
    },
    /// An output path that cannot be written the way wingcheck writes (see [`paths`]).
    #[error("{path} cannot be used as an output: {reason}")]
    BadOutput {
        /// The path as given.
        path: PathBuf,
        /// Why.
        reason: String,
    },
}

fn io<'a>(action: &'static str, path: &'a Path) -> impl FnOnce(std::io::Error) -> IoError + 'a {
    move |source| IoError::Io { action, path: path.to_path_buf(), source }
}

fn parent_of(p: &Path) -> PathBuf {
    match p.parent() {
        Some(q) if !q.as_os_str().is_empty() => q.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// The file-system steps of a directory swap, replaceable for fault-injection tests.
pub trait DirOps {
    /// Atomically exchanges `a` and `b`; `Ok(false)` if the platform or file system cannot.
    fn exchange(&self, a: &Path, b: &Path) -> std::io::Result<bool>;
    /// `rename(from, to)`.
    fn rename(&self, from: &Path, to: &Path) -> std::io::Result<()>;
}

/// The real file system: `renameat2(RENAME_EXCHANGE)` on Linux, plain `rename` elsewhere.
#[derive(Debug, Clone, Copy, Default)]
pub struct SystemOps;

impl DirOps for SystemOps {
    #[cfg(target_os = "linux")]
    fn exchange(&self, a: &Path, b: &Path) -> std::io::Result<bool> {
        use rustix::fs::{renameat_with, RenameFlags, CWD};
        match renameat_with(CWD, a, CWD, b, RenameFlags::EXCHANGE) {
            Ok(()) => Ok(true),
            Err(e) if e == rustix::io::Errno::INVAL || e == rustix::io::Errno::NOSYS => Ok(false),
            Err(e) => Err(e.into()),
        }
    }
    #[cfg(not(target_os = "linux"))]
    fn exchange(&self, _a: &Path, _b: &Path) -> std::io::Result<bool> {
        Ok(false)
    }
    fn rename(&self, from: &Path, to: &Path) -> std::io::Result<()> {
        std::fs::rename(from, to)
    }
}

const STAGING_TAG: &str = "wingcheck-staging";
const OLD_TAG: &str = "wingcheck-old";

fn unique_suffix() -> String {
    let nanos = SystemTime::now().duration_since(UNIX_EPOCH).map(|d| d.subsec_nanos()).unwrap_or(0);
    format!("{}-{nanos}", std::process::id())
}

/// The hidden sibling name `.{name}.{tag}-{suffix}` of `target` (bytes of the name as given:
/// a name that is not UTF-8 keeps its bytes).
fn sibling_name(target: &Path, tag: &str, suffix: &str) -> Option<std::ffi::OsString> {
    let name = target.file_name()?;
    let mut out = std::ffi::OsString::from(".");
    out.push(name);
    out.push(format!(".{tag}-{suffix}"));
    Some(out)
}

/// Hidden sibling names of `target` carrying `tag`, with the pid that made them.
fn own_siblings(target: &Path, tag: &str) -> Vec<(PathBuf, u32)> {
    let Some(prefix) = sibling_name(target, tag, "") else { return vec![] };
    let prefix = prefix.as_encoded_bytes().to_vec();
    let Ok(entries) = std::fs::read_dir(parent_of(target)) else { return vec![] };
    let mut out: Vec<(PathBuf, u32)> = entries
        .filter_map(Result::ok)
        .filter_map(|e| {
            let n = e.file_name();
            let rest = n.as_encoded_bytes().strip_prefix(prefix.as_slice())?;
            let rest = std::str::from_utf8(rest).ok()?;
            let pid: u32 = rest.split('-').next()?.parse().ok()?;
            Some((e.path(), pid))
        })
        .collect();
    out.sort();
    out
}

/// Removes stale staging directories of dead processes for `target`; if `target` is missing
/// and a set-aside old directory of a dead process exists (a crash inside the fallback swap),
/// puts it back. Returns the paths removed or restored.
pub fn recover(target: &Path) -> Vec<PathBuf> {
    let mut touched = Vec::new();
    let parent = parent_of(target);
    let process_alive = |pid: u32| owner_alive(&parent, pid);
    for (p, pid) in own_siblings(target, STAGING_TAG) {
        if !process_alive(pid) && std::fs::remove_dir_all(&p).is_ok() {
            touched.push(p);
        }
    }
    for (p, pid) in own_siblings(target, OLD_TAG) {
        if process_alive(pid) {
            continue;
        }
        if !target.exists() {
            if std::fs::rename(&p, target).is_ok() {
                touched.push(p);
            }
        } else if std::fs::remove_dir_all(&p).is_ok() {
            touched.push(p);
        }
    }
    remove_stale_locks(&parent);
    touched
}

/// Refuses `dir` unless every file in it (recursively, paths relative to `dir` with `/`) is in
/// `allowed`, and every subdirectory holds one of those files (an empty or otherwise unlisted
/// directory is the user's: it is named with a trailing `/` and refused, never deleted with the
/// old output). A missing `dir` passes.
pub fn only_listed_files(dir: &Path, allowed: &BTreeSet<String>) -> Result<(), IoError> {
    fn walk(root: &Path, dir: &Path, allowed: &BTreeSet<String>, out: &mut Vec<String>) -> Result<(), IoError> {
        for e in std::fs::read_dir(dir).map_err(io("read directory", dir))? {
            let e = e.map_err(io("read directory", dir))?;
            let p = e.path();
            let ty = e.file_type().map_err(io("inspect", &p))?;
            let rel = p.strip_prefix(root).unwrap_or(&p).to_string_lossy().replace('\\', "/");
            if ty.is_dir() {
                let prefix = format!("{rel}/");
                if !allowed.iter().any(|f| f.starts_with(&prefix)) {
                    out.push(prefix);
                    continue;
                }
                walk(root, &p, allowed, out)?;
            } else if !ty.is_file() {
                // a FIFO, device, socket or symlink under a listed name is not a file we wrote
                out.push(format!("{rel} ({})", paths::kind_of(ty)));
            } else {
                out.push(rel);
            }
        }
        Ok(())
    }
    match std::fs::symlink_metadata(dir) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(e) => return Err(io("inspect", dir)(e)),
        Ok(m) if !m.is_dir() => {
            return Err(IoError::BadTarget { path: dir.to_path_buf(), reason: "exists and is not a directory".into() })
        }
        Ok(_) => {}
    }
    let mut files = Vec::new();
    walk(dir, dir, allowed, &mut files)?;
    let foreign: Vec<String> = files.into_iter().filter(|f| !allowed.contains(f)).collect();
    if foreign.is_empty() {
        return Ok(());
    }
    let mut shown: Vec<String> = foreign.iter().take(8).cloned().collect();
    if foreign.len() > 8 {
        shown.push(format!("and {} more", foreign.len() - 8));
    }
    Err(IoError::Foreign { path: dir.to_path_buf(), files: shown.join(", ") })
}

/// A directory under construction beside its target; removed on drop unless committed.
#[derive(Debug)]
pub struct StagingDir {
    dir: PathBuf,
    target: PathBuf,
    committed: bool,
    // Held while the staging (and any set-aside old) directory exists; dropped after them.
    _lock: DirLock,
}

impl StagingDir {
    /// Creates a fresh hidden staging directory beside `target` (creating the parent), after
    /// [`recover`]ing leftovers of dead processes for the same target. The target is checked
    /// first ([`check_output_dir`]: its name leaves room for the staging suffix, and it is a
    /// directory or missing).
    pub fn new(target: &Path) -> Result<StagingDir, IoError> {
        check_output_dir(target, true)?;
        let parent = parent_of(target);
        std::fs::create_dir_all(&parent).map_err(io("create directory", &parent))?;
        recover(target);
        let lock = DirLock::acquire(&parent).map_err(io("lock", &parent))?;
        let staged = sibling_name(target, STAGING_TAG, &unique_suffix()).expect("the name was checked above");
        let dir = parent.join(staged);
        std::fs::create_dir(&dir).map_err(io("create directory", &dir))?;
        Ok(StagingDir { dir, target: target.to_path_buf(), committed: false, _lock: lock })
    }

    /// The staging directory.
    pub fn path(&self) -> &Path {
        &self.dir
    }

    /// The final location.
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Writes one file (a relative path; parent directories are created) with mode 0644.
    pub fn write(&self, rel: &str, bytes: &[u8]) -> Result<(), IoError> {
        let path = self.dir.join(rel);
        if let Some(p) = path.parent() {
            std::fs::create_dir_all(p).map_err(io("create directory", p))?;
        }
        let mut f = std::fs::File::create(&path).map_err(io("create", &path))?;
        f.write_all(bytes).map_err(io("write", &path))?;
        set_mode_0644(&f, &path)?;
        f.sync_all().map_err(io("sync", &path))
    }

    /// Swaps the staging directory in with the real file system; see [`Self::commit_with`].
    pub fn commit(self, owned: impl FnOnce(&Path) -> Result<(), IoError>) -> Result<(), IoError> {
        self.commit_with(owned, &SystemOps)
    }

    /// Moves the staging directory to the target. An existing target must pass `owned` (e.g.
    /// [`only_listed_files`]); it is then exchanged with the staging directory atomically, or,
    /// where exchange is unavailable, renamed aside, replaced, and restored if the second rename
    /// fails. The old directory is deleted only once the new one is in place.
    pub fn commit_with(
        mut self,
        owned: impl FnOnce(&Path) -> Result<(), IoError>,
        ops: &dyn DirOps,
    ) -> Result<(), IoError> {
        let target = self.target.clone();
        match std::fs::symlink_metadata(&target) {
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                ops.rename(&self.dir, &target).map_err(io("rename into place", &target))?;
                self.committed = true;
                return Ok(());
            }
            Err(e) => return Err(io("inspect", &target)(e)),
            Ok(m) if !m.is_dir() => {
                return Err(IoError::BadTarget { path: target, reason: "exists and is not a directory".into() })
            }
            Ok(_) => {}
        }
        owned(&target)?;
        if ops.exchange(&self.dir, &target).map_err(io("exchange with", &target))? {
            // The staging path now holds the old directory; dropping self removes it.
            return Ok(());
        }
        let old = parent_of(&target).join(sibling_name(&target, OLD_TAG, &unique_suffix()).expect("checked in new"));
        ops.rename(&target, &old).map_err(io("move the old directory aside from", &target))?;
        if let Err(e) = ops.rename(&self.dir, &target) {
            // Put the old one back; if even that fails, `recover` restores it on the next run.
            let _ = ops.rename(&old, &target);
            return Err(io("rename into place", &target)(e));
        }
        self.committed = true;
        std::fs::remove_dir_all(&old).map_err(io("remove the replaced directory", &old))
    }
}

impl Drop for StagingDir {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_dir_all(&self.dir);
        }
    }
}
