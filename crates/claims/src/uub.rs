//! The `UUB` row, Theorem 2, (33)–(37): uniform ultimate boundedness and the bound
//! |q(z,t)| ≤ √(s³/λ2 · (W(0)e^{−λt} + ε/λ)), |θ(z,t)| ≤ √(s/λ2 · (W(0)e^{−λt} + ε/λ)).
//!
//! The bound needs λ2 > 0 (W-bounds) and μ1…μ6 > 0 (mu-conditions). Where the configured
//! weights violate them the bound is evaluated at the μ row's fallback point (a/b = r*/2, same
//! b), with the tight λ2 there, and compared with the simulated envelope max_z |q(z,t)|,
//! max_z |θ(z,t)| of the FTDO closed loop at the same gains. (36) prints κ ≤ W/λ; the chain
//! needs κ ≤ W/λ2 — used here. W(0) is finite only for a clamp-compatible initial shape: it is
//! computed on 16, 32 and 64 uniform elements and called divergent when it keeps growing
//! (ratio W(0)₆₄/W(0)₃₂ > 1.5; the linear shape z/s has q'(0) ≠ 0, so ∫q''² = ∞ and W(0) grows
//! like 1/h).

use std::time::Instant;

use serde::{Deserialize, Serialize};
use wingcheck_model::{Config, ControllerKind};
use wingcheck_sim::Discretisation;

use crate::ledger::{evidence_map, ClaimId};
use crate::lyapunov::{assemble, decimal, tight_constants, Coupling, LyapunovParams};
use crate::mu::MuResult;
use crate::study::Study;
use crate::wbounds::{num, WBounds};
use crate::{Basis, ClaimRow, ClaimsError, Line, PlotData, Verdict};

/// Ratio bound/measured above which a bound that holds is called vacuous.
pub const VACUITY_RATIO: f64 = 100.0;

/// W(0) for zero initial velocity: b × the elastic energy of the discretised initial shape,
/// on a uniform FE mesh of `elements` elements.
pub fn w_initial(cfg: &Config, b: f64, elements: usize) -> f64 {
    let mut c = cfg.clone();
    c.discretisation.grading = 0.0;
    let d = Discretisation::with(&c, wingcheck_model::Method::Fe, elements);
    b * 0.5 * d.stiffness.form(&d.x0, &d.x0)
}

/// The evidence of the `UUB` row (present when a point satisfying (32) exists).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct UubEvidence {
    /// λ2 > 0 and (32) hold at the configured gains.
    pub hypotheses_hold_at_config: bool,
    /// a of the point where the bound is evaluated.
    pub evaluated_at_a: f64,
    /// b there.
    pub evaluated_at_b: f64,
    /// λ (1/s) at the ε/λ-optimal η's.
    pub lambda: f64,
    /// 1/λ (s).
    pub decay_time_constant_s: f64,
    /// ε of (32).
    pub epsilon: f64,
    /// Tight λ2 at the evaluation point (16 elements).
    pub lambda2_tight: f64,
    /// W(0) on 16, 32, 64 uniform elements.
    pub w0_by_elements: [(usize, f64); 3],
    /// W(0) keeps growing under refinement (W(0) = ∞ for the PDE).
    pub w0_diverges: bool,
    /// √(s³/λ2 · ε/λ) (m).
    pub ultimate_bound_q_m: f64,
    /// The bound (37) at T with the 16-element W(0) (m).
    pub bound_q_at_t_end_m: f64,
    /// Simulated max_z |q| over the second half of the horizon (m).
    pub measured_max_abs_q_second_half_m: f64,
    /// bound at T / measured, for q and θ.
    pub ratio_bound_over_measured_q: f64,
    /// The same for θ.
    pub ratio_bound_over_measured_theta: f64,
    /// The simulated envelope exceeds the bound somewhere.
    pub bound_violated: bool,
    /// Output grid points in z used for the envelope (`horizon.field_points`).
    pub field_points: usize,
    /// At the configured gains: max |q(s,t)|, |θ(s,t)| over the second half.
    pub config_max_abs_q_tip_second_half_m: f64,
    /// max |θ(s,t)| there (rad).
    pub config_max_abs_theta_tip_second_half_rad: f64,
}

/// Verdict from the evidence.
pub fn verdict(e: &UubEvidence) -> (Verdict, Basis) {
    if e.bound_violated {
        (Verdict::Fails, Basis::Simulation)
    } else if e.w0_diverges {
        (Verdict::Vacuous, Basis::Analytic)
    } else if e.ratio_bound_over_measured_q.min(e.ratio_bound_over_measured_theta) > VACUITY_RATIO {
        (Verdict::Vacuous, Basis::Simulation)
    } else {
        (Verdict::Holds, Basis::Simulation)
    }
}

