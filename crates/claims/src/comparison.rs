//! Section 4, Figs 3–20: the proposed FTDO controller against DOBC (57, corrected).
//!
//! Both controllers use the same law (15) and gains; they differ only in ĝ. The FTDO runs with
//! the configured sampling rule (the other rule is a secondary comparison). Metrics come from
//! [`wingcheck_sim::metrics`] (the one definition of RMS, peaks and settling): RMS over the
//! windows [0, t_end] ("full") and [t_end/2, t_end] ("late") of the output samples, peaks and
//! the RMS of τ at full rate. The (a, b) sweep multiplies and divides each configured weight by
//! [`CheckSettings::sweep_factor`]. [`compute`] gathers the facts; [`explain`] turns them into
//! the row.

mod explain;
mod refine;

use rayon::prelude::*;
use wingcheck_model::{Config, ControllerKind, ObserverRule};
use wingcheck_sim::metrics::{self, Window};
use wingcheck_sim::SimOutput;

use crate::finite_time::reach::zeta;
use crate::settings::CheckSettings;
use crate::study::refine::{refinement_error, refinements};
use crate::study::Study;
use crate::ClaimsError;

pub use explain::{check, ComparisonEvidence, RunRecord, SweepRecord, TipDifferences};
pub use refine::{metric_errors, quotient_error};

/// Metrics of one run (units: m, rad, N, N m, s).
#[derive(Debug, Clone, PartialEq)]
pub struct Metrics {
    /// RMS of q(s,t) over [0, t_end] (m).
    pub rms_q_full: f64,
    /// RMS of q(s,t) over [t_end/2, t_end] (m).
    pub rms_q_late: f64,
    /// max |q(s,t)| over the run, full rate (m).
    pub peak_q: f64,
    /// RMS of θ(s,t) over [0, t_end] (rad).
    pub rms_theta_full: f64,
    /// RMS of θ(s,t) over [t_end/2, t_end] (rad).
    pub rms_theta_late: f64,
    /// max |θ(s,t)| over the run, full rate (rad).
    pub peak_theta: f64,
    /// Settling time of q(s,t) ([`metrics::tip_settle_time`]) (s).
    pub settle_q: Option<f64>,
    /// Settling time of θ(s,t) (s).
    pub settle_theta: Option<f64>,
    /// RMS of τ1 over the run, full rate (N).
    pub rms_tau1: f64,
    /// Peak |τ1|, full rate (N).
    pub peak_tau1: f64,
    /// RMS of τ2 over the run, full rate (N m).
    pub rms_tau2: f64,
    /// Peak |τ2|, full rate (N m).
    pub peak_tau2: f64,
    /// RMS of g̃ over [0, t_end], per channel (N, N m).
    pub rms_gtilde_full: [f64; 2],
    /// RMS of g̃ over [t_end/2, t_end], per channel.
    pub rms_gtilde_late: [f64; 2],
    /// Last exit of |g̃| from the convergence threshold, per channel (s).
    pub gtilde_settle: [Option<f64>; 2],
}

impl Metrics {
    /// The four tip RMS metrics compared: q, θ over [0, t_end] and over [t_end/2, t_end].
    pub fn tip(&self) -> [f64; 4] {
        [self.rms_q_full, self.rms_theta_full, self.rms_q_late, self.rms_theta_late]
    }

    /// Late RMS of g̃, both channels combined (hypot).
    pub fn gtilde_late(&self) -> f64 {
        self.rms_gtilde_late[0].hypot(self.rms_gtilde_late[1])
    }
}

/// Metrics of one run.
pub fn metrics(out: &SimOutput, settings: &CheckSettings) -> Metrics {
    let s = &out.series;
    let whole = Window::whole(&s.t);
    let late = Window::second_half(whole.t1);
    let rms = |v: &[f64], w: Window| metrics::rms_in(&s.t, v, w).unwrap_or(0.0);
    let gt = [metrics::observer_error(s, 0), metrics::observer_error(s, 1)];
    let settle = |x: &[f64]| metrics::tip_settle_time(&s.t, x, settings.settle_fraction);
    Metrics {
        rms_q_full: rms(&s.q_tip, whole),
        rms_q_late: rms(&s.q_tip, late),
        peak_q: out.peaks.q_tip.abs_max,
        rms_theta_full: rms(&s.theta_tip, whole),
        rms_theta_late: rms(&s.theta_tip, late),
        peak_theta: out.peaks.theta_tip.abs_max,
        settle_q: settle(&s.q_tip),
        settle_theta: settle(&s.theta_tip),
        rms_tau1: metrics::tau_rms_in(s, 0, whole).unwrap_or(0.0),
        peak_tau1: metrics::tau_peak(out, 0),
        rms_tau2: metrics::tau_rms_in(s, 1, whole).unwrap_or(0.0),
        peak_tau2: metrics::tau_peak(out, 1),
        rms_gtilde_full: [rms(&gt[0], whole), rms(&gt[1], whole)],
        rms_gtilde_late: [rms(&gt[0], late), rms(&gt[1], late)],
        gtilde_settle: metrics::gtilde_band(out, settings.gtilde_threshold).entry,
    }
}

