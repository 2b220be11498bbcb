//! The one atomic file write of wingcheck, in three forms: replace one file
//! ([`write_file_atomic`]), create one file that must not exist yet ([`create_file_atomic`]),
//! and commit several files together ([`FileSet`]).
//!
//! Every form follows the same discipline: the bytes go to a temp file in the destination's
//! directory, which is written, given mode 0644 (subject to nothing: set explicitly), and
//! `fsync`ed; it is then renamed (or, for a create, hard-linked) to the destination, and the
//! directory is `fsync`ed (best effort: not every platform syncs directories). A reader sees
//! the old file or the complete new one, never a part.
//!
//! Temp files are named `.{name}.tmp-{pid}-{n}` (single writes; `n` counts this process's
//! writes, so threads writing the same destination do not share a temp file) and
//! `.{name}.set-tmp-{pid}` ([`FileSet`]). While they exist the process holds its lock
//! `.wingcheck-{pid}.lock` in the same directory ([`crate::DirLock`]); [`remove_stale_temps`]
//! removes the temp files whose writer no longer holds it (killed during a write), so a
//! directory written again after a kill holds exactly the files of an uninterrupted run.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use crate::{io, parent_of, paths, DirLock, IoError};

/// Tag of the temp files of single writes.
const TMP_TAG: &str = ".tmp-";
/// Tag of the temp files of a [`FileSet`].
const SET_TAG: &str = ".set-tmp-";

/// The temp file `.{name}{tag}{suffix}` of `path` (the name's bytes as given: a name that is
/// not UTF-8 keeps them).
fn temp_path(path: &Path, tag: &str, suffix: &str) -> PathBuf {
    let mut name = std::ffi::OsString::from(".");
    name.push(path.file_name().unwrap_or_default());
    name.push(format!("{tag}{suffix}"));
    path.with_file_name(name)
}

/// A fresh single-write temp path of `path` for this process.
fn single_temp(path: &Path) -> PathBuf {
    static WRITES: AtomicU64 = AtomicU64::new(0);
    let n = WRITES.fetch_add(1, Ordering::Relaxed);
    temp_path(path, TMP_TAG, &format!("{}-{n}", std::process::id()))
}

/// The pid that wrote temp file `name` (`.{file}.tmp-{pid}`, `.{file}.tmp-{pid}-{n}` or
/// `.{file}.set-tmp-{pid}`), if `name` is one.
fn temp_owner(name: &str) -> Option<u32> {
    if !name.starts_with('.') {
        return None;
    }
    [SET_TAG, TMP_TAG].iter().find_map(|tag| {
        let (_, rest) = name.rsplit_once(tag)?;
        let (pid, n) = rest.split_once('-').unwrap_or((rest, "0"));
        n.parse::<u64>().ok()?;
        pid.parse::<u32>().ok()
    })
}

/// Whether `name` is a temp file of an atomic write of this module, or the lock file of its
/// writer.
pub fn is_temp(name: &str) -> bool {
    temp_owner(name).is_some() || crate::is_lock_file(name)
}

/// Removes the temp files of this module in `dir` whose writer no longer holds its lock there
/// (killed during a write), and such writers' lock files; those of live processes are left
/// alone.
pub fn remove_stale_temps(dir: &Path) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for e in entries.flatten() {
        let name = e.file_name().to_string_lossy().to_string();
        if !e.file_type().is_ok_and(|t| t.is_file()) {
            continue;
        }
        if let Some(pid) = temp_owner(&name) {
            if !crate::owner_alive(dir, pid) {
                let _ = std::fs::remove_file(e.path());
            }
        }
    }
    crate::remove_stale_locks(dir);
}

/// Creates the temp file `tmp` for `dest` (refusing one that exists: never shared).
fn create_temp(tmp: &Path, dest: &Path) -> Result<std::fs::File, IoError> {
    std::fs::OpenOptions::new().write(true).create_new(true).open(tmp).map_err(io("create a temporary file for", dest))
}