/// Summary from the evidence.
pub fn summary(e: &UubEvidence) -> String {
    let hyp = if e.hypotheses_hold_at_config {
        String::new()
    } else {
        "The hypotheses (λ2 > 0, μ1…μ6 > 0) fail at the configured gains (see W-bounds, mu-conditions). ".into()
    };
    let w0 = e.w0_by_elements;
    let w0_text = if e.w0_diverges {
        format!(
            "W(0) is {:.3e}, {:.3e}, {:.3e} on {}, {}, {} elements and keeps growing: the initial shape violates the clamp's q'(0) = 0, so W(0) = ∞ for the PDE and the bound (37) is infinite for all t at this initial condition; the finite values below use the 16-element W(0). ",
            w0[0].1, w0[1].1, w0[2].1, w0[0].0, w0[1].0, w0[2].0
        )
    } else {
        format!("W(0) converges under refinement ({:.4e} on {} elements). ", w0[2].1, w0[2].0)
    };
    format!(
        "{hyp}{w0_text}At a = {:.3e}, b = {} (λ = {:.3e} 1/s, a certified decay time of {:.3e} s; ε = {:.3e}; tight λ2 = {:.3e}) \
         the bound (37) at T gives |q| ≤ {:.3e} m against a simulated max_z|q| of {:.3e} m over the second half on a {}-point grid in z (ratio {:.2e}; θ ratio {:.2e}){}. \
         The ultimate bound √(s³ε/(λ2λ)) is {:.3e} m. In simulation at the configured gains the tip stays bounded (max |q(s,t)| = {:.3e} m, |θ(s,t)| = {:.3e} rad over the second half).",
        e.evaluated_at_a,
        e.evaluated_at_b,
        e.lambda,
        e.decay_time_constant_s,
        e.epsilon,
        e.lambda2_tight,
        e.bound_q_at_t_end_m,
        e.measured_max_abs_q_second_half_m,
        e.field_points,
        e.ratio_bound_over_measured_q,
        e.ratio_bound_over_measured_theta,
        if e.bound_violated { " — the bound is VIOLATED" } else { "" },
        e.ultimate_bound_q_m,
        e.config_max_abs_q_tip_second_half_m,
        e.config_max_abs_theta_tip_second_half_rad,
    )
}

const CLAIM: &str = "q, θ uniformly ultimately bounded, with the printed bound";