/// Relative excess (y − x)/|x| (0 when both vanish, ±1 when only x does).
pub fn rel_excess(x: f64, y: f64) -> f64 {
    if x != 0.0 {
        (y - x) / x.abs()
    } else if y == 0.0 {
        0.0
    } else {
        y.signum()
    }
}

/// (DOBC − FTDO)/FTDO of the four tip RMS metrics.
fn rel(f: &Metrics, d: &Metrics) -> [f64; 4] {
    let (x, y) = (f.tip(), d.tip());
    [0, 1, 2, 3].map(|j| rel_excess(x[j], y[j]))
}

/// The (a, b) sweep around the configured weights (each × and ÷ `factor`): the points whose
/// configuration is valid, and, in words, those left out because a weight leaves the range
/// the validator allows (`a × 2 = 2e12 is above control.a's range`).
pub fn sweep_weights(cfg: &Config, factor: f64) -> (Vec<(f64, f64)>, Vec<String>) {
    let (a0, b0) = (cfg.control.a, cfg.control.b);
    let f = wingcheck_model::quantity::format_value(factor, None);
    let points = [
        (a0 / factor, b0, format!("a ÷ {f}")),
        (a0 * factor, b0, format!("a × {f}")),
        (a0, b0 / factor, format!("b ÷ {f}")),
        (a0, b0 * factor, format!("b × {f}")),
    ];
    let (mut kept, mut left_out) = (Vec::new(), Vec::new());
    for (a, b, name) in points {
        match variant(cfg, cfg.control.kind, cfg.observer.rule, a, b).validate() {
            Ok(()) => kept.push((a, b)),
            Err(e) => left_out.push(format!("{name} (outside the configuration's range: {e})")),
        }
    }
    (kept, left_out)
}

/// `cfg` with the given controller, rule and weights: the run [`compute`] asks the study for.
pub fn variant(cfg: &Config, kind: ControllerKind, rule: ObserverRule, a: f64, b: f64) -> Config {
    let mut c = cfg.clone();
    c.control.kind = kind;
    c.observer.rule = rule;
    c.control.a = a;
    c.control.b = b;
    c
}

/// One point of the (a, b) sweep (configured rule).
#[derive(Debug, Clone, PartialEq)]
pub struct SweepPoint {
    /// a.
    pub a: f64,
    /// b.
    pub b: f64,
    /// (DOBC − FTDO)/FTDO of the tip RMS: q, θ full; q, θ late.
    pub rel: [f64; 4],
    /// Late RMS g̃ DOBC / FTDO (None when FTDO's vanishes).
    pub gtilde_ratio: Option<f64>,
    /// The errors of `rel` ([`quotient_error`] from the runs' [`metric_errors`]).
    pub rel_error: [f64; 4],
    /// The error of `gtilde_ratio`.
    pub gtilde_ratio_error: Option<f64>,
}

