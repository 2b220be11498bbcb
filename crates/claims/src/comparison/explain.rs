//! The ftdo-vs-dobc row's evidence (labelled quantities), verdict and words.

use wingcheck_model::{Config, ErrorSource, ObserverRule, Quantity, Unit, ValueBasis};
use wingcheck_sim::SimOutput;

use super::{compute, other_rule, Computed, Metrics};
use crate::display::{Flag, Maybe, Table, Text, NEVER_SETTLED};
use crate::explain::Explain;
use crate::settings::CheckSettings;
use crate::study::Study;
use crate::{Basis, ClaimId, ClaimRow, ClaimsError, Line, PlotData, Verdict};

/// One run at the configured gains.
#[derive(Debug, Clone, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct RunRecord {
    /// Which controller and rule.
    pub run: Text,
    /// RMS q(s,t) over [0, t_end].
    pub rms_q_full: Quantity,
    /// RMS q(s,t) over [t_end/2, t_end].
    pub rms_q_late: Quantity,
    /// Peak |q(s,t)|.
    pub peak_q: Quantity,
    /// RMS θ(s,t) over [0, t_end].
    pub rms_theta_full: Quantity,
    /// RMS θ(s,t) over [t_end/2, t_end].
    pub rms_theta_late: Quantity,
    /// Peak |θ(s,t)|.
    pub peak_theta: Quantity,
    /// Settling time of q(s,t).
    pub settle_q: Maybe,
    /// Settling time of θ(s,t).
    pub settle_theta: Maybe,
    /// RMS τ1.
    pub rms_tau1: Quantity,
    /// Peak |τ1|.
    pub peak_tau1: Quantity,
    /// RMS τ2.
    pub rms_tau2: Quantity,
    /// Peak |τ2|.
    pub peak_tau2: Quantity,
    /// RMS g̃1 over [t_end/2, t_end].
    pub rms_gtilde1_late: Quantity,
    /// RMS g̃2 over [t_end/2, t_end].
    pub rms_gtilde2_late: Quantity,
    /// Time after which |g̃1| stays below the threshold.
    pub gtilde1_settle: Maybe,
    /// The same for g̃2.
    pub gtilde2_settle: Maybe,
}

/// What a simulated metric's ± covers ([`crate::study::refine::refinement_error`]).
const REFINED: [ErrorSource; 3] = [ErrorSource::Grid, ErrorSource::TimeStep, ErrorSource::RoundOff];

