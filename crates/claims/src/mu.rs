//! The `mu-conditions` row, (29)–(32): conditions μ1…μ6 > 0 on the gains and the η's,
//! λ3 = min μ3..μ6, λ = λ3/λ1, ε.
//!
//! Evidence → verdict → text: [`evidence`] computes [`MuEvidence`] from the closed forms of
//! [`crate::theory`] (satisfiability decided in exact rational arithmetic; the best point's
//! μ's re-checked exactly) and the clarabel cross-checks of [`crate::convex`]; [`verdict`] and
//! [`summary`] read only that evidence.

use std::time::Instant;

use serde::{Deserialize, Serialize};
use wingcheck_model::Config;

use crate::convex::{check_epsilon, check_lambda3, CrossCheck};
use crate::ledger::ClaimId;
use crate::study::Study;
use crate::theory::{self, BestPoint, DisturbanceBounds, Obstruction};
use crate::{Basis, ClaimRow, ClaimsError, Line, PlotData, Verdict};

pub use crate::theory::MuData;

/// Relative agreement required between a clarabel value and its closed form.
pub const CROSS_CHECK_TOLERANCE: f64 = 1e-6;

/// Closed-form largest a/b for which (32) can hold (0 if none): the smallest positive root
/// of (α − rρ)(β − rI_p) = (2ρx_c r)², α = ξEI/(2s⁴), β = ξGJ/(2s²), capped at 1/(2ξ).
pub fn ratio_boundary(cfg: &Config) -> f64 {
    let w = &cfg.wing;
    if w.xi <= 0.0 {
        return 0.0;
    }
    let alpha = w.xi * w.ei / (2.0 * w.span.powi(4));
    let beta = w.xi * w.gj / (2.0 * w.span * w.span);
    let c = 2.0 * w.rho_xc.abs();
    let lin = alpha * w.ip + beta * w.rho;
    let disc = (alpha * w.ip - beta * w.rho).powi(2) + 4.0 * c * c * alpha * beta;
    let r34 = 2.0 * alpha * beta / (lin + disc.sqrt());
    r34.min(1.0 / (2.0 * w.xi))
}

impl MuData {
    /// Closed-form boundary of a/b ([`ratio_boundary`]).
    pub fn closed_form_ratio(cfg: &Config) -> f64 {
        ratio_boundary(cfg)
    }
}

/// One point of the closed-form-vs-solver grid around the boundary.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GridPoint {
    /// a/b.
    pub ratio: f64,
    /// λ3*/b from the closed form.
    pub lambda3_sup_over_b: f64,
    /// λ3*/b from clarabel (only when accepted).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub solver_over_b: Option<f64>,
}

/// The evidence of the `mu-conditions` row.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MuEvidence {
    /// Configured a.
    pub a: f64,
    /// Configured b.
    pub b: f64,
    /// Configured k1, k2.
    pub k1: f64,
    /// k2.
    pub k2: f64,
    /// (32) satisfiable at the configured gains (closed-form criterion, exact arithmetic).
    pub satisfiable: bool,
    /// Which condition fails when not satisfiable.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub obstruction: Option<Obstruction>,
    /// λ3* = sup min{μ3..μ6} at the configured (a, b) (closed form; a, b > 0 only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda3_sup: Option<f64>,
    /// clarabel's max λ3, re-verified (a, b > 0 only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda3_socp: Option<CrossCheck>,
    /// Closed-form largest a/b (0: none).
    pub a_over_b_boundary: f64,
    /// Grid points where clarabel's answer was accepted and agrees in sign with the closed form.
    pub grid_agree: usize,
    /// Grid points where clarabel's answer was accepted (away from the boundary).
    pub grid_accepted: usize,
    /// Grid points tried.
    pub grid_total: usize,
    /// The bounds g_hmax, ζ3, ζ4 used in ε.
    pub bounds: DisturbanceBounds,
    /// Whether the best point is at the configured gains (else at a/b = r*/2, same b).
    pub best_at_configured: bool,
    /// The ε/λ-optimal point (configured gains if satisfiable, else a/b = r*/2).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub best: Option<BestPoint>,
    /// clarabel's min ε_η at the best point's λ3, re-verified.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub epsilon_socp: Option<CrossCheck>,
}

