//! On-disk formats: the manifest, chunk files (JSON lines, written via temp file + rename),
//! per-shard progress files, and the final `results.csv`, `results.json`, `best.json`,
//! `timings.csv`.
//!
//! Floats: chunk files store every metric as the text of Rust's shortest round-trip form
//! (`format!("{x}")`), parsed back with `str::parse::<f64>` (exact), so results read from
//! chunks equal the computed values bit for bit.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use serde_json::{json, Map, Value};

use crate::point::{PointResult, Status, METRICS};
use crate::SearchError;

/// Directory of the chunk files inside an output directory.
pub const CHUNK_DIR: &str = "chunks";

/// Write `bytes` to `path` atomically (temp file in the same directory + rename).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), SearchError> {
    wingcheck_sim::output::write_atomic(path, bytes)
        .map_err(|e| SearchError::Io { path: path.display().to_string(), detail: e.to_string() })
}

/// Read a file to a string.
pub fn read(path: &Path) -> Result<String, SearchError> {
    std::fs::read_to_string(path)
        .map_err(|e| SearchError::Io { path: path.display().to_string(), detail: e.to_string() })
}

/// Create a directory (and parents).
pub fn mkdir(path: &Path) -> Result<(), SearchError> {
    std::fs::create_dir_all(path)
        .map_err(|e| SearchError::Io { path: path.display().to_string(), detail: e.to_string() })
}

/// Path of chunk c.
pub fn chunk_path(dir: &Path, c: usize) -> PathBuf {
    dir.join(CHUNK_DIR).join(format!("chunk-{c:05}.jsonl"))
}

/// One line of a chunk file.
#[derive(Debug, Serialize, Deserialize)]
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

/// Serialise a chunk (one JSON line per point, in index order).
pub fn chunk_text(points: &[PointResult]) -> String {
    let mut out = String::new();
    for p in points {
        let line = ChunkLine {
            index: p.index,
            values: p.values.clone(),
            status: p.status,
            message: p.message.clone(),
            w_positive_definite: p.w_positive_definite,
            feasible_32: p.feasible_32,
            metrics: p.metrics.iter().map(|m| m.map(|x| format!("{x}"))).collect(),
            sim_seconds: p.sim_seconds,
            theory_seconds: p.theory_seconds,
        };
        out.push_str(&serde_json::to_string(&line).expect("chunk line serialises"));
        out.push('\n');
    }
    out
}

/// Read chunk c if present and complete: exactly the points `range`, in order. A missing or
/// malformed chunk gives `Ok(None)` (it is recomputed).
pub fn read_chunk(
    dir: &Path,
    c: usize,
    range: std::ops::Range<usize>,
) -> Result<Option<Vec<PointResult>>, SearchError> {
    let path = chunk_path(dir, c);
    if !path.exists() {
        return Ok(None);
    }
    let text = read(&path)?;
    let mut out = Vec::with_capacity(range.len());
    for line in text.lines().filter(|l| !l.trim().is_empty()) {
        let Ok(l) = serde_json::from_str::<ChunkLine>(line) else { return Ok(None) };
        if l.metrics.len() != METRICS.len() {
            return Ok(None);
        }
        let mut metrics = Vec::with_capacity(METRICS.len());
        for m in &l.metrics {
            match m {
                None => metrics.push(None),
                Some(s) => match s.parse::<f64>() {
                    Ok(x) => metrics.push(Some(x)),
                    Err(_) => return Ok(None),
                },
            }
        }
        out.push(PointResult {
            index: l.index,
            values: l.values,
            status: l.status,
            message: l.message,
            w_positive_definite: l.w_positive_definite,
            feasible_32: l.feasible_32,
            metrics,
            sim_seconds: l.sim_seconds,
            theory_seconds: l.theory_seconds,
        });
    }
    let ok = out.len() == range.len() && out.iter().zip(range).all(|(p, i)| p.index == i);
    Ok(ok.then_some(out))
}

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

