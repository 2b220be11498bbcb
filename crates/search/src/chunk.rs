//! Chunk files: one header line naming the search they belong to, then one JSON line per point.
//!
//! The header carries the search's identity — the SHA-256 of its `manifest.json` text (the base
//! configuration and its hash, the axes, the options) and the tool version — the chunk number,
//! its first point and point count, and the SHA-256 of the point lines that follow. A chunk is
//! accepted for resuming, merging and assembling only if all of that matches and every line is
//! a point of this grid: its index in the chunk's range, its values exactly the grid's values
//! there, every metric finite or absent, the message empty exactly when the status is `ok`.
//! Anything else is refused naming the file (a chunk of another search, an edited one, one of
//! another tool version) — never merged, never silently recomputed over.
//!
//! Floats: every metric is stored as the text of Rust's shortest round-trip form
//! (`format!("{x}")`), parsed back with `str::parse::<f64>` (exact), so results read from
//! chunks equal the computed values bit for bit.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::metric::METRICS;
use crate::point::{PointResult, PointVerdicts, Status};
use crate::store::{chunk_path, read};
use crate::{Search, SearchError};

/// Value of a chunk header's `format`.
pub const CHUNK_FORMAT: &str = "wingcheck-search-chunk";

/// The tool version written into chunk headers; chunks of another version are refused (their
/// points may have been computed differently).
pub const TOOL: &str = concat!("wingcheck ", env!("CARGO_PKG_VERSION"));

pub use wingcheck_io::sha256_hex;

/// The first line of a chunk file.
#[derive(Debug, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
struct Header {
    format: String,
    tool: String,
    /// SHA-256 of the search's manifest.json text.
    search: String,
    chunk: usize,
    first: usize,
    points: usize,
    /// SHA-256 of the point lines (everything after the header line).
    sha256: String,
}

/// One point line of a chunk file.
#[derive(Debug, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
struct ChunkLine {
    index: usize,
    values: Vec<String>,
    status: Status,
    message: String,
    w_positive_definite: Option<bool>,
    feasible_32: Option<bool>,
    metrics: Vec<Option<String>>,
    sim_seconds: f64,
    theory_seconds: f64,
}

/// Serialise chunk `c` of `search` (its points, in index order): the header line, then one JSON
/// line per point. A metric that is not finite is written as absent (no NaN or ∞ reaches the
/// result files).
pub fn chunk_text(search: &Search, c: usize, points: &[PointResult]) -> String {
    let mut body = String::new();
    for p in points {
        let line = ChunkLine {
            index: p.index,
            values: p.values.clone(),
            status: p.status,
            message: p.message.clone(),
            w_positive_definite: p.w_positive_definite,
            feasible_32: p.feasible_32,
            metrics: p.metrics.iter().map(|m| m.filter(|x| x.is_finite()).map(|x| format!("{x}"))).collect(),
            sim_seconds: finite_or_zero(p.sim_seconds),
            theory_seconds: finite_or_zero(p.theory_seconds),
        };
        body.push_str(&serde_json::to_string(&line).expect("chunk line serialises"));
        body.push('\n');
    }
    let header = Header {
        format: CHUNK_FORMAT.into(),
        tool: TOOL.into(),
        search: search.identity(),
        chunk: c,
        first: search.chunk_range(c).start,
        points: points.len(),
        sha256: sha256_hex(body.as_bytes()),
    };
    serde_json::to_string(&header).expect("chunk header serialises") + "\n" + &body
}

fn finite_or_zero(x: f64) -> f64 {
    if x.is_finite() && x >= 0.0 {
        x
    } else {
        0.0
    }
}

/// Read chunk `c` of `search` from `dir`: `Ok(None)` if the file does not exist, the points if
/// it is this search's complete chunk (see the module documentation), else
/// [`SearchError::Chunk`] naming the file and what is wrong.
pub fn read_chunk(dir: &Path, search: &Search, c: usize) -> Result<Option<Vec<PointResult>>, SearchError> {
    let path = chunk_path(dir, c);
    match std::fs::symlink_metadata(&path) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(source) => return Err(SearchError::FileSystem { path, source }),
        Ok(m) if !m.is_file() => return Err(foreign(&path, ChunkProblem::NotAFile)),
        Ok(_) => {}
    }
    let text = read(&path)?;
    parse_chunk(&text, search, c).map(Some).map_err(|reason| foreign(&path, reason))
}

