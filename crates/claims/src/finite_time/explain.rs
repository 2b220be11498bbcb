//! The finite-time rows' evidence (labelled quantities), verdict and words.

use crate::numerics::NumericsError;
use wingcheck_model::{Config, ErrorSource, ObserverRule, Quantity, Unit, ValueBasis};

use super::{channel_index, channel_unit, compute, plots, reference_period, Channel, Computed};
use crate::display::{Flag, Maybe, Table, Text};
use crate::explain::Explain;
use crate::settings::CheckSettings;
use crate::{Basis, ClaimId, ClaimRow, ClaimsError, Verdict};

/// The switching gain of channel `ix` (0: κ2 of (20), 1: κ5 of (21)).
fn kappa_sw(ix: usize) -> &'static str {
    if ix == 0 {
        "κ2"
    } else {
        "κ5"
    }
}

/// One digital run of the observer (rule × hold period).
#[derive(Debug, Clone, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct DigitalRecord {
    /// The sampling rule.
    pub rule: Text,
    /// The hold period T_s.
    pub period: Quantity,
    /// When σ_k reaches its band (implicit: entry into |σ_k| ≤ T_s κ2 (κ5) for good; explicit:
    /// first crossing of 0) — not t_reach, the Filippov time.
    pub reach: Maybe,
    /// max |σ_k| after reaching.
    pub sigma_after_max: Maybe,
    /// max |g(t_k) − ĝ_k| over the chatter window (named in the label).
    pub gtilde_max: Quantity,
    /// max |ĝ_{k+1} − ĝ_k| over the chatter window.
    pub ghat_jump_max: Quantity,
    /// max |τ_{k+1} − τ_k| over the chatter window.
    pub tau_jump_max: Quantity,
}

/// The evidence of the `finite-time-1` / `finite-time-2` rows.
#[derive(Debug, Clone, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct FiniteTimeEvidence {
    /// σ(0) of the channel.
    pub sigma0: Quantity,
    /// ζ = sup_t |g| (tight).
    pub zeta: Quantity,
    /// The switching gain κ2 or κ5.
    pub kappa_switching: Quantity,
    /// The theorem's hypothesis κ2 ≥ ζ1 (κ5 ≥ ζ2).
    pub hypothesis_holds: Flag,
    /// The bound t_f of (38)/(39) as read.
    pub bound_s: Quantity,
    /// The bound with the exponents read literally.
    pub bound_literal_s: Quantity,
    /// The Filippov reaching time t_reach with its error.
    pub measured_s: Maybe,
    /// How it was integrated.
    pub filippov_method: Text,
    /// σ reaches 0 and stays (reached and the hypothesis holds).
    pub stays_at_zero_filippov: Flag,
    /// sup |ġ|.
    pub gdot_sup: Quantity,
    /// Horizon of the digital runs.
    pub run_t_end_s: Quantity,
    /// Length of the chatter window at the end of each digital run, over which the runs' max
    /// |g̃|, |Δĝ|, |Δτ| are taken.
    pub chatter_window_s: Quantity,
    /// Filippov time / bound for g ≡ κ2 sign σ0 (κ5) (1: the bound is sharp).
    pub sharp_ratio: Maybe,
    /// Worst Filippov time / bound over the σ(0) sweep.
    pub sweep_max_ratio: Maybe,
    /// The digital runs.
    pub digital: Table<DigitalRecord>,
    /// The implicit observer stays in |σ_k| ≤ T_s ζ after reaching, at every T_s.
    pub implicit_stays_in_band: Flag,
    /// max over T_s of (implicit reach − Filippov time).
    pub implicit_reach_excess_max_s: Quantity,
    /// The channel (context, not serialised).
    #[serde(skip)]
    pub channel: Channel,
    /// The reference hold period of the words (context, not serialised).
    #[serde(skip)]
    pub reference_period: f64,
}

