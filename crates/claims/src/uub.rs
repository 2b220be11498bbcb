//! The `UUB` row, Theorem 2, (33)–(37): uniform ultimate boundedness and the bound
//! |q(z,t)| ≤ √(s³/λ2 · (W(0)e^{−λt} + ε/λ)), |θ(z,t)| ≤ √(s/λ2 · (W(0)e^{−λt} + ε/λ)).
//!
//! The bound needs λ2 > 0 (W-bounds) and μ1…μ6 > 0 (mu-conditions). Where the configured
//! weights violate them the bound is evaluated at the μ row's fallback point (a/b = r*/2, same
//! b), with the tight λ2 there, and compared with the simulated envelope max_z |q(z,t)|,
//! max_z |θ(z,t)| of the FTDO closed loop at the same gains. (36) prints κ ≤ W/λ; the chain
//! needs κ ≤ W/λ2 — used here. W(0) is finite only for a clamp-compatible initial shape: it is
//! computed on three uniform meshes and called divergent when it keeps growing (the linear
//! shape z/s has q'(0) ≠ 0, so ∫q''² = ∞ and W(0) grows like 1/h). The Galerkin λ2 (≥ λ2*)
//! and λ (≥ the true λ, its λ1 being a lower bound of sup W/κ) both make the evaluated bound a
//! lower bound of the theorem's bound with the exact constants: it errs on the optimistic side.

use crate::numerics::NumericsError;
use wingcheck_model::{Config, ControllerKind, Quantity, Unit, ValueBasis};
use wingcheck_sim::metrics::{max_abs_in, window_indices, Window};
use wingcheck_sim::Discretisation;

use crate::display::{ratio_of, Flag, Table};
use crate::explain::Explain;
use crate::mu::MuResult;
use crate::settings::CheckSettings;
use crate::study::Study;
use crate::wbounds::{num, WBounds};
use crate::{Basis, ClaimId, ClaimRow, ClaimsError, Line, PlotData, Verdict};
use wingcheck_theory::lyapunov::{assemble, decimal, tight_constants, Coupling, LyapunovParams};
use wingcheck_theory::uub::UubBound;
use wingcheck_theory::Decision;

/// W(0) for zero initial velocity: b × the elastic energy of the discretised initial shape,
/// on a uniform FE mesh of `elements` elements.
pub fn w_initial(cfg: &Config, b: f64, elements: usize) -> f64 {
    let mut c = cfg.clone();
    c.discretisation.grading = 0.0;
    let d = Discretisation::with(&c, wingcheck_model::Method::Fe, elements);
    b * 0.5 * d.stiffness.form(&d.x0, &d.x0)
}

/// W(0) on one mesh.
#[derive(Debug, Clone, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct W0Record {
    /// Uniform FE elements.
    pub elements: Quantity,
    /// W(0) there.
    pub w0: Quantity,
}

impl W0Record {
    fn of(&(n, v): &(usize, f64)) -> W0Record {
        W0Record {
            elements: Quantity::count("uniform FE elements", n),
            w0: Quantity::based("W(0)", v, Unit::JouleSecond, ValueBasis::ClosedForm),
        }
    }
}