fn foreign(path: &Path, reason: ChunkProblem) -> SearchError {
    SearchError::Chunk { path: path.display().to_string(), reason }
}

/// The points of chunk text, checked against the search (the reason when it is not its chunk).
fn parse_chunk(text: &str, search: &Search, c: usize) -> Result<Vec<PointResult>, ChunkProblem> {
    let (head, body) = text.split_once('\n').ok_or(ChunkProblem::NoHeader)?;
    let h: Header = serde_json::from_str(head).map_err(ChunkProblem::Header)?;
    if h.format != CHUNK_FORMAT {
        return Err(ChunkProblem::Format { found: h.format });
    }
    if h.tool != TOOL {
        return Err(ChunkProblem::Tool { found: h.tool });
    }
    if h.search != search.identity() {
        return Err(ChunkProblem::OtherSearch);
    }
    let range = search.chunk_range(c);
    if h.chunk != c || h.first != range.start || h.points != range.len() {
        return Err(ChunkProblem::Range {
            chunk: h.chunk,
            points: h.first..h.first + h.points,
            expected_chunk: c,
            expected: range,
        });
    }
    if sha256_hex(body.as_bytes()) != h.sha256 {
        return Err(ChunkProblem::Hash);
    }
    let mut out = Vec::with_capacity(range.len());
    for (line, index) in body.lines().zip(range.clone()) {
        let at = |problem| ChunkProblem::Point { index, problem };
        let l: ChunkLine = serde_json::from_str(line).map_err(|e| at(PointProblem::Json(e)))?;
        out.push(point(l, search, index).map_err(at)?);
    }
    if out.len() != range.len() || body.lines().count() != range.len() {
        return Err(ChunkProblem::LineCount { found: body.lines().count(), expected: range.len() });
    }
    Ok(out)
}

/// A point line checked against the grid.
fn point(l: ChunkLine, search: &Search, index: usize) -> Result<PointResult, PointProblem> {
    if l.index != index {
        return Err(PointProblem::Index { found: l.index, expected: index });
    }
    let want = search.grid.texts(index);
    if l.values != want {
        return Err(PointProblem::Values { found: l.values, grid: want });
    }
    if l.metrics.len() != METRICS.len() {
        return Err(PointProblem::MetricCount { found: l.metrics.len(), expected: METRICS.len() });
    }
    let mut metrics = Vec::with_capacity(METRICS.len());
    for (name, m) in METRICS.iter().zip(&l.metrics) {
        metrics.push(match m {
            None => None,
            Some(s) => match s.parse::<f64>() {
                Ok(x) if x.is_finite() => Some(x),
                _ => return Err(PointProblem::Metric { name: name.clone(), text: s.clone() }),
            },
        });
    }
    if (l.status == Status::Ok) != l.message.is_empty() {
        return Err(PointProblem::Status { status: l.status.name(), message: l.message });
    }
    for (name, x) in [("sim_seconds", l.sim_seconds), ("theory_seconds", l.theory_seconds)] {
        if !(x.is_finite() && x >= 0.0) {
            return Err(PointProblem::Time { name, seconds: x });
        }
    }
    Ok(PointResult {
        index: l.index,
        values: l.values,
        status: l.status,
        message: l.message,
        w_positive_definite: l.w_positive_definite,
        feasible_32: l.feasible_32,
        metrics,
        sim_seconds: l.sim_seconds,
        theory_seconds: l.theory_seconds,
    })
}