/// Everything the comparison computes, before it is put into words.
#[derive(Debug, Clone)]
pub struct Computed {
    /// The configured sampling rule of the FTDO.
    pub rule: ObserverRule,
    /// FTDO with the configured rule, configured gains.
    pub ftdo: Metrics,
    /// FTDO with the other rule.
    pub ftdo_other: Metrics,
    /// DOBC.
    pub dobc: Metrics,
    /// The errors of `ftdo`'s metrics ([`metric_errors`]; for the explicit rule's RMS τ, its
    /// `explicit_rms_tau` error, which adds the spread over starts).
    pub ftdo_error: Metrics,
    /// The errors of `ftdo_other`'s metrics (likewise).
    pub ftdo_other_error: Metrics,
    /// The errors of `dobc`'s metrics.
    pub dobc_error: Metrics,
    /// Full-rate RMS τ1, τ2 of the explicit-rule FTDO run, and their errors
    /// ([`explicit_rms_error`]: grid + time step + start spread + round-off).
    pub explicit_rms_tau: [(f64, f64); 2],
    /// Full-rate RMS τ1, τ2 of the explicit-rule FTDO from the two [`START_NUDGE`]d starts
    /// (ν(0) + δ, ν(0) − δ), per channel.
    pub explicit_rms_starts: [[f64; 2]; 2],
    /// The time scheme of the explicit-rule runs.
    pub explicit_stepper: wingcheck_model::TimeScheme,
    /// The largest eigenbasis round-off estimate (relative) of the explicit FTDO's error runs
    /// ([`crate::Study::statistics`]); 0 where all of them stepped in the dense form.
    pub error_runs_eigenbasis_roundoff: f64,
    /// The sweep around the configured (a, b).
    pub sweep: Vec<SweepPoint>,
    /// ζ1, ζ2 = sup |g1|, sup |g2| (N, N m).
    pub zetas: (f64, f64),
}

impl Computed {
    /// (DOBC − FTDO)/FTDO at the configured gains, configured rule.
    pub fn here(&self) -> [f64; 4] {
        rel(&self.ftdo, &self.dobc)
    }

    /// The same against the other rule.
    pub fn here_other(&self) -> [f64; 4] {
        rel(&self.ftdo_other, &self.dobc)
    }

    /// Every compared pair's four relative differences: the configured point with both rules,
    /// then the sweep (configured rule).
    pub fn pairs(&self) -> Vec<[f64; 4]> {
        let mut v = vec![self.here(), self.here_other()];
        v.extend(self.sweep.iter().map(|p| p.rel));
        v
    }

    /// The errors of [`Computed::pairs`], in its order.
    pub fn pair_errors(&self) -> Vec<[f64; 4]> {
        let mut v = vec![
            rel_error(&self.ftdo, &self.ftdo_error, &self.dobc, &self.dobc_error),
            rel_error(&self.ftdo_other, &self.ftdo_other_error, &self.dobc, &self.dobc_error),
        ];
        v.extend(self.sweep.iter().map(|p| p.rel_error));
        v
    }

    /// [`gtilde_ratio`] at the configured gains with the FTDO of `rule` (the configured one or
    /// the other), and its error.
    pub fn gtilde_ratio(&self, configured_rule: bool) -> Option<(f64, f64)> {
        let (f, fe) =
            if configured_rule { (&self.ftdo, &self.ftdo_error) } else { (&self.ftdo_other, &self.ftdo_other_error) };
        gtilde_ratio(f, &self.dobc).zip(gtilde_ratio_error(f, fe, &self.dobc, &self.dobc_error))
    }
}

/// The errors of [`rel`]'s four differences from the runs' metric errors.
fn rel_error(f: &Metrics, f_error: &Metrics, d: &Metrics, d_error: &Metrics) -> [f64; 4] {
    let (x, dx, y, dy) = (f.tip(), f_error.tip(), d.tip(), d_error.tip());
    [0, 1, 2, 3].map(|j| quotient_error(x[j], dx[j], y[j], dy[j]))
}

/// The error of [`gtilde_ratio`].
fn gtilde_ratio_error(f: &Metrics, f_error: &Metrics, d: &Metrics, d_error: &Metrics) -> Option<f64> {
    (f.gtilde_late() > 0.0).then(|| {
        let (dx, dy) = (refine::gtilde_late_error(f_error), refine::gtilde_late_error(d_error));
        quotient_error(f.gtilde_late(), dx, d.gtilde_late(), dy)
    })
}

/// Late RMS g̃ of DOBC over FTDO's (None when FTDO's vanishes).
fn gtilde_ratio(f: &Metrics, d: &Metrics) -> Option<f64> {
    (f.gtilde_late() > 0.0).then(|| d.gtilde_late() / f.gtilde_late())
}

/// The other sampling rule.
pub fn other_rule(rule: ObserverRule) -> ObserverRule {
    match rule {
        ObserverRule::Implicit => ObserverRule::Explicit,
        ObserverRule::Explicit => ObserverRule::Implicit,
    }
}

