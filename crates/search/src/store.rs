//! On-disk formats: the manifest, chunk files ([`crate::chunk`]: JSON lines under a header
//! naming their search), per-shard progress files, and the final `results.csv`,
//! `results.json`, `best.json`, `timings.csv`. Every file is written through
//! [`wingcheck_io`]'s atomic writes (`write_file_atomic`, `create_file_atomic`, `FileSet`),
//! whose temp files a later run removes once their writer is gone
//! ([`wingcheck_io::remove_stale_temps`]).

use std::path::{Path, PathBuf};

use serde::Serialize;
use serde_json::{Map, Value};

use crate::records::{BestDocument, PointRecord};

pub use crate::chunk::{chunk_text, read_chunk};
use crate::metric::{Metric, Ranking, METRICS};
use crate::point::{PointResult, Status};
use crate::SearchError;

/// Directory of the chunk files inside an output directory.
pub const CHUNK_DIR: &str = "chunks";

/// Largest file a search reads (a manifest, a chunk: ≈ 0.6 kB per point).
pub const MAX_READ_BYTES: u64 = 4 << 30;

/// Read a regular file to a string (a FIFO or device is refused without being opened:
/// [`wingcheck_io::read_regular`]).
pub fn read(path: &Path) -> Result<String, SearchError> {
    let bytes = wingcheck_io::read_regular(path, MAX_READ_BYTES)
        .map_err(|source| SearchError::Read { path: path.to_path_buf(), source })?;
    String::from_utf8(bytes).map_err(|_| SearchError::NotText { path: path.to_path_buf() })
}

/// Create a directory (and parents).
pub fn mkdir(path: &Path) -> Result<(), SearchError> {
    std::fs::create_dir_all(path).map_err(|source| SearchError::FileSystem { path: path.to_path_buf(), source })
}

/// Path of chunk c.
pub fn chunk_path(dir: &Path, c: usize) -> PathBuf {
    dir.join(CHUNK_DIR).join(format!("chunk-{c:05}.jsonl"))
}

/// A verdict as written in results.csv: `true`/`false`, with `false` also when undecided (the
/// `*_decided` column says which).
fn verdict(b: Option<bool>) -> &'static str {
    if b == Some(true) {
        "true"
    } else {
        "false"
    }
}

fn decided(b: Option<bool>) -> &'static str {
    if b.is_some() {
        "true"
    } else {
        "false"
    }
}

/// A text cell: the text, or `none` (no cell is left empty but a metric without a value,
/// which `missing_metrics` names).
fn text_cell(s: &str) -> &str {
    if s.is_empty() {
        "none"
    } else {
        s
    }
}

/// The status columns of results.csv, between the axis values and the metrics.
pub const RESULT_STATUS_COLUMNS: [&str; 8] = [
    "status",
    "w_decided",
    "w_positive_definite",
    "feasible_32_decided",
    "feasible_32",
    "theorem_feasible",
    "settled",
    "missing_metrics",
];

/// Header of `results.csv`: `index`, the axis keys as columns (`control.a` → `control__a`),
/// [`RESULT_STATUS_COLUMNS`], the metrics with their unit suffixes ([`metric_columns`]),
/// `message` (docs/outputs.md).
pub fn results_csv_header(keys: &[String]) -> String {
    let mut head = vec!["index".to_string()];
    head.extend(keys.iter().map(|k| wingcheck_io::key_column(k)));
    head.extend(RESULT_STATUS_COLUMNS.map(String::from));
    head.extend(metric_columns());
    head.push("message".into());
    wingcheck_io::csv_record(head)
}

/// The metric columns' names: each metric with its unit suffix (`rms_q_tip_m`, `lambda_per_s`).
pub fn metric_columns() -> Vec<String> {
    METRICS.to_vec()
}

/// One row of `results.csv` (points in index order; f64 in Rust's shortest round-trip form).
/// A metric cell is empty exactly when the metric has no value, and `missing_metrics` then
/// names it (`settling_time` also sets `settled` to false).
pub fn results_csv_row(p: &PointResult) -> String {
    let mut row = vec![p.index.to_string()];
    row.extend(p.values.iter().cloned());
    let settling = p.metric(Metric::SettlingTime);
    let missing: Vec<&str> =
        METRICS.iter().zip(&p.metrics).filter(|(_, m)| m.is_none()).map(|(n, _)| n.as_str()).collect();
    row.extend(
        [
            p.status.name(),
            decided(p.w_positive_definite),
            verdict(p.w_positive_definite),
            decided(p.feasible_32),
            verdict(p.feasible_32),
            verdict(p.theorem_feasible()),
            if settling.is_some() { "true" } else { "false" },
        ]
        .map(String::from),
    );
    row.push(if missing.is_empty() { "none".into() } else { missing.join(";") });
    row.extend(p.metrics.iter().map(|m| m.map(wingcheck_io::number).unwrap_or_default()));
    row.push(text_cell(&p.message).to_string());
    wingcheck_io::csv_record(row)
}

/// One point as a JSON object ([`PointRecord`]).
pub fn point_json(keys: &[String], p: &PointResult) -> PointRecord {
    PointRecord::new(keys, p)
}

/// The points of `results.json`, pulled one at a time from a stream while serde_json writes
/// them: only the point being written exists in memory (and its JSON tree). The first error of
/// the stream stops the document and is kept in `error`.
struct LazyPoints<'a, I> {
    keys: &'a [String],
    points: std::cell::RefCell<I>,
    error: std::cell::RefCell<Option<SearchError>>,
}

