//! On-disk formats: the manifest, chunk files ([`crate::chunk`]: JSON lines under a header
//! naming their search, written via temp file + rename), per-shard progress files, and the final
//! `results.csv`, `results.json`, `best.json`, `timings.csv`.

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

/// Tag of this process's temp files: `.{name}.tmp-{pid}` (one file at a time) and
/// `.{name}.set-tmp-{pid}` ([`FileSet`]). While they exist the process holds its lock
/// `.wingcheck-{pid}.lock` in the same directory ([`wingcheck_io::DirLock`]); a run removes the
/// temp files whose writer no longer holds it ([`remove_stale_temps`]), so a directory resumed
/// after a kill holds exactly the files of an uninterrupted run.
const TMP_TAGS: [&str; 2] = [".tmp-", ".set-tmp-"];

/// The temp file `.{name}{tag}{pid}` of `path` (the name's bytes as given: a name that is not
/// UTF-8 keeps them).
fn temp_path(path: &Path, tag: &str) -> PathBuf {
    let mut name = std::ffi::OsString::from(".");
    name.push(path.file_name().unwrap_or_default());
    name.push(format!("{tag}{}", std::process::id()));
    path.with_file_name(name)
}

/// Refuses to rename over `path` unless it is missing or a regular file (a FIFO, device or
/// symlink a user put there is never replaced).
fn check_replaceable(path: &Path) -> Result<(), SearchError> {
    wingcheck_io::paths::check_replaceable_file(path)
        .map_err(|e| SearchError::Io { path: path.display().to_string(), detail: e.to_string() })
}

/// Write `bytes` to `path` atomically: temp file `.{name}.tmp-{pid}` in the same directory,
/// fsync, mode 0644, rename over `path` (refused if `path` is not a regular file).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), SearchError> {
    check_replaceable(path)?;
    use std::io::Write;
    let err = |e: std::io::Error| SearchError::Io { path: path.display().to_string(), detail: e.to_string() };
    let tmp = temp_path(path, TMP_TAGS[0]);
    let dir = path.parent().unwrap_or(Path::new("."));
    let _lock = wingcheck_io::DirLock::acquire(dir).map_err(err)?;
    let write = || -> std::io::Result<()> {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            f.set_permissions(std::fs::Permissions::from_mode(0o644))?;
        }
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    };
    write().map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        err(e)
    })
}

fn io_error(p: &Path) -> impl Fn(std::io::Error) -> SearchError + '_ {
    move |e| SearchError::Io { path: p.display().to_string(), detail: e.to_string() }
}

/// Write a chunk and the progress file that counts it together: both staged (temp file, fsync)
/// before either is renamed into place, the chunk first. A kill between the two renames leaves
/// the progress file one chunk behind, which the next run rewrites before any work.
pub fn write_with_progress(
    chunk: &Path,
    bytes: &[u8],
    progress: &Path,
    progress_bytes: &[u8],
) -> Result<(), SearchError> {
    use std::io::Write;
    check_replaceable(chunk)?;
    check_replaceable(progress)?;
    let (chunk_tmp, progress_tmp) = (temp_path(chunk, TMP_TAGS[0]), temp_path(progress, TMP_TAGS[0]));
    let dir = chunk.parent().unwrap_or(Path::new("."));
    let pdir = progress.parent().unwrap_or(Path::new("."));
    let _locks = (
        wingcheck_io::DirLock::acquire(dir).map_err(io_error(chunk))?,
        wingcheck_io::DirLock::acquire(pdir).map_err(io_error(progress))?,
    );
    let stage = |tmp: &Path, bytes: &[u8]| -> std::io::Result<()> {
        let mut f = std::fs::File::create(tmp)?;
        f.write_all(bytes)?;
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            f.set_permissions(std::fs::Permissions::from_mode(0o644))?;
        }
        f.sync_all()
    };
    let result = stage(&chunk_tmp, bytes)
        .map_err(io_error(chunk))
        .and_then(|()| stage(&progress_tmp, progress_bytes).map_err(io_error(progress)))
        .and_then(|()| std::fs::rename(&chunk_tmp, chunk).map_err(io_error(chunk)))
        .and_then(|()| std::fs::rename(&progress_tmp, progress).map_err(io_error(progress)));
    if result.is_err() {
        let _ = std::fs::remove_file(&chunk_tmp);
        let _ = std::fs::remove_file(&progress_tmp);
    }
    result
}

/// Create `path` holding `bytes` unless it exists, atomically and without overwriting: the
/// bytes go to a temp file (as in [`write_atomic`]) that is then hard-linked to `path`, which
/// fails if another process created `path` first. Returns whether this call created it.
pub fn write_new(path: &Path, bytes: &[u8]) -> Result<bool, SearchError> {
    use std::io::Write;
    let err = |e: std::io::Error| SearchError::Io { path: path.display().to_string(), detail: e.to_string() };
    let tmp = temp_path(path, TMP_TAGS[0]);
    let dir = path.parent().unwrap_or(Path::new("."));
    let _lock = wingcheck_io::DirLock::acquire(dir).map_err(err)?;
    let write = || -> std::io::Result<bool> {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            f.set_permissions(std::fs::Permissions::from_mode(0o644))?;
        }
        f.sync_all()?;
        match std::fs::hard_link(&tmp, path) {
            Ok(()) => Ok(true),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => Ok(false),
            Err(e) => Err(e),
        }
    };
    let created = write();
    let _ = std::fs::remove_file(&tmp);
    created.map_err(err)
}

