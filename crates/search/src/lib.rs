//! Parameter searches for wingcheck (`wingcheck search`, `wingcheck merge`).
//!
//! A search sweeps any config keys over grids ([`Axis`]: `key=lo..hi:log:N`,
//! `key=lo..hi:lin:N`, `key=v1,v2,…`). Every point (config = base + overrides) gets
//!
//! - the theory ([`theory`]): tight λ2, λ1 of W/κ (W ≻ 0?), the best λ3 of (29)–(32)
//!   ((32) feasible?), and where feasible λ, ε and Theorem 2's ultimate bound;
//! - the closed-loop simulation of the configured controller and its metrics ([`point`]).
//!
//! Points are numbered row-major (first axis slowest) and grouped into chunks of
//! `chunk_size` consecutive points. Chunk c belongs to shard K/N iff c mod N = K − 1. Each
//! chunk is written as `chunks/chunk-CCCCC.jsonl` via temp file + rename, so a killed run
//! restarts where it stopped, and the final files are always assembled from the chunk files
//! in index order ([`finalize`]): a single run, a resumed run and merged shards give
//! byte-identical `manifest.json`, `results.csv`, `results.json`, `best.json`,
//! `boundary.csv` and heatmaps (only `timings.csv` and the progress files hold wall times).
//! Results never depend on the number of rayon threads: points are pure functions of their
//! config, collected in index order.

pub mod axis;
mod heatmap;
pub mod modal;
pub mod point;
mod refine;
pub mod store;
pub mod theory;

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use wingcheck_model::Config;

pub use axis::{parse_axes, validate_axes, Axis, Grid, Spacing};
pub use heatmap::heatmap_svg;
pub use point::{PointResult, Status, METRICS};
pub use refine::{boundaries, boundary_csv, BoundaryRow};
pub use theory::{Theory, TheoryCache, Verdicts};

/// Errors of a search (a failing point is a status in the results, not an error).
#[derive(Debug, thiserror::Error)]
pub enum SearchError {
    /// An `--over` axis is malformed or makes the configuration invalid.
    #[error("axis `{axis}`: {reason}")]
    Axis {
        /// The axis as given.
        axis: String,
        /// What is wrong.
        reason: String,
    },
    /// Bad search options (shard, metric, window, tolerance, chunk size).
    #[error("{0}")]
    Options(String),
    /// A file could not be read or written.
    #[error("{path}: {detail}")]
    Io {
        /// The file.
        path: String,
        /// What happened.
        detail: String,
    },
    /// A directory holds a different search, or shards disagree.
    #[error("{dir}: {reason}")]
    Mismatch {
        /// The directory.
        dir: String,
        /// What differs.
        reason: String,
    },
    /// Merging found chunks that no shard has produced.
    #[error("{missing} of {total} chunks are missing (first: {first:?}); run the missing shards first")]
    MissingChunks {
        /// Number missing.
        missing: usize,
        /// Number of chunks of the search.
        total: usize,
        /// The first few missing chunk numbers.
        first: Vec<usize>,
    },
    /// A theory computation failed (eigenproblem, SOCP).
    #[error("theory ({what}): {detail}")]
    Theory {
        /// Which computation.
        what: String,
        /// What happened.
        detail: String,
    },
}

/// Options that change results (all recorded in the manifest).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SearchOptions {
    /// Metric window [t0, t1] (s); None: the second half of the horizon.
    pub window: Option<(f64, f64)>,
    /// Points per chunk (≥ 1).
    pub chunk_size: usize,
    /// Boundary refinement tolerance: relative (hi/lo − 1) on log axes, a fraction of the axis
    /// span on lin axes. None: report the coarse brackets only.
    pub refine: Option<f64>,
    /// Metric ranking `best.json` (minimised; prefix `-` to maximise).
    pub best_metric: String,
    /// Points listed in `best.json`.
    pub best_count: usize,
    /// Elements N of the Galerkin space of W and κ.
    pub lyapunov_elements: usize,
}

impl Default for SearchOptions {
    fn default() -> Self {
        SearchOptions {
            window: None,
            chunk_size: 32,
            refine: None,
            best_metric: "rms_q_tip".into(),
            best_count: 10,
            lyapunov_elements: 8,
        }
    }
}

/// `manifest.json`: everything that defines a search's results.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    /// Format of the directory.
    pub format: u32,
    /// The base configuration.
    pub base_config: Config,
    /// SHA-256 of the base configuration (`wingcheck_claims::config_sha256`).
    pub base_config_sha256: String,
    /// The axes.
    pub axes: Vec<Axis>,
    /// The axes in command-line form.
    pub axis_specs: Vec<String>,
    /// Number of points.
    pub points: usize,
    /// Number of chunks.
    pub chunks: usize,
    /// Point numbering.
    pub point_order: String,
    /// Shard rule.
    pub sharding: String,
    /// Options.
    pub options: SearchOptions,
    /// Metric columns.
    pub metrics: Vec<String>,
}