/// The evidence of the `UUB` row (present when a point satisfying (32) exists).
#[derive(Debug, Clone, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct UubEvidence {
    /// λ2 > 0 and (32) hold at the configured gains.
    pub hypotheses_hold_at_config: Flag,
    /// a of the point where the bound is evaluated.
    pub evaluated_at_a: Quantity,
    /// b there.
    pub evaluated_at_b: Quantity,
    /// λ at the ε/λ-optimal η's there.
    pub lambda: Quantity,
    /// 1/λ.
    pub decay_time_constant_s: Quantity,
    /// ε of (32).
    pub epsilon: Quantity,
    /// Tight λ2 at the evaluation point.
    pub lambda2_tight: Quantity,
    /// W(0) per mesh.
    pub w0_by_elements: Table<W0Record>,
    /// W(0) keeps growing under refinement (W(0) = ∞ for the PDE).
    pub w0_diverges: Flag,
    /// √(s³/λ2 · ε/λ).
    pub ultimate_bound_q_m: Quantity,
    /// The bound (37) on |q| at t_end with the coarsest mesh's W(0).
    pub bound_q_at_t_end_m: Quantity,
    /// Simulated max_z |q| over [t_end/2, t_end] at the evaluation point.
    pub measured_max_abs_q_second_half_m: Quantity,
    /// bound at t_end / simulated envelope there, for q (absent if the envelope is 0).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ratio_bound_over_measured_q: Option<Quantity>,
    /// The same for θ.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ratio_bound_over_measured_theta: Option<Quantity>,
    /// Ratio above which a bound that holds is called vacuous.
    pub vacuity_ratio: Quantity,
    /// The simulated envelope exceeds the bound somewhere.
    pub bound_violated: Flag,
    /// Output grid points in z used for the envelope.
    pub field_points: Quantity,
    /// W(0) of the simulated run at the evaluation point (its discretised initial state).
    pub w0_of_run: Quantity,
    /// max over the run's samples of W(t)/(W(0)e^{−λt} + ε/λ), the simulated W against (35)
    /// (> 1: W exceeds the bound evaluated with the optimistic λ).
    pub max_w_over_bound35: Quantity,
    /// At the configured gains: max |q(s,t)| over the second half.
    pub config_max_abs_q_tip_second_half_m: Quantity,
    /// max |θ(s,t)| there.
    pub config_max_abs_theta_tip_second_half_rad: Quantity,
}

impl Explain for UubEvidence {
    /// Violated somewhere → fails (simulation); W(0) = ∞ → vacuous (analytic); a bound more
    /// than the vacuity ratio above the envelope → vacuous; else holds (simulation).
    fn verdict(&self) -> (Verdict, Basis) {
        let ratio = [&self.ratio_bound_over_measured_q, &self.ratio_bound_over_measured_theta]
            .iter()
            .filter_map(|r| r.as_ref().map(|q| q.value))
            .reduce(f64::min);
        if self.bound_violated.value {
            (Verdict::Fails, Basis::Simulation)
        } else if self.w0_diverges.value {
            (Verdict::Vacuous, Basis::Analytic)
        } else if ratio.is_none_or(|r| r > self.vacuity_ratio.value) {
            (Verdict::Vacuous, Basis::Simulation)
        } else {
            (Verdict::Holds, Basis::Simulation)
        }
    }

    fn finding(&self) -> Vec<String> {
        let at = format!("a = {}, b = {}", self.evaluated_at_a.value_text(), self.evaluated_at_b.value_text());
        let mut f = vec![if self.hypotheses_hold_at_config.value {
            format!("The hypotheses (λ2 > 0, μ1…μ6 > 0) hold at the configured gains ({at}).")
        } else {
            format!("The hypotheses (λ2 > 0, μ1…μ6 > 0) fail at the configured gains, so the bound is evaluated where they hold: {at}.")
        }];
        if self.w0_diverges.value {
            f.push("W(0) grows without bound under refinement (the initial shape violates the clamp's q'(0) = 0), so the bound (37) is infinite.".into());
        }
        f.push(if self.bound_violated.value {
            "The simulated envelope exceeds the bound: the bound is violated.".to_string()
        } else {
            match &self.ratio_bound_over_measured_q {
                Some(r) => format!(
                    "{}the bound at t_end is {} × the simulated envelope there.",
                    if self.w0_diverges.value { "Even with the coarsest mesh's W(0), " } else { "There " },
                    r.value_text()
                ),
                None => "The simulated envelope is 0, so the bound's sharpness cannot be measured.".into(),
            }
        });
        f
    }

    fn decisive(&self) -> Vec<Quantity> {
        let mut out = vec![self.bound_q_at_t_end_m.clone(), self.measured_max_abs_q_second_half_m.clone()];
        out.extend(self.ratio_bound_over_measured_q.iter().cloned());
        out.push(self.decay_time_constant_s.clone());
        out
    }

