//! Whether the writer of a temp or staging file is still running: an advisory file lock
//! (`fs4`, `flock` on Unix, `LockFileEx` on Windows) instead of looking the writer's pid up in
//! `/proc`. A process that leaves files named with its pid in a directory holds the lock on
//! `.wingcheck-{pid}.lock` in that directory while they exist ([`DirLock`]); the OS drops the
//! lock when the process ends however it ends, so [`owner_alive`] is true exactly while the
//! writer lives — on every platform fs4 supports, and without being fooled by a reused pid.

use std::collections::HashMap;
use std::fs::File;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use fs4::FileExt;

/// Name of the lock file of process `pid`.
pub fn lock_name(pid: u32) -> String {
    format!(".wingcheck-{pid}.lock")
}

/// The pid a lock file name belongs to (`.wingcheck-{pid}.lock`).
pub fn lock_owner(name: &str) -> Option<u32> {
    name.strip_prefix(".wingcheck-")?.strip_suffix(".lock")?.parse().ok()
}

/// Prefix of a lock file still under its temporary name ([`DirLock::acquire`] locks it, then
/// renames it to [`lock_name`]).
const STAGING_PREFIX: &str = ".wingcheck-lock-";

/// A staging lock file that nobody holds is removed only once it is this old: between its
/// creation and its lock (microseconds) it is unlocked but in use.
const STAGING_STALE_AFTER: std::time::Duration = std::time::Duration::from_secs(10);

/// Whether `name` is a lock file: `.wingcheck-{pid}.lock` or one still under its temporary
/// name.
pub fn is_lock_file(name: &str) -> bool {
    lock_owner(name).is_some() || name.starts_with(STAGING_PREFIX)
}

/// Locks held by this process, by directory, with how many holders share each.
static HELD: Mutex<Option<HashMap<PathBuf, (File, usize)>>> = Mutex::new(None);

/// This process's lock in one directory, shared by every holder in the process (threads
/// writing chunks side by side); the last one dropped unlocks and removes the lock file.
#[derive(Debug)]
pub struct DirLock {
    dir: PathBuf,
}

impl DirLock {
    /// Takes (or shares) this process's lock in `dir`.
    pub fn acquire(dir: &Path) -> std::io::Result<DirLock> {
        let dir = if dir.as_os_str().is_empty() { PathBuf::from(".") } else { dir.to_path_buf() };
        let mut held = HELD.lock().unwrap_or_else(|p| p.into_inner());
        let map = held.get_or_insert_with(HashMap::new);
        if let Some((_, n)) = map.get_mut(&dir) {
            *n += 1;
            return Ok(DirLock { dir });
        }
        let file = create_locked(&dir, &dir.join(lock_name(std::process::id())))?;
        map.insert(dir.clone(), (file, 1));
        Ok(DirLock { dir })
    }
}

/// Creates `path` already locked, so that whoever sees the name sees it locked.
///
/// On Linux the file is born unnamed (`O_TMPFILE`), locked, then linked to `path`: a kill at
/// any instant leaves either nothing or `path`, which a later run removes once the lock is gone
/// ([`remove_stale_locks`]). Where the file system has no unnamed files (and off Linux) it is
/// locked under a staging name ([`STAGING_PREFIX`]) and renamed; a kill between the two leaves
/// a staging file that is removed only after [`STAGING_STALE_AFTER`].
fn create_locked(dir: &Path, path: &Path) -> std::io::Result<File> {
    #[cfg(target_os = "linux")]
    if let Some(file) = create_locked_unnamed(dir, path)? {
        return Ok(file);
    }
    let tmp = tempfile::Builder::new().prefix(STAGING_PREFIX).tempfile_in(dir)?;
    FileExt::lock(tmp.as_file())?;
    tmp.persist(path).map_err(|e| e.error)
}