/// The configurations the comparison simulates, in the order [`compute`] asks for them:
/// the FTDO with the configured rule, with the other rule, DOBC (all at the configured gains),
/// the explicit-rule FTDO at dt/2 and on the doubled grid (its time-step and grid errors), then
/// the sweep's FTDO and DOBC pairs.
pub struct Runs {
    /// FTDO, configured rule.
    pub ftdo: Config,
    /// FTDO, the other rule.
    pub other: Config,
    /// DOBC.
    pub dobc: Config,
    /// The explicit-rule FTDO at dt/2.
    pub explicit_half: Config,
    /// The explicit-rule FTDO on the doubled grid (`simulate --error-estimate`'s refinement).
    pub explicit_fine: Config,
    /// The explicit-rule FTDO started at ν(0) + δ and ν(0) − δ ([`START_NUDGE`]): the spread of
    /// its chattering statistics over starts that differ below any physical resolution.
    pub explicit_nudged: [Config; 2],
    /// (a, b, FTDO, DOBC) per sweep point.
    pub sweep: Vec<(f64, f64, Config, Config)>,
}

impl Runs {
    /// The comparison's runs for `cfg`.
    pub fn of(cfg: &Config, settings: &CheckSettings) -> Runs {
        let (a0, b0) = (cfg.control.a, cfg.control.b);
        let rule = cfg.observer.rule;
        let explicit = variant(cfg, ControllerKind::Ftdo, ObserverRule::Explicit, a0, b0);
        let f = settings.sweep_factor;
        let [explicit_fine, explicit_half] = refinements(&explicit);
        Runs {
            ftdo: variant(cfg, ControllerKind::Ftdo, rule, a0, b0),
            other: variant(cfg, ControllerKind::Ftdo, other_rule(rule), a0, b0),
            dobc: variant(cfg, ControllerKind::Dobc, rule, a0, b0),
            explicit_half,
            explicit_fine,
            explicit_nudged: [1.0, -1.0].map(|sign| {
                let mut c = explicit.clone();
                c.observer.nu1_0 += sign * START_NUDGE * c.observer.nu1_0.abs().max(1.0);
                c.observer.nu2_0 += sign * START_NUDGE * c.observer.nu2_0.abs().max(1.0);
                c
            }),
            sweep: sweep_weights(cfg, f)
                .0
                .into_iter()
                .map(|(a, b)| {
                    (
                        a,
                        b,
                        variant(cfg, ControllerKind::Ftdo, rule, a, b),
                        variant(cfg, ControllerKind::Dobc, rule, a, b),
                    )
                })
                .collect(),
        }
    }

    /// The runs simulated in full ([`Study::simulate`]), the explicit FTDO's first.
    pub fn full(&self) -> Vec<&Config> {
        let mut v = vec![&self.other, &self.ftdo, &self.dobc];
        for (_, _, f, d) in &self.sweep {
            v.extend([f, d]);
        }
        v
    }

    /// The refinements of every full run ([`refinements`]), for the ± of their metrics.
    pub fn refined(&self) -> Vec<Config> {
        self.full().into_iter().flat_map(refinements).collect()
    }

    /// The explicit FTDO's error runs, simulated as statistics runs ([`Study::statistics`]),
    /// the doubled grid's first.
    pub fn error_runs(&self) -> [&Config; 4] {
        [&self.explicit_fine, &self.explicit_half, &self.explicit_nudged[0], &self.explicit_nudged[1]]
    }
}

/// Relative nudge of the explicit FTDO's start ν(0) (of max(1, |ν(0)|)) for its spread: 1e-12.
/// At rest σ(0) = 0 exactly and ĝ₀ = φ(σ₀) evaluates sign(0), so the chatter pattern, and with it
/// RMS τ, depends on which side of 0 the start falls (measured: 1.3 % on RMS τ1 at the paper's
/// point, 2.3 % at k1 = 3, a = 0.5, ξ = 0.3); the grid acts as such a perturbation too (RMS τ1
/// converges in h at order 0.16 there), so no refinement bounds the error without it.
pub const START_NUDGE: f64 = 1e-12;

