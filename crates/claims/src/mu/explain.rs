//! The mu-conditions row's evidence (labelled quantities), its verdict and its words.

use wingcheck_model::{Config, ErrorSource, Quantity, Unit, ValueBasis};

use super::{compute, Computed};
use crate::display::{Flag, Table, Text};
use crate::explain::Explain;
use crate::settings::CheckSettings;
use crate::study::Study;
use crate::{Basis, ClaimId, ClaimRow, ClaimsError, Line, PlotData, Verdict};
use wingcheck_theory::convex::{check_lambda3, CrossCheck};
use wingcheck_theory::{ratio_boundary, BestPoint, MuData};

/// What the mu-conditions row found, reused by the UUB row.
#[derive(Debug, Clone)]
pub struct MuResult {
    /// The ledger row.
    pub row: ClaimRow,
    /// Its evidence.
    pub evidence: MuEvidence,
    /// The facts behind it (typed: the obstruction, the best point).
    pub computed: Computed,
}

impl MuResult {
    /// The best point (configured or fallback).
    pub fn best(&self) -> Option<&BestPoint> {
        self.computed.best.as_ref()
    }
}

/// One clarabel cross-check of a closed form.
#[derive(Debug, Clone, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct CrossCheckRecord {
    /// Which quantity.
    pub quantity: Text,
    /// clarabel's status.
    pub status: Text,
    /// Solved and re-verified against the printed constraints.
    pub accepted: Flag,
    /// The solver's value, recomputed from its η's with the printed formulas.
    pub solver_value: Quantity,
    /// The closed form's value.
    pub closed_form_value: Quantity,
    /// |solver − closed form| relative to the problem's scale.
    pub relative_difference: Quantity,
}

impl CrossCheckRecord {
    fn of(what: &str, c: &CrossCheck) -> CrossCheckRecord {
        CrossCheckRecord {
            quantity: Text::text("quantity", what),
            status: Text::text("clarabel status", c.status.name()),
            accepted: Flag::new("accepted", c.accepted),
            solver_value: Quantity::based("clarabel", c.solver_value, Unit::Joule, ValueBasis::Solver),
            closed_form_value: Quantity::based("closed form", c.closed_form_value, Unit::Joule, ValueBasis::ClosedForm),
            relative_difference: Quantity::based(
                "relative difference",
                c.relative_difference,
                Unit::Dimensionless,
                ValueBasis::Derived,
            ),
        }
    }
}

/// The ε/λ-optimal point of (32).
#[derive(Debug, Clone, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct BestPointEvidence {
    /// a there.
    pub a: Quantity,
    /// b there.
    pub b: Quantity,
    /// λ3* there.
    pub lambda3_sup: Quantity,
    /// sup λ = λ3*/λ1 (not attained).
    pub lambda_sup: Quantity,
    /// λ at the ε/λ-optimal η's.
    pub lambda: Quantity,
    /// ε of (32) there.
    pub epsilon: Quantity,
    /// The η-part of ε there.
    pub epsilon_eta_part: Quantity,
    /// μ3..μ6 > 0 there re-checked in exact rational arithmetic.
    pub verified_exact: Flag,
}

impl BestPointEvidence {
    fn of(p: &BestPoint, elements: usize) -> BestPointEvidence {
        let rate = |label: &str, v: f64| {
            Quantity::based(
                format!("{label} (λ1 on {elements} elements: optimistic)"),
                v,
                Unit::PerSecond,
                ValueBasis::UpperBound,
            )
        };
        let w = |label: &str, v: f64| Quantity::based(label, v, Unit::Joule, ValueBasis::ClosedForm);
        BestPointEvidence {
            a: Quantity::based("a of the ε/λ-optimal point", p.a, Unit::Dimensionless, ValueBasis::ClosedForm),
            b: Quantity::configured("b of the ε/λ-optimal point", p.b, Unit::Second),
            lambda3_sup: w("λ3* there", p.lambda3_sup),
            lambda_sup: rate("sup λ = λ3*/λ1 there, not attained", p.lambda_sup),
            lambda: rate("decay rate λ at the ε/λ-optimal η's", p.lambda),
            epsilon: w("ε of (32) at those η's", p.epsilon),
            epsilon_eta_part: w("η-part of ε", p.epsilon_eta_part),
            verified_exact: Flag::new("μ3…μ6 > 0 there re-checked in exact arithmetic", p.verified_exact),
        }
    }
}

