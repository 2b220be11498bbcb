//! Writing results: atomic file writes (temp file + rename) and the CSV/JSON forms of a run.

use std::path::Path;

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

/// The series as CSV with a header line; numbers in Rust's shortest round-trip form, so the
/// file is bit-reproducible and re-reads to the same f64 values.
pub fn series_csv(series: &Series) -> String {
    let mut out = Series::COLUMNS.join(",");
    out.push('\n');
    let cols = series.columns();
    for i in 0..series.len() {
        let row: Vec<String> = cols.iter().map(|c| format!("{}", c[i])).collect();
        out.push_str(&row.join(","));
        out.push('\n');
    }
    out
}

/// The full JSON document of a run: config, series, fields, statistics.
#[derive(Serialize)]
pub struct RunDocument<'a> {
    /// Tool name and version.
    pub tool: String,
    /// The configuration used (after overrides).
    pub config: &'a Config,
    /// The run.
    #[serde(flatten)]
    pub output: &'a SimOutput,
}

/// Serialise a run to pretty JSON.
pub fn run_json(cfg: &Config, output: &SimOutput) -> String {
    let doc = RunDocument { tool: format!("wingcheck {}", env!("CARGO_PKG_VERSION")), config: cfg, output };
    serde_json::to_string_pretty(&doc).expect("run serialises")
}

/// Write a run to `path` (`.csv`: the series; `.json`: [`run_json`]), atomically.
pub fn write_run(path: &Path, cfg: &Config, output: &SimOutput) -> Result<(), OutputError> {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    let text = match ext.as_str() {
        "csv" => series_csv(&output.series),
        "json" => run_json(cfg, output),
        _ => return Err(OutputError::Format(path.display().to_string())),
    };
    write_atomic(path, text.as_bytes())
}
