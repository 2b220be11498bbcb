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

#![forbid(unsafe_code)]

mod assemble;
pub mod axis;
pub mod bench;
pub mod chunk;
mod error;
mod exec;
pub mod heatmap;
mod heatmap_blocks;
pub mod limits;
pub mod metric;
pub mod modal;
pub mod point;
pub mod records;
mod refine;
pub mod store;
pub mod theory;
pub mod verify;

use std::path::PathBuf;

use serde::{Deserialize, Serialize};
use wingcheck_model::{Config, TimeScheme};
use wingcheck_sim::ControllerFactory;

pub use assemble::{assemble, finalize, ChunkStream};
pub use axis::{parse_axes, validate_axes, Axis, Grid, Spacing};
pub use error::{SearchError, WorkLimit};
pub use exec::{merge, merge_with, run};
pub use heatmap::heatmap_svg;
pub use limits::{WorkEstimate, MAX_CORE_SECONDS, MAX_POINTS, MAX_POINTS_OVERRIDE};
pub use metric::{Metric, Ranking, METRICS, METRIC_UNITS};
pub use point::{PointResult, PointVerdicts, Status};
pub use refine::{boundaries, boundary_csv, BoundaryRow};
pub use theory::{Theory, TheoryCache, Verdicts};
pub use verify::ChunkCheck;

/// Options that change results (all recorded in the manifest).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct SearchOptions {
    /// Metric window [t0, t1] (s); absent: the second half of the horizon.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub window: Option<(f64, f64)>,
    /// Points per chunk (≥ 1).
    pub chunk_size: usize,
    /// Boundary refinement tolerance: relative (hi/lo − 1) on log axes, a fraction of the axis
    /// span on lin axes. Absent: report the coarse brackets only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub refine: Option<f64>,
    /// How `best.json` ranks the points.
    pub best: Ranking,
    /// Points listed in `best.json`.
    pub best_count: usize,
    /// Elements N of the Galerkin space of W and κ (default: the ledger's
    /// [`wingcheck_claims::CheckSettings::mu_lambda1_elements`], so a point's λ1 and the
    /// mu-conditions row's agree).
    pub lyapunov_elements: usize,
    /// The name of a controller of the user's that every point runs in place of `control.kind`
    /// (its factory is handed to [`run`] as [`RunControl::controller`]); absent: the built-in
    /// one. Recorded so that a directory holds one controller's results (a resume or merge
    /// under another name is another search).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub controller: Option<String>,
}

impl Default for SearchOptions {
    fn default() -> Self {
        SearchOptions {
            window: None,
            chunk_size: 32,
            refine: None,
            best: Ranking::default(),
            best_count: 10,
            lyapunov_elements: wingcheck_claims::CheckSettings::default().mu_lambda1_elements,
            controller: None,
        }
    }
}

/// `manifest.json`: everything that defines a search's results.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Manifest {
    /// Layout version of this file ([`wingcheck_io::SCHEMA_VERSION`]; docs/schema/).
    #[serde(default)]
    pub schema_version: u32,
    /// Format of the directory.
    pub format: u32,
    /// The base configuration.
    pub base_config: Config,
    /// SHA-256 of the base configuration (`Config::sha256`).
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
    pub point_order: PointOrder,
    /// Shard rule.
    pub sharding: Sharding,
    /// Options.
    pub options: SearchOptions,
    /// Metric columns.
    pub metrics: Vec<String>,
    /// Time scheme of the base point's closed loop (`Config::expected_time_scheme`:
    /// `discretisation.stepper` with `auto` resolved — `exponential` for the explicit FTDO in the
    /// modal basis, `trbdf2` otherwise); points whose axes change the rule, the controller or the
    /// grid follow the same rule.
    #[serde(default)]
    pub time_scheme: TimeScheme,
}

/// How points are numbered (the manifest's `point_order`, written as the rule in words).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema)]
pub enum PointOrder {
    /// Row-major over the axes: the first axis varies slowest ([`Grid`]).
    #[default]
    #[serde(rename = "row-major: the first axis varies slowest")]
    RowMajor,
}