/// Writes `bytes` to a fresh temp file `tmp` of `dest`: written, mode 0644, fsynced.
fn stage(tmp: &Path, dest: &Path, bytes: &[u8]) -> Result<(), IoError> {
    let mut f = create_temp(tmp, dest)?;
    f.write_all(bytes).map_err(io("write", dest))?;
    set_mode_0644(&f, dest)?;
    f.sync_all().map_err(io("sync", dest))
}

/// `fsync` of a directory, best effort (not every platform can).
fn sync_dir(dir: &Path) {
    if let Ok(d) = std::fs::File::open(dir) {
        let _ = d.sync_all();
    }
}

/// Writes `bytes` to `path` atomically (temp file, fsync, rename over `path`, fsync of the
/// directory), file mode 0644. An existing `path` that is not a regular file (a symlink, FIFO,
/// device, directory) is refused, never replaced ([`paths::check_replaceable_file`]). On an
/// error the temp file is removed and `path` is as it was.
pub fn write_file_atomic(path: &Path, bytes: &[u8]) -> Result<(), IoError> {
    paths::check_replaceable_file(path)?;
    let dir = parent_of(path);
    let _lock = DirLock::acquire(&dir).map_err(io("lock", &dir))?;
    let tmp = single_temp(path);
    let written =
        stage(&tmp, path, bytes).and_then(|()| std::fs::rename(&tmp, path).map_err(io("rename into place", path)));
    if written.is_err() {
        let _ = std::fs::remove_file(&tmp);
    } else {
        sync_dir(&dir);
    }
    written
}

/// Creates `path` holding `bytes`, atomically and without overwriting: the bytes are staged
/// as in [`write_file_atomic`] and the temp file is then hard-linked to `path`, which the file
/// system refuses if `path` exists — also when another process created it a moment earlier.
/// Then `path` is left untouched and the error is [`IoError::Exists`]. Readers never see a
/// partly written `path`.
pub fn create_file_atomic(path: &Path, bytes: &[u8]) -> Result<(), IoError> {
    let dir = parent_of(path);
    let _lock = DirLock::acquire(&dir).map_err(io("lock", &dir))?;
    let tmp = single_temp(path);
    let created = stage(&tmp, path, bytes).and_then(|()| match std::fs::hard_link(&tmp, path) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => Err(IoError::Exists { path: path.to_path_buf() }),
        Err(e) => Err(io("create", path)(e)),
    });
    let _ = std::fs::remove_file(&tmp);
    if created.is_ok() {
        sync_dir(&dir);
    }
    created
}

#[cfg(unix)]
pub(crate) fn set_mode_0644(f: &std::fs::File, path: &Path) -> Result<(), IoError> {
    use std::os::unix::fs::PermissionsExt;
    f.set_permissions(std::fs::Permissions::from_mode(0o644)).map_err(io("set permissions of", path))
}

#[cfg(not(unix))]
pub(crate) fn set_mode_0644(_f: &std::fs::File, _path: &Path) -> Result<(), IoError> {
    Ok(())
}

/// Several files written together, all or nothing as far as a failure before the commit goes.
///
/// [`FileSet::add`] (or [`FileSet::open`] … [`StagedFile::finish`]) writes each file in full to
/// its temp file `.{name}.set-tmp-{pid}` in the destination's own directory (files may lie in
/// different directories), fsynced, so that a full disk, a missing directory or any other
/// write error shows while no destination has been touched; dropped without a commit, the set
/// removes its temp files. [`FileSet::commit`] first checks every destination can be replaced
/// (missing or a regular file), then renames the files into place in the order they were
/// added and fsyncs their directories.
///
/// Each rename is atomic, the set as a whole is not: a failure among the renames themselves
/// (a destination's directory removed or made read-only between staging and commit) leaves
/// the files renamed before it in place — each destination holds its old or its complete new
/// content, never a part — and the rest unchanged (their temp files removed). Callers whose
/// files must agree order them so that an earlier file without the later ones is a state they
/// recover from (a search writes a chunk before the progress file counting it).
///
/// A process stages a given destination in at most one set at a time (its temp file is
/// created exclusively: a second staging of the same name fails instead of sharing it).
#[derive(Debug, Default)]
pub struct FileSet {
    staged: Vec<PathBuf>,
    committed: bool,
    // This process's lock in each directory holding a temp file of the set (dropped after
    // `Drop` removed the temp files).
    locks: Vec<DirLock>,
    dirs: Vec<PathBuf>,
}

