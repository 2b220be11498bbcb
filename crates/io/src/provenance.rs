//! Where an output came from: the build (tool version, git commit and whether the tree was
//! dirty, rustc) and the configuration's SHA-256. One record type, [`Provenance`], for every
//! output: JSON outputs embed it (`"provenance": {…}`); a CSV file, which has no place for it
//! that standard loaders skip, gets it in the sidecar `FILE.provenance.json` beside it
//! ([`sidecar_path`]), and a directory output (report, search) holds one `provenance.json`
//! naming its data files. The build facts come from `wingcheck-app`'s build script (the CLI
//! and the Python extension both register them), registered once at start-up
//! ([`set_build`]); a library used on its own reports [`BuildInfo::unknown`].

use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

/// Version of the [`Provenance`] record and of every JSON output's layout (`schema_version`
/// in each document; the schemas are in `docs/schema/`). Raised when a field changes meaning
/// or is removed.
pub const SCHEMA_VERSION: u32 = 1;

/// Lowercase hex SHA-256 of `bytes` (the one hex encoding of wingcheck: the `hex` crate).
pub fn sha256_hex(bytes: &[u8]) -> String {
    hex::encode(Sha256::digest(bytes))
}

/// The state of the source tree a binary was built from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum TreeState {
    /// The commit, with no tracked file changed.
    Clean,
    /// The commit with uncommitted changes to tracked files (`git describe --dirty`).
    Dirty,
    /// Not built from a git checkout (a tarball, or git not installed).
    Unknown,
}

/// The build of the tool.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct BuildInfo {
    /// Tool version (Cargo package version).
    pub version: String,
    /// Full git commit hash the binary was built from, or `unknown`.
    pub commit: String,
    /// Whether the tree had uncommitted changes.
    pub tree: TreeState,
    /// `git describe --always --dirty` (e.g. `0f867b9-dirty`), or `unknown`.
    pub describe: String,
    /// `rustc --version` of the compiler, or `unknown`.
    pub rustc: String,
}

impl BuildInfo {
    /// A build whose commit is not known (a library used without the binary).
    pub fn unknown() -> BuildInfo {
        BuildInfo {
            version: env!("CARGO_PKG_VERSION").to_string(),
            commit: "unknown".into(),
            tree: TreeState::Unknown,
            describe: "unknown".into(),
            rustc: "unknown".into(),
        }
    }

    /// One line: `wingcheck 0.1.0 (commit 0f867b9…, dirty)`.
    pub fn line(&self) -> String {
        match self.tree {
            TreeState::Unknown => format!("wingcheck {} (commit unknown)", self.version),
            TreeState::Clean => format!("wingcheck {} (commit {})", self.version, self.commit),
            TreeState::Dirty => {
                format!("wingcheck {} (commit {}, with uncommitted changes)", self.version, self.commit)
            }
        }
    }
}

impl Default for BuildInfo {
    fn default() -> Self {
        BuildInfo::unknown()
    }
}

static BUILD: std::sync::OnceLock<BuildInfo> = std::sync::OnceLock::new();

/// Registers the build of the running program (the `wingcheck` binary and the Python
/// extension do this first thing, from `wingcheck-app`'s build script); later calls are
/// ignored.
pub fn set_build(build: BuildInfo) {
    let _ = BUILD.set(build);
}

/// The build of the running binary, or [`BuildInfo::unknown`] if none was registered (a
/// library used on its own, e.g. in the crates' tests).
pub fn build() -> &'static BuildInfo {
    BUILD.get_or_init(BuildInfo::unknown)
}

/// The provenance of one output (a file, or a directory of files).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Provenance {
    /// [`SCHEMA_VERSION`].
    pub schema_version: u32,
    /// Always `wingcheck`.
    pub tool: String,
    /// The build that wrote the output.
    pub build: BuildInfo,
    /// SHA-256 (hex) of the configuration's compact JSON (for a search: the base configuration).
    pub config_sha256: String,
    /// Where every column and field is explained.
    pub documentation: String,
    /// The data files described (a sidecar: the one file; a directory: each CSV in it).
    pub files: Vec<FileRecord>,
}

/// One data file of an output.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct FileRecord {
    /// File name (relative to the provenance record's directory).
    pub file: String,
    /// What the file holds, in words, with the units of generic columns (a figure's `x`, `y`).
    pub contents: String,
}

impl Provenance {
    /// The record for files written by this binary ([`build`]) from a configuration with hash
    /// `config_sha256`.
    pub fn new(config_sha256: &str, files: Vec<FileRecord>) -> Provenance {
        Provenance {
            schema_version: SCHEMA_VERSION,
            tool: "wingcheck".into(),
            build: build().clone(),
            config_sha256: config_sha256.to_string(),
            documentation:
                "docs/outputs.md of the wingcheck repository (columns, units, meanings); JSON Schemas in docs/schema/"
                    .into(),
            files,
        }
    }

    /// Pretty JSON with a trailing newline.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("provenance serialises") + "\n"
    }
}

/// What a file's provenance sidecar adds to its name ([`sidecar_path`]).
pub const SIDECAR_SUFFIX: &str = ".provenance.json";

/// The sidecar of a single CSV file: `run.csv` → `run.csv.provenance.json`.
pub fn sidecar_path(file: &std::path::Path) -> std::path::PathBuf {
    let mut name = file.file_name().map(|n| n.to_os_string()).unwrap_or_default();
    name.push(SIDECAR_SUFFIX);
    file.with_file_name(name)
}
