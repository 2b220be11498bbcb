//! The simulations behind the report, run in parallel: the paper's three closed loops
//! (no control, FTDO, DOBC) with fields, and the grid-convergence runs of the accuracy
//! section (FD and FE at [`GRIDS`] elements, uniform grid).

use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::prelude::*;
use wingcheck_model::{apply_overrides, Config};
use wingcheck_sim::{simulate, RunOptions, SimOutput};

use crate::{Progress, ReportError};

/// Element counts of the accuracy study.
pub const GRIDS: [usize; 4] = [8, 16, 32, 64];

/// Discretisation methods of the accuracy study.
pub const METHODS: [&str; 2] = ["fd", "fe"];

/// All runs of a report.
pub struct Runs {
    /// τ1 = τ2 = 0 (paper Figs 3–4).
    pub none: SimOutput,
    /// Proposed controller (Figs 5–12).
    pub ftdo: SimOutput,
    /// DOBC comparison (Figs 13–20).
    pub dobc: SimOutput,
    /// Accuracy runs: `accuracy[m][g]` for `METHODS[m]`, `GRIDS[g]` (controller as in the config).
    pub accuracy: Vec<Vec<SimOutput>>,
}

/// `cfg` with overrides applied, errors naming the variant.
pub fn variant(cfg: &Config, sets: &[String]) -> Result<Config, ReportError> {
    apply_overrides(cfg, sets).map_err(|source| ReportError::Config { variant: sets.join(" "), source })
}

/// The controller variants of the paper's figures.
pub fn controller(cfg: &Config, kind: &str) -> Result<Config, ReportError> {
    variant(cfg, &[format!("control.kind={kind}")])
}

/// The accuracy-study variant: `method` at `elements`, uniform grid.
pub fn accuracy_variant(cfg: &Config, method: &str, elements: usize) -> Result<Config, ReportError> {
    variant(
        cfg,
        &[
            format!("discretisation.method={method}"),
            format!("discretisation.elements={elements}"),
            format!("discretisation.fd_points={elements}"),
            "discretisation.grading=0".to_string(),
        ],
    )
}

/// Run everything (in parallel), reporting each finished run to `progress`.
pub fn run_all(cfg: &Config, progress: Option<&(dyn Fn(Progress) + Sync)>) -> Result<Runs, ReportError> {
    let mut jobs: Vec<(String, Config, bool)> = Vec::new();
    for kind in ["none", "ftdo", "dobc"] {
        jobs.push((kind.to_string(), controller(cfg, kind)?, true));
    }
    for m in METHODS {
        for n in GRIDS {
            jobs.push((format!("{m}-{n}"), accuracy_variant(cfg, m, n)?, false));
        }
    }
    let done = AtomicUsize::new(0);
    let total = jobs.len();
    let mut outs: Vec<SimOutput> = jobs
        .par_iter()
        .map(|(name, c, fields)| {
            let out = simulate(c, RunOptions { fields: *fields, progress: None })
                .map_err(|source| ReportError::Sim { run: name.clone(), source });
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
