//! (29)–(32): conditions μ1…μ6 > 0 on the gains and the η's, λ3 = min μ3..μ6, λ = λ3/λ1, ε.
//!
//! For fixed gains the conditions are convex in the η's: μ3 and the silent conditions are
//! linear, and the terms c/η (μ4, μ5, μ6) are handled by rotated second-order cones u·η ≥ 1,
//! so "maximise λ3" is an SOCP (clarabel). Conditions the proof needs but does not state:
//! the coefficients of ∫q''² and ∫θ''² in (31), bξEI/2 − aξEIη3 and bξGJ/2 − aξGJη4, must be
//! ≥ 0, i.e. η3, η4 ≤ b/(2a) (otherwise those positive terms cannot be dropped).
//!
//! Closed form of the feasibility boundary (η1, η2 → 0⁺; μ5, μ6 only constrain η3, η4, η6, η7
//! and are satisfiable whenever ξ < b/(2a)): with r = a/b, α = ξEI/(2s⁴), β = ξGJ/(2s²),
//! c = 2ρx_c, μ3, μ4 > 0 need η5 with c η5 < α/r − ρ and c/η5 < β/r − I_p, i.e.
//! (α/r − ρ)(β/r − I_p) > c² with both factors positive: r < r* = 1/x₊, x₊ the larger root of
//! αβ x² − (αI_p + βρ) x + ρI_p − c² = 0.

use std::collections::BTreeMap;
use std::time::Instant;

use serde_json::json;
use wingcheck_model::{apply_overrides, Config};

use crate::socp::{Socp, SocpOutcome};
use crate::wbounds::WBounds;
use crate::{Basis, ClaimRow, ClaimsError, Line, PlotData, Verdict};

const T: usize = 0;
const ETA: [usize; 8] = [usize::MAX, 1, 2, 3, 4, 5, 6, 7]; // ETA[i] = index of η_i, i = 1..7
const U3: usize = 8;
const U4: usize = 9;
const U5: usize = 10;
const V1: usize = 11;
const V2: usize = 12;
const V6: usize = 13;
const V7: usize = 14;

/// The constants of (29)–(32) for given weights.
#[derive(Debug, Clone, Copy)]
pub struct MuData {
    /// a.
    pub a: f64,
    /// b.
    pub b: f64,
    rho: f64,
    rho_xc: f64,
    ei: f64,
    gj: f64,
    ip: f64,
    x_ac: f64,
    xi: f64,
    s: f64,
}

impl MuData {
    /// From a configuration with weights (a, b).
    pub fn new(cfg: &Config, a: f64, b: f64) -> Self {
        let w = &cfg.wing;
        MuData { a, b, rho: w.rho, rho_xc: w.rho_xc, ei: w.ei, gj: w.gj, ip: w.ip, x_ac: w.x_ac, xi: w.xi, s: w.span }
    }

    /// The SOCP with constraints μ_i ≥ t (i = 3..6), η ≥ 0, η3, η4 ≤ b/(2a), u_i·η_i ≥ 1.
    fn base(&self, n: usize) -> Socp {
        let d = self;
        let mut p = Socp::new(n);
        let c = 2.0 * d.a * d.rho_xc;
        p.le(vec![(T, 1.0), (ETA[1], d.b), (ETA[5], c)], d.b * d.xi * d.ei / (2.0 * d.s.powi(4)) - d.a * d.rho);
        p.le(vec![(T, 1.0), (ETA[2], d.b * d.x_ac), (U5, c)], d.b * d.xi * d.gj / (2.0 * d.s * d.s) - d.a * d.ip);
        p.le(vec![(T, 1.0), (U3, d.a * d.xi * d.ei), (ETA[6], d.a * d.s.powi(4))], d.a * d.ei);
        p.le(vec![(T, 1.0), (U4, d.a * d.xi * d.gj), (ETA[7], d.a * d.s * d.s * d.x_ac)], d.a * d.gj);
        for i in 1..=7 {
            p.le(vec![(ETA[i], -1.0)], 0.0);
        }
        if d.a > 0.0 {
            p.le(vec![(ETA[3], 1.0)], d.b / (2.0 * d.a));
            p.le(vec![(ETA[4], 1.0)], d.b / (2.0 * d.a));
        }
        p.hyperbolic(U3, ETA[3], 1.0).hyperbolic(U4, ETA[4], 1.0).hyperbolic(U5, ETA[5], 1.0);
        // keep the problem bounded in directions that do not matter
        for i in 1..=7 {
            p.le(vec![(ETA[i], 1.0)], 1e6);
        }
        p
    }