    fn deciding(&self) -> String {
        if self.bound_violated.value {
            return "the simulated envelope exceeds the bound (37)".into();
        }
        let ratio = self.ratio_bound_over_measured_q.as_ref().map(Quantity::value_text);
        match (self.w0_diverges.value, ratio) {
            (true, _) => "W(0) → ∞ under refinement: the bound (37) is infinite".into(),
            (false, Some(r)) => format!("bound (37) / simulated |q| at t_end = {r}"),
            (false, None) => "the simulated envelope is 0: the bound's sharpness is not measured".into(),
        }
    }

    fn details(&self) -> Vec<String> {
        let w0: Vec<String> = self
            .w0_by_elements
            .rows
            .iter()
            .map(|r| format!("{} on {} elements", r.w0.value_text(), r.elements.value_text()))
            .collect();
        vec![
            format!("W(0) is {}.", w0.join(", ")),
            format!(
                "At the evaluation point λ = {} (a decay time of {}), ε = {}, λ2 = {}; the ultimate bound √(s³ε/(λ2λ)) is {}.",
                self.lambda.value_text(),
                self.decay_time_constant_s.value_text(),
                self.epsilon.value_text(),
                self.lambda2_tight.value_text(),
                self.ultimate_bound_q_m.value_text()
            ),
            format!(
                "Along the simulated run W(t) = b·E(t) + a·⟨x, Mv⟩ starts at W(0) = {} and reaches at most {} × the bound (35) W(0)e^(−λt) + ε/λ{}.",
                self.w0_of_run.value_text(),
                self.max_w_over_bound35.value_text(),
                if self.max_w_over_bound35.value > 1.0 {
                    " (above 1: the simulated W exceeds (35) as evaluated with the optimistic λ)"
                } else {
                    ""
                }
            ),
            format!(
                "In simulation at the configured gains the tip stays bounded: max |q(s,t)| = {}, max |θ(s,t)| = {} over [t_end/2, t_end].",
                self.config_max_abs_q_tip_second_half_m.value_text(),
                self.config_max_abs_theta_tip_second_half_rad.value_text()
            ),
        ]
    }

    fn correction(&self) -> Option<String> {
        Some(format!(
            "(36): κ ≤ W/λ2 (not W/λ); the bound needs the hypotheses of (32){}",
            if self.w0_diverges.value { " and a clamp-compatible initial shape (W(0) < ∞)" } else { "" }
        ))
    }
}

/// Why the bound cannot be evaluated (no point satisfies (32)).
fn no_operating_point(cfg: &Config, m: &MuResult) -> ClaimRow {
    let why = match m.computed.obstruction {
        Some(o)
            if m.computed.r_star <= 0.0 || cfg.control.k1 <= 0.0 || cfg.control.k2 <= 0.0 || cfg.control.b <= 0.0 =>
        {
            format!(
                "{}; no operating point satisfies (32), so Theorem 2's decay rate λ and the bound do not exist.",
                o.text()
            )
        }
        _ => "No operating point satisfies (32), so the bound cannot be evaluated.".into(),
    };
    let mut row = ClaimRow::inconclusive(ClaimId::Uub, Basis::Analytic, why);
    row.assumptions.push("config keys involved: control.a, control.b, control.k1, control.k2, wing.xi".into());
    row
}

/// The FTDO run at the operating point (a, b) whose envelope the bound is compared with.
pub fn operating_run(cfg: &Config, a: f64, b: f64) -> Config {
    let mut c = cfg.clone();
    c.control.a = a;
    c.control.b = b;
    c.control.kind = ControllerKind::Ftdo;
    c
}

