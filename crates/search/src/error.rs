//! [`SearchError`]: what stops a search, a merge or an assembly (a failing point is a status in
//! the results, not an error).

use std::path::PathBuf;

use crate::limits::WorkEstimate;

/// Which work limit a search is above ([`crate::limits::check`]).
#[derive(Debug, Clone, PartialEq)]
pub enum WorkLimit {
    /// Above [`crate::MAX_POINTS_OVERRIDE`]: refused even with the override.
    Override,
    /// Above [`crate::MAX_POINTS`], [`crate::MAX_CORE_SECONDS`] or the memory limit; `flag` is
    /// the front end's spelling of the override.
    Limits {
        /// The override, e.g. `--allow-large`.
        flag: String,
    },
}

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
    /// `--chunk-size` 0 (points per chunk must be ≥ 1).
    #[error("chunk size must be ≥ 1")]
    ChunkSize,
    /// `--refine` outside (0, 1).
    #[error("--refine {value}: the tolerance must lie in (0, 1)")]
    RefineTolerance {
        /// The tolerance given.
        value: f64,
    },
    /// `--window t0,t1` not finite with 0 ≤ t0 < t1 (s).
    #[error("--window {t0},{t1}: needs finite 0 ≤ t0 < t1 (s)")]
    WindowOrder {
        /// Start (s).
        t0: f64,
        /// End (s).
        t1: f64,
    },
    /// `--window t0,t1` outside a point's horizon [0, t_end] or holding no output sample.
    #[error(
        "--window {t0},{t1}: must lie inside the horizon [0, {t_end}] s and hold an output sample (every {dt_out} s)"
    )]
    WindowOutsideHorizon {
        /// Start (s).
        t0: f64,
        /// End (s).
        t1: f64,
        /// The horizon of the point that refuses it (s).
        t_end: f64,
        /// Its output sample period (s).
        dt_out: f64,
    },
    /// Galerkin elements of W and κ outside [1, 64].
    #[error("lyapunov elements {value}: must lie in [1, 64]")]
    LyapunovElements {
        /// The number given.
        value: usize,
    },
    /// The name of the user's controller is empty.
    #[error("controller: the name of your own controller must not be empty")]
    ControllerName,
    /// The options name a controller of the user's and none was handed over.
    #[error("the search runs a controller of your own ({name}) and none was handed over")]
    ControllerMissing {
        /// The name in the options.
        name: String,
    },
    /// A controller was handed over that the options do not name.
    #[error("a controller was handed over but the search options name none")]
    ControllerUnexpected,
    /// Shards that ran the user's controller cannot be merged (a merge recomputes points).
    #[error(
        "the shards ran a controller of your own ({name}), which a merge cannot recompute to verify them: \
         run the shards into one directory instead"
    )]
    MergeOwnController {
        /// The controller's name.
        name: String,
    },
    /// `--shard` not `K/N` with 1 ≤ K ≤ N.
    #[error("--shard `{text}`: expected K/N with 1 ≤ K ≤ N")]
    Shard {
        /// As given.
        text: String,
    },
    /// `--threads` outside [1, 4 × the cores].
    #[error("--threads {requested}: must lie in [1, {max}] (4 × the cores available)")]
    Threads {
        /// As given.
        requested: usize,
        /// The largest allowed.
        max: usize,
    },
    /// The worker threads could not be started.
    #[error("cannot start {threads} threads: {source}")]
    ThreadPool {
        /// How many.
        threads: usize,
        /// Why.
        source: rayon::ThreadPoolBuildError,
    },
    /// `merge` without a directory.
    #[error("merge needs at least one directory")]
    MergeNothing,
    /// A file could not be read (missing, not a regular file, too large).
    #[error("{}: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        source: wingcheck_io::ReadError,
    },
    /// A file that should hold text is not UTF-8.
    #[error("{}: not UTF-8 text", path.display())]
    NotText {
        /// The file.
        path: PathBuf,
    },
    /// A directory could not be created or listed, or a file inspected.
    #[error("{}: {source}", path.display())]
    FileSystem {
        /// The path.
        path: PathBuf,
        /// The OS error.
        source: std::io::Error,
    },
    /// A manifest that does not parse.
    #[error("{}: {source}", path.display())]
    Manifest {
        /// The manifest.
        path: PathBuf,
        /// Why.
        source: serde_json::Error,
    },
    /// `results.json` could not be written (serde_json's error, which carries an I/O error).
    #[error("{}: {source}", path.display())]
    Serialise {
        /// The file.
        path: PathBuf,
        /// Why.
        source: serde_json::Error,
    },
    /// Points reached the assembly out of index order.
    #[error("{}: point {got} arrived where point {expected} was expected", path.display())]
    OutOfOrder {
        /// The file being assembled.
        path: PathBuf,
        /// The point's index.
        got: usize,
        /// The index expected.
        expected: usize,
    },
    /// Fewer or more points were assembled than the search has.
    #[error("{}: {assembled} points assembled, the search has {expected}", dir.display())]
    PointCount {
        /// The chunk directory.
        dir: PathBuf,
        /// Points assembled.
        assembled: usize,
        /// Points of the search.
        expected: usize,
    },
    /// A heatmap's cells do not match its grid.
    #[error("{name}.svg: {values} values and {verdicts} verdicts for {nx} × {ny} cells")]
    HeatmapCells {
        /// The heatmap (`heatmap-<metric>`).
        name: String,
        /// Values given.
        values: usize,
        /// Verdicts given.
        verdicts: usize,
        /// Cells along x.
        nx: usize,
        /// Cells along y.
        ny: usize,
    },
    /// A heatmap could not be drawn.
    #[error("{}.svg: {}", source.name, source.cause)]
    Heatmap {
        /// The chart's error (names the heatmap).
        source: wingcheck_chart::ChartError,
    },
    /// A chunk file is not this search's (another search's, another tool version's, edited, or
    /// holding points that are not this grid's): refused, never merged or recomputed over.
    #[error("{path}: {reason}; it is not a chunk of this search (move it away to recompute it)")]
    Chunk {
        /// The chunk file.
        path: String,
        /// What does not match.
        reason: crate::chunk::ChunkProblem,
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
    /// The search is above a work limit (see [`crate::limits`]).
    #[error("search too large: {}", too_large(estimate, limit))]
    TooLarge {
        /// The estimate of the refused work.
        estimate: Box<WorkEstimate>,
        /// Which limit.
        limit: WorkLimit,
    },
    /// A file could not be written, or an output path cannot be used (its name, its type;
    /// [`wingcheck_io`]: the error names the path).
    #[error(transparent)]
    Output(#[from] wingcheck_io::IoError),
    /// A configuration the search derives (a benchmark's) is invalid.
    #[error(transparent)]
    Config(#[from] wingcheck_model::ConfigError),
    /// A simulation outside the points (a benchmark's) failed.
    #[error(transparent)]
    Simulation(#[from] wingcheck_sim::SimError),
    /// The run was stopped through [`crate::RunControl::cancel`] (nothing of this invocation is
    /// kept in a directory it created).
    #[error(transparent)]
    Cancelled(#[from] wingcheck_model::Cancelled),
    /// A theory computation failed (the W pencil, its eigenvalues).
    #[error("theory ({what}): {cause}")]
    Theory {
        /// Which computation.
        what: &'static str,
        /// What happened.
        #[source]
        cause: wingcheck_theory::numerics::PencilError,
    },
    /// The converged ω₁ (the W ≻ 0 threshold, `theory::w_threshold`) could not be computed.
    #[error("theory (ω₁): {0}")]
    Omega1(#[source] wingcheck_sim::SimError),
}

/// The refusal of [`SearchError::TooLarge`]: the estimate, the limit and the way out.
fn too_large(w: &WorkEstimate, limit: &WorkLimit) -> String {
    use crate::limits::{MAX_CORE_SECONDS, MAX_MEMORY_BYTES, MAX_POINTS, MAX_POINTS_OVERRIDE};
    let what = w.text();
    match limit {
        WorkLimit::Override => format!(
            "{what}: more than {MAX_POINTS_OVERRIDE} points cannot be searched in one directory \
             (the heatmaps of a 2-D search are drawn in memory, ≈ 140 bytes per point); \
             split the axes into several searches"
        ),
        WorkLimit::Limits { flag } => format!(
            "{what}: above the limits of {MAX_POINTS} points, {} core-hours and {} of memory; \
             pass {flag} to run it anyway (or --shard it over several machines, or use fewer --threads; a \
             long horizon or a small dt costs memory: an observer signal holds 24 bytes per integrator step)",
            MAX_CORE_SECONDS / 3600.0,
            wingcheck_model::work::human_bytes(MAX_MEMORY_BYTES)
        ),
    }
}