/// Removes the temp files ([`TMP_TAGS`]) in `dir` whose writer no longer holds its lock there
/// (killed during a write or the final assembly), and such writers' lock files; those of live
/// processes are left alone.
pub fn remove_stale_temps(dir: &Path) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for e in entries.flatten() {
        let name = e.file_name().to_string_lossy().to_string();
        if !name.starts_with('.') || !e.file_type().is_ok_and(|t| t.is_file()) {
            continue;
        }
        let pid = TMP_TAGS.iter().find_map(|tag| name.rsplit_once(tag).and_then(|(_, p)| p.parse::<u32>().ok()));
        if let Some(pid) = pid {
            if !wingcheck_io::owner_alive(dir, pid) {
                let _ = std::fs::remove_file(e.path());
            }
        }
    }
    wingcheck_io::remove_stale_locks(dir);
}

/// Whether `name` is a temp file of [`write_atomic`] or [`FileSet`], or the lock file of their
/// writer.
pub fn is_temp(name: &str) -> bool {
    name.starts_with('.')
        && (TMP_TAGS.iter().any(|tag| name.rsplit_once(tag).is_some_and(|(_, p)| p.parse::<u32>().is_ok()))
            || wingcheck_io::is_lock_file(name))
}

/// Largest file a search reads (a manifest, a chunk: ≈ 0.6 kB per point).
pub const MAX_READ_BYTES: u64 = 4 << 30;

/// Read a regular file to a string (a FIFO or device is refused without being opened:
/// [`wingcheck_io::read_regular`]).
pub fn read(path: &Path) -> Result<String, SearchError> {
    let io = |detail: String| SearchError::Io { path: path.display().to_string(), detail };
    let bytes = wingcheck_io::read_regular(path, MAX_READ_BYTES).map_err(|e| io(e.to_string()))?;
    String::from_utf8(bytes).map_err(|_| io("not UTF-8 text".into()))
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
    path: &str,
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
    let io = |e: String| SearchError::Io { path: path.to_string(), detail: e };
    let written = serde_json::to_writer_pretty(&mut *out, &doc);
    if let Some(e) = lazy.error.borrow_mut().take() {
        return Err(e);
    }
    written.map_err(|e| io(e.to_string()))?;
    out.write_all(b"\n").map_err(|e| io(e.to_string()))
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

/// Writes a set of files into a directory all or nothing: [`FileSet::stage`] writes each file
/// to a temp file in the directory at once (where a full disk shows, and so its text can be
/// dropped), [`FileSet::commit`] renames them all into place; dropped without a commit (an
/// error on the way), it removes its temp files and no file of the set is touched.
pub struct FileSet {
    dir: PathBuf,
    staged: Vec<String>,
    committed: bool,
    // Held while temp files of the set may exist (dropped after `Drop` removed them).
    _lock: wingcheck_io::DirLock,
}

impl FileSet {
    /// An empty set for `dir` (taking this process's lock there).
    pub fn new(dir: &Path) -> Result<FileSet, SearchError> {
        let lock = wingcheck_io::DirLock::acquire(dir)
            .map_err(|e| SearchError::Io { path: dir.display().to_string(), detail: format!("cannot lock: {e}") })?;
        Ok(FileSet { dir: dir.to_path_buf(), staged: Vec::new(), committed: false, _lock: lock })
    }

    fn tmp(&self, name: &str) -> PathBuf {
        self.dir.join(format!(".{name}{}{}", TMP_TAGS[1], std::process::id()))
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

    /// Open the temp file of `name` for writing piece by piece; [`Staged::finish`] it before
    /// the commit.
    pub fn open(&mut self, name: &str) -> Result<Staged, SearchError> {
        self.staged.push(name.to_string());
        let path = self.dir.join(name).display().to_string();
        let file = std::fs::File::create(self.tmp(name))
            .map_err(|e| SearchError::Io { path: path.clone(), detail: e.to_string() })?;
        Ok(Staged { out: std::io::BufWriter::new(file), path })
    }

    /// Rename every staged file into place (none if any target is not a regular file); returns
    /// their names.
    pub fn commit(mut self) -> Result<Vec<String>, SearchError> {
        for name in &self.staged {
            check_replaceable(&self.dir.join(name))?;
        }
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

/// A file of a [`FileSet`] being written piece by piece (buffered).
pub struct Staged {
    out: std::io::BufWriter<std::fs::File>,
    path: String,
}

impl Staged {
    /// Append `text`.
    pub fn write(&mut self, text: &str) -> Result<(), SearchError> {
        use std::io::Write;
        self.out.write_all(text.as_bytes()).map_err(|e| self.error(e))
    }

    /// The full path of the file (what its errors name).
    pub fn path(&self) -> &str {
        &self.path
    }

    /// The underlying writer (errors name the file via [`Staged::error`]).
    pub fn writer(&mut self) -> &mut std::io::BufWriter<std::fs::File> {
        &mut self.out
    }

    /// An I/O error of this file.
    pub fn error(&self, e: impl std::fmt::Display) -> SearchError {
        SearchError::Io { path: self.path.clone(), detail: e.to_string() }
    }

    /// Flush and sync.
    pub fn finish(self) -> Result<(), SearchError> {
        let path = self.path;
        let err = |e: String| SearchError::Io { path: path.clone(), detail: e };
        let file = self.out.into_inner().map_err(|e| err(e.error().to_string()))?;
        file.sync_all().map_err(|e| err(e.to_string()))
    }
}