/// The facts of the bound at the operating point, before they are put into words.
struct Computed {
    /// The operating point (configured gains, or the mu row's fallback).
    best: wingcheck_theory::BestPoint,
    /// λ2 on the Galerkin space at the operating point.
    lambda2: f64,
    /// (elements, W(0)) per mesh.
    w0s: [(usize, f64); 3],
    /// The bound (37) with the coarsest mesh's W(0).
    bound: UubBound,
    /// Sample times (s), the simulated envelopes max_z |q|, max_z |θ| and the bounds there.
    t: Vec<f64>,
    env: [Vec<f64>; 2],
    bounds: [Vec<f64>; 2],
    /// Output grid points in z of the envelope.
    field_points: usize,
    /// max |q(s,t)|, |θ(s,t)| over [t_end/2, t_end] at the configured gains.
    config_tail: [f64; 2],
    /// W(t) = b·E(t) + a·⟨x, Mv⟩ of the operating run at its samples (J s), and b·E(t).
    lyapunov: LyapunovAlongRun,
}

/// The Lyapunov function along the operating run: W(t) of (22)–(23) (with the kinetic-energy
/// coupling ρx_c) evaluated on the run's discretised state, W = b·E + a·⟨x, Mv⟩, against the
/// bound (35) W(0)e^{−λt} + ε/λ with the run's own W(0).
struct LyapunovAlongRun {
    /// W(t_k) (J s).
    w: Vec<f64>,
    /// b·E(t_k), the part of W without the a-weighted cross term (J s).
    b_energy: Vec<f64>,
    /// The bound (35) at t_k with W(0) = w[0] (J s).
    bound: Vec<f64>,
    /// max_k W(t_k)/bound(t_k).
    max_ratio: f64,
}

impl LyapunovAlongRun {
    fn of(series: &wingcheck_sim::Series, bound: &UubBound, a: f64, b: f64) -> LyapunovAlongRun {
        let w: Vec<f64> =
            series.energy.iter().zip(&series.displacement_momentum).map(|(e, xmv)| b * e + a * xmv).collect();
        let run_bound = UubBound { w0: w.first().copied().unwrap_or(0.0), ..*bound };
        let bound: Vec<f64> = series.t.iter().map(|&t| run_bound.lyapunov(t)).collect();
        let max_ratio = w.iter().zip(&bound).map(|(w, c)| w / c).fold(0.0, f64::max);
        LyapunovAlongRun { b_energy: series.energy.iter().map(|e| b * e).collect(), w, bound, max_ratio }
    }
}

/// λ2 at the operating point, the W(0) study, the simulated envelope and the bound.
fn compute(
    cfg: &Config,
    best: wingcheck_theory::BestPoint,
    lambda2: f64,
    study: &Study,
    settings: &CheckSettings,
) -> Result<Computed, ClaimsError> {
    let out = study.simulate(&operating_run(cfg, best.a, best.b))?;
    let fields = out.fields.as_ref().ok_or_else(|| num("the UUB envelope")(NumericsError::NoFields))?;
    let envelope = |f: &[Vec<f64>]| f.iter().map(|r| r.iter().fold(0.0f64, |a, v| a.max(v.abs()))).collect::<Vec<_>>();
    let w0s = settings.uub_w0_elements.map(|n| (n, w_initial(cfg, best.b, n)));
    let bound = UubBound { span: cfg.wing.span, lambda2, lambda: best.lambda, epsilon: best.epsilon, w0: w0s[0].1 };
    let t = out.series.t.clone();
    let lyapunov = LyapunovAlongRun::of(&out.series, &bound, best.a, best.b);
    let bounds = [t.iter().map(|&tt| bound.q(tt)).collect(), t.iter().map(|&tt| bound.theta(tt)).collect()];
    let here = study.simulate(cfg)?;
    let late = Window::second_half(cfg.horizon.t_end);
    let tail = |v: &[f64]| wingcheck_sim::metrics::max_abs(&v[window_indices(&here.series.t, late)]).unwrap_or(0.0);
    Ok(Computed {
        best,
        lambda2,
        w0s,
        bound,
        env: [envelope(&fields.q), envelope(&fields.theta)],
        bounds,
        t,
        field_points: fields.z.len(),
        config_tail: [tail(&here.series.q_tip), tail(&here.series.theta_tip)],
        lyapunov,
    })
}