/// The digital runs of the channel as records, whether the implicit rule stays in its band at
/// every hold period, and the largest delay of its reaching time behind the Filippov time.
fn digital_records(c: &Computed, window_s: f64) -> (Vec<DigitalRecord>, bool, (f64, f64)) {
    let ix = channel_index(c.channel);
    let n = ix + 1;
    let u = channel_unit(c.channel);
    let window = chatter_window(c.run_t_end, window_s);
    let not_reached = |label: &str| Text::text(label, crate::NOT_REACHED);
    let covers = [ErrorSource::Grid, ErrorSource::TimeStep, ErrorSource::RoundOff];
    let sim = |label: String, v: f64, e: f64| Quantity::with_error(label, v, e, u, &covers);
    let mut stays_band = true;
    let mut excess: (f64, f64) = (0.0, 0.0);
    let mut digital = Vec::new();
    for (r, errors) in c.runs.iter().zip(c.run_errors.iter()) {
        let ch = &r.channels[ix];
        let e = &errors[ix];
        digital.push(DigitalRecord {
            rule: Text::text("sampling rule", r.rule.name()),
            period: Quantity::exact("hold period T_s", r.period, Unit::Second),
            reach: Maybe::of(
                ch.reach_s
                    .map(|t| Quantity::with_error(DIGITAL_REACH, t, e.reach_s.unwrap_or(t), Unit::Second, &covers)),
                || not_reached(DIGITAL_REACH),
            ),
            sigma_after_max: Maybe::of(
                ch.reach_s.map(|_| sim("max |σ_k| after reaching".into(), ch.sigma_after_max, e.sigma_after_max)),
                || not_reached("max |σ_k| after reaching"),
            ),
            gtilde_max: sim(format!("max |g̃{n}| over {window}"), ch.gtilde_max, e.gtilde_max),
            ghat_jump_max: sim(format!("max |Δĝ{n}| per sample over {window}"), ch.ghat_jump_max, e.ghat_jump_max),
            tau_jump_max: sim(format!("max |Δτ{n}| per sample over {window}"), ch.tau_jump_max, e.tau_jump_max),
        });
        if r.rule == ObserverRule::Implicit {
            stays_band &= ch.reach_s.is_some() && ch.sigma_after_max <= r.period * c.zeta * (1.0 + 1e-9) + 1e-15;
            // the delay and its error: the band entry's and the Filippov time's
            let delay = ch.reach_s.unwrap_or(c.run_t_end) - c.fil.reach_s.unwrap_or(0.0);
            if delay >= excess.0 {
                excess = (delay, e.reach_s.unwrap_or(0.0) + c.fil.error_s);
            }
        }
    }
    (digital, stays_band, excess)
}

/// What the digital runs' band entry is called (not t_reach: that is the Filippov time).
const DIGITAL_REACH: &str = "σ_k reaches its band (digital)";

/// The chatter window [t_end − window, t_end] of the digital runs, in words.
pub(super) fn chatter_window(run_t_end: f64, window_s: f64) -> String {
    let v = wingcheck_model::format::exact;
    format!("t ∈ [{}, {}] s", v(((run_t_end - window_s) * 1e9).round() / 1e9), v(run_t_end))
}