/// The evidence of the `mu-conditions` row.
#[derive(Debug, Clone, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct MuEvidence {
    /// Configured a.
    pub a: Quantity,
    /// Configured b.
    pub b: Quantity,
    /// a/b.
    pub a_over_b: Quantity,
    /// Configured k1.
    pub k1: Quantity,
    /// Configured k2.
    pub k2: Quantity,
    /// (32) satisfiable at the configured gains (closed-form criterion, exact arithmetic).
    pub satisfiable: Flag,
    /// The condition that fails, when not satisfiable.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub obstruction: Option<Text>,
    /// λ3* = sup min{μ3..μ6} at the configured (a, b) (a, b > 0 only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda3_sup: Option<Quantity>,
    /// Closed-form largest a/b (0: none).
    pub a_over_b_boundary: Quantity,
    /// The clarabel cross-checks of the closed forms.
    pub cross_checks: Table<CrossCheckRecord>,
    /// Grid points around r* where clarabel's accepted answer agrees in sign.
    pub grid_agree: Quantity,
    /// Grid points where clarabel's answer was accepted.
    pub grid_accepted: Quantity,
    /// Grid points tried.
    pub grid_total: Quantity,
    /// g_hmax.
    pub g_hmax: Quantity,
    /// ζ3 = sup |g̃1|.
    pub zeta3: Quantity,
    /// ζ4 = sup |g̃2|.
    pub zeta4: Quantity,
    /// The best point is at the configured gains (else at a/b = r*/2, same b).
    pub best_at_configured: Flag,
    /// The ε/λ-optimal point.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub best: Option<BestPointEvidence>,
}

fn evidence_of(cfg: &Config, c: &Computed, settings: &CheckSettings) -> MuEvidence {
    let ctl = &cfg.control;
    let mut checks = Vec::new();
    if let Some(x) = &c.lambda3_socp {
        checks.push(CrossCheckRecord::of("λ3* at the configured a, b", x));
    }
    if let Some(x) = &c.epsilon_socp {
        checks.push(CrossCheckRecord::of("min ε at the best point's λ3", x));
    }
    let (agree, accepted, tried) = c.grid;
    MuEvidence {
        a: Quantity::configured("weight a of (15)", ctl.a, Unit::Dimensionless),
        b: Quantity::configured("weight b of (15)", ctl.b, Unit::Second),
        a_over_b: Quantity::configured("a/b", if ctl.b > 0.0 { ctl.a / ctl.b } else { 0.0 }, Unit::PerSecond),
        k1: Quantity::configured("bending gain k1", ctl.k1, Unit::NewtonPerMetre),
        k2: Quantity::configured("torsion gain k2", ctl.k2, Unit::NewtonMetre),
        satisfiable: Flag::new("(29)–(32) satisfiable at the configured gains", c.obstruction.is_none()),
        obstruction: c.obstruction.map(|o| Text::text("the condition that fails", o.text())),
        lambda3_sup: c.lambda3_sup.map(|v| {
            Quantity::based(
                "λ3* = sup over the η's of min μ3…μ6, at the configured a, b",
                v,
                Unit::Joule,
                ValueBasis::ClosedForm,
            )
        }),
        a_over_b_boundary: Quantity::based(
            "largest a/b for which (32) can hold: r*",
            c.r_star,
            Unit::PerSecond,
            ValueBasis::ClosedForm,
        ),
        cross_checks: Table::new("clarabel cross-checks of the closed forms", checks),
        grid_agree: Quantity::count("grid points around r* where clarabel agrees in sign", agree),
        grid_accepted: Quantity::count("grid points where clarabel's answer was accepted", accepted),
        grid_total: Quantity::count("grid points tried", tried),
        g_hmax: Quantity::based(
            "g_hmax = max |g_h| over the horizon",
            c.bounds.g_hmax,
            Unit::NewtonPerMetre,
            ValueBasis::SearchMaximum,
        ),
        zeta3: Quantity::with_error(
            "ζ3 = sup |g̃1| over [0, t_end] of the FTDO run",
            c.bounds.zeta3,
            c.zeta_errors[0],
            Unit::Newton,
            &[ErrorSource::Grid, ErrorSource::TimeStep, ErrorSource::RoundOff],
        ),
        zeta4: Quantity::with_error(
            "ζ4 = sup |g̃2| over [0, t_end] of the FTDO run",
            c.bounds.zeta4,
            c.zeta_errors[1],
            Unit::NewtonMetre,
            &[ErrorSource::Grid, ErrorSource::TimeStep, ErrorSource::RoundOff],
        ),
        best_at_configured: Flag::new("the best point is at the configured gains", c.obstruction.is_none()),
        best: c.best.as_ref().map(|p| BestPointEvidence::of(p, settings.mu_lambda1_elements)),
    }
}