/// Where the row's numbers are evaluated, as their labels say it: the configured point, or the
/// feasible point the row moves to when the hypotheses fail there.
fn evaluated_at(a: f64, b: f64, configured: bool) -> String {
    // the configured values as typed; the feasible a (r*·b/2, computed) to 4 digits
    let (exact, fmt) = (wingcheck_model::format::exact, |v: f64| wingcheck_model::quantity::format_value(v, None));
    if configured {
        format!("at the configured a = {}, b = {} s", exact(a), exact(b))
    } else {
        format!("at the feasible a = {}, b = {} s (not the configured point)", fmt(a), exact(b))
    }
}

/// W(0) and max W/bound (35) along the run at the evaluated point, and the configured run's
/// late tip maxima.
fn run_quantities(c: &Computed, at: &str) -> [Quantity; 4] {
    let sim = |label: String, v: f64, unit: Unit| Quantity::based(label, v, unit, ValueBasis::Simulation);
    [
        sim(
            format!("W(0) of the simulated run {at} (its grid, zero initial velocity)"),
            c.lyapunov.w.first().copied().unwrap_or(0.0),
            Unit::JouleSecond,
        ),
        Quantity::based(
            format!("max over t of simulated W(t) / bound (35) {at}"),
            c.lyapunov.max_ratio,
            Unit::Dimensionless,
            ValueBasis::Simulation,
        ),
        sim("max |q(s,t)| over [t_end/2, t_end] at the configured gains".into(), c.config_tail[0], Unit::Metre),
        sim("max |θ(s,t)| over [t_end/2, t_end] at the configured gains".into(), c.config_tail[1], Unit::Radian),
    ]
}

fn evidence_of(c: &Computed, hypotheses_here: bool, cfg: &Config, settings: &CheckSettings) -> UubEvidence {
    let (best, n2) = (&c.best, settings.uub_lambda2_elements);
    let at = evaluated_at(best.a, best.b, hypotheses_here);
    let lower = |label: String, v: f64| Quantity::based(label, v, Unit::Metre, ValueBasis::LowerBound);
    let sim = |label: String, v: f64, unit: Unit| Quantity::based(label, v, unit, ValueBasis::Simulation);
    let based = |label: String, v: f64, unit: Unit, basis: ValueBasis| Quantity::based(label, v, unit, basis);
    let late = Window::second_half(cfg.horizon.t_end);
    let tail = |v: &[f64]| max_abs_in(&c.t, v, late).unwrap_or(0.0);
    let [bq, bt] = [c.bounds[0].last().copied().unwrap_or(0.0), c.bounds[1].last().copied().unwrap_or(0.0)];
    let violated = (0..2).any(|k| c.env[k].iter().zip(&c.bounds[k]).any(|(e, b)| e > b));
    let [w0_of_run, max_w_over_bound35, config_max_abs_q_tip_second_half_m, config_max_abs_theta_tip_second_half_rad] =
        run_quantities(c, &at);
    UubEvidence {
        hypotheses_hold_at_config: Flag::new("λ2 > 0 and (32) hold at the configured gains", hypotheses_here),
        evaluated_at_a: based(
            "a where the bound is evaluated".into(),
            best.a,
            Unit::Dimensionless,
            ValueBasis::ClosedForm,
        ),
        evaluated_at_b: Quantity::configured("b where the bound is evaluated", best.b, Unit::Second),
        lambda: based(format!("decay rate λ {at} (optimistic)"), best.lambda, Unit::PerSecond, ValueBasis::UpperBound),
        decay_time_constant_s: based(
            format!("decay time 1/λ {at}"),
            1.0 / best.lambda,
            Unit::Second,
            ValueBasis::LowerBound,
        ),
        epsilon: based(format!("ε of (32) {at}"), best.epsilon, Unit::Joule, ValueBasis::ClosedForm),
        lambda2_tight: based(
            format!("λ2({n2}) = min W/κ {at} (≥ λ2*)"),
            c.lambda2,
            Unit::JouleSecond,
            ValueBasis::UpperBound,
        ),
        w0_by_elements: Table::new("W(0) under refinement", c.w0s.iter().map(W0Record::of).collect()),
        w0_diverges: Flag::new(
            "W(0) keeps growing under refinement",
            c.w0s[2].1 > settings.uub_w0_divergence_ratio * c.w0s[1].1,
        ),
        ultimate_bound_q_m: lower(format!("ultimate bound √(s³ε/(λ2λ)) on |q| {at}"), c.bound.ultimate_q()),
        bound_q_at_t_end_m: lower(format!("bound (37) on |q| at t_end {at}, W(0) on {} elements", c.w0s[0].0), bq),
        measured_max_abs_q_second_half_m: sim(
            format!("simulated max over z of |q| in [t_end/2, t_end] {at}"),
            tail(&c.env[0]),
            Unit::Metre,
        ),
        ratio_bound_over_measured_q: ratio_of(
            format!("bound / simulated envelope of q at t_end {at}"),
            bq,
            tail(&c.env[0]),
            ValueBasis::Derived,
        ),
        ratio_bound_over_measured_theta: ratio_of(
            format!("bound / simulated envelope of θ at t_end {at}"),
            bt,
            tail(&c.env[1]),
            ValueBasis::Derived,
        ),
        vacuity_ratio: Quantity::exact(
            "ratio above which a bound that holds is called vacuous",
            settings.vacuity_ratio,
            Unit::Dimensionless,
        ),
        bound_violated: Flag::new("the simulated envelope exceeds the bound somewhere", violated),
        field_points: Quantity::count("output grid points in z of the envelope", c.field_points),
        w0_of_run,
        max_w_over_bound35,
        config_max_abs_q_tip_second_half_m,
        config_max_abs_theta_tip_second_half_rad,
    }
}