fn evidence_of(c: &Computed, settings: &CheckSettings) -> FiniteTimeEvidence {
    let ix = channel_index(c.channel);
    let n = ix + 1;
    let u = channel_unit(c.channel);
    let rate = if ix == 0 { Unit::NewtonPerSecond } else { Unit::NewtonMetrePerSecond };
    let s = |label: String, v: f64| Quantity::based(label, v, Unit::Second, ValueBasis::ClosedForm);
    let (digital, stays_band, excess) = digital_records(c, settings.chatter_window_s);
    let sweep_max = c.sweep.iter().try_fold(0.0f64, |m, (_, r)| r.map(|r| m.max(r)));
    let ratio = |label: &str, v: Option<f64>| {
        Maybe::of(v.map(|r| Quantity::based(label, r, Unit::Dimensionless, ValueBasis::Derived)), || {
            Text::text(label, "not reached within 60 s")
        })
    };
    let hypothesis = c.gain.switching >= c.zeta;
    FiniteTimeEvidence {
        sigma0: Quantity::based(format!("σ{n}(0) from the initial state"), c.sigma0, u, ValueBasis::ClosedForm),
        zeta: Quantity::based(format!("ζ{n} = sup |g{n}|"), c.zeta, u, ValueBasis::ClosedForm),
        kappa_switching: Quantity::configured(format!("switching gain {}", kappa_sw(ix)), c.gain.switching, u),
        hypothesis_holds: Flag::new(format!("hypothesis {} ≥ ζ{n} holds", kappa_sw(ix)), hypothesis),
        bound_s: s(format!("bound t_f{n} of ({}) as read", if ix == 0 { 38 } else { 39 }), c.bound),
        bound_literal_s: s("bound with the exponents read literally".into(), c.bound_literal),
        measured_s: Maybe::of(
            c.fil.reach_s.map(|t| {
                Quantity::with_error(
                    "Filippov reaching time t_reach",
                    t,
                    c.fil.error_s,
                    Unit::Second,
                    &[ErrorSource::TimeStep],
                )
            }),
            || Text::text("Filippov reaching time t_reach", "not reached within 60 s"),
        ),
        filippov_method: Text::text("Filippov integration", c.fil.method),
        stays_at_zero_filippov: Flag::new(
            "σ stays at 0 after reaching (Filippov)",
            c.fil.reach_s.is_some() && hypothesis,
        ),
        gdot_sup: Quantity::based(format!("sup |ġ{n}|"), (c.g.amp * c.g.freq).abs(), rate, ValueBasis::ClosedForm),
        run_t_end_s: Quantity::exact("horizon of the digital runs", c.run_t_end, Unit::Second),
        chatter_window_s: Quantity::exact(
            "chatter window (the end of each digital run)",
            settings.chatter_window_s,
            Unit::Second,
        ),
        sharp_ratio: ratio(&format!("t_reach / t_f{n} for g{n} ≡ {} sign σ{n}(0)", kappa_sw(ix)), c.sharp_ratio),
        sweep_max_ratio: ratio(&format!("worst t_reach / t_f{n} over σ{n}(0) ∈ ±[10⁻³, 10²]"), sweep_max),
        digital: Table::new("digital observer runs", digital),
        implicit_stays_in_band: Flag::new(
            "the implicit rule stays in |σ_k| ≤ T_s ζ after reaching, every T_s",
            stays_band,
        ),
        implicit_reach_excess_max_s: Quantity::with_error(
            "max over T_s of (implicit band entry − t_reach)",
            excess.0,
            excess.1,
            Unit::Second,
            &[ErrorSource::Grid, ErrorSource::TimeStep, ErrorSource::RoundOff],
        ),
        channel: c.channel,
        reference_period: reference_period(settings),
    }
}

impl FiniteTimeEvidence {
    /// The Filippov time is within the bound (plus its error estimate).
    fn within_bound(&self) -> bool {
        let b = self.bound_s.value;
        self.measured_s.quantity().is_some_and(|m| m.value <= b + m.error().unwrap_or(0.0) + 1e-12 * b.max(1.0))
    }

    fn sweep_ok(&self) -> bool {
        self.sweep_max_ratio.quantity().is_some_and(|q| q.value <= 1.0 + 1e-6)
    }

    fn run(&self, rule: ObserverRule) -> Option<&DigitalRecord> {
        self.digital.rows.iter().find(|r| r.rule.value == rule.name() && r.period.value == self.reference_period)
    }

    fn n(&self) -> usize {
        channel_index(self.channel) + 1
    }
}