    /// max t = λ3 over the η's (t free): λ3* > 0 ⟺ the conditions are satisfiable.
    pub fn max_lambda3(&self) -> Result<SocpOutcome, ClaimsError> {
        let mut p = self.base(11);
        p.cost[T] = -1.0;
        p.solve().map_err(|e| ClaimsError::Numerical { what: "μ SOCP".into(), detail: e })
    }

    /// The feasibility problem μ3..μ6 ≥ 0 (t = 0): clarabel answers infeasible with a certificate
    /// when no η's exist.
    pub fn feasibility(&self) -> Result<SocpOutcome, ClaimsError> {
        let mut p = self.base(11);
        p.le(vec![(T, -1.0)], 0.0);
        p.le(vec![(T, 1.0)], 0.0);
        p.solve().map_err(|e| ClaimsError::Numerical { what: "μ feasibility".into(), detail: e })
    }

    /// min ε over the η's subject to μ_i ≥ t (ε of (32) with η8 = 1/k1, η9 = 1/k2, their infima).
    pub fn min_epsilon(
        &self,
        t: f64,
        sg2: f64,
        zeta3: f64,
        zeta4: f64,
        k1: f64,
        k2: f64,
    ) -> Result<(f64, Vec<f64>), ClaimsError> {
        let mut p = self.base(15);
        p.le(vec![(T, -1.0)], -t);
        for (v, i) in [(V1, 1), (V2, 2), (V6, 6), (V7, 7)] {
            p.hyperbolic(v, ETA[i], 1.0);
        }
        p.cost[V1] = self.b * sg2;
        p.cost[V2] = self.b * self.x_ac * sg2;
        p.cost[V6] = self.a * sg2;
        p.cost[V7] = self.a * self.x_ac * sg2;
        let out = p.solve().map_err(|e| ClaimsError::Numerical { what: "ε SOCP".into(), detail: e })?;
        if !out.solved() {
            return Err(ClaimsError::Numerical { what: "ε SOCP".into(), detail: format!("status {:?}", out.status) });
        }
        let eps = out.objective + zeta3 * zeta3 / k1 + zeta4 * zeta4 / k2;
        Ok((eps, out.x[1..=7].to_vec()))
    }

    /// Closed-form largest a/b for which μ1…μ6 > 0 can hold (module docs).
    pub fn closed_form_ratio(cfg: &Config) -> f64 {
        let w = &cfg.wing;
        let alpha = w.xi * w.ei / (2.0 * w.span.powi(4));
        let beta = w.xi * w.gj / (2.0 * w.span * w.span);
        let c = 2.0 * w.rho_xc;
        let (qa, qb, qc) = (alpha * beta, -(alpha * w.ip + beta * w.rho), w.rho * w.ip - c * c);
        let disc = (qb * qb - 4.0 * qa * qc).max(0.0);
        let root = (-qb + disc.sqrt()) / (2.0 * qa);
        let x = root.max(w.rho / alpha).max(w.ip / beta);
        (1.0 / x).min(1.0 / (2.0 * w.xi.max(1e-300)))
    }
}

/// Feasible point of the conditions at the best weights, for the UUB row.
#[derive(Debug, Clone)]
pub struct BestPoint {
    /// a used (b kept from the config).
    pub a: f64,
    /// b.
    pub b: f64,
    /// λ3 at the chosen η's.
    pub lambda3: f64,
    /// λ = λ3/λ1 with the tight λ1 at (a, b).
    pub lambda: f64,
    /// ε of (32).
    pub epsilon: f64,
    /// η1..η7.
    pub etas: Vec<f64>,
}

/// Result of the μ-conditions check, reused by the UUB row.
#[derive(Debug, Clone)]
pub struct MuResult {
    /// The ledger row.
    pub row: ClaimRow,
    /// Best decay rate λ = λ3/λ1 at the configured weights (None if infeasible).
    pub lambda: Option<f64>,
    /// ε of (32) at the configured weights (None if infeasible).
    pub epsilon: Option<f64>,
    /// A feasible operating point (the configured one if feasible, else a/b = r*/2).
    pub best: Option<BestPoint>,
    /// Closed-form boundary r* of a/b.
    pub ratio_boundary: f64,
    /// Assumed disturbance bounds (g_hmax, ζ3, ζ4).
    pub bounds: (f64, f64, f64),
}

