//! Atomic report directories over [`wingcheck_io`]: everything is rendered into a staging
//! directory beside the target and swapped in at the end (one `renameat2(RENAME_EXCHANGE)` on
//! Linux), so `--out` holds the complete old report or the complete new one at every instant.
//! An existing directory is replaced only if it is a report (marker file [`MARKER`]) holding
//! nothing but the files its marker lists, or is empty; a directory with anything else in it
//! is refused and left untouched — the tool never deletes files it did not write.

use std::collections::BTreeSet;
use std::path::Path;
use std::sync::Mutex;

use wingcheck_io::marked::{Owned, FILES_HEADER};
use wingcheck_io::{only_listed_files, StagingDir};

use crate::ReportError;

/// Name of the marker file that identifies a report directory; it lists the report's files.
pub const MARKER: &str = ".wingcheck-report";

/// The files a report directory owns according to its marker (the marker included). A marker
/// of an older version without a file list owns only itself: which of the files beside it that
/// version wrote cannot be told from their names (a user's `notes.csv` looks like a figure's
/// data), so such a directory is refused naming them, and nothing is deleted. A marker that is
/// not a regular file is never opened ([`wingcheck_io::marked::owned_files`]).
fn owned_files(dir: &Path) -> Option<Owned> {
    wingcheck_io::marked::owned_files(dir, MARKER)
}

/// `Ok` if `out` may be replaced: missing, an empty directory, or a report holding only its
/// own files.
pub fn check_replaceable(out: &Path) -> Result<(), ReportError> {
    wingcheck_io::check_output_dir(out, true)?;
    match std::fs::symlink_metadata(out) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(ReportError::io("inspect", out)(e)),
        Ok(m) if !m.is_dir() => Err(ReportError::NotAReport { path: out.to_path_buf(), marker: MARKER }),
        Ok(_) => match owned_files(out) {
            Some(Owned::Listed(set)) => Ok(only_listed_files(out, &set)?),
            Some(Owned::Legacy) => only_listed_files(out, &BTreeSet::from([MARKER.to_string()])).map_err(|e| match e {
                wingcheck_io::IoError::Foreign { path, files } => ReportError::Output(wingcheck_io::IoError::Foreign {
                    path,
                    files: format!("{files}; its marker, from an older wingcheck, does not list the files it wrote"),
                }),
                other => ReportError::Output(other),
            }),
            None => {
                let mut entries = std::fs::read_dir(out).map_err(ReportError::io("read directory", out))?;
                if entries.next().is_none() {
                    Ok(())
                } else {
                    Err(ReportError::NotAReport { path: out.to_path_buf(), marker: MARKER })
                }
            }
        },
    }
}

/// A staging directory that is removed on drop unless [`Staging::commit`] moved it into place.
pub struct Staging {
    dir: StagingDir,
    written: Mutex<Vec<String>>,
}

impl Staging {
    /// Create a fresh staging directory beside `target` (creating `target`'s parent if needed;
    /// stale staging directories of dead wingcheck processes for `target` are removed).
    pub fn new(target: &Path) -> Result<Staging, ReportError> {
        Ok(Staging { dir: StagingDir::new(target)?, written: Mutex::new(Vec::new()) })
    }

    /// The staging directory.
    pub fn path(&self) -> &Path {
        self.dir.path()
    }

    /// Write one file (mode 0644) into the staging directory; returns its name.
    pub fn write(&self, name: &str, bytes: &[u8]) -> Result<String, ReportError> {
        self.dir.write(name, bytes)?;
        self.written.lock().expect("no panics while holding the lock").push(name.to_string());
        Ok(name.to_string())
    }

    /// Write the marker (with the list of files) and swap the staging directory into place.
    /// The old report is deleted only after the new one is in place.
    pub fn commit(self, marker_text: &str) -> Result<(), ReportError> {
        let mut files = self.written.into_inner().expect("no panics while holding the lock");
        files.sort();
        let marker = format!("{}\n{FILES_HEADER}\n{}\n", marker_text.trim_end(), files.join("\n"));
        self.dir.write(MARKER, marker.as_bytes())?;
        self.dir.commit(|old| {
            check_replaceable(old).map_err(|e| match e {
                ReportError::Output(io) => io,
                other => wingcheck_io::IoError::BadTarget { path: old.to_path_buf(), reason: other.to_string() },
            })
        })?;
        Ok(())
    }
}
