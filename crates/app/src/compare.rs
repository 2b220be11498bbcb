//! `compare`: controllers side by side on the same wing, disturbances and metrics — the
//! built-in ones by `control.kind` and controllers of the user's ([`ControllerFactory`]).
//!
//! Every row is one run of the configuration under its controller plus the two refinements of
//! `--error-estimate` (the doubled grid and the halved step, [`wingcheck_sim::refinements`], with
//! the base run's time scheme). Each metric m carries the error F·(|m(2N) − m(N)| + |m(dt/2) −
//! m(dt)|), F = [`RICHARDSON_2`], the rule the error estimate applies to every tip value. The
//! metrics are the claim ledger's ([`wingcheck_claims::comparison::metrics`]: the one RMS, peak
//! and settling definitions of `wingcheck_sim::metrics`), plus the energy at t_end relative to
//! the start. Every row steps in the basis the configuration resolves to (a built-in row's runs
//! are those of `check`; a controller of the user's is sampled from the state there, the same
//! discrete equations).

use serde::Serialize;
use wingcheck_claims::comparison::{metrics, Metrics};
use wingcheck_claims::CheckSettings;
use wingcheck_model::quantity::ErrorSource;
use wingcheck_model::{Cancel, Config, ControllerKind, Quantity, Unit};
use wingcheck_sim::{refinements, simulate, ControllerFactory, RunOptions, SimOutput, RICHARDSON_2};

use crate::{AppError, SimulateRequest, WorkPolicy};

pub use crate::compare_view::{check_svg_path, svg, table, write_svg};

/// One contestant of a comparison.
#[derive(Clone, Copy)]
pub enum Entrant<'a> {
    /// A built-in controller (`control.kind`; the configuration's observer rule).
    BuiltIn(ControllerKind),
    /// A controller of the user's.
    Own(ControllerFactory<'a>),
}

/// One row of the table: the controller's name and its metrics with their errors.
#[derive(Debug, Clone, Serialize)]
pub struct CompareRow {
    /// The name the caller gave.
    pub name: String,
    /// `modal` or `nodal`: the basis the row's runs stepped in.
    pub basis: String,
    /// The metrics, in [`COLUMNS`] order (a settling time that is never reached is absent).
    pub values: Vec<Option<Quantity>>,
    /// The base run's output samples: t (s), q(s,t) (m), θ(s,t) (rad), τ1 (N), τ2 (N m).
    pub series: [Vec<f64>; 5],
    /// The base run's full-rate (min, max) of τ1 (N) and τ2 (N m) per output interval
    /// ([`wingcheck_sim::Envelope`]): what the samples of a chattering input alias.
    #[serde(skip)]
    pub tau_range: [Vec<(f64, f64)>; 2],
}

/// The metrics of a row: (label, unit).
pub const COLUMNS: [(&str, Unit); 11] = [
    ("RMS q(s,t) over [t_end/2, t_end]", Unit::Metre),
    ("peak |q(s,t)|", Unit::Metre),
    ("RMS θ(s,t) over [t_end/2, t_end]", Unit::Radian),
    ("peak |θ(s,t)|", Unit::Radian),
    ("q(s,t) settling time", Unit::Second),
    ("θ(s,t) settling time", Unit::Second),
    ("RMS τ1", Unit::Newton),
    ("peak |τ1|", Unit::Newton),
    ("RMS τ2", Unit::NewtonMetre),
    ("peak |τ2|", Unit::NewtonMetre),
    ("E(t_end)/E(0)", Unit::Dimensionless),
];

/// The settling-time columns of [`COLUMNS`].
const SETTLING: [usize; 2] = [4, 5];

/// The claims of the ledger that say nothing about a controller of the user's, and why.
pub const NOT_APPLICABLE: [(&str, &str); 5] = [
    ("W-bounds", "conditions (22)–(28) on the paper's Lyapunov function for law (15) with the FTDO"),
    ("mu-conditions", "conditions (29)–(32) on the gains of law (15) and the observer in that Lyapunov function"),
    ("UUB", "the bound (33)–(37) of the closed loop with the FTDO, from that Lyapunov function"),
    ("finite-time", "convergence (38)–(39) of the FTDO's estimate ĝ, an observer a foreign controller need not have"),
    ("ftdo-vs-dobc", "compares the paper's two controllers; this table is its counterpart for any set"),
];