impl<I: Iterator<Item = Result<PointResult, SearchError>>> Serialize for LazyPoints<'_, I> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::{Error, SerializeSeq};
        let mut seq = s.serialize_seq(None)?;
        for p in &mut *self.points.borrow_mut() {
            match p {
                Ok(p) => seq.serialize_element(&point_json(self.keys, &p))?,
                Err(e) => {
                    let text = e.to_string();
                    *self.error.borrow_mut() = Some(e);
                    return Err(S::Error::custom(text));
                }
            }
        }
        seq.end()
    }
}

/// Write `results.json` to `out`, consuming `points` (index order) lazily: the fields of
/// [`crate::records::ResultsDocument`] in its order, pretty-printed by serde_json with a
/// trailing newline — the same bytes as `serde_json::to_string_pretty` of the whole document.
pub fn write_results_json<I>(
    out: &mut impl std::io::Write,
    path: &Path,
    keys: &[String],
    provenance: &wingcheck_io::Provenance,
    points: I,
) -> Result<(), SearchError>
where
    I: Iterator<Item = Result<PointResult, SearchError>>,
{
    #[derive(Serialize)]
    #[serde(bound = "")]
    struct Doc<'a, I: Iterator<Item = Result<PointResult, SearchError>>> {
        schema_version: u32,
        provenance: &'a wingcheck_io::Provenance,
        axes: &'a [String],
        metrics: &'a [String],
        units: Map<String, Value>,
        points: &'a LazyPoints<'a, I>,
    }
    let lazy = LazyPoints { keys, points: std::cell::RefCell::new(points), error: std::cell::RefCell::new(None) };
    let doc = Doc {
        schema_version: wingcheck_io::SCHEMA_VERSION,
        provenance,
        axes: keys,
        metrics: &METRICS[..],
        units: crate::records::metric_units(),
        points: &lazy,
    };
    let written = serde_json::to_writer_pretty(&mut *out, &doc);
    if let Some(e) = lazy.error.borrow_mut().take() {
        return Err(e);
    }
    written.map_err(|source| SearchError::Serialise { path: path.to_path_buf(), source })?;
    out.write_all(b"\n").map_err(|e| wingcheck_io::IoError::Io {
        action: "write",
        path: path.to_path_buf(),
        source: e,
    })?;
    Ok(())
}

/// The `count` best `ok` points by a [`Ranking`], overall and among the theorem-feasible ones; ties by index. Fed the points in
/// index order, it keeps at most `2 × count` of them.
#[derive(Debug)]
pub struct BestPoints {
    ranking: Ranking,
    count: usize,
    overall: Vec<(f64, PointResult)>,
    feasible: Vec<(f64, PointResult)>,
}

impl BestPoints {
    /// The `count` best points by `ranking`.
    pub fn new(ranking: Ranking, count: usize) -> BestPoints {
        BestPoints { ranking, count, overall: vec![], feasible: vec![] }
    }

    fn insert(list: &mut Vec<(f64, PointResult)>, x: f64, p: &PointResult, maximise: bool, count: usize) {
        // points arrive in index order, so an equal value goes after those already kept
        let pos =
            list.partition_point(|(y, _)| if maximise { y.total_cmp(&x).is_ge() } else { y.total_cmp(&x).is_le() });
        if pos < count {
            list.insert(pos, (x, p.clone()));
            list.truncate(count);
        }
    }

    /// Consider the next point (points must come in increasing index order).
    pub fn add(&mut self, p: &PointResult) {
        if p.status != Status::Ok {
            return;
        }
        let Some(x) = p.metric(self.ranking.metric).filter(|x| x.is_finite()) else { return };
        Self::insert(&mut self.overall, x, p, self.ranking.maximise, self.count);
        if p.theorem_feasible() == Some(true) {
            Self::insert(&mut self.feasible, x, p, self.ranking.maximise, self.count);
        }
    }

    /// `best.json` ([`BestDocument`]).
    pub fn json(&self, keys: &[String]) -> String {
        let list = |l: &[(f64, PointResult)]| l.iter().map(|(_, p)| point_json(keys, p)).collect::<Vec<PointRecord>>();
        let doc = BestDocument {
            schema_version: wingcheck_io::SCHEMA_VERSION,
            metric: self.ranking.metric.column().to_string(),
            order: if self.ranking.maximise { "descending" } else { "ascending" }.to_string(),
            unit: BestDocument::unit_of(self.ranking.metric),
            best: list(&self.overall),
            best_theorem_feasible: list(&self.feasible),
        };
        serde_json::to_string_pretty(&doc).expect("best serialises") + "\n"
    }
}

/// Header of `timings.csv` (index, simulation and theory wall time in s; not deterministic).
pub fn timings_header() -> String {
    wingcheck_io::csv_record(["index", "sim_wall_s", "theory_wall_s"])
}

/// One row of `timings.csv`.
pub fn timings_row(p: &PointResult) -> String {
    wingcheck_io::csv_record([
        p.index.to_string(),
        wingcheck_io::number(p.sim_seconds),
        wingcheck_io::number(p.theory_seconds),
    ])
}

/// Header of `failures.csv`: `index,<axis key columns>,status,message` (the whole file when
/// every point succeeded).
pub fn failures_header(keys: &[String]) -> String {
    let mut head = vec!["index".to_string()];
    head.extend(keys.iter().map(|k| wingcheck_io::key_column(k)));
    head.extend(["status".to_string(), "message".to_string()]);
    wingcheck_io::csv_record(head)
}

/// The row of `failures.csv` of a point whose status is not `ok` (None for an `ok` point).
pub fn failures_row(p: &PointResult) -> Option<String> {
    if p.status == Status::Ok {
        return None;
    }
    let mut row = vec![p.index.to_string()];
    row.extend(p.values.iter().cloned());
    row.push(p.status.name().to_string());
    row.push(text_cell(&p.message).to_string());
    Some(wingcheck_io::csv_record(row))
}
