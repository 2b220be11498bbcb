//! Atomic report directories: everything is rendered into a staging directory next to the
//! target (same parent, so the final `rename` cannot cross file systems) and renamed into
//! place at the end. An interrupted or failed run leaves the old report (or nothing), never
//! half a report. An existing directory is replaced only if it carries the marker file
//! [`MARKER`] (or is empty); anything else is refused.

use std::path::{Path, PathBuf};
use std::time::{SystemTime, UNIX_EPOCH};

use crate::ReportError;

/// Name of the marker file that identifies a report directory.
pub const MARKER: &str = ".wingcheck-report";

/// Refuse `out` if it exists and is not a report directory (or an empty directory).
pub fn check_replaceable(out: &Path) -> Result<(), ReportError> {
    let refuse = || ReportError::NotAReport { path: out.to_path_buf(), marker: MARKER };
    match std::fs::symlink_metadata(out) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(ReportError::io("inspect", out)(e)),
        Ok(m) if !m.is_dir() => Err(refuse()),
        Ok(_) => {
            if out.join(MARKER).is_file() {
                return Ok(());
            }
            let mut entries = std::fs::read_dir(out).map_err(ReportError::io("read directory", out))?;
            if entries.next().is_none() {
                Ok(())
            } else {
                Err(refuse())
            }
        }
    }
}

/// A staging directory that is removed on drop unless [`Staging::commit`] moved it into place.
pub struct Staging {
    dir: PathBuf,
    target: PathBuf,
    committed: bool,
}

impl Staging {
    /// Create a fresh staging directory beside `target` (creating `target`'s parent if needed).
    pub fn new(target: &Path) -> Result<Staging, ReportError> {
        let name = target.file_name().ok_or_else(|| ReportError::InvalidOutDir(target.to_path_buf()))?;
        let parent = parent_of(target);
        std::fs::create_dir_all(&parent).map_err(ReportError::io("create directory", &parent))?;
        let dir = parent.join(format!(".{}.tmp-{}", name.to_string_lossy(), unique_suffix()));
        std::fs::create_dir(&dir).map_err(ReportError::io("create directory", &dir))?;
        Ok(Staging { dir, target: target.to_path_buf(), committed: false })
    }

    /// The staging directory.
    pub fn path(&self) -> &Path {
        &self.dir
    }

    /// Write one file into the staging directory; returns its name.
    pub fn write(&self, name: &str, bytes: &[u8]) -> Result<String, ReportError> {
        let path = self.dir.join(name);
        std::fs::write(&path, bytes).map_err(ReportError::io("write", &path))?;
        Ok(name.to_string())
    }

    /// Write the marker and move the staging directory into place. An existing report is
    /// swapped out by rename first and deleted only after the new one is in place; if the
    /// final rename fails, the old report is put back.
    pub fn commit(mut self, marker_text: &str) -> Result<(), ReportError> {
        self.write(MARKER, marker_text.as_bytes())?;
        check_replaceable(&self.target)?;
        let target = self.target.clone();
        let old = if target.exists() {
            let name = target.file_name().expect("checked in new").to_string_lossy().to_string();
            let old = parent_of(&target).join(format!(".{name}.old-{}", unique_suffix()));
            std::fs::rename(&target, &old).map_err(ReportError::io("move the old report aside from", &target))?;
            Some(old)
        } else {
            None
        };
        if let Err(e) = std::fs::rename(&self.dir, &target) {
            if let Some(old) = &old {
                let _ = std::fs::rename(old, &target);
            }
            return Err(ReportError::io("rename into place", &target)(e));
        }
        self.committed = true;
        if let Some(old) = old {
            std::fs::remove_dir_all(&old).map_err(ReportError::io("remove the replaced report", &old))?;
        }
        Ok(())
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_dir_all(&self.dir);
        }
    }
}

fn parent_of(p: &Path) -> PathBuf {
    match p.parent() {
        Some(q) if !q.as_os_str().is_empty() => q.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

fn unique_suffix() -> String {
    let nanos = SystemTime::now().duration_since(UNIX_EPOCH).map(|d| d.subsec_nanos()).unwrap_or(0);
    format!("{}-{nanos}", std::process::id())
}