/// Tight disturbance bounds: g_hmax = max_t |φ(t)|·|slope|·s on a 1e-4 s grid over [0, T],
/// and ζ3, ζ4 = sup_t |g̃1|, |g̃2| from the FTDO simulation of the configuration.
pub fn disturbance_bounds(cfg: &Config) -> Result<(f64, f64, f64), ClaimsError> {
    let d = &cfg.disturbance.distributed;
    let steps = (cfg.horizon.t_end / 1e-4).round() as usize;
    let phi_max = (0..=steps).map(|k| d.phi(k as f64 * 1e-4).abs()).fold(0.0, f64::max);
    let g_hmax = phi_max * d.slope.abs() * cfg.wing.span;
    let ftdo = apply_overrides(cfg, &["control.kind=ftdo".into()])
        .map_err(|e| ClaimsError::Numerical { what: "config".into(), detail: e.to_string() })?;
    let s = wingcheck_sim::simulate(&ftdo, Default::default())?.series;
    let sup = |g: &[f64], h: &[f64]| g.iter().zip(h).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    Ok((g_hmax, sup(&s.g1, &s.g1_hat), sup(&s.g2, &s.g2_hat)))
}

/// Tight λ1 (sup W/κ) at weights (a, b), N = 8.
fn lambda1_at(cfg: &Config, a: f64, b: f64) -> Result<f64, ClaimsError> {
    use crate::lyapunov::{assemble, decimal, tight_constants, Coupling, LyapunovParams};
    let p = LyapunovParams::from_config(cfg, Coupling::Corrected, 8).with_weights(&decimal(a), &decimal(b));
    let f = assemble(&p).map_err(|d| ClaimsError::Numerical { what: "assembly".into(), detail: d })?;
    Ok(tight_constants(&f).map_err(|d| ClaimsError::Numerical { what: "eigen".into(), detail: d })?.lambda1)
}

/// Best (λ, ε) at weights (a, b): λ3 fixed at a fraction of λ3* chosen to minimise ε/λ.
pub fn best_point(cfg: &Config, a: f64, b: f64, bounds: (f64, f64, f64)) -> Result<Option<BestPoint>, ClaimsError> {
    let d = MuData::new(cfg, a, b);
    let top = d.max_lambda3()?;
    if !top.solved() || top.x[T] <= 0.0 {
        return Ok(None);
    }
    let l1 = lambda1_at(cfg, a, b)?;
    let sg2 = cfg.wing.span * bounds.0 * bounds.0;
    let (k1, k2) = (cfg.control.k1.max(1e-300), cfg.control.k2.max(1e-300));
    let mut best: Option<BestPoint> = None;
    for frac in [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9] {
        let t = frac * top.x[T];
        let (eps, etas) = d.min_epsilon(t, sg2, bounds.1, bounds.2, k1, k2)?;
        let cand = BestPoint { a, b, lambda3: t, lambda: t / l1, epsilon: eps, etas };
        if best.as_ref().is_none_or(|p| cand.epsilon / cand.lambda < p.epsilon / p.lambda) {
            best = Some(cand);
        }
    }
    Ok(best)
}