/// W(t) along the run against (35), with b·E(t) on a log axis where it can be told apart from
/// W (the cross term a·⟨x, Mv⟩ at least 1 % of W somewhere; below that the two lines coincide
/// at the plot's scale and only W is drawn, its label saying so).
fn lyapunov_plot(c: &Computed) -> PlotData {
    let stride = (c.t.len() / 400).max(1);
    let pick = |v: &[f64]| v.iter().step_by(stride).copied().collect::<Vec<_>>();
    let l = &c.lyapunov;
    let top = l.w.iter().chain(&l.bound).copied().fold(0.0, f64::max);
    let floor = |v: &[f64]| pick(v).into_iter().map(|x| x.max(1e-12 * top)).collect::<Vec<_>>();
    let fmt = |v: f64| wingcheck_model::quantity::format_value(v, None);
    let cross =
        l.w.iter().zip(&l.b_energy).map(|(w, e)| (w - e).abs() / w.abs().max(f64::MIN_POSITIVE)).fold(0.0, f64::max);
    let apart = cross >= 0.01;
    let mut lines = vec![
        Line { label: "bound (35) W(0)e^(−λt) + ε/λ".into(), x: pick(&c.t), y: floor(&l.bound), points: false },
        Line {
            label: if apart {
                "simulated W(t) = b·E + a·⟨x, Mv⟩".into()
            } else {
                format!(
                    "simulated W(t) = b·E + a·⟨x, Mv⟩ (b·E(t) coincides: a·⟨x, Mv⟩ is at most {} % of W)",
                    fmt(100.0 * cross)
                )
            },
            x: pick(&c.t),
            y: floor(&l.w),
            points: false,
        },
    ];
    if apart {
        lines.push(Line {
            label: "b·E(t) (energy part of W)".into(),
            x: pick(&c.t),
            y: floor(&l.b_energy),
            points: false,
        });
    }
    PlotData {
        name: "uub-lyapunov-vs-bound".into(),
        title: format!(
            "The Lyapunov function W(t) along the run against the bound (35) at a = {}, b = {}; max W/bound {}",
            fmt(c.best.a),
            wingcheck_model::format::exact(c.best.b),
            fmt(l.max_ratio)
        ),
        x_label: "t (s)".into(),
        y_label: "W (J s)".into(),
        log_x: false,
        log_y: true,
        lines,
    }
}