/// Which shard evaluates which chunk (the manifest's `sharding`, written as the rule in words;
/// [`Shard::owns`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema)]
pub enum Sharding {
    /// Chunk c belongs to shard K/N iff c mod N = K − 1.
    #[default]
    #[serde(rename = "chunk c = points [c·chunk_size, (c+1)·chunk_size) belongs to shard K/N iff c mod N = K − 1")]
    ChunkModulo,
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
            return Err(SearchError::ChunkSize);
        }
        if let Some(t) = o.refine {
            if !(t > 0.0 && t < 1.0) {
                return Err(SearchError::RefineTolerance { value: t });
            }
        }
        if let Some(w) = o.window {
            check_window(&base, &axes, w)?;
        }
        if !(1..=64).contains(&o.lyapunov_elements) {
            return Err(SearchError::LyapunovElements { value: o.lyapunov_elements });
        }
        if o.controller.as_ref().is_some_and(|name| name.trim().is_empty()) {
            return Err(SearchError::ControllerName);
        }
        Ok(Search { base, grid: Grid::new(axes), options })
    }

    /// The work estimate of the whole search ([`limits::estimate`]).
    pub fn estimate(&self) -> WorkEstimate {
        limits::estimate(&self.base, &self.grid.axes)
    }

    /// The work estimate for `threads` worker threads ([`limits::estimate_with_threads`]).
    pub fn estimate_with_threads(&self, threads: usize) -> WorkEstimate {
        limits::estimate_with_threads(&self.base, &self.grid.axes, threads)
    }

    /// The work estimate [`run`] checks for [`RunControl::threads`] (`None`: the current rayon
    /// pool's threads).
    pub fn estimate_for(&self, threads: Option<usize>) -> WorkEstimate {
        self.estimate_with_threads(threads.unwrap_or_else(rayon::current_num_threads))
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

    /// Evaluate one point (simulation + theory) under the built-in controller.
    pub fn evaluate(&self, p: usize, cache: &TheoryCache, runs: &modal::RunCache) -> PointResult {
        self.evaluate_with(p, cache, runs, None)
    }

    /// [`Search::evaluate`] under a controller of the user's (`Some`: made for the point's run
    /// as `simulate` makes it, [`wingcheck_sim::RunOptions::controller`]).
    pub fn evaluate_with(
        &self,
        p: usize,
        cache: &TheoryCache,
        runs: &modal::RunCache,
        controller: Option<ControllerFactory<'_>>,
    ) -> PointResult {
        point::evaluate(&self.grid, &self.base, self.options.window, cache, runs, controller, p)
    }

    /// Refuse a controller factory the options do not name, or a name without a factory.
    pub fn check_controller(&self, controller: Option<ControllerFactory<'_>>) -> Result<(), SearchError> {
        match (&self.options.controller, controller) {
            (Some(_), Some(_)) | (None, None) => Ok(()),
            (Some(name), None) => Err(SearchError::ControllerMissing { name: name.clone() }),
            (None, Some(_)) => Err(SearchError::ControllerUnexpected),
        }
    }

    /// The manifest.
    pub fn manifest(&self) -> Manifest {
        Manifest {
            schema_version: wingcheck_io::SCHEMA_VERSION,
            format: 1,
            base_config: self.base.clone(),
            base_config_sha256: self.base.sha256(),
            axes: self.grid.axes.clone(),
            axis_specs: self.grid.axes.iter().map(Axis::spec).collect(),
            points: self.points(),
            chunks: self.chunks(),
            point_order: PointOrder::RowMajor,
            sharding: Sharding::ChunkModulo,
            options: self.options.clone(),
            metrics: METRICS.iter().map(|m| m.to_string()).collect(),
            time_scheme: self.base.expected_time_scheme(),
        }
    }

    /// The manifest as written (pretty JSON, trailing newline).
    pub fn manifest_text(&self) -> String {
        serde_json::to_string_pretty(&self.manifest()).expect("manifest serialises") + "\n"
    }

    /// The search's identity in its chunk headers: SHA-256 of [`Search::manifest_text`] (base
    /// configuration and its hash, axes, options, metrics, scheme).
    pub fn identity(&self) -> String {
        chunk::sha256_hex(self.manifest_text().as_bytes())
    }

    fn from_manifest(m: Manifest) -> Result<Search, SearchError> {
        Search::from_axes(m.base_config, m.axes, m.options)
    }
}