/// Why a chunk file is not a complete chunk of this search ([`SearchError::Chunk`]).
#[derive(Debug, thiserror::Error)]
pub enum ChunkProblem {
    /// The path is not a regular file.
    #[error("not a regular file")]
    NotAFile,
    /// No newline ends a header line.
    #[error("no header line")]
    NoHeader,
    /// The header line is not a chunk header.
    #[error("no valid chunk header ({0})")]
    Header(#[source] serde_json::Error),
    /// The header names another format.
    #[error("format {found:?}, expected {CHUNK_FORMAT:?}")]
    Format {
        /// The header's format.
        found: String,
    },
    /// Another version of the tool wrote it.
    #[error("written by {found}, this is {TOOL}")]
    Tool {
        /// The header's tool.
        found: String,
    },
    /// Another search's chunk.
    #[error("written for another search (its manifest — base config, axes or options — differs)")]
    OtherSearch,
    /// The header's chunk or point range is not this file's.
    #[error(
        "header says chunk {chunk} with points {}..{}, expected chunk {expected_chunk} with points {}..{}",
        points.start,
        points.end,
        expected.start,
        expected.end
    )]
    Range {
        /// The header's chunk.
        chunk: usize,
        /// The header's points.
        points: std::ops::Range<usize>,
        /// The chunk the file is named for.
        expected_chunk: usize,
        /// Its points.
        expected: std::ops::Range<usize>,
    },
    /// The point lines do not hash to the header's sha256.
    #[error("its points do not hash to the header's sha256 (edited or truncated)")]
    Hash,
    /// A point line is wrong.
    #[error("point {index}: {problem}")]
    Point {
        /// The point's index in the grid.
        index: usize,
        /// What is wrong.
        problem: PointProblem,
    },
    /// Not one line per point.
    #[error("{found} point lines, expected {expected}")]
    LineCount {
        /// Lines found.
        found: usize,
        /// Points of the chunk.
        expected: usize,
    },
    /// A stored point recomputes differently ([`crate::verify::difference`]).
    #[error("point {index} recomputes differently ({why}): edited, or written by another build")]
    Recomputed {
        /// The point's index in the grid.
        index: usize,
        /// The first difference.
        #[source]
        why: PointDifference,
    },
}

/// What is wrong with a point line of a chunk ([`ChunkProblem::Point`]).
#[derive(Debug, thiserror::Error)]
pub enum PointProblem {
    /// The line is not a point's JSON.
    #[error(transparent)]
    Json(serde_json::Error),
    /// The line's index is another point's.
    #[error("index {found} where {expected} belongs")]
    Index {
        /// The line's index.
        found: usize,
        /// The index of its place.
        expected: usize,
    },
    /// The axis values are not the grid's at this index.
    #[error("values {found:?}, the grid has {grid:?} there")]
    Values {
        /// The line's values.
        found: Vec<String>,
        /// The grid's.
        grid: Vec<String>,
    },
    /// Not one metric per [`METRICS`] entry.
    #[error("{found} metrics, expected {expected}")]
    MetricCount {
        /// Metrics found.
        found: usize,
        /// [`METRICS`]' length.
        expected: usize,
    },
    /// A metric that is not a finite number.
    #[error("metric {name} = {text:?} is not a finite number")]
    Metric {
        /// The metric's name.
        name: String,
        /// Its text.
        text: String,
    },
    /// `ok` with a message, or another status without one.
    #[error("status {status} with message {message:?}")]
    Status {
        /// The status's name.
        status: &'static str,
        /// The message.
        message: String,
    },
    /// A CPU time (s) that is not finite and non-negative.
    #[error("{name} = {seconds} is not a finite time")]
    Time {
        /// `sim_seconds` or `theory_seconds`.
        name: &'static str,
        /// The time (s).
        seconds: f64,
    },
}

/// How a stored point differs from its recomputation: the first deterministic field that
/// is not the same, bit for bit ([`difference`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PointDifference {
    /// The swept values.
    #[error("values {stored:?}, recomputed {fresh:?}")]
    Values {
        /// Stored values.
        stored: Vec<String>,
        /// Recomputed values.
        fresh: Vec<String>,
    },
    /// The status or its message.
    #[error("status {} {stored_message:?}, recomputed {} {fresh_message:?}", stored.name(), fresh.name())]
    Status {
        /// Stored status.
        stored: Status,
        /// Stored message.
        stored_message: String,
        /// Recomputed status.
        fresh: Status,
        /// Recomputed message.
        fresh_message: String,
    },
    /// The theory verdicts.
    #[error("verdicts {stored:?}, recomputed {fresh:?}")]
    Verdicts {
        /// Stored verdicts.
        stored: PointVerdicts,
        /// Recomputed verdicts.
        fresh: PointVerdicts,
    },
    /// A metric (absent where not finite, as the chunk writes it).
    #[error("{name} = {}, recomputed {}", shown(*stored), shown(*fresh))]
    Metric {
        /// The metric's column name.
        name: String,
        /// Stored value.
        stored: Option<f64>,
        /// Recomputed value.
        fresh: Option<f64>,
    },
}

/// A metric's value as [`PointDifference::Metric`] prints it.
fn shown(x: Option<f64>) -> String {
    x.map_or("absent".to_string(), |x| format!("{x}"))
}