/// Check Theorem 2.
pub fn check(cfg: &Config, w: &WBounds, m: &MuResult, study: &Study) -> Result<ClaimRow, ClaimsError> {
    let start = Instant::now();
    let hypotheses_here = w.evidence.w_positive_definite == crate::theory::Decision::Yes && m.evidence.satisfiable;
    let Some(best) = m.best().copied() else {
        let why = match m.evidence.obstruction {
            Some(o)
                if m.evidence.a_over_b_boundary <= 0.0
                    || cfg.control.k1 <= 0.0
                    || cfg.control.k2 <= 0.0
                    || cfg.control.b <= 0.0 =>
            {
                format!(
                    "{}; no operating point satisfies (32), so Theorem 2's decay rate λ and the bound do not exist",
                    o.text()
                )
            }
            _ => "no operating point satisfies (32), so the bound cannot be evaluated".into(),
        };
        let mut row = ClaimRow::inconclusive(ClaimId::Uub, CLAIM, &why);
        row.basis = Basis::Analytic;
        row.assumptions.push("config keys involved: control.a, control.b, control.k1, control.k2, wing.xi".into());
        return Ok(row);
    };
    let p = LyapunovParams::from_config(cfg, Coupling::Corrected, 16).with_weights(&decimal(best.a), &decimal(best.b));
    let lambda2 = tight_constants(&assemble(&p).map_err(num("assembly"))?).map_err(num("eigen"))?.lambda2;
    if lambda2 <= 0.0 {
        let mut row = ClaimRow::inconclusive(
            ClaimId::Uub,
            CLAIM,
            &format!("at the operating point a = {:.3e}, b = {} W is not positive definite (λ2 = {lambda2:.3e}), so (37) does not apply", best.a, best.b),
        );
        row.basis = Basis::FloatSolver;
        return Ok(row);
    }
    let mut sim_cfg = cfg.clone();
    sim_cfg.control.a = best.a;
    sim_cfg.control.b = best.b;
    sim_cfg.control.kind = ControllerKind::Ftdo;
    let out = study.simulate(&sim_cfg)?;
    let fields = out.fields.as_ref().expect("the study records fields");
    let t = &out.series.t;
    let env_q: Vec<f64> = fields.q.iter().map(|r| r.iter().fold(0.0f64, |a, v| a.max(v.abs()))).collect();
    let env_t: Vec<f64> = fields.theta.iter().map(|r| r.iter().fold(0.0f64, |a, v| a.max(v.abs()))).collect();
    let s = cfg.wing.span;
    let w0s = [16usize, 32, 64].map(|n| (n, w_initial(cfg, best.b, n)));
    let w0 = w0s[0].1;
    let w0_diverges = w0s[2].1 > 1.5 * w0s[1].1;
    let (lam, eps) = (best.lambda, best.epsilon);
    let core = |tt: f64| w0 * (-lam * tt).exp() + eps / lam;
    let bound_q: Vec<f64> = t.iter().map(|&tt| (s.powi(3) / lambda2 * core(tt)).sqrt()).collect();
    let bound_t: Vec<f64> = t.iter().map(|&tt| (s / lambda2 * core(tt)).sqrt()).collect();
    let violated = env_q.iter().zip(&bound_q).any(|(e, b)| e > b) || env_t.iter().zip(&bound_t).any(|(e, b)| e > b);
    let n = t.len();
    let tail = n / 2;
    let max_tail = |v: &[f64]| v[tail..].iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let ratio = |b: f64, m: f64| if m > 0.0 { b / m } else { f64::MAX };
    let here = study.simulate(cfg)?;
    let e = UubEvidence {
        hypotheses_hold_at_config: hypotheses_here,
        evaluated_at_a: best.a,
        evaluated_at_b: best.b,
        lambda: lam,
        decay_time_constant_s: 1.0 / lam,
        epsilon: eps,
        lambda2_tight: lambda2,
        w0_by_elements: w0s,
        w0_diverges,
        ultimate_bound_q_m: (s.powi(3) / lambda2 * eps / lam).sqrt(),
        bound_q_at_t_end_m: bound_q[n - 1],
        measured_max_abs_q_second_half_m: max_tail(&env_q),
        ratio_bound_over_measured_q: ratio(bound_q[n - 1], max_tail(&env_q)),
        ratio_bound_over_measured_theta: ratio(bound_t[n - 1], max_tail(&env_t)),
        bound_violated: violated,
        field_points: fields.z.len(),
        config_max_abs_q_tip_second_half_m: max_tail(&here.series.q_tip[..]),
        config_max_abs_theta_tip_second_half_rad: {
            let v = &here.series.theta_tip;
            v[v.len() / 2..].iter().fold(0.0f64, |a, x| a.max(x.abs()))
        },
    };
    let (verdict, basis) = verdict(&e);
    let stride = (n / 400).max(1);
    let pick = |v: &[f64]| v.iter().step_by(stride).copied().collect::<Vec<_>>();
    Ok(ClaimRow {
        id: ClaimId::Uub,
        equation: ClaimId::Uub.equation().into(),
        claim: CLAIM.into(),
        verdict,
        basis,
        summary: summary(&e),
        correction: Some(format!(
            "(36): κ ≤ W/λ2 (not W/λ); the bound needs a/b < r* = {:.4e} (μ-conditions){}",
            m.evidence.a_over_b_boundary,
            if e.w0_diverges { " and a clamp-compatible initial shape (W(0) < ∞)" } else { "" }
        )),
        highlights: [
            "ratio_bound_over_measured_q",
            "decay_time_constant_s",
            "bound_q_at_t_end_m",
            "measured_max_abs_q_second_half_m",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
        assumptions: vec![
            if m.evidence.best_at_configured {
                "operating point: the configured gains (they satisfy (32))".to_string()
            } else {
                format!("operating point a = {:.4e}, b = {} = half the closed-form μ boundary (the configured gains do not satisfy (32))", best.a, best.b)
            },
            "W(0) from the discretised initial state (uniform FE elements, zero initial velocity)".into(),
            format!(
                "simulated envelope: max over the {}-point output grid in z (horizon.field_points)",
                e.field_points
            ),
            "ζ3, ζ4 from the FTDO run at the configured gains".into(),
        ],
        evidence: evidence_map(&e),
        certificates: Vec::new(),
        plots: vec![PlotData {
            name: "uub-bound-vs-envelope".into(),
            title: format!(
                "Theorem 2 bound vs simulated envelope at a = {:.2e}, b = {}; ratio at T = {:.1e}",
                best.a, best.b, e.ratio_bound_over_measured_q
            ),
            x_label: "t (s)".into(),
            y_label: "max_z |q(z,t)| (m)".into(),
            log_x: false,
            log_y: true,
            lines: vec![
                Line { label: "bound (37)".into(), x: pick(t), y: pick(&bound_q), points: false },
                Line {
                    label: "simulated max_z |q|".into(),
                    x: pick(t),
                    y: pick(&env_q).iter().map(|v| v.max(1e-12)).collect(),
                    points: false,
                },
            ],
        }],
        seconds: start.elapsed().as_secs_f64(),
    })
}