impl RunRecord {
    /// The record of a run with metrics `m` and their errors `e` ([`super::metric_errors`]);
    /// `spread`: the RMS τ errors include the spread over nudged starts (the explicit rule).
    fn of(run: &str, m: &Metrics, e: &Metrics, spread: bool, settings: &CheckSettings) -> RunRecord {
        let sim = |label: &str, v: f64, error: f64, u: Unit| Quantity::with_error(label, v, error, u, &REFINED);
        let tau_covers: &[ErrorSource] = if spread {
            &[ErrorSource::Grid, ErrorSource::TimeStep, ErrorSource::Spread, ErrorSource::RoundOff]
        } else {
            &REFINED
        };
        let tau = |label: &str, v: f64, error: f64, u: Unit| Quantity::with_error(label, v, error, u, tau_covers);
        let settle = |label: String, t: Option<f64>, error: Option<f64>| {
            let read = |t: f64| {
                let covers = [ErrorSource::Grid, ErrorSource::TimeStep, ErrorSource::Sampling, ErrorSource::RoundOff];
                Quantity::with_error(&label, t, error.unwrap_or(t.abs()), Unit::Second, &covers)
            };
            Maybe::of(t.map(read), || Text::text(label.clone(), NEVER_SETTLED))
        };
        let pct = wingcheck_model::quantity::format_value(100.0 * settings.settle_fraction, None);
        let thr = wingcheck_model::quantity::format_value(settings.gtilde_threshold, None);
        RunRecord {
            run: Text::text("run", run),
            rms_q_full: sim("RMS q(s,t) over [0, t_end]", m.rms_q_full, e.rms_q_full, Unit::Metre),
            rms_q_late: sim("RMS q(s,t) over [t_end/2, t_end]", m.rms_q_late, e.rms_q_late, Unit::Metre),
            peak_q: sim("peak |q(s,t)| over [0, t_end]", m.peak_q, e.peak_q, Unit::Metre),
            rms_theta_full: sim("RMS θ(s,t) over [0, t_end]", m.rms_theta_full, e.rms_theta_full, Unit::Radian),
            rms_theta_late: sim("RMS θ(s,t) over [t_end/2, t_end]", m.rms_theta_late, e.rms_theta_late, Unit::Radian),
            peak_theta: sim("peak |θ(s,t)| over [0, t_end]", m.peak_theta, e.peak_theta, Unit::Radian),
            settle_q: settle(format!("q(s,t) settles to {pct} % of q(s,0)"), m.settle_q, e.settle_q),
            settle_theta: settle(format!("θ(s,t) settles to {pct} % of θ(s,0)"), m.settle_theta, e.settle_theta),
            rms_tau1: tau("RMS τ1 over [0, t_end] (full rate)", m.rms_tau1, e.rms_tau1, Unit::Newton),
            peak_tau1: sim("peak |τ1| over [0, t_end] (full rate)", m.peak_tau1, e.peak_tau1, Unit::Newton),
            rms_tau2: tau("RMS τ2 over [0, t_end] (full rate)", m.rms_tau2, e.rms_tau2, Unit::NewtonMetre),
            peak_tau2: sim("peak |τ2| over [0, t_end] (full rate)", m.peak_tau2, e.peak_tau2, Unit::NewtonMetre),
            rms_gtilde1_late: sim(
                "RMS g̃1 over [t_end/2, t_end]",
                m.rms_gtilde_late[0],
                e.rms_gtilde_late[0],
                Unit::Newton,
            ),
            rms_gtilde2_late: sim(
                "RMS g̃2 over [t_end/2, t_end]",
                m.rms_gtilde_late[1],
                e.rms_gtilde_late[1],
                Unit::NewtonMetre,
            ),
            gtilde1_settle: settle(
                format!("t_band: |g̃1| stays ≤ {thr} N from (full rate)"),
                m.gtilde_settle[0],
                e.gtilde_settle[0],
            ),
            gtilde2_settle: settle(
                format!("t_band: |g̃2| stays ≤ {thr} N m from (full rate)"),
                m.gtilde_settle[1],
                e.gtilde_settle[1],
            ),
        }
    }
}

/// One point of the (a, b) sweep.
#[derive(Debug, Clone, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct SweepRecord {
    /// a.
    pub a: Quantity,
    /// b.
    pub b: Quantity,
    /// (DOBC − FTDO)/FTDO of the tip RMS there.
    #[serde(flatten)]
    pub rel: TipDifferences,
    /// Late RMS g̃ DOBC / FTDO.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gtilde_ratio_late: Option<Quantity>,
}

/// A relative difference `v` (a fraction) with its error `e`, in percent.
fn pct(label: &str, v: f64, e: f64) -> Quantity {
    Quantity::with_error(label, 100.0 * v, 100.0 * e, Unit::Percent, &REFINED)
}

/// (DOBC − FTDO)/FTDO of the four tip RMS metrics of one pair of runs.
#[derive(Debug, Clone, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct TipDifferences {
    /// RMS q over [0, t_end].
    pub rel_diff_rms_q_full: Quantity,
    /// RMS θ over [0, t_end].
    pub rel_diff_rms_theta_full: Quantity,
    /// RMS q over [t_end/2, t_end].
    pub rel_diff_rms_q_late: Quantity,
    /// RMS θ over [t_end/2, t_end].
    pub rel_diff_rms_theta_late: Quantity,
}

impl TipDifferences {
    fn of(r: &[f64; 4], e: &[f64; 4]) -> TipDifferences {
        TipDifferences {
            rel_diff_rms_q_full: pct("(DOBC − FTDO)/FTDO of RMS q over [0, t_end]", r[0], e[0]),
            rel_diff_rms_theta_full: pct("(DOBC − FTDO)/FTDO of RMS θ over [0, t_end]", r[1], e[1]),
            rel_diff_rms_q_late: pct("(DOBC − FTDO)/FTDO of RMS q over [t_end/2, t_end]", r[2], e[2]),
            rel_diff_rms_theta_late: pct("(DOBC − FTDO)/FTDO of RMS θ over [t_end/2, t_end]", r[3], e[3]),
        }
    }
}