/// Result of the μ-conditions check, reused by the UUB row.
#[derive(Debug, Clone)]
pub struct MuResult {
    /// The ledger row.
    pub row: ClaimRow,
    /// The evidence.
    pub evidence: MuEvidence,
}

impl MuResult {
    /// The best point (configured or fallback).
    pub fn best(&self) -> Option<&BestPoint> {
        self.evidence.best.as_ref()
    }
}

/// Tight λ1 (sup W/κ) at weights (a, b), N = 8.
pub fn lambda1_at(cfg: &Config, a: f64, b: f64) -> Result<f64, ClaimsError> {
    use crate::lyapunov::{assemble, decimal, tight_constants, Coupling, LyapunovParams};
    let p = LyapunovParams::from_config(cfg, Coupling::Corrected, 8).with_weights(&decimal(a), &decimal(b));
    let f = assemble(&p).map_err(|d| ClaimsError::Numerical { what: "assembly".into(), detail: d })?;
    Ok(tight_constants(&f).map_err(|d| ClaimsError::Numerical { what: "eigen".into(), detail: d })?.lambda1)
}

/// The ε/λ-optimal point at weights (a, b) with bounds (g_hmax, ζ3, ζ4) ([`theory::best_point`]
/// with the tight λ1 at N = 8).
pub fn best_point(cfg: &Config, a: f64, b: f64, bounds: (f64, f64, f64)) -> Result<Option<BestPoint>, ClaimsError> {
    let d = MuData::new(cfg, a, b);
    if d.obstruction_exact(cfg.control.k1, cfg.control.k2).is_some() {
        return Ok(None);
    }
    let l1 = lambda1_at(cfg, a, b)?;
    let bounds = DisturbanceBounds { g_hmax: bounds.0, zeta3: bounds.1, zeta4: bounds.2 };
    Ok(theory::best_point(&d, l1, &bounds, cfg.control.k1, cfg.control.k2))
}

/// Compute the evidence.
pub fn evidence(cfg: &Config, study: &Study) -> Result<MuEvidence, ClaimsError> {
    let (a, b, k1, k2) = (cfg.control.a, cfg.control.b, cfg.control.k1, cfg.control.k2);
    let d = MuData::new(cfg, a, b);
    let obstruction = d.obstruction_exact(k1, k2);
    let weights_positive = a > 0.0 && b > 0.0;
    let r_star = ratio_boundary(cfg);
    let bounds = study.disturbance_bounds(cfg)?;
    let (mut agree, mut accepted, mut grid_total) = (0, 0, 0);
    if r_star > 0.0 && b > 0.0 {
        for i in 0..24 {
            let r = r_star * 10f64.powf(-1.5 + 3.0 * i as f64 / 23.0);
            let di = MuData::new(cfg, r * b, b);
            let cc = check_lambda3(&di);
            grid_total += 1;
            if cc.accepted && (r / r_star).ln().abs() > 0.05 {
                accepted += 1;
                if (cc.solver_value > 0.0) == (r < r_star) {
                    agree += 1;
                }
            }
        }
    }
    let here = obstruction.is_none();
    let at = if here {
        Some((a, b))
    } else if r_star > 0.0 && b > 0.0 && k1 > 0.0 && k2 > 0.0 {
        Some((0.5 * r_star * b, b))
    } else {
        None
    };
    let best = match at {
        Some((aa, bb)) => {
            let dd = MuData::new(cfg, aa, bb);
            let l1 = lambda1_at(cfg, aa, bb)?;
            theory::best_point(&dd, l1, &bounds, k1, k2)
        }
        None => None,
    };
    let epsilon_socp = best.as_ref().map(|p| check_epsilon(&MuData::new(cfg, p.a, p.b), p.lambda3));
    Ok(MuEvidence {
        a,
        b,
        k1,
        k2,
        satisfiable: here,
        obstruction,
        lambda3_sup: weights_positive.then(|| d.lambda3_sup()),
        lambda3_socp: weights_positive.then(|| check_lambda3(&d)),
        a_over_b_boundary: r_star,
        grid_agree: agree,
        grid_accepted: accepted,
        grid_total,
        bounds,
        best_at_configured: here,
        best,
        epsilon_socp,
    })
}

