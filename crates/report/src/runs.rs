//! The simulations behind the report, run in parallel through the claims' [`Study`] (so a run
//! the ledger also needs — the FTDO and DOBC loops at the configured gains — is simulated
//! once): the paper's three closed loops (no control, FTDO, DOBC) with fields, and the
//! grid-convergence runs of the accuracy section (FD and FE at [`GRIDS`] elements, uniform
//! grid).

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

use rayon::prelude::*;
use wingcheck_claims::Study;
use wingcheck_model::{Config, ControllerKind, Method};
use wingcheck_sim::SimOutput;

use crate::{Progress, ReportError};

/// Element counts of the accuracy study.
pub const GRIDS: [usize; 4] = wingcheck_model::work::REPORT_ACCURACY_GRIDS;

/// Discretisation methods of the accuracy study.
pub const METHODS: [Method; 2] = [Method::Fd, Method::Fe];

/// The estimated discretisation error of a run's tip values (the `--error-estimate` machinery,
/// [`wingcheck_sim::estimate_from_runs`]: one refinement in h and one in dt, Richardson with
/// the safety factor 1.25, maximised over ±0.1 s), per output sample.
pub struct TipErrors {
    /// |error| of q(s,t_k) (m).
    pub q: Vec<f64>,
    /// |error| of θ(s,t_k) (rad).
    pub theta: Vec<f64>,
    /// max of `q` over the run (m).
    pub max_q: f64,
    /// max of `theta` over the run (rad).
    pub max_theta: f64,
    /// Grid of the spatial refinement (2N).
    pub refined_grid: usize,
    /// Step of the temporal refinement (s).
    pub refined_dt: f64,
    /// Largest estimated error of the sampled τ1 (N), τ2 (N m) over the run (the same rule,
    /// [`wingcheck_sim::series_error`]).
    pub tau: [f64; 2],
    /// Largest estimated relative error of the sampled |g̃1|, |g̃2| over the samples where
    /// g̃ ≠ 0 (the same rule; at most 1).
    pub gtilde_relative: [f64; 2],
}

/// All runs of a report.
pub struct Runs {
    /// τ1 = τ2 = 0 (paper Figs 3–4).
    pub none: Arc<SimOutput>,
    /// Proposed controller (Figs 5–12).
    pub ftdo: Arc<SimOutput>,
    /// DOBC comparison (Figs 13–20).
    pub dobc: Arc<SimOutput>,
    /// Accuracy runs: `accuracy[m][g]` for `METHODS[m]`, `GRIDS[g]` (controller as in the config).
    pub accuracy: Vec<Vec<Arc<SimOutput>>>,
    /// The tip errors of the no-control, FTDO and DOBC runs, in that order.
    pub errors: [TipErrors; 3],
}

/// The three controllers of the paper's figures, in the order of [`Runs`].
const KINDS: [ControllerKind; 3] = [ControllerKind::None, ControllerKind::Ftdo, ControllerKind::Dobc];

/// The refinements of a figure run (the doubled grid and the halved step), with the time
/// scheme the run itself uses: `scheme` from the run, or as `auto` resolves it in the basis
/// `auto` would choose (for the plan, before anything runs).
fn refined(c: &Config, scheme: Option<wingcheck_model::TimeScheme>) -> (Config, Config) {
    wingcheck_sim::refinements(c, scheme.unwrap_or_else(|| c.expected_time_scheme()))
}

/// `cfg` with another controller (the paper's figure groups).
pub fn controller(cfg: &Config, kind: ControllerKind) -> Config {
    let mut c = cfg.clone();
    c.control.kind = kind;
    c
}

/// The accuracy-study variant: `method` at `elements`, uniform grid.
pub fn accuracy_variant(cfg: &Config, method: Method, elements: usize) -> Config {
    let mut c = cfg.clone();
    c.discretisation.method = method;
    c.discretisation.elements = elements;
    c.discretisation.fd_points = elements;
    c.discretisation.grading = 0.0;
    c
}

/// The runs of the figures, named, in the order of [`Runs`]: the three controllers, then the
/// accuracy study (the report's work estimate counts these, [`crate::estimate`]).
fn jobs(cfg: &Config) -> Vec<(String, Config)> {
    let mut jobs: Vec<(String, Config)> = Vec::new();
    for kind in KINDS {
        jobs.push((kind.name().to_string(), controller(cfg, kind)));
    }
    for m in METHODS {
        for n in GRIDS {
            jobs.push((format!("{}-{n}", m.name()), accuracy_variant(cfg, m, n)));
        }
    }
    jobs
}