/// The late RMS g̃ ratio DOBC / FTDO with its error.
fn gratio(v: Option<(f64, f64)>) -> Option<Quantity> {
    v.map(|(r, e)| {
        Quantity::with_error("RMS g̃ over [t_end/2, t_end], DOBC / FTDO", r, e, Unit::Dimensionless, &REFINED)
    })
}

/// The evidence of the `ftdo-vs-dobc` row.
#[derive(Debug, Clone, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct ComparisonEvidence {
    /// The FTDO's sampling rule (the configured one).
    pub rule: Text,
    /// The three runs at the configured gains.
    pub runs: Table<RunRecord>,
    /// (DOBC − FTDO)/FTDO of the tip RMS at the configured rule and gains.
    #[serde(flatten)]
    pub rel: TipDifferences,
    /// Late RMS g̃ DOBC / FTDO, both channels combined (configured rule).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gtilde_ratio_late: Option<Quantity>,
    /// The same against the FTDO with the other rule.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gtilde_ratio_late_other_rule: Option<Quantity>,
    /// Full-rate RMS τ1 of the explicit-rule FTDO with its grid, time-step, start-spread and round-off error.
    pub explicit_rms_tau1: Quantity,
    /// Full-rate RMS τ2 of the explicit-rule FTDO with its grid, time-step, start-spread and round-off error.
    pub explicit_rms_tau2: Quantity,
    /// Whether the explicit-rule FTDO's RMS τ is start-sensitive
    /// ([`super::start_sensitive`]), with both nudged starts' values when it is.
    pub explicit_start_sensitivity: Text,
    /// Time scheme of the explicit-rule runs.
    pub explicit_stepper: Text,
    /// How the explicit-rule FTDO's error runs (dt/2, doubled grid, nudged starts) were
    /// stepped: the dense form, or the closed loop's eigenbasis with its round-off estimate
    /// (which the RMS τ ± includes).
    pub explicit_error_runs: Text,
    /// The sweep around the configured (a, b).
    pub ab_sweep: Table<SweepRecord>,
    /// max |relative difference| over every pair and tip metric.
    pub max_abs_rel_diff_tip: Quantity,
    /// Most negative late-window relative difference (< 0: DOBC smaller there).
    pub late_min_rel_diff: Quantity,
    /// DOBC worse by more than the indistinguishability margin in every tip metric of every pair.
    pub tip_response_clearly_better: Flag,
    /// FTDO's late g̃ smaller by more than the margin.
    pub gtilde_clearly_smaller: Flag,
    /// The indistinguishability margin.
    pub indistinguishable: Quantity,
    /// ζ1 = sup |g1|.
    pub zeta1: Quantity,
    /// ζ2 = sup |g2|.
    pub zeta2: Quantity,
    /// (min, max) over the pairs of the four relative differences (context, not serialised).
    #[serde(skip)]
    pub ranges: [(f64, f64); 4],
}

/// Which RMS τ of the explicit FTDO are start-sensitive ([`super::start_sensitive`]), naming
/// both nudged starts' values; or that none is.
fn start_sensitivity_text(c: &Computed) -> String {
    use wingcheck_model::quantity::format_value;
    let sensitive: Vec<String> = (0..2)
        .filter(|&ch| {
            let (v, e) = c.explicit_rms_tau[ch];
            super::start_sensitive(v, e, c.explicit_rms_starts[ch])
        })
        .map(|ch| {
            let (name, unit) = if ch == 0 { ("τ1", Unit::Newton) } else { ("τ2", Unit::NewtonMetre) };
            let [a, b] = c.explicit_rms_starts[ch];
            let apart = 100.0 * (a - b).abs() / a.abs().min(b.abs());
            // to the digits of their difference, so two values that differ read differently
            let [up, down] = [a, b].map(|x| format_value(x, Some((a - b).abs())));
            format!(
                "RMS {name} is {up} {u} from ν(0) + δ and {down} {u} from ν(0) − δ ({} % apart)",
                format_value(apart, None),
                u = unit.symbol()
            )
        })
        .collect();
    let nudge = wingcheck_model::format::exact(super::START_NUDGE);
    if sensitive.is_empty() {
        format!("not start-sensitive: starts ν(0) ± δ (δ = {nudge} relative) move RMS τ1 and τ2 by less than their other error sources together")
    } else {
        format!(
            "start-sensitive (starts ν(0) ± δ, δ = {nudge} relative, differ by more than every other error source together): {}",
            sensitive.join("; ")
        )
    }
}