impl Explain for MuEvidence {
    /// Satisfiable → holds, else fails; both rest on the closed-form criterion decided in exact
    /// arithmetic.
    fn verdict(&self) -> (Verdict, Basis) {
        (if self.satisfiable.value { Verdict::Holds } else { Verdict::Fails }, Basis::Analytic)
    }

    fn finding(&self) -> Vec<String> {
        let ratio = self.a_over_b.value_text();
        let r_star = self.a_over_b_boundary.value_text();
        let mut f = vec![match &self.obstruction {
            None => format!("At the configured a/b = {ratio} the conditions μ1…μ6 > 0 can be met."),
            Some(o) => format!("At the configured a/b = {ratio} the conditions cannot hold: {}.", o.value),
        }];
        f.push(if self.a_over_b_boundary.value > 0.0 {
            format!(
                "(32) is satisfiable exactly for a/b < r* = {r_star} (with k1, k2 > 0), decided in exact arithmetic."
            )
        } else {
            "No a/b satisfies (32) for this wing.".to_string()
        });
        if let Some(p) = &self.best {
            let at = if self.best_at_configured.value {
                "At the configured gains".to_string()
            } else {
                format!("At a = {}, b = {} (a/b = r*/2)", p.a.value_text(), p.b.value_text())
            };
            f.push(format!(
                "{at} the decay rate at the ε/λ-optimal η's is λ = {} (λ1 from a Galerkin space, so optimistic).",
                p.lambda.value_text()
            ));
        }
        f
    }

    fn decisive(&self) -> Vec<Quantity> {
        let mut out: Vec<Quantity> = self.lambda3_sup.iter().cloned().collect();
        out.push(self.a_over_b_boundary.clone());
        if let Some(p) = &self.best {
            let at = if self.best_at_configured.value {
                "at the configured gains".to_string()
            } else {
                format!("at a = {}, b = {} (a/b = r*/2, not the configured point)", p.a.value_text(), p.b.value_text())
            };
            out.push(
                p.lambda.clone().relabel(format!("decay rate λ at the ε/λ-optimal η's (not sup λ), {at}, optimistic")),
            );
        }
        out
    }

    fn deciding(&self) -> String {
        let (ratio, r_star) = (self.a_over_b.equals_text(), self.a_over_b_boundary.value_text());
        let above = self.a_over_b.value >= self.a_over_b_boundary.value;
        match &self.obstruction {
            None => format!("a/b {ratio} < r* = {r_star}: μ1…μ6 > 0 can be met"),
            Some(_) if self.a_over_b_boundary.value <= 0.0 => "no a/b satisfies (32) for this wing".into(),
            Some(_) if above => format!("a/b {ratio} ≥ r* = {r_star}: (32) cannot hold"),
            Some(o) => format!("(32) cannot hold: {}", o.value),
        }
    }

    fn details(&self) -> Vec<String> {
        let mut d = Vec::new();
        if let Some(p) = &self.best {
            d.push(format!(
                "There sup λ = λ3*/λ1 = {} is not attained; at the ε/λ-optimal η's ε = {} (η-part {}); μ3…μ6 > 0 there {}.",
                p.lambda_sup.value_text(),
                p.epsilon.value_text(),
                p.epsilon_eta_part.value_text(),
                if p.verified_exact.value { "re-checked in exact rational arithmetic" } else { "NOT confirmed in exact arithmetic" }
            ));
        }
        for c in &self.cross_checks.rows {
            d.push(if c.accepted.value {
                format!(
                    "clarabel agrees on {} to {} relative (status {}, rows re-verified).",
                    c.quantity.value,
                    c.relative_difference.value_text(),
                    c.status.value
                )
            } else {
                format!(
                    "clarabel's answer on {} was not accepted (status {}); the closed form stands alone.",
                    c.quantity.value, c.status.value
                )
            });
        }
        d.push(format!(
            "On a grid of a/b around r*, clarabel agrees with the closed form in sign at {} of {} accepted points ({} tried).",
            self.grid_agree.value_text(),
            self.grid_accepted.value_text(),
            self.grid_total.value_text()
        ));
        d
    }
}