/// [`create_locked`] through an `O_TMPFILE` file; `Ok(None)` where the file system or kernel
/// cannot (then the caller uses a staging name).
#[cfg(target_os = "linux")]
fn create_locked_unnamed(dir: &Path, path: &Path) -> std::io::Result<Option<File>> {
    use rustix::fs::{linkat, openat, AtFlags, Mode, OFlags, CWD};
    use rustix::io::Errno;
    use std::os::fd::AsRawFd;
    let flags = OFlags::TMPFILE | OFlags::RDWR | OFlags::CLOEXEC;
    let fd = match openat(CWD, dir, flags, Mode::from_raw_mode(0o644)) {
        Ok(fd) => fd,
        Err(e) if [Errno::OPNOTSUPP, Errno::ISDIR, Errno::INVAL, Errno::NOSYS].contains(&e) => return Ok(None),
        Err(e) => return Err(e.into()),
    };
    let file = File::from(fd);
    FileExt::lock(&file)?;
    let fd_path = format!("/proc/self/fd/{}", file.as_raw_fd());
    // A lock file under this pid already there is a dead process's (a reused pid), as `rename`
    // over it in the staging route would assume: replace it.
    for replace in [true, false] {
        match linkat(CWD, fd_path.as_str(), CWD, path, AtFlags::SYMLINK_FOLLOW) {
            Ok(()) => return Ok(Some(file)),
            Err(Errno::EXIST) if replace => std::fs::remove_file(path)?,
            // no /proc to name the file by
            Err(Errno::NOENT) if !Path::new("/proc/self/fd").exists() => return Ok(None),
            Err(e) => return Err(e.into()),
        }
    }
    Err(std::io::Error::new(std::io::ErrorKind::AlreadyExists, format!("{} keeps reappearing", path.display())))
}

impl Drop for DirLock {
    fn drop(&mut self) {
        let mut held = HELD.lock().unwrap_or_else(|p| p.into_inner());
        let Some(map) = held.as_mut() else { return };
        let last = match map.get_mut(&self.dir) {
            Some((_, n)) if *n > 1 => {
                *n -= 1;
                false
            }
            Some(_) => true,
            None => false,
        };
        if last {
            if let Some((file, _)) = map.remove(&self.dir) {
                let _ = std::fs::remove_file(self.dir.join(lock_name(std::process::id())));
                let _ = FileExt::unlock(&file);
            }
        }
    }
}

/// Whether process `pid`, which named files in `dir` after itself, is still running: it is
/// while it holds its lock there. This process is always alive; a lock file that is missing or
/// that can be locked belongs to a writer that has ended.
pub fn owner_alive(dir: &Path, pid: u32) -> bool {
    if pid == std::process::id() {
        return true;
    }
    let Ok(file) = File::open(dir.join(lock_name(pid))) else { return false };
    match FileExt::try_lock(&file) {
        Ok(()) => {
            let _ = FileExt::unlock(&file);
            false
        }
        Err(fs4::TryLockError::WouldBlock) => true,
        // A file system without locks: assume alive, so nothing of another process is removed.
        Err(fs4::TryLockError::Error(_)) => true,
    }
}

/// Removes the lock files in `dir` of processes that have ended (left by a kill), also those
/// killed before renaming their lock file: unlocked and older than [`STAGING_STALE_AFTER`].
pub fn remove_stale_locks(dir: &Path) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for e in entries.flatten() {
        let name = e.file_name().to_string_lossy().to_string();
        if let Some(pid) = lock_owner(&name) {
            if !owner_alive(dir, pid) {
                let _ = std::fs::remove_file(e.path());
            }
        } else if name.starts_with(STAGING_PREFIX) {
            let old = e
                .metadata()
                .and_then(|m| m.modified())
                .is_ok_and(|t| t.elapsed().is_ok_and(|age| age >= STAGING_STALE_AFTER));
            let unheld = File::open(e.path()).is_ok_and(|f| match FileExt::try_lock(&f) {
                Ok(()) => {
                    let _ = FileExt::unlock(&f);
                    true
                }
                Err(_) => false,
            });
            if old && unheld {
                let _ = std::fs::remove_file(e.path());
            }
        }
    }
}