/// The explicit-rule error runs' form, for [`ComparisonEvidence::explicit_error_runs`].
fn error_runs_text(c: &Computed) -> String {
    let form = if c.error_runs_eigenbasis_roundoff > 0.0 {
        format!(
            "in the closed loop's eigenbasis where its checks passed: round-off estimate at most {} relative \
             of the state, included in the RMS τ ±",
            wingcheck_model::quantity::format_value(c.error_runs_eigenbasis_roundoff, None)
        )
    } else if c.explicit_stepper == wingcheck_model::TimeScheme::Exponential {
        "exponential scheme in its dense form".to_string()
    } else {
        format!("{} scheme", c.explicit_stepper.name())
    };
    format!("runs that record the RMS only (the start not re-run at a finer step, no search for peaks inside a step), {form}")
}

/// The three runs at the configured gains with their errors (the explicit rule's RMS τ with the
/// spread over starts).
fn run_table(c: &Computed, settings: &CheckSettings) -> Table<RunRecord> {
    let (rule, other) = (c.rule.name(), other_rule(c.rule).name());
    let explicit_here = c.rule == wingcheck_model::ObserverRule::Explicit;
    Table::new(
        "the runs at the configured gains",
        vec![
            RunRecord::of(&format!("FTDO, {rule} rule"), &c.ftdo, &c.ftdo_error, explicit_here, settings),
            RunRecord::of("DOBC", &c.dobc, &c.dobc_error, false, settings),
            RunRecord::of(&format!("FTDO, {other} rule"), &c.ftdo_other, &c.ftdo_other_error, !explicit_here, settings),
        ],
    )
}

/// The (a, b) sweep's points with their errors.
fn sweep_table(c: &Computed, settings: &CheckSettings) -> Table<SweepRecord> {
    Table::new(
        format!("sweep: each weight × and ÷ {}", wingcheck_model::quantity::format_value(settings.sweep_factor, None)),
        c.sweep
            .iter()
            .map(|p| SweepRecord {
                a: Quantity::configured("a", p.a, Unit::Dimensionless),
                b: Quantity::configured("b", p.b, Unit::Second),
                rel: TipDifferences::of(&p.rel, &p.rel_error),
                gtilde_ratio_late: gratio(p.gtilde_ratio.zip(p.gtilde_ratio_error)),
            })
            .collect(),
    )
}