impl Explain for FiniteTimeEvidence {
    /// Hypothesis κ2 ≥ ζ1 (κ5 ≥ ζ2) fails → inconclusive (the theorem does not apply); the Filippov time
    /// exceeds the bound, or some σ(0) of the sweep does → fails; σ(0) = 0 → trivially true;
    /// else holds. Basis: simulation.
    fn verdict(&self) -> (Verdict, Basis) {
        let v = if !self.hypothesis_holds.value {
            Verdict::Inconclusive
        } else if !self.within_bound() || !self.sweep_ok() {
            Verdict::Fails
        } else if self.sigma0.value == 0.0 {
            Verdict::TriviallyTrue
        } else {
            Verdict::Holds
        };
        (v, Basis::Simulation)
    }

    fn finding(&self) -> Vec<String> {
        let n = self.n();
        let sweep = self.sweep_max_ratio.text();
        let mut f = Vec::new();
        if !self.hypothesis_holds.value {
            f.push(format!(
                "The hypothesis fails: {} = {} < ζ{n} = {}, so the theorem promises nothing here.",
                kappa_sw(n - 1),
                self.kappa_switching.value_text(),
                self.zeta.value_text()
            ));
        }
        if self.sigma0.value == 0.0 {
            f.push(format!("σ{n}(0) = 0, so the bound t_f{n} is 0 s and nothing is tested at the configured state."));
        } else {
            f.push(format!(
                "The Filippov reaching time t_reach = {} is {} the bound t_f{n} = {}.",
                self.measured_s.text(),
                if self.within_bound() { "within" } else { "NOT within" },
                self.bound_s.value_text()
            ));
        }
        f.push(format!("Over a sweep of σ{n}(0) the worst t_reach/t_f{n} is {sweep}."));
        if let (Some(i), Some(e)) = (self.run(ObserverRule::Implicit), self.run(ObserverRule::Explicit)) {
            f.push(format!(
                "At T_s = {} the implicit observer {} (max |g̃{n}| over {} = {}); the explicit one chatters (max |g̃{n}| over the same window = {}).",
                i.period.value_text(),
                if self.implicit_stays_in_band.value { "reaches and stays" } else { "does not stay in its band" },
                chatter_window(self.run_t_end_s.value, self.chatter_window_s.value),
                i.gtilde_max.value_text(),
                e.gtilde_max.value_text()
            ));
        }
        f.truncate(3);
        f
    }

    fn decisive(&self) -> Vec<Quantity> {
        let mut out = vec![self.bound_s.clone()];
        out.extend(self.measured_s.quantity().cloned());
        out.extend(self.sweep_max_ratio.quantity().cloned());
        if let Some(e) = self.run(ObserverRule::Explicit) {
            out.push(e.gtilde_max.clone().relabel(format!(
                "{}, explicit rule, T_s = {}",
                e.gtilde_max.label,
                e.period.value_text()
            )));
        }
        out
    }

    fn deciding(&self) -> String {
        let n = self.n();
        let bound = self.bound_s.value_text();
        if !self.hypothesis_holds.value {
            return format!(
                "{} = {} < ζ{n} = {}: the theorem does not apply",
                kappa_sw(n - 1),
                self.kappa_switching.value_text(),
                self.zeta.value_text()
            );
        }
        match self.measured_s.quantity() {
            None => format!("σ{n} does not reach 0 within 60 s; t_f{n} = {bound}"),
            Some(m) if !self.within_bound() => format!("t_reach = {} > t_f{n} = {bound}", m.value_text()),
            Some(_) if !self.sweep_ok() => {
                format!("worst t_reach/t_f{n} over σ{n}(0) = {} > 1", self.sweep_max_ratio.text())
            }
            Some(_) if self.sigma0.value == 0.0 => format!("σ{n}(0) = 0, so t_f{n} = {bound}: nothing is tested"),
            Some(m) => format!("t_reach = {} ≤ t_f{n} = {bound}", m.value_text()),
        }
    }