impl FileSet {
    /// An empty set.
    pub fn new() -> FileSet {
        FileSet::default()
    }

    fn tmp(path: &Path) -> PathBuf {
        temp_path(path, SET_TAG, &std::process::id().to_string())
    }

    /// Takes this process's lock in `path`'s directory (once per directory) and records `path`.
    fn enter(&mut self, path: &Path) -> Result<(), IoError> {
        let dir = parent_of(path);
        if !self.dirs.contains(&dir) {
            self.locks.push(DirLock::acquire(&dir).map_err(io("lock", &dir))?);
            self.dirs.push(dir);
        }
        Ok(())
    }

    /// Stages `bytes` as the new content of `path`.
    pub fn add(&mut self, path: &Path, bytes: &[u8]) -> Result<(), IoError> {
        self.enter(path)?;
        let tmp = Self::tmp(path);
        let staged = stage(&tmp, path, bytes);
        if staged.is_ok() {
            self.staged.push(path.to_path_buf());
        } else {
            let _ = std::fs::remove_file(&tmp);
        }
        staged
    }

    /// Opens the temp file of `path` for writing piece by piece; [`StagedFile::finish`] it
    /// before the commit.
    pub fn open(&mut self, path: &Path) -> Result<StagedFile, IoError> {
        self.enter(path)?;
        let file = create_temp(&Self::tmp(path), path)?;
        self.staged.push(path.to_path_buf());
        Ok(StagedFile { out: std::io::BufWriter::new(file), path: path.to_path_buf() })
    }

    /// Renames every staged file into place (none if any destination is not a regular file;
    /// see the type's documentation for a failure among the renames); returns their paths in
    /// the order added.
    pub fn commit(mut self) -> Result<Vec<PathBuf>, IoError> {
        for path in &self.staged {
            paths::check_replaceable_file(path)?;
        }
        for k in 0..self.staged.len() {
            let path = self.staged[k].clone();
            if let Err(e) = std::fs::rename(Self::tmp(&path), &path) {
                // the renamed ones are in place; Drop removes the temp files of the rest
                self.staged.drain(..k);
                return Err(io("rename into place", &path)(e));
            }
        }
        self.committed = true;
        for dir in &self.dirs {
            sync_dir(dir);
        }
        Ok(std::mem::take(&mut self.staged))
    }
}

impl Drop for FileSet {
    fn drop(&mut self) {
        if !self.committed {
            for path in &self.staged {
                let _ = std::fs::remove_file(Self::tmp(path));
            }
        }
    }
}

/// A file of a [`FileSet`] being written piece by piece (buffered).
#[derive(Debug)]
pub struct StagedFile {
    out: std::io::BufWriter<std::fs::File>,
    path: PathBuf,
}

impl StagedFile {
    /// Appends `bytes`.
    pub fn write(&mut self, bytes: &[u8]) -> Result<(), IoError> {
        self.out.write_all(bytes).map_err(io("write", &self.path))
    }

    /// The destination (what its errors name).
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The underlying writer (name its errors with [`StagedFile::error`]).
    pub fn writer(&mut self) -> &mut std::io::BufWriter<std::fs::File> {
        &mut self.out
    }

    /// A write error of this file.
    pub fn error(&self, e: std::io::Error) -> IoError {
        io("write", &self.path)(e)
    }

    /// Flushes, sets mode 0644 and fsyncs the temp file.
    pub fn finish(self) -> Result<(), IoError> {
        let path = self.path;
        let file = self.out.into_inner().map_err(|e| io("write", &path)(e.into_error()))?;
        set_mode_0644(&file, &path)?;
        file.sync_all().map_err(io("sync", &path))
    }
}