fn evidence_of(c: &Computed, settings: &CheckSettings) -> ComparisonEvidence {
    let rule = c.rule.name();
    let other = other_rule(c.rule).name();
    let pairs = c.pairs();
    let pair_errors = c.pair_errors();
    let with_errors = || pairs.iter().flatten().zip(pair_errors.iter().flatten());
    // the largest |difference| and the most negative late one, each with its own error
    let (worst, worst_error) =
        with_errors().fold((0.0_f64, 0.0), |m, (x, e)| if x.abs() > m.0 { (x.abs(), *e) } else { m });
    let late_min = pairs
        .iter()
        .zip(&pair_errors)
        .flat_map(|(d, e)| [(d[2], e[2]), (d[3], e[3])])
        .fold((f64::MAX, 0.0), |m, (x, e)| if x < m.0 { (x, e) } else { m });
    let range = |j: usize| {
        let v = pairs.iter().map(|d| d[j]);
        (v.clone().fold(f64::MAX, f64::min), v.fold(f64::MIN, f64::max))
    };
    let ranges = [range(0), range(1), range(2), range(3)];
    let ratio = c.gtilde_ratio(true);
    let margin = settings.indistinguishable;
    let tau = |ch: usize| {
        let (v, e) = c.explicit_rms_tau[ch];
        let (name, unit) = if ch == 0 { ("τ1", Unit::Newton) } else { ("τ2", Unit::NewtonMetre) };
        Quantity::with_error(
            format!("full-rate RMS {name} over [0, t_end], FTDO explicit rule"),
            v,
            e,
            unit,
            &[ErrorSource::Grid, ErrorSource::TimeStep, ErrorSource::Spread, ErrorSource::RoundOff],
        )
    };
    ComparisonEvidence {
        rule: Text::text("FTDO sampling rule compared (the configured one)", rule),
        runs: run_table(c, settings),
        rel: TipDifferences::of(&c.here(), &pair_errors[0]),
        gtilde_ratio_late: gratio(ratio),
        gtilde_ratio_late_other_rule: gratio(c.gtilde_ratio(false))
            .map(|q| q.relabel(format!("RMS g̃ over [t_end/2, t_end], DOBC / FTDO with the {other} rule"))),
        explicit_rms_tau1: tau(0),
        explicit_rms_tau2: tau(1),
        explicit_start_sensitivity: Text::text(
            "start sensitivity of the explicit-rule FTDO's RMS τ",
            start_sensitivity_text(c),
        ),
        explicit_stepper: Text::text("time scheme of the explicit-rule runs", c.explicit_stepper.name()),
        explicit_error_runs: Text::text("how the explicit-rule error runs were stepped", error_runs_text(c)),
        ab_sweep: sweep_table(c, settings),
        max_abs_rel_diff_tip: pct("largest |tip RMS difference| over the sweep and both rules", worst, worst_error),
        late_min_rel_diff: pct("most negative late-window difference (< 0: DOBC smaller)", late_min.0, late_min.1),
        tip_response_clearly_better: Flag::new(
            "DOBC worse by more than the margin, beyond the error, in every tip metric of every pair",
            with_errors().all(|(x, e)| x - e > margin),
        ),
        gtilde_clearly_smaller: Flag::new(
            "FTDO's late g̃ smaller than DOBC's by more than the margin, beyond the error",
            ratio.is_some_and(|(r, e)| r - e > 1.0 + margin),
        ),
        indistinguishable: Quantity::exact("indistinguishability margin", 100.0 * margin, Unit::Percent),
        zeta1: Quantity::based("ζ1 = sup |g1|", c.zetas.0, Unit::Newton, ValueBasis::ClosedForm),
        zeta2: Quantity::based("ζ2 = sup |g2|", c.zetas.1, Unit::NewtonMetre, ValueBasis::ClosedForm),
        ranges,
    }
}

impl ComparisonEvidence {
    fn run(&self, i: usize) -> &RunRecord {
        &self.runs.rows[i]
    }
}

fn label_of(m: &Maybe) -> &str {
    match m {
        Maybe::Value(q) => &q.label,
        Maybe::Missing(t) => &t.label,
    }
}

fn fmt_pct_range(r: (f64, f64)) -> String {
    let f = |v: f64| wingcheck_model::quantity::format_value(100.0 * v, None);
    format!("{} … {} %", f(r.0), f(r.1))
}

impl Explain for ComparisonEvidence {
    /// Holds only if DOBC is worse by a clear margin in every tip metric of every pair and
    /// FTDO's disturbance error is clearly smaller; partly reproduced if exactly one of the two
    /// is; fails if neither. Basis: simulation.
    fn verdict(&self) -> (Verdict, Basis) {
        let v = match (self.tip_response_clearly_better.value, self.gtilde_clearly_smaller.value) {
            (true, true) => Verdict::Holds,
            (false, false) => Verdict::Fails,
            _ => Verdict::PartlyReproduced,
        };
        (v, Basis::Simulation)
    }