/// Error of a full-rate RMS τ of the explicit-rule FTDO, `value` at the configured grid and
/// step, from its values on the doubled grid (`fine`), at dt/2 (`half_dt`) and from the
/// [`START_NUDGE`]d starts (`nudged`): the grid part ([`crate::study::refine::EXPLICIT_RMS_GRID_FACTOR`]), the
/// time-step part (F·|Δ|, F = [`wingcheck_sim::RICHARDSON_2`], order 2 in dt), the spread (the
/// largest change over the nudged starts) and a round-off floor of 256 ulp of the value, plus
/// the eigenbasis round-off of the refined runs (`eigenbasis_roundoff`, relative, the largest
/// of theirs; 0 where they stepped in the dense form) through the same factors, since each
/// enters the error through its difference from `value`.
/// That is [`refinement_error`] plus the spread and the nudged runs' own round-off.
pub fn explicit_rms_error(value: f64, fine: f64, half_dt: f64, nudged: [f64; 2], eigenbasis_roundoff: f64) -> f64 {
    refinement_error(value, fine, half_dt, eigenbasis_roundoff)
        + start_spread(value, nudged)
        + eigenbasis_roundoff * value.abs()
}

/// The largest change of `value` over its [`START_NUDGE`]d starts.
fn start_spread(value: f64, nudged: [f64; 2]) -> f64 {
    nudged.iter().map(|n| (value - n).abs()).fold(0.0, f64::max)
}

/// Whether a full-rate RMS τ of the explicit FTDO is start-sensitive: its [`START_NUDGE`]d
/// starts (`starts`) move it by more than every other source of its `error`
/// ([`explicit_rms_error`]) together — the spread is then most of the ±, and the value depends
/// on the start more than on the grid or the step (measured at a = 0.5, b = 2000 with tip
/// amplitudes 0.6 and 0.2: RMS τ1 0.45 N and 1.11 N from starts 1e-12 apart; an independent
/// simulator agrees on both branches).
pub fn start_sensitive(value: f64, error: f64, starts: [f64; 2]) -> bool {
    let spread = start_spread(value, starts);
    spread > error - spread
}

/// The runs (through the study) and their metrics. Returns the facts and the two full outputs
/// behind the plots (FTDO with the configured rule, DOBC).
pub fn compute(
    cfg: &Config,
    study: &Study,
    settings: &CheckSettings,
) -> Result<(Computed, std::sync::Arc<SimOutput>, std::sync::Arc<SimOutput>), ClaimsError> {
    let rule = cfg.observer.rule;
    let plan = Runs::of(cfg, settings);
    prefetch(&plan, study);
    let ftdo = study.simulate(&plan.ftdo)?;
    let other = study.simulate(&plan.other)?;
    let dobc = study.simulate(&plan.dobc)?;
    let explicit = if rule == ObserverRule::Explicit { &ftdo } else { &other };
    // the error runs serve RMS τ only: statistics runs (eigenbasis where it passes)
    let explicit_half = study.statistics(&plan.explicit_half)?;
    let explicit_fine = study.statistics(&plan.explicit_fine)?;
    let nudged = [study.statistics(&plan.explicit_nudged[0])?, study.statistics(&plan.explicit_nudged[1])?];
    let roundoff = [&explicit_half, &explicit_fine, &nudged[0], &nudged[1]]
        .iter()
        .filter_map(|o| o.stats.eigenbasis_roundoff)
        .fold(0.0, f64::max);
    let whole = Window::whole(&explicit.series.t);
    let rms_tau = |o: &SimOutput, c| metrics::tau_rms_in(&o.series, c, whole).unwrap_or(0.0);
    let explicit_rms_starts = [0, 1].map(|c| [rms_tau(&nudged[0], c), rms_tau(&nudged[1], c)]);
    let explicit_rms_tau = [0, 1].map(|c| {
        let v = rms_tau(explicit, c);
        let starts = explicit_rms_starts[c];
        (v, explicit_rms_error(v, rms_tau(&explicit_fine, c), rms_tau(&explicit_half, c), starts, roundoff))
    });
    let sweep = sweep_points(&plan, study, settings)?;
    // the explicit rule's RMS τ: its own error (grid, step, spread over starts, round-off)
    let with_explicit_tau = |(m, mut e): (Metrics, Metrics), explicit_rule: bool| {
        if explicit_rule {
            (e.rms_tau1, e.rms_tau2) = (explicit_rms_tau[0].1, explicit_rms_tau[1].1);
        }
        (m, e)
    };
    let (ftdo_m, ftdo_error) =
        with_explicit_tau(measured(study, &plan.ftdo, settings)?, rule == ObserverRule::Explicit);
    let (other_m, ftdo_other_error) =
        with_explicit_tau(measured(study, &plan.other, settings)?, rule != ObserverRule::Explicit);
    let (dobc_m, dobc_error) = measured(study, &plan.dobc, settings)?;
    let d = &cfg.disturbance;
    let computed = Computed {
        rule,
        ftdo: ftdo_m,
        ftdo_other: other_m,
        dobc: dobc_m,
        ftdo_error,
        ftdo_other_error,
        dobc_error,
        explicit_rms_tau,
        explicit_rms_starts,
        explicit_stepper: explicit.stats.stepper,
        error_runs_eigenbasis_roundoff: roundoff,
        sweep,
        zetas: (zeta(&d.tip_bending), zeta(&d.tip_torsion)),
    };
    Ok((computed, ftdo, dobc))
}