fn plot(c: &Computed, e: &UubEvidence) -> PlotData {
    let stride = (c.t.len() / 400).max(1);
    let pick = |v: &[f64]| v.iter().step_by(stride).copied().collect::<Vec<_>>();
    let fmt = |v: f64| wingcheck_model::quantity::format_value(v, None);
    PlotData {
        name: "uub-bound-vs-envelope".into(),
        title: format!(
            "Theorem 2's bound (37) against the simulated envelope at a = {}, b = {}{}",
            fmt(c.best.a),
            wingcheck_model::format::exact(c.best.b),
            e.ratio_bound_over_measured_q
                .as_ref()
                .map_or(String::new(), |r| format!("; ratio at t_end {}", r.value_text()))
        ),
        x_label: "t (s)".into(),
        y_label: "max over z of |q(z,t)| (m)".into(),
        log_x: false,
        log_y: true,
        lines: vec![
            Line { label: "bound (37)".into(), x: pick(&c.t), y: pick(&c.bounds[0]), points: false },
            Line {
                label: "simulated max over z of |q|".into(),
                x: pick(&c.t),
                y: pick(&c.env[0]).iter().map(|v| v.max(1e-12)).collect(),
                points: false,
            },
        ],
    }
}

/// Check Theorem 2.
pub fn check(
    cfg: &Config,
    w: &WBounds,
    m: &MuResult,
    study: &Study,
    settings: &CheckSettings,
) -> Result<ClaimRow, ClaimsError> {
    let hypotheses_here = w.evidence.w_positive_definite.value == Decision::Yes && m.evidence.satisfiable.value;
    let Some(best) = m.best().copied() else { return Ok(no_operating_point(cfg, m)) };
    let n2 = settings.uub_lambda2_elements;
    let p = LyapunovParams::from_config(cfg, Coupling::Corrected, n2).with_weights(&decimal(best.a), &decimal(best.b));
    let lambda2 = tight_constants(&assemble(&p).map_err(num("assembly"))?).map_err(num("eigen"))?.lambda2;
    let fmt = |v: f64| wingcheck_model::quantity::format_value(v, None);
    if lambda2 <= 0.0 {
        return Ok(ClaimRow::inconclusive(
            ClaimId::Uub,
            Basis::FloatSolver,
            format!(
                "At the operating point a = {}, b = {} W is not positive definite (λ2 = {}), so (37) does not apply.",
                fmt(best.a),
                fmt(best.b),
                fmt(lambda2)
            ),
        ));
    }
    let c = compute(cfg, best, lambda2, study, settings)?;
    let e = evidence_of(&c, hypotheses_here, cfg, settings);
    let at = format!("a = {}, b = {}", fmt(best.a), fmt(best.b));
    let assumptions = vec![
        if m.evidence.best_at_configured.value {
            "operating point: the configured gains (they satisfy (32))".to_string()
        } else {
            format!("operating point {at} = half the closed-form μ boundary (the configured gains do not satisfy (32))")
        },
        format!(
            "W(0) from the discretised initial state (uniform FE meshes of {:?} elements, zero initial velocity)",
            settings.uub_w0_elements
        ),
        format!("simulated envelope: max over the {}-point output grid in z (horizon.field_points)", c.field_points),
        "ζ3, ζ4 from the FTDO run at the configured gains".into(),
        format!("λ2 on {n2} Galerkin elements and λ with λ1 on a Galerkin space: both make the evaluated bound a lower bound of the theorem's bound (optimistic)"),
    ];
    let plots = vec![plot(&c, &e), lyapunov_plot(&c)];
    Ok(ClaimRow::decided(ClaimId::Uub, e, assumptions, plots))
}
