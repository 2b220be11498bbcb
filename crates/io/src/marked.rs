//! Output directories that wingcheck owns by a marker file: the marker's text, a line
//! `files:`, then the directory's files, one per line. A directory is replaced (atomically,
//! [`crate::StagingDir`]) only when it is missing, empty, or holds nothing but the files its
//! marker lists; anything else is refused and left untouched. `report` (marker
//! `.wingcheck-report`) and `schema` (marker `.wingcheck-schema`) write their directories so.

use std::collections::BTreeSet;
use std::path::Path;

use crate::{only_listed_files, paths, IoError, StagingDir};

/// Line of a marker after which the directory's files are listed, one per line.
pub const FILES_HEADER: &str = "files:";

/// Largest marker file read (a marker lists a few hundred names).
const MARKER_MAX_BYTES: u64 = 1 << 20;

/// What a directory's marker says it owns.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Owned {
    /// The files listed (the marker included).
    Listed(BTreeSet<String>),
    /// A marker without a list (an older version's): it owns only itself.
    Legacy,
}

/// What the marker `marker` in `dir` says the directory owns; `None` without a readable
/// marker (missing, or not a regular file: never opened then).
pub fn owned_files(dir: &Path, marker: &str) -> Option<Owned> {
    let bytes = paths::read_regular(&dir.join(marker), MARKER_MAX_BYTES).ok()?;
    let text = String::from_utf8(bytes).ok()?;
    match text.split_once(&format!("\n{FILES_HEADER}\n")) {
        Some((_, list)) => {
            let mut set: BTreeSet<String> = list.lines().filter(|l| !l.is_empty()).map(str::to_string).collect();
            set.insert(marker.to_string());
            Some(Owned::Listed(set))
        }
        None => Some(Owned::Legacy),
    }
}

/// `Ok` if `dir` may be replaced by a directory with marker `marker`: missing, empty, or
/// holding only what its marker lists. `what` names the kind of directory in the refusal
/// (`a schema directory`).
pub fn check_marked_replaceable(dir: &Path, marker: &str, what: &str) -> Result<(), IoError> {
    paths::check_output_dir(dir, true)?;
    if !dir.exists() {
        return Ok(());
    }
    match owned_files(dir, marker) {
        Some(Owned::Listed(set)) => only_listed_files(dir, &set),
        Some(Owned::Legacy) => only_listed_files(dir, &BTreeSet::from([marker.to_string()])),
        None => {
            let mut entries = std::fs::read_dir(dir).map_err(|e| IoError::Io {
                action: "read directory",
                path: dir.to_path_buf(),
                source: e,
            })?;
            if entries.next().is_none() {
                Ok(())
            } else {
                Err(IoError::BadOutput {
                    path: dir.to_path_buf(),
                    reason: format!(
                        "it exists, is not empty and is not {what} (no {marker} marker); wingcheck never replaces \
                         files it did not write: choose another --out or move them away"
                    ),
                })
            }
        }
    }
}

/// Writes `files` (name, bytes) and the marker into a new directory that replaces `dir`
/// atomically, after [`check_marked_replaceable`]; the previous directory is deleted only once
/// the new one is in place.
pub fn write_marked_dir(
    dir: &Path,
    marker: &str,
    marker_text: &str,
    what: &str,
    files: &[(String, Vec<u8>)],
) -> Result<(), IoError> {
    check_marked_replaceable(dir, marker, what)?;
    let staging = StagingDir::new(dir)?;
    let mut names: Vec<&str> = files.iter().map(|(n, _)| n.as_str()).collect();
    for (name, bytes) in files {
        staging.write(name, bytes)?;
    }
    names.sort_unstable();
    let text = format!("{}\n{FILES_HEADER}\n{}\n", marker_text.trim_end(), names.join("\n"));
    staging.write(marker, text.as_bytes())?;
    staging.commit(|old| check_marked_replaceable(old, marker, what))
}