fn lambda3_plot(cfg: &Config, e: &MuEvidence) -> Option<PlotData> {
    let (b, r_star) = (e.b.value, e.a_over_b_boundary.value);
    if !(r_star > 0.0 && b > 0.0) {
        return None;
    }
    let ratio = e.a.value / b;
    // a/b from 1.5 decades either side of r*, widened to include the configured a/b.
    let lo = (r_star * 10f64.powf(-1.5)).min(ratio / 3.0).log10();
    let hi = (r_star * 10f64.powf(1.5)).max(ratio * 3.0).log10();
    const SAMPLES: usize = 32;
    let (mut x, mut closed, mut sx, mut sy) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for i in 0..SAMPLES {
        let r = 10f64.powf(lo + (hi - lo) * i as f64 / (SAMPLES - 1) as f64);
        let d = MuData::new(cfg, r * b, b);
        let cc = check_lambda3(&d);
        x.push(r);
        closed.push(d.lambda3_sup() / b);
        if cc.accepted {
            sx.push(r);
            sy.push(cc.solver_value / b);
        }
    }
    let (ymin, ymax) = closed.iter().fold((f64::MAX, f64::MIN), |(l, h), &y| (l.min(y), h.max(y)));
    Some(PlotData {
        name: "mu-lambda3-vs-ratio".into(),
        title: format!(
            "sup λ3/b over the η's against a/b (b = {}, configured a/b = {}); closed-form boundary r* = {}",
            e.b.value_text(),
            e.a_over_b.value_text(),
            e.a_over_b_boundary.value_text()
        ),
        x_label: "a/b (1/s)".into(),
        y_label: "λ3*/b (J/s)".into(),
        log_x: true,
        log_y: false,
        lines: vec![
            Line { label: "λ3*/b closed form".into(), x, y: closed, points: false },
            Line { label: "λ3*/b clarabel (accepted)".into(), x: sx, y: sy, points: true },
            Line { label: "r* (closed form)".into(), x: vec![r_star, r_star], y: vec![ymin, ymax], points: false },
        ],
    })
}

/// Check the μ-conditions.
pub fn check(cfg: &Config, study: &Study, settings: &CheckSettings) -> Result<MuResult, ClaimsError> {
    let computed = compute(cfg, study, settings)?;
    let e = evidence_of(cfg, &computed, settings);
    debug_assert_eq!(ratio_boundary(cfg), e.a_over_b_boundary.value);
    let mut assumptions = vec![
        format!("a = {}, b = {} (not given by the paper)", e.a.value_text(), e.b.value_text()),
        "silent conditions added: η3 ≤ b/(2a), η4 ≤ b/(2a) (the coefficients of ∫q''², ∫θ''² in (31) must be ≥ 0)".into(),
        "ρx_c and x_ac enter through their magnitudes (the Young inequalities behind μ3, μ4 bound |cross terms|)".into(),
        format!(
            "g_hmax = {} = max over t ∈ [0, t_end] of |g_h|; ζ3 = {}, ζ4 = {} = sup over t of |g̃1|, |g̃2| in the FTDO simulation at full rate (the ε terms bound g̃², not ĝ²)",
            e.g_hmax.value_text(),
            e.zeta3.value_text(),
            e.zeta4.value_text()
        ),
        "η8 = 1/k1, η9 = 1/k2 (the infima allowed by μ1, μ2 > 0), minimising ε".into(),
        format!(
            "λ1 in λ = λ3/λ1 is the tight sup W/κ at the same (a, b) on {} Galerkin elements (a lower bound of sup W/κ, so λ errs on the optimistic side)",
            settings.mu_lambda1_elements
        ),
    ];
    if computed.obstruction.is_some() {
        assumptions.push("config keys involved: control.a, control.b, control.k1, control.k2, wing.*".into());
    }
    let plots = lambda3_plot(cfg, &e).into_iter().collect();
    let row = ClaimRow::decided(ClaimId::MuConditions, e.clone(), assumptions, plots);
    Ok(MuResult { row, evidence: e, computed })
}