fn opt_bool(b: Option<bool>) -> String {
    b.map(|b| b.to_string()).unwrap_or_default()
}

/// `results.csv`: header `index,<axis keys>,status,w_positive_definite,feasible_32,
/// theorem_feasible,<METRICS>,message`; one row per point in index order; f64 in Rust's
/// shortest round-trip form; missing values empty.
pub fn results_csv(keys: &[String], points: &[PointResult]) -> String {
    let mut head = vec!["index".to_string()];
    head.extend(keys.iter().map(|k| csv_field(k)));
    head.extend(["status", "w_positive_definite", "feasible_32", "theorem_feasible"].map(String::from));
    head.extend(METRICS.iter().map(|m| m.to_string()));
    head.push("message".into());
    let mut out = head.join(",");
    out.push('\n');
    for p in points {
        let mut row = vec![p.index.to_string()];
        row.extend(p.values.iter().map(|v| csv_field(v)));
        row.push(p.status.name().into());
        row.push(opt_bool(p.w_positive_definite));
        row.push(opt_bool(p.feasible_32));
        row.push(opt_bool(p.theorem_feasible()));
        row.extend(p.metrics.iter().map(|m| m.map(|x| format!("{x}")).unwrap_or_default()));
        row.push(csv_field(&p.message));
        out.push_str(&row.join(","));
        out.push('\n');
    }
    out
}

/// A swept value as JSON: the number or literal it parses as, else a string.
fn value_json(text: &str) -> Value {
    serde_json::from_str(text).unwrap_or_else(|_| Value::String(text.to_string()))
}

/// One point as a JSON object (metrics keyed by name; missing → null).
pub fn point_json(keys: &[String], p: &PointResult) -> Value {
    let mut values = Map::new();
    for (k, v) in keys.iter().zip(&p.values) {
        values.insert(k.clone(), value_json(v));
    }
    let mut metrics = Map::new();
    for (name, m) in METRICS.iter().zip(&p.metrics) {
        metrics.insert(name.to_string(), m.map_or(Value::Null, |x| json!(x)));
    }
    json!({
        "index": p.index,
        "values": values,
        "status": p.status,
        "message": p.message,
        "w_positive_definite": p.w_positive_definite,
        "feasible_32": p.feasible_32,
        "theorem_feasible": p.theorem_feasible(),
        "metrics": metrics,
    })
}

/// The points of `results.json`, serialised one at a time (the JSON tree of one point exists
/// only while it is written, so memory does not hold a tree of every point).
struct PointsSeq<'a> {
    keys: &'a [String],
    points: &'a [PointResult],
}

impl Serialize for PointsSeq<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(self.points.iter().map(|p| point_json(self.keys, p)))
    }
}

/// `results.json`: `{"axes": [keys], "metrics": [names], "points": [point_json …]}` (keys in
/// that order, as serde_json's map of a `json!` document sorts them).
pub fn results_json(keys: &[String], points: &[PointResult]) -> String {
    #[derive(Serialize)]
    struct Doc<'a> {
        axes: &'a [String],
        metrics: &'a [&'a str],
        points: PointsSeq<'a>,
    }
    let doc = Doc { axes: keys, metrics: &METRICS, points: PointsSeq { keys, points } };
    serde_json::to_string_pretty(&doc).expect("results serialise") + "\n"
}