/// A validated search.
#[derive(Debug, Clone)]
pub struct Search {
    /// The base configuration.
    pub base: Config,
    /// The grid.
    pub grid: Grid,
    /// The options.
    pub options: SearchOptions,
}

impl Search {
    /// Parse and validate the axes (`--over` specs) and options; no work is done here.
    pub fn new(base: Config, specs: &[String], options: SearchOptions) -> Result<Search, SearchError> {
        let axes = parse_axes(&base, specs)?;
        Search::from_axes(base, axes, options)
    }

    /// From typed axes (validated here).
    /// Integer keys are detected here ([`Axis::detect_integer`]).
    pub fn from_axes(base: Config, mut axes: Vec<Axis>, options: SearchOptions) -> Result<Search, SearchError> {
        for a in &mut axes {
            a.detect_integer(&base);
        }
        validate_axes(&base, &axes)?;
        let o = &options;
        if o.chunk_size == 0 {
            return Err(SearchError::Options("chunk size must be ≥ 1".into()));
        }
        if let Some(t) = o.refine {
            if !(t > 0.0 && t < 1.0) {
                return Err(SearchError::Options(format!("--refine {t}: the tolerance must lie in (0, 1)")));
            }
        }
        if let Some((a, b)) = o.window {
            if !(a.is_finite() && b.is_finite() && a <= b) {
                return Err(SearchError::Options(format!("metric window [{a}, {b}] must be finite with t0 ≤ t1")));
            }
        }
        if !(1..=64).contains(&o.lyapunov_elements) {
            return Err(SearchError::Options("lyapunov elements must lie in [1, 64]".into()));
        }
        store::best_json(&[], &[], &o.best_metric, 0)?;
        Ok(Search { base, grid: Grid::new(axes), options })
    }

    /// Number of points.
    pub fn points(&self) -> usize {
        self.grid.len()
    }

    /// Number of chunks.
    pub fn chunks(&self) -> usize {
        self.points().div_ceil(self.options.chunk_size)
    }

    /// Point indices of chunk c.
    pub fn chunk_range(&self, c: usize) -> std::ops::Range<usize> {
        let cs = self.options.chunk_size;
        c * cs..((c + 1) * cs).min(self.points())
    }

    /// Evaluate one point (simulation + theory).
    pub fn evaluate(&self, p: usize, cache: &TheoryCache, runs: &modal::RunCache) -> PointResult {
        point::evaluate(&self.grid, &self.base, self.options.window, cache, runs, p)
    }

    /// The manifest.
    pub fn manifest(&self) -> Manifest {
        Manifest {
            format: 1,
            base_config: self.base.clone(),
            base_config_sha256: wingcheck_claims::config_sha256(&self.base),
            axes: self.grid.axes.clone(),
            axis_specs: self.grid.axes.iter().map(Axis::spec).collect(),
            points: self.points(),
            chunks: self.chunks(),
            point_order: "row-major: the first axis varies slowest".into(),
            sharding: "chunk c = points [c·chunk_size, (c+1)·chunk_size) belongs to shard K/N iff c mod N = K − 1"
                .into(),
            options: self.options.clone(),
            metrics: METRICS.iter().map(|m| m.to_string()).collect(),
        }
    }

    /// The manifest as written (pretty JSON, trailing newline).
    pub fn manifest_text(&self) -> String {
        serde_json::to_string_pretty(&self.manifest()).expect("manifest serialises") + "\n"
    }

    fn from_manifest(m: Manifest) -> Result<Search, SearchError> {
        Search::from_axes(m.base_config, m.axes, m.options)
    }
}

/// Shard K of N (1-based K), parsed from `K/N`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// This shard (1..=n).
    pub k: usize,
    /// Number of shards.
    pub n: usize,
}

impl Default for Shard {
    fn default() -> Self {
        Shard { k: 1, n: 1 }
    }
}

impl std::str::FromStr for Shard {
    type Err = SearchError;
    fn from_str(s: &str) -> Result<Shard, SearchError> {
        let bad = || SearchError::Options(format!("--shard `{s}`: expected K/N with 1 ≤ K ≤ N"));
        let (k, n) = s.split_once('/').ok_or_else(bad)?;
        let (k, n): (usize, usize) = (k.trim().parse().map_err(|_| bad())?, n.trim().parse().map_err(|_| bad())?);
        if k == 0 || k > n {
            return Err(bad());
        }
        Ok(Shard { k, n })
    }
}

impl Shard {
    /// Whether chunk c belongs to this shard.
    pub fn owns(&self, c: usize) -> bool {
        c % self.n == self.k - 1
    }
}