    fn details(&self) -> Vec<String> {
        let n = self.n();
        let mut d = vec![format!(
            "ζ{n} = {} against {} = {}; sup |ġ{n}| = {}.",
            self.zeta.value_text(),
            kappa_sw(n - 1),
            self.kappa_switching.value_text(),
            self.gdot_sup.value_text()
        )];
        d.push(match self.sharp_ratio.quantity() {
            Some(q) if (q.value - 1.0).abs() <= 1e-6 => {
                format!(
                    "The bound is sharp: for g{n} ≡ {} sign σ{n}(0) t_reach/t_f{n} = {}.",
                    kappa_sw(n - 1),
                    wingcheck_model::quantity::format_value(q.value, Some(1e-9))
                )
            }
            Some(q) => {
                format!("For g{n} ≡ {} sign σ{n}(0) t_reach/t_f{n} = {} (not sharp).", kappa_sw(n - 1), q.value_text())
            }
            None => format!("For g{n} ≡ {} sign σ{n}(0) σ{n} does not reach 0 within 60 s.", kappa_sw(n - 1)),
        });
        d.push(format!(
            "The implicit rule enters its band at most {} after t_reach; the theorem promises g̃{n} = σ̇{n} = 0 after t_f{n} in continuous time, which a digital observer gets only to O(T_s) and only with the implicit rule.",
            self.implicit_reach_excess_max_s.value_text()
        ));
        d.push(format!(
            "The literal reading Q(0)^(a2 − a1/a2) of the exponents in ({}) (Q = σ{n}²/2) would give {}.",
            if n == 1 { 38 } else { 39 },
            self.bound_literal_s.value_text()
        ));
        d
    }
}

/// Check the finite-time claim of one channel ((38) with Theorem 3, or (39) with Theorem 4).
pub fn check(cfg: &Config, channel: Channel, settings: &CheckSettings) -> Result<ClaimRow, ClaimsError> {
    check_with(cfg, channel, settings, &super::digital_runs(cfg, settings)?)
}

/// [`check`] reading the digital `runs` ([`super::digital_runs`] of the same `cfg` and
/// `settings`), which the ledger computes once for both rows.
pub fn check_with(
    cfg: &Config,
    channel: Channel,
    settings: &CheckSettings,
    runs: &super::DigitalRuns,
) -> Result<ClaimRow, ClaimsError> {
    let c = compute(cfg, channel, settings, runs)?;
    let reference = reference_period(settings);
    if c.run(ObserverRule::Implicit, reference).is_none() || c.run(ObserverRule::Explicit, reference).is_none() {
        return Err(super::reach::num_err("finite_time", NumericsError::MissingReferenceRuns));
    }
    let e = evidence_of(&c, settings);
    let n = channel_index(channel) + 1;
    let id = if n == 1 { ClaimId::FiniteTime1 } else { ClaimId::FiniteTime2 };
    let assumptions = vec![
        format!("ζ{n} = sup over t ≥ 0 of |g{n}| = |mean| + |amplitude| = {} (tight: the sine reaches ±1)", e.zeta.value_text()),
        "exponents read as Q0^((a2−a1)/a2), 2^(a1/a2 − 1), σ^((2a1−a2)/a2) = sig^r(σ)".into(),
        "continuous-time claim checked in the Filippov sense (σ slides on 0; ĝ takes the equivalent value g)".into(),
        format!(
            "digital runs: FTDO, hold periods T_s ∈ {{{}}} s, integrator step T_s/⌈T_s/dt⌉ with the configured dt, horizon {}, chatter window the last {}",
            settings.hold_periods.map(wingcheck_model::format::exact).join(", "),
            e.run_t_end_s.value_text(),
            e.chatter_window_s.value_text()
        ),
        "σ(0) from the configured initial state and ν(0) (q'''(s,0), θ'(s,0) of the initial shape)".into(),
    ];
    let plots = plots(&c, settings);
    Ok(ClaimRow::decided(id, e, assumptions, plots))
}