/// Check the μ-conditions.
pub fn check(cfg: &Config, _w: &WBounds) -> Result<MuResult, ClaimsError> {
    let start = Instant::now();
    let (a, b) = (cfg.control.a, cfg.control.b);
    let d = MuData::new(cfg, a, b);
    let top = d.max_lambda3()?;
    let feas = d.feasibility()?;
    let r_star = MuData::closed_form_ratio(cfg);
    let bounds = disturbance_bounds(cfg)?;
    // grid check of the closed form against the solver, away from the boundary
    let mut agree = 0;
    let mut total = 0;
    let mut ratios = Vec::new();
    let mut lam3 = Vec::new();
    for i in 0..24 {
        let r = r_star * 10f64.powf(-1.5 + 3.0 * i as f64 / 23.0);
        let t = MuData::new(cfg, r * b, b).max_lambda3()?;
        let margin = (r / r_star).ln().abs();
        if t.solved() && margin > 0.05 {
            total += 1;
            if (t.x[T] > 0.0) == (r < r_star) {
                agree += 1;
            }
        }
        if t.solved() {
            ratios.push(r);
            lam3.push(t.x[T]);
        }
    }
    let feasible_here = top.solved() && top.x[T] > 0.0;
    let here = if feasible_here { best_point(cfg, a, b, bounds)? } else { None };
    let best = match &here {
        Some(p) => Some(p.clone()),
        None => best_point(cfg, 0.5 * r_star * b, b, bounds)?,
    };
    let c3 = b * cfg.wing.xi * cfg.wing.ei / (2.0 * cfg.wing.span.powi(4)) - a * cfg.wing.rho;
    let mut ev = BTreeMap::new();
    ev.insert("a".into(), json!(a));
    ev.insert("b".into(), json!(b));
    ev.insert("lambda3_max".into(), json!(if top.solved() { top.x[T] } else { f64::NAN }));
    ev.insert("feasible".into(), json!(feasible_here));
    ev.insert("clarabel_feasibility_status".into(), json!(format!("{:?}", feas.status)));
    ev.insert("a_over_b_boundary_closed_form".into(), json!(r_star));
    ev.insert("closed_form_grid_agreement".into(), json!(format!("{agree}/{total}")));
    ev.insert("mu3_constant_term".into(), json!(c3));
    ev.insert("g_hmax".into(), json!(bounds.0));
    ev.insert("zeta3_sup_abs_g1_tilde".into(), json!(bounds.1));
    ev.insert("zeta4_sup_abs_g2_tilde".into(), json!(bounds.2));
    if let Some(p) = &best {
        ev.insert("best_a".into(), json!(p.a));
        ev.insert("best_lambda3".into(), json!(p.lambda3));
        ev.insert("best_lambda".into(), json!(p.lambda));
        ev.insert("best_epsilon".into(), json!(p.epsilon));
        ev.insert("best_etas_1_to_7".into(), json!(p.etas));
    }
    let (verdict, basis, summary) = if feasible_here {
        let p = here.as_ref().expect("feasible");
        (
            Verdict::Holds,
            Basis::FloatSolver,
            format!(
                "At a/b = {:.3e} < r* = {r_star:.4e} the conditions μ1…μ6 > 0 are satisfiable: λ3* = {:.4e}; at the η's minimising ε/λ, λ = {:.4e} 1/s, ε = {:.4e}. \
                 The derivation (29)–(31) itself is taken as printed (plus the silent conditions η3, η4 ≤ b/(2a)).",
                a / b, top.x[T], p.lambda, p.epsilon
            ),
        )
    } else {
        let exact = c3 < 0.0;
        (
            Verdict::Fails,
            if exact { Basis::ExactCertificate } else { Basis::FloatSolver },
            format!(
                "At a/b = {:.3} the conditions cannot hold: max λ3 over all η's is {:.4} < 0 (clarabel: {:?} for μ ≥ 0). {}They are satisfiable only for \
                 a/b < r* = {r_star:.4e} (closed form from μ3, μ4; the solver agrees at {agree}/{total} grid points), where the best λ = {:.3e} 1/s with ε = {:.3e}.",
                a / b,
                if top.solved() { top.x[T] } else { f64::NAN },
                feas.status,
                if exact {
                    format!("Exactly: μ3 ≤ bξEI/(2s⁴) − aρ = {c3:.4} < 0 for all η1, η5 ≥ 0 (Farkas certificate). ")
                } else {
                    String::new()
                },
                best.as_ref().map(|p| p.lambda).unwrap_or(f64::NAN),
                best.as_ref().map(|p| p.epsilon).unwrap_or(f64::NAN),
            ),
        )
    };
    let row = ClaimRow {
        id: "mu-conditions".into(),
        equation: "(29)–(32)".into(),
        claim: "conditions on the gains and the η's make Ẇ ≤ −λW + ε with the printed λ, ε".into(),
        verdict,
        basis,
        summary,
        correction: None,
        evidence: ev,
        highlights: ["lambda3_max", "a_over_b_boundary_closed_form", "best_lambda", "best_epsilon"].iter().map(|s| s.to_string()).collect(),
        assumptions: vec![
            format!("a = {a}, b = {b} (not given by the paper)"),
            "silent conditions added: η3 ≤ b/(2a), η4 ≤ b/(2a) (coefficients of ∫q''², ∫θ''² in (31) must be ≥ 0)".into(),
            format!("g_hmax = {:.4} = max_t |g_h| over the horizon (tight), ζ3 = {:.3e}, ζ4 = {:.3e} = sup_t |g̃| of the FTDO simulation (the ε terms bound g̃², not ĝ²)", bounds.0, bounds.1, bounds.2),
            "η8 = 1/k1, η9 = 1/k2 (the infima allowed by μ1, μ2 > 0), minimising ε".into(),
            "λ1 in λ = λ3/λ1 is the tight sup W/κ at the same (a, b)".into(),
        ],
        certificates: vec!["mu-conditions-infeasible.json".into()],
        plots: vec![PlotData {
            name: "mu-lambda3-vs-ratio".into(),
            title: format!("Best λ3 over the η's vs a/b (b = {b}); closed-form boundary r* = {r_star:.3e}"),
            x_label: "a/b".into(),
            y_label: "max λ3".into(),
            log_x: true,
            log_y: false,
            lines: vec![Line { label: "max λ3 (clarabel SOCP)".into(), x: ratios, y: lam3, points: true }],
        }],
        seconds: start.elapsed().as_secs_f64(),
    };
    let (lambda, epsilon) = match &here {
        Some(p) => (Some(p.lambda), Some(p.epsilon)),
        None => (None, None),
    };
    Ok(MuResult { row, lambda, epsilon, best, ratio_boundary: r_star, bounds })
}