/// The configurations the figures simulate (with the refinements of the error bands).
pub fn plan(cfg: &Config) -> Vec<Config> {
    let mut v: Vec<Config> = jobs(cfg).into_iter().map(|(_, c)| c).collect();
    for kind in KINDS {
        let (a, b) = refined(&controller(cfg, kind), None);
        v.extend([a, b]);
    }
    v
}

/// The tip errors of `out` (a run of `c`) from its two refinements, simulated through `study`.
fn tip_errors(c: &Config, out: &SimOutput, study: &Study) -> Result<TipErrors, ReportError> {
    let (space_cfg, time_cfg) = refined(c, Some(out.stats.stepper));
    let sim = |x: &Config, what: &str| {
        study
            .simulate(x)
            .map_err(|source| ReportError::Sim { run: format!("{} {what}", c.control.kind.name()), source })
    };
    let (space, time) = rayon::join(|| sim(&space_cfg, "2N"), || sim(&time_cfg, "dt/2"));
    let lite = SimOutput {
        series: out.series.clone(),
        fields: None,
        peaks: out.peaks,
        // only the series' errors are used here: no layer check of the peaks
        peaks_after_layer: out.peaks_after_layer,
        initial_layer: None,
        envelope: Default::default(),
        gtilde_band_entry: out.gtilde_band_entry,
        stats: out.stats.clone(),
    };
    let (space, time) = (space?, time?);
    let no_fourth = wingcheck_sim::ExtraRunError::NotMade("the report uses the series' errors only");
    let e = wingcheck_sim::estimate_from_runs(lite, &space, &time, Err(&no_fourth), &space_cfg, &time_cfg);
    Ok(TipErrors {
        q: e.q_tip_error,
        theta: e.theta_tip_error,
        max_q: e.max_q_tip_error,
        max_theta: e.max_theta_tip_error,
        refined_grid: e.refined_grid,
        refined_dt: e.refined_dt,
        tau: [0, 1].map(|c| {
            let col = |o: &SimOutput| if c == 0 { o.series.tau1.clone() } else { o.series.tau2.clone() };
            let err = wingcheck_sim::series_error(&out.series.t, &col(out), &col(&space), &col(&time));
            err.into_iter().fold(0.0, f64::max)
        }),
        gtilde_relative: [0, 1].map(|c| {
            let col = |o: &SimOutput| wingcheck_sim::metrics::observer_error(&o.series, c);
            let v = col(out);
            let err = wingcheck_sim::series_error(&out.series.t, &v, &col(&space), &col(&time));
            v.iter().zip(&err).filter(|(v, _)| **v != 0.0).map(|(v, e)| (e / v.abs()).min(1.0)).fold(0.0, f64::max)
        }),
    })
}

/// Run everything (in parallel) through `study`, reporting each finished run to `progress`.
pub fn run_all(cfg: &Config, study: &Study, progress: Option<&(dyn Fn(Progress) + Sync)>) -> Result<Runs, ReportError> {
    let jobs = jobs(cfg);
    let done = AtomicUsize::new(0);
    let total = jobs.len();
    let mut outs: Vec<Arc<SimOutput>> = jobs
        .par_iter()
        .map(|(name, c)| {
            let out = study.simulate(c).map_err(|source| ReportError::Sim { run: name.clone(), source });
            let k = done.fetch_add(1, Ordering::SeqCst) + 1;
            if let Some(p) = progress {
                p(Progress { stage: "simulations", done: k, total });
            }
            out
        })
        .collect::<Result<_, _>>()?;
    let accuracy_flat = outs.split_off(3);
    let mut it = outs.into_iter();
    let (none, ftdo, dobc) = (it.next().expect("3"), it.next().expect("3"), it.next().expect("3"));
    let mut accuracy = Vec::new();
    let mut acc = accuracy_flat.into_iter();
    for _ in METHODS {
        accuracy.push(acc.by_ref().take(GRIDS.len()).collect());
    }
    let base = [&none, &ftdo, &dobc];
    let errors: Vec<TipErrors> = KINDS
        .par_iter()
        .zip(base.par_iter())
        .map(|(k, out)| tip_errors(&controller(cfg, *k), out, study))
        .collect::<Result<_, _>>()?;
    let mut e = errors.into_iter();
    let errors = [e.next().expect("3"), e.next().expect("3"), e.next().expect("3")];
    Ok(Runs { none, ftdo, dobc, accuracy, errors })
}