/// The verdict from the evidence: satisfiable → holds, else fails; both rest on the closed-form
/// criterion decided in exact arithmetic ("analytic").
pub fn verdict(e: &MuEvidence) -> (Verdict, Basis) {
    if e.satisfiable {
        (Verdict::Holds, Basis::Analytic)
    } else {
        (Verdict::Fails, Basis::Analytic)
    }
}

fn cross_check_text(name: &str, c: &CrossCheck) -> String {
    if c.accepted {
        format!(
            "{name}: clarabel agrees to {:.1e} relative (status {}, rows re-verified to {:.0e})",
            c.relative_difference,
            c.status,
            crate::convex::ROW_TOLERANCE
        )
    } else {
        format!("{name}: clarabel's answer not accepted (status {}), the closed form stands alone", c.status)
    }
}

/// The summary from the evidence.
pub fn summary(e: &MuEvidence) -> String {
    let mut s = String::new();
    let ratio_text = if e.b > 0.0 { format!("a/b = {:.4e}", e.a / e.b) } else { "b = 0".to_string() };
    if e.satisfiable {
        s.push_str(&format!(
            "At a = {}, b = {} ({ratio_text} < r* = {:.4e}) the conditions μ1…μ6 > 0 are satisfiable. ",
            e.a, e.b, e.a_over_b_boundary
        ));
    } else {
        let why = e.obstruction.map(Obstruction::text).unwrap_or("");
        s.push_str(&format!("At a = {}, b = {} ({ratio_text}) the conditions cannot hold: {why}. ", e.a, e.b));
    }
    if let Some(l3) = e.lambda3_sup {
        s.push_str(&format!("sup over the η's of λ3 = min μ3..μ6 is {l3:.4e} (closed form). "));
    }
    if e.a_over_b_boundary > 0.0 {
        s.push_str(&format!(
            "(32) is satisfiable exactly for a/b < r* = {:.4e} (with k1, k2 > 0); clarabel agrees in sign at {}/{} accepted grid points ({} tried). ",
            e.a_over_b_boundary, e.grid_agree, e.grid_accepted, e.grid_total
        ));
    } else {
        s.push_str("No a/b satisfies (32) for this wing (ξ = 0 makes μ3 < 0). ");
    }
    if let Some(p) = &e.best {
        s.push_str(&format!(
            "{} a = {:.4e}, b = {}: sup λ = λ3*/λ1 = {:.4e} 1/s (not attained); at the η's minimising ε/λ, λ = {:.4e} 1/s and ε = {:.4e} (of which the η-part {:.4e}); μ3..μ6 > 0 there {}. ",
            if e.best_at_configured { "At the configured" } else { "At the fallback point a/b = r*/2," },
            p.a,
            p.b,
            p.lambda_sup,
            p.lambda,
            p.epsilon,
            p.epsilon_eta_part,
            if p.verified_exact { "re-checked in exact rational arithmetic" } else { "NOT confirmed in exact arithmetic" }
        ));
    }
    if let Some(c) = &e.lambda3_socp {
        s.push_str(&cross_check_text("λ3*", c));
        s.push_str("; ");
    }
    if let Some(c) = &e.epsilon_socp {
        s.push_str(&cross_check_text("min ε", c));
        s.push('.');
    }
    s
}