/// The metric window [t0, t1] must be finite, 0 ≤ t0 < t1 ≤ T and hold an output sample, for
/// the base config and for every value of every axis (others at the base): a window outside
/// the horizon would give empty metrics.
fn check_window(base: &Config, axes: &[Axis], (t0, t1): (f64, f64)) -> Result<(), SearchError> {
    if !(t0.is_finite() && t1.is_finite() && 0.0 <= t0 && t0 < t1) {
        return Err(SearchError::WindowOrder { t0, t1 });
    }
    let mut cfgs = vec![base.clone()];
    for a in axes {
        // every value of a list over the horizon or the sample periods (not the first 256)
        let idx = limits::estimated_values(a);
        cfgs.extend(idx.into_iter().filter_map(|i| wingcheck_model::apply_overrides(base, &[a.override_expr(i)]).ok()));
    }
    for cfg in &cfgs {
        let t_end = cfg.horizon.t_end;
        let dt_out = cfg.samples_per_output() as f64 * cfg.observer.sample_period;
        let tol = 1e-9 * (1.0 + t1.abs());
        let has_sample = (t1 / dt_out + 1e-9).floor() * dt_out >= t0 - tol || t1 >= t_end - tol;
        if t1 > t_end + tol || !has_sample {
            return Err(SearchError::WindowOutsideHorizon { t0, t1, t_end, dt_out });
        }
    }
    Ok(())
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
        let bad = || SearchError::Shard { text: s.to_string() };
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
    /// Worker threads (a local rayon pool, 1..=[`limits::max_threads`]); None: the current
    /// pool (all cores by default).
    pub threads: Option<usize>,
    /// Run even above [`MAX_POINTS`] / [`MAX_CORE_SECONDS`] (never above [`MAX_POINTS_OVERRIDE`]).
    pub allow_large: bool,
    /// How many points of each chunk found on disk are recomputed before it is resumed from
    /// ([`verify`]; `--verify-chunks`: all).
    pub verify: ChunkCheck,
    /// How the caller's front end spells `allow_large` in the refusal (None:
    /// [`wingcheck_model::work::ALLOW_LARGE_FLAG`]).
    pub allow_large_flag: Option<&'a str>,
    /// Checked before every point: once set, the run stops with [`SearchError::Cancelled`]
    /// without writing the chunk in progress.
    pub cancel: wingcheck_model::Cancel,
    /// The controller of the user's that [`SearchOptions::controller`] names (each point's run
    /// makes one); `None` for the built-in one. The work estimate counts the built-in
    /// controller's cost.
    pub controller: Option<ControllerFactory<'a>>,
}

/// What a run or merge did.
#[derive(Debug, Clone, Default, Serialize, schemars::JsonSchema)]
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
    /// Sum of the points' simulation wall times (s) in this invocation (each includes time its
    /// thread waited for a core).
    pub sim_seconds: f64,
    /// Sum of the points' theory wall times (s) in this invocation.
    pub theory_seconds: f64,
    /// Wall time of the invocation (s).
    pub wall_seconds: f64,
    /// CPU time of the process over the invocation (user + system of all threads, s;
    /// [`wingcheck_io::clock`]; None off Linux or for a merge).
    pub cpu_seconds: Option<f64>,
    /// Points evaluated in this invocation whose status is not `ok`.
    pub failed: usize,
    /// Points of chunks found on disk recomputed to prove them this search's own ([`verify`]).
    pub verified: usize,
    /// When complete: points of the whole search whose status is not `ok` (listed in
    /// `failures.csv`), by status: (diverged, error).
    pub failed_total: Option<(usize, usize)>,
}