    fn finding(&self) -> Vec<String> {
        let rule = &self.rule.value;
        let g = match &self.gtilde_ratio_late {
            Some(r) if r.value >= 1.0 => {
                format!(
                    "Over [t_end/2, t_end], FTDO's ({rule} rule) disturbance error (RMS) is {} × smaller than DOBC's.",
                    r.value_text()
                )
            }
            Some(r) => format!(
                "Over [t_end/2, t_end], DOBC's disturbance error (RMS) is {} × smaller than FTDO's ({rule} rule).",
                wingcheck_model::quantity::format_value(1.0 / r.value, None)
            ),
            None => format!("Over [t_end/2, t_end], FTDO's ({rule} rule) disturbance error vanishes."),
        };
        let [fq, ft, lq, lt] = self.ranges;
        let lo = fq.0.min(ft.0).min(lq.0).min(lt.0);
        let hi = fq.1.max(ft.1).max(lq.1).max(lt.1);
        let tip = format!(
            "Over the configured (a, b), the sweep around it and both rules, DOBC's tip RMS differs from FTDO's by {}: {}.",
            fmt_pct_range((lo, hi)),
            if self.tip_response_clearly_better.value {
                "FTDO's tip response is clearly better"
            } else {
                "a clearly better FTDO tip response is not shown"
            }
        );
        let (f, d) = (self.run(0), self.run(1));
        let cost = format!(
            "FTDO's peak |τ2| over [0, t_end] is {} against DOBC's {}.",
            f.peak_tau2.value_text(),
            d.peak_tau2.value_text()
        );
        vec![g, tip, cost]
    }

    fn deciding(&self) -> String {
        let [fq, ft, lq, lt] = self.ranges;
        let (lo, hi) = (fq.0.min(ft.0).min(lq.0).min(lt.0), fq.1.max(ft.1).max(lq.1).max(lt.1));
        let g = match &self.gtilde_ratio_late {
            // four significant digits on the one line (the ± and the full value are in the row)
            Some(r) => format!(
                "RMS g̃ on [t_end/2, t_end]: DOBC/FTDO ≈ {}",
                wingcheck_model::quantity::with_significant(r.value, 4)
            ),
            None => "FTDO's g̃ on [t_end/2, t_end] vanishes".into(),
        };
        format!("{g}; tip RMS DOBC − FTDO: {}", fmt_pct_range((lo, hi)))
    }

    fn decisive(&self) -> Vec<Quantity> {
        let mut out: Vec<Quantity> = self.gtilde_ratio_late.iter().cloned().collect();
        out.push(self.rel.rel_diff_rms_q_late.clone());
        out.push(self.max_abs_rel_diff_tip.clone());
        out
    }

    fn details(&self) -> Vec<String> {
        let [fq, ft, lq, lt] = self.ranges;
        let (f, d) = (self.run(0), self.run(1));
        let mut out = vec![
            format!(
                "(DOBC − FTDO)/FTDO of the tip RMS over all pairs: q over [0, t_end] {}, θ over [0, t_end] {}, q over [t_end/2, t_end] {}, θ over [t_end/2, t_end] {}.",
                fmt_pct_range(fq),
                fmt_pct_range(ft),
                fmt_pct_range(lq),
                fmt_pct_range(lt)
            ),
            format!(
                "At the configured gains RMS q(s,t) over [0, t_end] is {} (FTDO) against {} (DOBC); {}: {} (FTDO) against {} (DOBC).",
                f.rms_q_full.value_text(),
                d.rms_q_full.value_text(),
                label_of(&f.settle_q),
                f.settle_q.text(),
                d.settle_q.text()
            ),
        ];
        if let Some(r) = &self.gtilde_ratio_late_other_rule {
            out.push(format!(
                "Against the FTDO with the other rule the late g̃ ratio DOBC / FTDO is {}.",
                r.value_text()
            ));
        }
        out.push(format!(
            "The explicit-rule FTDO's full-rate RMS τ1 is {} and RMS τ2 {} ({} scheme; the ± covers {}; its error runs: {}); the tip disturbances are bounded by ζ1 = {}, ζ2 = {}.",
            self.explicit_rms_tau1.pm_text(),
            self.explicit_rms_tau2.pm_text(),
            self.explicit_stepper.value,
            self.explicit_rms_tau1.covers_text().unwrap_or_else(|| "nothing: no error estimate".into()),
            self.explicit_error_runs.value,
            self.zeta1.value_text(),
            self.zeta2.value_text()
        ));
        if self.explicit_start_sensitivity.value.starts_with("start-sensitive") {
            out.push(format!(
                "The explicit-rule FTDO's RMS τ is {}: the value depends on the observer's start, not only on the model.",
                self.explicit_start_sensitivity.value
            ));
        }
        out
    }
}