/// Progress of a run: points evaluated in this invocation out of those it has to evaluate
/// (chunks found complete on disk are not counted).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Progress {
    /// Points done.
    pub done: usize,
    /// Points to do in this invocation.
    pub total: usize,
}

/// How to run (does not change results).
#[derive(Default)]
pub struct RunControl<'a> {
    /// Which shard to evaluate.
    pub shard: Shard,
    /// Called (from worker threads) after every point.
    pub progress: Option<&'a (dyn Fn(Progress) + Sync)>,
    /// Stop after this many chunks have been written (to test interruption).
    pub stop_after_chunks: Option<usize>,
    /// Worker threads (a local rayon pool); None: the current pool (all cores by default).
    pub threads: Option<usize>,
}

/// What a run or merge did.
#[derive(Debug, Clone, Default, Serialize)]
pub struct RunSummary {
    /// Output directory.
    pub out_dir: PathBuf,
    /// Points of the whole search.
    pub points_total: usize,
    /// Points evaluated in this invocation.
    pub evaluated: usize,
    /// Points of this shard found complete on disk.
    pub skipped: usize,
    /// Whether every chunk is present and the final files were written.
    pub complete: bool,
    /// Final files written (relative names).
    pub files: Vec<String>,
    /// Sum of the points' simulation wall times (s) in this invocation.
    pub sim_seconds: f64,
    /// Sum of the points' theory wall times (s) in this invocation.
    pub theory_seconds: f64,
    /// Wall time of the invocation (s).
    pub wall_seconds: f64,
}

fn check_manifest(dir: &Path, text: &str) -> Result<(), SearchError> {
    let path = dir.join("manifest.json");
    if path.exists() {
        if store::read(&path)? != text {
            return Err(SearchError::Mismatch {
                dir: dir.display().to_string(),
                reason: "manifest.json describes a different search (config, axes or options); use another --out"
                    .into(),
            });
        }
    } else {
        store::write_atomic(&path, text.as_bytes())?;
    }
    Ok(())
}

/// Run (this shard of) a search into `out`, resuming from chunks already there; when every
/// chunk of the search is present, write the final files ([`finalize`]).
pub fn run(search: &Search, out: &Path, ctl: RunControl<'_>) -> Result<RunSummary, SearchError> {
    if let Some(n) = ctl.threads {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .map_err(|e| SearchError::Options(format!("cannot start {n} threads: {e}")))?;
        return pool.install(|| run(search, out, RunControl { threads: None, ..ctl }));
    }
    let start = Instant::now();
    store::mkdir(&out.join(store::CHUNK_DIR))?;
    check_manifest(out, &search.manifest_text())?;
    let mine: Vec<usize> = (0..search.chunks()).filter(|&c| ctl.shard.owns(c)).collect();
    let mut todo = Vec::new();
    let mut skipped = 0;
    for &c in &mine {
        match store::read_chunk(out, c, search.chunk_range(c))? {
            Some(_) => skipped += search.chunk_range(c).len(),
            None => todo.push(c),
        }
    }
    let total: usize = todo.iter().map(|&c| search.chunk_range(c).len()).sum();
    let done = AtomicUsize::new(0);
    if let Some(p) = ctl.progress {
        p(Progress { done: 0, total });
    }
    let cache = TheoryCache::new(search.options.lyapunov_elements);
    let runs = modal::RunCache::new();
    let mut summary =
        RunSummary { out_dir: out.to_path_buf(), points_total: search.points(), skipped, ..Default::default() };
    for (i, &c) in todo.iter().enumerate() {
        if ctl.stop_after_chunks == Some(i) {
            break;
        }
        let points: Vec<PointResult> = search
            .chunk_range(c)
            .into_par_iter()
            .map(|p| {
                let r = search.evaluate(p, &cache, &runs);
                let d = done.fetch_add(1, Ordering::Relaxed) + 1;
                if let Some(cb) = ctl.progress {
                    cb(Progress { done: d, total });
                }
                r
            })
            .collect();
        store::write_atomic(&store::chunk_path(out, c), store::chunk_text(&points).as_bytes())?;
        summary.evaluated += points.len();
        summary.sim_seconds += points.iter().map(|p| p.sim_seconds).sum::<f64>();
        summary.theory_seconds += points.iter().map(|p| p.theory_seconds).sum::<f64>();
        let completed: Vec<usize> = mine.iter().copied().filter(|&c| store::chunk_path(out, c).exists()).collect();
        let progress = serde_json::json!({
            "shard": format!("{}/{}", ctl.shard.k, ctl.shard.n),
            "chunks_owned": mine.len(),
            "completed_chunks": completed,
        });
        let name = format!("progress-{}-of-{}.json", ctl.shard.k, ctl.shard.n);
        store::write_atomic(
            &out.join(name),
            (serde_json::to_string_pretty(&progress).expect("json") + "\n").as_bytes(),
        )?;
    }
    if (0..search.chunks()).all(|c| store::chunk_path(out, c).exists()) {
        summary.files = finalize(out)?;
        summary.complete = true;
    }
    summary.wall_seconds = start.elapsed().as_secs_f64();
    Ok(summary)
}

