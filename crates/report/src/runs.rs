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
    for kind in [ControllerKind::None, ControllerKind::Ftdo, ControllerKind::Dobc] {
        jobs.push((kind.name().to_string(), controller(cfg, kind)));
    }
    for m in METHODS {
        for n in GRIDS {
            jobs.push((format!("{}-{n}", m.name()), accuracy_variant(cfg, m, n)));
        }
    }
    jobs
}

/// The configurations the figures simulate.
pub fn plan(cfg: &Config) -> Vec<Config> {
    jobs(cfg).into_iter().map(|(_, c)| c).collect()
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
    Ok(Runs { none, ftdo, dobc, accuracy })
}