fn plots(rule: ObserverRule, f: &SimOutput, d: &SimOutput) -> Vec<PlotData> {
    let (fs, ds) = (&f.series, &d.series);
    let line = |label: String, x: &[f64], y: Vec<f64>| Line { label, x: x.to_vec(), y, points: false };
    let ftdo = format!("FTDO ({} rule)", rule.name());
    let mk = |name: &str, what: &str, unit: Unit, yf: Vec<f64>, yd: Vec<f64>| PlotData {
        name: format!("ftdo-vs-dobc-{name}"),
        title: format!("{what}: FTDO ({} rule) against DOBC", rule.name()),
        x_label: "t (s)".into(),
        y_label: format!("{what} ({})", unit.symbol()),
        log_x: false,
        log_y: false,
        lines: vec![line(ftdo.clone(), &fs.t, yf), line("DOBC".into(), &ds.t, yd)],
    };
    let gt = |s: &wingcheck_sim::Series, c| wingcheck_sim::metrics::observer_error(s, c);
    // drawing data: at most MAX_DRAWN_SAMPLES per line, whatever the horizon
    [
        mk("q-tip", "tip bending q(s,t)", Unit::Metre, fs.q_tip.clone(), ds.q_tip.clone()),
        mk("theta-tip", "tip twist θ(s,t)", Unit::Radian, fs.theta_tip.clone(), ds.theta_tip.clone()),
        mk("gtilde1", "g̃1 = g1 − ĝ1", Unit::Newton, gt(fs, 0), gt(ds, 0)),
        mk("gtilde2", "g̃2 = g2 − ĝ2", Unit::NewtonMetre, gt(fs, 1), gt(ds, 1)),
        mk("tau1", "τ1", Unit::Newton, fs.tau1.clone(), ds.tau1.clone()),
        mk("tau2", "τ2", Unit::NewtonMetre, fs.tau2.clone(), ds.tau2.clone()),
    ]
    .into_iter()
    .map(PlotData::thinned)
    .collect()
}

/// Compare FTDO and DOBC (Section 4, Figs 3–20).
pub fn check(cfg: &Config, study: &Study, settings: &CheckSettings) -> Result<ClaimRow, ClaimsError> {
    let (c, f, d) = compute(cfg, study, settings)?;
    let e = evidence_of(&c, settings);
    let fmt = |v: f64| wingcheck_model::quantity::format_value(v, None);
    let (a0, b0) = (cfg.control.a, cfg.control.b);
    let sf = fmt(settings.sweep_factor);
    let left_out = super::sweep_weights(cfg, settings.sweep_factor).1;
    let mut assumptions = vec![
        "DOBC (57) corrected: b q̇(s) in τ1, ĝ from d ĝ/dt = g − ĝ with p(0) = 0; the same k1, k2, a, b and sampling rule as the FTDO".into(),
        format!(
            "(a, b) not given by the paper: the configured ({}, {}) and the sweep a × {sf}, a ÷ {sf}, b × {sf}, b ÷ {sf}",
            fmt(a0),
            fmt(b0)
        ),
        format!(
            "RMS over the {} s output samples; peaks and RMS τ at full rate; settling to {} % of the initial tip values; |g̃| ≤ {} counts as converged",
            fmt(cfg.horizon.sample_every),
            fmt(100.0 * settings.settle_fraction),
            fmt(settings.gtilde_threshold)
        ),
        format!("indistinguishable = tip RMS within {} %", fmt(100.0 * settings.indistinguishable)),
    ];
    if !left_out.is_empty() {
        assumptions.push(format!("the sweep leaves out {}", left_out.join("; ")));
    }
    Ok(ClaimRow::decided(ClaimId::FtdoVsDobc, e, assumptions, plots(c.rule, &f, &d)))
}