/// Check the μ-conditions.
pub fn check(cfg: &Config, study: &Study) -> Result<MuResult, ClaimsError> {
    let start = Instant::now();
    let e = evidence(cfg, study)?;
    let (verdict, basis) = verdict(&e);
    let b = e.b;
    let r_star = e.a_over_b_boundary;
    let mut lines = Vec::new();
    if r_star > 0.0 && b > 0.0 {
        let ratio = e.a / b;
        // a/b from 1.5 decades either side of r*, widened to include the configured a/b.
        let lo = (r_star * 10f64.powf(-1.5)).min(ratio / 3.0).log10();
        let hi = (r_star * 10f64.powf(1.5)).max(ratio * 3.0).log10();
        const SAMPLES: usize = 32;
        let pts: Vec<GridPoint> = (0..SAMPLES)
            .map(|i| {
                let r = 10f64.powf(lo + (hi - lo) * i as f64 / (SAMPLES - 1) as f64);
                let d = MuData::new(cfg, r * b, b);
                let cc = check_lambda3(&d);
                GridPoint {
                    ratio: r,
                    lambda3_sup_over_b: d.lambda3_sup() / b,
                    solver_over_b: cc.accepted.then(|| cc.solver_value / b),
                }
            })
            .collect();
        lines.push(Line {
            label: "λ3*/b closed form".into(),
            x: pts.iter().map(|p| p.ratio).collect(),
            y: pts.iter().map(|p| p.lambda3_sup_over_b).collect(),
            points: false,
        });
        let acc: Vec<&GridPoint> = pts.iter().filter(|p| p.solver_over_b.is_some()).collect();
        lines.push(Line {
            label: "λ3*/b clarabel (accepted)".into(),
            x: acc.iter().map(|p| p.ratio).collect(),
            y: acc.iter().filter_map(|p| p.solver_over_b).collect(),
            points: true,
        });
        let ys = pts.iter().map(|p| p.lambda3_sup_over_b);
        let (ymin, ymax) = ys.fold((f64::MAX, f64::MIN), |(l, h), y| (l.min(y), h.max(y)));
        lines.push(Line {
            label: "r* (closed form)".into(),
            x: vec![r_star, r_star],
            y: vec![ymin, ymax],
            points: false,
        });
    }
    let certificates = if e.obstruction == Some(Obstruction::Mu3Constant) {
        vec!["mu-conditions-infeasible.json".into()]
    } else {
        Vec::new()
    };
    let mut assumptions = vec![
        format!("a = {}, b = {} (not given by the paper)", e.a, e.b),
        "silent conditions added: η3 ≤ b/(2a), η4 ≤ b/(2a) (coefficients of ∫q''², ∫θ''² in (31) must be ≥ 0)".into(),
        "ρx_c and x_ac enter through their magnitudes (the Young inequalities behind μ3, μ4 bound |cross terms|)".into(),
        format!(
            "g_hmax = {:.4} = max_t |g_h| over the horizon (tight), ζ3 = {:.3e}, ζ4 = {:.3e} = sup_t |g̃| of the FTDO simulation (the ε terms bound g̃², not ĝ²)",
            e.bounds.g_hmax, e.bounds.zeta3, e.bounds.zeta4
        ),
        "η8 = 1/k1, η9 = 1/k2 (the infima allowed by μ1, μ2 > 0), minimising ε".into(),
        "λ1 in λ = λ3/λ1 is the tight sup W/κ at the same (a, b) (Galerkin, 8 elements)".into(),
    ];
    if !e.satisfiable {
        assumptions.push("config keys involved: control.a, control.b, control.k1, control.k2, wing.*".into());
    }
    let row = ClaimRow {
        id: ClaimId::MuConditions,
        equation: "(29)–(32)".into(),
        claim: "conditions on the gains and the η's make Ẇ ≤ −λW + ε with the printed λ, ε".into(),
        verdict,
        basis,
        summary: summary(&e),
        correction: None,
        evidence: crate::ledger::evidence_map(&e),
        highlights: ["lambda3_sup", "a_over_b_boundary", "best", "satisfiable"].iter().map(|s| s.to_string()).collect(),
        assumptions,
        certificates,
        plots: vec![PlotData {
            name: "mu-lambda3-vs-ratio".into(),
            title: format!(
                "sup λ3 / b over the η's vs a/b (b = {b}, configured a/b = {}); closed-form boundary r* = {r_star:.3e}",
                if b > 0.0 { format!("{:.3e}", e.a / b) } else { "undefined".into() }
            ),
            x_label: "a/b (1/s)".into(),
            y_label: "λ3*/b (units of λ3/b)".into(),
            log_x: true,
            log_y: false,
            lines,
        }],
        seconds: start.elapsed().as_secs_f64(),
    };
    Ok(MuResult { row, evidence: e })
}