/// Combine shard directories into `out`: check that they hold the same search, copy every
/// chunk (the first valid copy found, in the order of `dirs`) and [`finalize`].
pub fn merge(dirs: &[PathBuf], out: &Path) -> Result<RunSummary, SearchError> {
    let start = Instant::now();
    let first = dirs.first().ok_or_else(|| SearchError::Options("merge needs at least one directory".into()))?;
    let text = store::read(&first.join("manifest.json"))?;
    for d in &dirs[1..] {
        if store::read(&d.join("manifest.json"))? != text {
            return Err(SearchError::Mismatch {
                dir: d.display().to_string(),
                reason: format!("manifest.json differs from {}'s: not shards of the same search", first.display()),
            });
        }
    }
    let manifest: Manifest = serde_json::from_str(&text).map_err(|e| SearchError::Io {
        path: first.join("manifest.json").display().to_string(),
        detail: e.to_string(),
    })?;
    let search = Search::from_manifest(manifest)?;
    store::mkdir(&out.join(store::CHUNK_DIR))?;
    check_manifest(out, &text)?;
    let mut missing = Vec::new();
    for c in 0..search.chunks() {
        let mut found = false;
        for d in dirs {
            if store::read_chunk(d, c, search.chunk_range(c))?.is_some() {
                let target = store::chunk_path(out, c);
                if store::chunk_path(d, c) != target {
                    store::write_atomic(&target, store::read(&store::chunk_path(d, c))?.as_bytes())?;
                }
                found = true;
                break;
            }
        }
        if !found {
            missing.push(c);
        }
    }
    if !missing.is_empty() {
        return Err(SearchError::MissingChunks {
            missing: missing.len(),
            total: search.chunks(),
            first: missing.iter().take(8).copied().collect(),
        });
    }
    let files = finalize(out)?;
    Ok(RunSummary {
        out_dir: out.to_path_buf(),
        points_total: search.points(),
        complete: true,
        files,
        wall_seconds: start.elapsed().as_secs_f64(),
        ..Default::default()
    })
}

/// Assemble the final files of a complete directory from `manifest.json` and the chunk files,
/// in index order: `results.csv`, `results.json`, `best.json`, `boundary.csv`, heatmaps
/// (2-D searches) and `timings.csv`. Returns the file names written.
pub fn finalize(dir: &Path) -> Result<Vec<String>, SearchError> {
    let path = dir.join("manifest.json");
    let manifest: Manifest = serde_json::from_str(&store::read(&path)?)
        .map_err(|e| SearchError::Io { path: path.display().to_string(), detail: e.to_string() })?;
    let search = Search::from_manifest(manifest)?;
    let mut points = Vec::with_capacity(search.points());
    let mut missing = Vec::new();
    for c in 0..search.chunks() {
        match store::read_chunk(dir, c, search.chunk_range(c))? {
            Some(p) => points.extend(p),
            None => missing.push(c),
        }
    }
    if !missing.is_empty() {
        return Err(SearchError::MissingChunks {
            missing: missing.len(),
            total: search.chunks(),
            first: missing.iter().take(8).copied().collect(),
        });
    }
    let keys: Vec<String> = search.grid.axes.iter().map(|a| a.key.clone()).collect();
    let o = &search.options;
    let mut files: Vec<(String, String)> = vec![
        ("results.csv".into(), store::results_csv(&keys, &points)),
        ("results.json".into(), store::results_json(&keys, &points)),
        ("best.json".into(), store::best_json(&keys, &points, &o.best_metric, o.best_count)?),
    ];
    let cache = TheoryCache::new(o.lyapunov_elements);
    let rows = boundaries(&search, &points, &cache, o.refine);
    files.push(("boundary.csv".into(), boundary_csv(&search.grid, &rows)));
    if search.grid.axes.len() == 2 && search.grid.dims().iter().all(|&n| n >= 2) {
        for (metric, log) in [("rms_q_tip", true), ("rms_theta_tip", true), ("settling_time", false)] {
            let svg = heatmap_svg(&search, &points, metric, log, &rows)?;
            files.push((format!("heatmap-{metric}.svg"), svg));
        }
    }
    files.push(("timings.csv".into(), store::timings_csv(&points)));
    for (name, text) in &files {
        store::write_atomic(&dir.join(name), text.as_bytes())?;
    }
    Ok(files.into_iter().map(|(n, _)| n).collect())
}