/// `best.json`: the `count` best `ok` points by `metric` (a name of [`METRICS`], minimised;
/// prefix `-` to maximise), overall and among the theorem-feasible ones; ties by index.
pub fn best_json(keys: &[String], points: &[PointResult], metric: &str, count: usize) -> Result<String, SearchError> {
    let (name, maximise) = match metric.strip_prefix('-') {
        Some(n) => (n, true),
        None => (metric, false),
    };
    if crate::point::metric_index(name).is_none() {
        return Err(SearchError::Options(format!("unknown metric `{name}`: use one of {}", METRICS.join(", "))));
    }
    let rank = |feasible_only: bool| -> Vec<Value> {
        let mut c: Vec<(&PointResult, f64)> = points
            .iter()
            .filter(|p| p.status == Status::Ok && (!feasible_only || p.theorem_feasible() == Some(true)))
            .filter_map(|p| p.metric(name).filter(|x| x.is_finite()).map(|x| (p, x)))
            .collect();
        c.sort_by(|a, b| {
            let o = if maximise { b.1.total_cmp(&a.1) } else { a.1.total_cmp(&b.1) };
            o.then(a.0.index.cmp(&b.0.index))
        });
        c.into_iter().take(count).map(|(p, _)| point_json(keys, p)).collect()
    };
    let doc = json!({
        "metric": name,
        "order": if maximise { "descending" } else { "ascending" },
        "best": rank(false),
        "best_theorem_feasible": rank(true),
    });
    Ok(serde_json::to_string_pretty(&doc).expect("best serialises") + "\n")
}

/// `timings.csv`: index, simulation and theory wall time (s). Not deterministic.
pub fn timings_csv(points: &[PointResult]) -> String {
    let mut out = String::from("index,sim_seconds,theory_seconds\n");
    for p in points {
        out.push_str(&format!("{},{},{}\n", p.index, p.sim_seconds, p.theory_seconds));
    }
    out
}

/// `failures.csv`: every point whose status is not `ok`, in index order: `index,<axis keys>,
/// status,message` (header only when every point succeeded).
pub fn failures_csv(keys: &[String], points: &[PointResult]) -> String {
    let mut out = String::from("index,");
    for k in keys {
        out.push_str(&csv_field(k));
        out.push(',');
    }
    out.push_str("status,message\n");
    for p in points.iter().filter(|p| p.status != Status::Ok) {
        out.push_str(&p.index.to_string());
        out.push(',');
        for v in &p.values {
            out.push_str(&csv_field(v));
            out.push(',');
        }
        out.push_str(p.status.name());
        out.push(',');
        out.push_str(&csv_field(&p.message));
        out.push('\n');
    }
    out
}

/// Writes a set of files into a directory all or nothing: [`FileSet::stage`] writes each file
/// to a temp file in the directory at once (where a full disk shows, and so its text can be
/// dropped), [`FileSet::commit`] renames them all into place; dropped without a commit (an
/// error on the way), it removes its temp files and no file of the set is touched.
pub struct FileSet {
    dir: PathBuf,
    staged: Vec<String>,
    committed: bool,
}

impl FileSet {
    /// An empty set for `dir`.
    pub fn new(dir: &Path) -> FileSet {
        FileSet { dir: dir.to_path_buf(), staged: Vec::new(), committed: false }
    }

    fn tmp(&self, name: &str) -> PathBuf {
        self.dir.join(format!(".{name}.set-tmp-{}", std::process::id()))
    }

    /// Write `text` to the temp file of `name`.
    pub fn stage(&mut self, name: &str, text: &str) -> Result<(), SearchError> {
        use std::io::Write;
        self.staged.push(name.to_string());
        let tmp = self.tmp(name);
        let write = || -> std::io::Result<()> {
            let mut f = std::fs::File::create(&tmp)?;
            f.write_all(text.as_bytes())?;
            f.sync_all()
        };
        write().map_err(|e| SearchError::Io { path: self.dir.join(name).display().to_string(), detail: e.to_string() })
    }

    /// Rename every staged file into place; returns their names.
    pub fn commit(mut self) -> Result<Vec<String>, SearchError> {
        for name in &self.staged {
            std::fs::rename(self.tmp(name), self.dir.join(name)).map_err(|e| SearchError::Io {
                path: self.dir.join(name).display().to_string(),
                detail: e.to_string(),
            })?;
        }
        self.committed = true;
        Ok(std::mem::take(&mut self.staged))
    }
}

impl Drop for FileSet {
    fn drop(&mut self) {
        if !self.committed {
            for name in &self.staged {
                let _ = std::fs::remove_file(self.tmp(name));
            }
        }
    }
}
