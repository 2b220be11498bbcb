//! Writing results: atomic file writes (temp file + rename) and the CSV/JSON forms of a run,
//! each with its provenance (a CSV's in its sidecar `FILE.provenance.json`).

use std::path::{Path, PathBuf};

use serde::Serialize;
use wingcheck_model::Config;

use crate::{Series, SimOutput};

/// Errors while writing outputs.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// The file or its directory cannot be written.
    #[error("cannot write {path}: {source}")]
    Io {
        /// Target path.
        path: String,
        /// Underlying error.
        source: std::io::Error,
    },
    /// The output format is not known.
    #[error("unknown output format for {0}: use a .csv or .json file name")]
    Format(String),
}

/// Write `bytes` to `path` atomically: a temp file in the same directory, fsync, rename.
/// An interrupted run leaves either the old file or the new one, never a half-written file.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
    wingcheck_io::write_file_atomic(path, bytes).map_err(|e| OutputError::Io {
        path: path.display().to_string(),
        source: match e {
            wingcheck_io::IoError::Io { source, .. } => source,
            other => std::io::Error::other(other.to_string()),
        },
    })
}

/// The series as CSV: the header names each column with its unit suffix
/// ([`Series::csv_header`], docs/outputs.md), numbers in Rust's shortest round-trip form, so the
/// file is bit-reproducible and re-reads to the same f64 values.
pub fn series_csv(series: &Series) -> String {
    let cols = series.columns();
    let rows = (0..series.len()).map(|i| cols.iter().map(move |c| c[i]));
    wingcheck_io::csv_numbers(Series::csv_header(), rows)
}

/// The full JSON document of a run (`run.json`): config, series, fields, statistics.
#[derive(Serialize, schemars::JsonSchema)]
pub struct RunDocument<'a> {
    /// Layout version ([`wingcheck_io::SCHEMA_VERSION`]).
    pub schema_version: u32,
    /// Tool name and version.
    pub tool: String,
    /// Tool build and the configuration's SHA-256.
    pub provenance: wingcheck_io::Provenance,
    /// The configuration used (after overrides).
    pub config: &'a Config,
    /// The run.
    #[serde(flatten)]
    pub output: &'a SimOutput,
}

/// Serialise a run to pretty JSON.
pub fn run_json(cfg: &Config, output: &SimOutput) -> String {
    let doc = RunDocument {
        schema_version: wingcheck_io::SCHEMA_VERSION,
        tool: format!("wingcheck {}", env!("CARGO_PKG_VERSION")),
        provenance: wingcheck_io::Provenance::new(&cfg.sha256(), vec![]),
        config: cfg,
        output,
    };
    serde_json::to_string_pretty(&doc).expect("run serialises")
}

/// The provenance sidecar of a run.csv (`run.csv.provenance.json`, [`wingcheck_io::sidecar_path`]).
pub fn csv_provenance(path: &Path, cfg: &Config) -> String {
    let file = path.file_name().map(|n| n.to_string_lossy().to_string()).unwrap_or_default();
    wingcheck_io::Provenance::new(
        &cfg.sha256(),
        vec![wingcheck_io::FileRecord {
            file,
            contents: "simulate's time series: one row per output sample, columns with unit-suffixed names (docs/outputs.md, run.csv)".into(),
        }],
    )
    .to_json()
}

/// Write a run to `path` (`.csv`: the series, and its provenance sidecar beside it; `.json`:
/// [`run_json`], provenance inside), each file atomically: [`render_run`] then
/// [`write_rendered`].
pub fn write_run(path: &Path, cfg: &Config, output: &SimOutput) -> Result<(), OutputError> {
    write_rendered(&render_run(path, cfg, output)?)
}

/// The files [`write_run`] writes and their text, rendered in memory (the slow part of writing
/// a long run), so that a caller can decide after it whether to move them into place.
pub fn render_run(path: &Path, cfg: &Config, output: &SimOutput) -> Result<Vec<(PathBuf, String)>, OutputError> {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    match ext.as_str() {
        "csv" => Ok(vec![
            (path.to_path_buf(), series_csv(&output.series)),
            (wingcheck_io::sidecar_path(path), csv_provenance(path, cfg)),
        ]),
        "json" => Ok(vec![(path.to_path_buf(), run_json(cfg, output))]),
        _ => Err(OutputError::Format(path.display().to_string())),
    }
}

/// Write rendered files ([`render_run`]), each atomically, in order.
pub fn write_rendered(files: &[(PathBuf, String)]) -> Result<(), OutputError> {
    for (path, text) in files {
        write_atomic(path, text.as_bytes())?;
    }
    Ok(())
}