/// Every run of the row at once on the pool, the longest first (the study keeps each result,
/// failures included; the reads after it find them done).
fn prefetch(plan: &Runs, study: &Study) {
    let refined = plan.refined();
    rayon::join(
        || plan.full().par_iter().for_each(|c| drop(study.simulate(c))),
        || {
            rayon::join(
                || plan.error_runs().par_iter().for_each(|c| drop(study.statistics(c))),
                || refined.par_iter().for_each(|c| drop(study.refinement(c))),
            )
        },
    );
}

/// The sweep's points: each pair's relative differences and g̃ ratio with their errors.
fn sweep_points(plan: &Runs, study: &Study, settings: &CheckSettings) -> Result<Vec<SweepPoint>, ClaimsError> {
    let mut sweep = Vec::new();
    for (a, b, f_cfg, d_cfg) in &plan.sweep {
        let (fm, fe) = measured(study, f_cfg, settings)?;
        let (dm, de) = measured(study, d_cfg, settings)?;
        sweep.push(SweepPoint {
            a: *a,
            b: *b,
            rel: rel(&fm, &dm),
            gtilde_ratio: gtilde_ratio(&fm, &dm),
            rel_error: rel_error(&fm, &fe, &dm, &de),
            gtilde_ratio_error: gtilde_ratio_error(&fm, &fe, &dm, &de),
        });
    }
    Ok(sweep)
}

/// The metrics of the run of `cfg` and their errors from its refinements ([`metric_errors`]).
pub fn measured(study: &Study, cfg: &Config, settings: &CheckSettings) -> Result<(Metrics, Metrics), ClaimsError> {
    let run = study.simulate(cfg)?;
    let base = metrics(&run, settings);
    let (fine, half_dt, roundoff) = study.refined_runs(cfg)?;
    // settling read off the output samples; g̃'s band entry where metrics::gtilde_band read it
    let output = cfg.horizon.sample_every;
    let band = metrics::gtilde_band(&run, settings.gtilde_threshold).sampling(cfg);
    let errors =
        metric_errors(&base, &metrics(&fine, settings), &metrics(&half_dt, settings), roundoff, [output, band]);
    Ok((base, errors))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The explicit FTDO's refinements step the scheme its run steps. At 96 elements (288
    /// unknowns, modal, exponential under `auto`) the doubled grid has 576 unknowns, above
    /// `MODAL_AUTO_UNKNOWNS` = 300, where `auto` alone would pick the nodal basis and TR-BDF2;
    /// at 24 elements both are modal and exponential either way.
    #[test]
    fn refinements_step_the_explicit_runs_scheme() {
        for elements in [24, 96] {
            let mut cfg = Config::paper();
            cfg.discretisation.elements = elements;
            let plan = Runs::of(&cfg, &CheckSettings::default());
            let base = plan.explicit_nudged[0].expected_time_scheme();
            assert_eq!(base, wingcheck_model::TimeScheme::Exponential, "{elements}");
            for refined in [&plan.explicit_fine, &plan.explicit_half] {
                assert_eq!(refined.expected_time_scheme(), base, "{elements}");
                assert!(refined.expected_modal(), "{elements}");
            }
            let mut unpinned = wingcheck_model::work::refined_in_space(&plan.explicit_nudged[0]);
            unpinned.discretisation.stepper = cfg.discretisation.stepper;
            assert_eq!(unpinned.expected_modal(), elements == 24, "{elements}: auto alone");
        }
    }
}