/// The comparison: one row per contestant, in the order given.
#[derive(Debug, Clone, Serialize)]
pub struct Comparison {
    /// Column labels and units ([`COLUMNS`]).
    pub columns: Vec<(String, String)>,
    /// The rows.
    pub rows: Vec<CompareRow>,
    /// The error rule, in words.
    pub error_rule: String,
    /// [`NOT_APPLICABLE`].
    pub not_applicable: Vec<(String, String)>,
}

/// The row's metric values from one run ([`COLUMNS`] order).
fn values(out: &SimOutput, settings: &CheckSettings) -> [Option<f64>; 11] {
    let m: Metrics = metrics(out, settings);
    let e = &out.series.energy;
    let energy = match (e.first(), e.last()) {
        (Some(&e0), Some(&e1)) if e0 > 0.0 => Some(e1 / e0),
        _ => None,
    };
    [
        Some(m.rms_q_late),
        Some(m.peak_q),
        Some(m.rms_theta_late),
        Some(m.peak_theta),
        m.settle_q,
        m.settle_theta,
        Some(m.rms_tau1),
        Some(m.peak_tau1),
        Some(m.rms_tau2),
        Some(m.peak_tau2),
        energy,
    ]
}

/// Run `cfg` under `entrant` with the refinements, cancellable.
fn row(cfg: &Config, name: &str, entrant: Entrant<'_>, cancel: &Cancel) -> Result<CompareRow, AppError> {
    let mut cfg = cfg.clone();
    let controller = match entrant {
        Entrant::BuiltIn(kind) => {
            cfg.control.kind = kind;
            None
        }
        Entrant::Own(f) => Some(f),
    };
    let opts = || RunOptions { cancel: cancel.clone(), controller, ..Default::default() };
    let base = simulate(&cfg, opts())?;
    let (space_cfg, time_cfg) = refinements(&cfg, base.stats.stepper);
    let space = simulate(&space_cfg, opts())?;
    let time = simulate(&time_cfg, opts())?;
    let settings = CheckSettings::default();
    let (v, vs, vt) = (values(&base, &settings), values(&space, &settings), values(&time, &settings));
    let values = (0..COLUMNS.len())
        .map(|j| {
            let (label, unit) = COLUMNS[j];
            let x = v[j]?;
            // a refinement that does not reach the metric (a settling time) leaves it unresolved
            let mut err = match (vs[j], vt[j]) {
                (Some(s), Some(t)) => RICHARDSON_2 * ((s - x).abs() + (t - x).abs()),
                _ => x.abs(),
            };
            let mut covers = vec![ErrorSource::Grid, ErrorSource::TimeStep];
            if SETTLING.contains(&j) {
                // a settling time is an output sample: the true exit lies within one interval
                err += cfg.horizon.sample_every;
                covers.push(ErrorSource::Sampling);
            }
            Some(Quantity::with_error(label, x, err, unit, &covers))
        })
        .collect();
    let s = &base.series;
    Ok(CompareRow {
        name: name.to_string(),
        basis: base.stats.basis.name().to_string(),
        values,
        series: [s.t.clone(), s.q_tip.clone(), s.theta_tip.clone(), s.tau1.clone(), s.tau2.clone()],
        tau_range: [base.envelope.tau1.clone(), base.envelope.tau2.clone()],
    })
}

/// Compare the `entrants` on `cfg` (each row: three runs; guarded like an error-estimated
/// `simulate` per row).
pub fn compare(
    cfg: &Config,
    entrants: &[(String, Entrant<'_>)],
    policy: WorkPolicy,
    cancel: &Cancel,
) -> Result<Comparison, AppError> {
    let req = SimulateRequest { error_estimate: true, ..Default::default() };
    let mut rows = Vec::with_capacity(entrants.len());
    for (name, entrant) in entrants {
        policy.guard(&req.estimate(cfg))?;
        rows.push(row(cfg, name, *entrant, cancel)?);
        cancel.check()?;
    }
    Ok(Comparison {
        columns: COLUMNS.iter().map(|(l, u)| (l.to_string(), u.symbol().to_string())).collect(),
        rows,
        error_rule: format!(
            "error = {RICHARDSON_2:.4} × (|m(2N) − m(N)| + |m(dt/2) − m(dt)|), the --error-estimate rule; \
             settling times (last exit from the 5 % band, at the output samples) add one output interval \
             ({} s), and one the refinements do not reach has an error as large as its value",
            cfg.horizon.sample_every
        ),
        not_applicable: NOT_APPLICABLE.iter().map(|(c, w)| (c.to_string(), w.to_string())).collect(),
    })
}
