//! Theorem 1, (22)–(28): bounds 0 ≤ λ2 κ ≤ W ≤ λ1 κ of the Lyapunov function.
//!
//! 1. The printed constants y1, y2, y3, λ1 = y1 + y3, λ2 = y2 − y3 and the printed condition
//!    b > 2y3/min{ρ, I_p, EI, GJ}, evaluated exactly. Analytic argument: y3 ≥ b ρx_c, so
//!    λ2 ≤ b(m/2 − ρx_c) and the condition needs m > 2ρx_c (m = min{ρ, I_p, EI, GJ}),
//!    independently of a, b; for the paper m = 0.2 < 7, so λ2 < 0 for all a, b > 0.
//! 2. The tightest constants λ2* = inf W/κ, λ1* = sup W/κ from the exact Galerkin forms
//!    ([`crate::lyapunov`]), by a generalised eigenvalue computation (faer), cross-checked by
//!    an SDP `max λ s.t. W − λκ ⪰ 0` in clarabel, with convergence under refinement.
//! 3. The largest a/b for which W is positive definite: W = b·W_b + a·W_a, so W ≻ 0 iff
//!    a/b < −1/μ_min(W_a, W_b). With the corrected cross term b ρx_c, minimising over the
//!    velocities gives W ≥ (b/2)[P − (a/b)² ∫ xᵀMx] ⇒ a/b_max = ω₁, the fundamental natural
//!    frequency of the undamped wing (closed form, checked against the FE modes).
//! 4. An exact witness: a state (rational coefficients) with W < 0 at the configured a, b
//!    when a/b exceeds the maximum, evaluated in rational arithmetic: a proof for the PDE,
//!    since the state lies in the true state space.

use std::collections::BTreeMap;
use std::time::Instant;

use num_rational::BigRational;
use num_traits::{Signed, Zero};
use serde_json::json;
use wingcheck_cert::exact::{parse_rational, to_f64};
use wingcheck_model::Config;

use crate::lyapunov::{self, Coupling, LyapunovParams};
use crate::{Basis, ClaimRow, ClaimsError, Line, PlotData, Verdict};

/// Element counts of the refinement study.
pub const GRIDS: [usize; 4] = [2, 4, 8, 16];

/// Result of the W-bounds check, reused by the μ-conditions and UUB rows.
#[derive(Debug, Clone)]
pub struct WBounds {
    /// The ledger row.
    pub row: ClaimRow,
    /// Tightest λ1* = sup W/κ (corrected cross term, Richardson-extrapolated).
    pub lambda1_tight: Option<f64>,
    /// Tightest λ2* = inf W/κ (corrected cross term, Richardson-extrapolated).
    pub lambda2_tight: Option<f64>,
    /// Printed λ1 = y1 + y3.
    pub lambda1_printed: f64,
    /// Printed λ2 = y2 − y3.
    pub lambda2_printed: f64,
}

/// The printed constants of (26)–(28), exactly.
#[derive(Debug, Clone)]
pub struct PrintedConstants {
    /// y1 = (b/2) max{EI, I_p, GJ, ρ}.
    pub y1: BigRational,
    /// y2 = (b/2) min{ρ, EI, I_p, GJ}.
    pub y2: BigRational,
    /// y3 = max{aρ + aρx_c + bρx_c, (aρ + aρx_c)s⁴, aI_p + aρx_c + bρx_c, (aI_p + aρx_c)s²}.
    pub y3: BigRational,
    /// Whether b > 2y3/min{ρ, I_p, EI, GJ} holds.
    pub condition_holds: bool,
}

fn q(x: f64) -> BigRational {
    parse_rational(&lyapunov::decimal(x)).expect("finite config value")
}

/// Evaluate the printed constants exactly for the configuration's parameters and (a, b).
pub fn printed_constants(cfg: &Config, a: f64, b: f64) -> PrintedConstants {
    let w = &cfg.wing;
    let (rho, rxc, ei, gj, ip, s) = (q(w.rho), q(w.rho_xc), q(w.ei), q(w.gj), q(w.ip), q(w.span));
    let (a, b) = (q(a), q(b));
    let half = BigRational::new(1.into(), 2.into());
    let all = [ei.clone(), ip.clone(), gj.clone(), rho.clone()];
    let max = all.iter().max().unwrap().clone();
    let min = all.iter().min().unwrap().clone();
    let s2 = &s * &s;
    let s4 = &s2 * &s2;
    let y3 = [
        &a * &rho + &a * &rxc + &b * &rxc,
        (&a * &rho + &a * &rxc) * &s4,
        &a * &ip + &a * &rxc + &b * &rxc,
        (&a * &ip + &a * &rxc) * &s2,
    ]
    .into_iter()
    .max()
    .unwrap();
    let condition_holds = b > BigRational::from_integer(2.into()) * &y3 / &min;
    PrintedConstants { y1: &half * &b * max, y2: &half * &b * min, y3, condition_holds }
}

/// Tight constants on V_N for both cross-term variants.
fn study(cfg: &Config, coupling: Coupling) -> Result<Vec<lyapunov::TightConstants>, ClaimsError> {
    GRIDS
        .iter()
        .map(|&n| {
            let f = lyapunov::assemble(&LyapunovParams::from_config(cfg, coupling, n)).map_err(num("assembly"))?;
            lyapunov::tight_constants(&f).map_err(num("generalised eigenproblem"))
        })
        .collect()
}

/// Map a numerical failure's detail text to [`ClaimsError::Numerical`] for `what`.
pub(crate) fn num(what: &'static str) -> impl Fn(String) -> ClaimsError {
    move |detail| ClaimsError::Numerical { what: what.into(), detail }
}

/// Largest a/b with W ≻ 0 on V_N: −1/μ_min of the pencil (W(a=1,b=0), W(a=0,b=1)).
pub fn a_over_b_max(cfg: &Config, coupling: Coupling, elements: usize) -> Result<f64, ClaimsError> {
    let p = LyapunovParams::from_config(cfg, coupling, elements);
    let wa = lyapunov::assemble(&p.with_weights("1", "0")).map_err(num("assembly"))?;
    let wb = lyapunov::assemble(&p.with_weights("0", "1")).map_err(num("assembly"))?;
    let (vals, _) =
        lyapunov::generalized_eigen(&lyapunov::to_dense(&wa.w), &lyapunov::to_dense(&wb.w)).map_err(num("pencil"))?;
    Ok(-1.0 / vals[0])
}

/// An exact witness of W(x) < 0 at the configured weights (if W is indefinite there): the
/// extremal state rounded to rationals and W(x), κ(x) evaluated exactly.
pub fn indefinite_witness(cfg: &Config, elements: usize) -> Result<Option<(Vec<BigRational>, f64, f64)>, ClaimsError> {
    let f = lyapunov::assemble(&LyapunovParams::from_config(cfg, Coupling::Corrected, elements))
        .map_err(num("assembly"))?;
    let t = lyapunov::tight_constants(&f).map_err(num("eigen"))?;
    if t.lambda2 >= 0.0 {
        return Ok(None);
    }
    let x = lyapunov::round_vector(&t.argmin);
    let wx = lyapunov::quadratic_form(&f.w, &x);
    let kx = lyapunov::quadratic_form(&f.kappa, &x);
    if !wx.is_negative() || kx.is_zero() {
        return Ok(None);
    }
    Ok(Some((x, to_f64(&wx), to_f64(&kx))))
}

fn richardson(c: f64, f: f64) -> f64 {
    (4.0 * f - c) / 3.0
}

fn dense_rows(m: &faer::Mat<f64>) -> Vec<Vec<f64>> {
    (0..m.nrows()).map(|i| (0..m.ncols()).map(|j| m[(i, j)]).collect()).collect()
}

/// SDP cross-check at N = 2 (dimension 22): max λ s.t. W − λκ ⪰ 0 and max μ s.t. −W − μκ ⪰ 0
/// (so λ1 = −μ), solved by clarabel. Returns (λ2, λ1, seconds).
pub fn sdp_cross_check(cfg: &Config, coupling: Coupling) -> Result<(f64, f64, f64), ClaimsError> {
    let f = lyapunov::assemble(&LyapunovParams::from_config(cfg, coupling, 2)).map_err(num("assembly"))?;
    let w = lyapunov::to_dense(&f.w);
    let k = dense_rows(&lyapunov::to_dense(&f.kappa));
    let neg_w: Vec<Vec<f64>> = dense_rows(&w).into_iter().map(|r| r.into_iter().map(|v| -v).collect()).collect();
    let lower = wingcheck_lapack::sdp::max_generalized_lambda(&dense_rows(&w), &k)
        .map_err(|e| ClaimsError::Numerical { what: "SDP".into(), detail: e.to_string() })?;
    let upper = wingcheck_lapack::sdp::max_generalized_lambda(&neg_w, &k)
        .map_err(|e| ClaimsError::Numerical { what: "SDP".into(), detail: e.to_string() })?;
    match (lower.lambda, upper.lambda) {
        (Some(l2), Some(m)) => Ok((l2, -m, lower.solve_time + upper.solve_time)),
        _ => Err(ClaimsError::Numerical {
            what: "SDP".into(),
            detail: format!("clarabel status {:?} / {:?}", lower.status, upper.status),
        }),
    }
}

/// Check Theorem 1.
pub fn check(cfg: &Config) -> Result<WBounds, ClaimsError> {
    let start = Instant::now();
    let (a, b) = (cfg.control.a, cfg.control.b);
    let pc = printed_constants(cfg, a, b);
    let l1p = to_f64(&(&pc.y1 + &pc.y3));
    let l2p = to_f64(&(&pc.y2 - &pc.y3));
    let w = &cfg.wing;
    let m = w.rho.min(w.ip).min(w.ei).min(w.gj);
    // Numerical check of the analytic argument over a log grid of (a, b).
    let mut grid_negative = 0usize;
    let mut grid_condition = 0usize;
    let mut grid_total = 0usize;
    for i in 0..25 {
        for j in 0..25 {
            let aa = 10f64.powf(-4.0 + 0.35 * i as f64);
            let bb = 10f64.powf(-2.0 + 0.25 * j as f64);
            let p = printed_constants(cfg, aa, bb);
            grid_total += 1;
            if p.y2 < p.y3 {
                grid_negative += 1;
            }
            if p.condition_holds {
                grid_condition += 1;
            }
        }
    }
    let corrected = study(cfg, Coupling::Corrected)?;
    let printed = study(cfg, Coupling::Printed)?;
    let k = GRIDS.len();
    let l2_star = richardson(corrected[k - 2].lambda2, corrected[k - 1].lambda2);
    let l1_star = richardson(corrected[k - 2].lambda1, corrected[k - 1].lambda1);
    let l2_star_printed = richardson(printed[k - 2].lambda2, printed[k - 1].lambda2);
    let l1_star_printed = richardson(printed[k - 2].lambda1, printed[k - 1].lambda1);
    let order = ((corrected[k - 3].lambda2 - corrected[k - 2].lambda2)
        / (corrected[k - 2].lambda2 - corrected[k - 1].lambda2))
        .log2();
    let ratio_max = a_over_b_max(cfg, Coupling::Corrected, 16)?;
    let ratio_max_printed = a_over_b_max(cfg, Coupling::Printed, 16)?;
    let omega1 = {
        let mut c = cfg.clone();
        c.discretisation.method = wingcheck_model::Method::Fe;
        c.discretisation.grading = 0.0;
        let disc = wingcheck_sim::Discretisation::with(&c, wingcheck_model::Method::Fe, 16);
        wingcheck_sim::modes::natural_frequencies(&disc, 1)?[0]
    };
    let (sdp_l2, sdp_l1, sdp_seconds) = sdp_cross_check(cfg, Coupling::Corrected)?;
    let witness = indefinite_witness(cfg, 4)?;
    let ratio = a / b;

    let mut ev = BTreeMap::new();
    ev.insert("a".into(), json!(a));
    ev.insert("b".into(), json!(b));
    ev.insert("y1".into(), json!(to_f64(&pc.y1)));
    ev.insert("y2".into(), json!(to_f64(&pc.y2)));
    ev.insert("y3".into(), json!(to_f64(&pc.y3)));
    ev.insert("lambda1_printed".into(), json!(l1p));
    ev.insert("lambda2_printed".into(), json!(l2p));
    ev.insert("printed_condition_b_gt_2y3_over_min".into(), json!(pc.condition_holds));
    ev.insert("min_rho_ip_ei_gj".into(), json!(m));
    ev.insert("two_rho_xc".into(), json!(2.0 * w.rho_xc));
    ev.insert("grid_points_checked".into(), json!(grid_total));
    ev.insert("grid_points_lambda2_printed_negative".into(), json!(grid_negative));
    ev.insert("grid_points_condition_holds".into(), json!(grid_condition));
    ev.insert("lambda1_tight".into(), json!(l1_star));
    ev.insert("lambda2_tight".into(), json!(l2_star));
    ev.insert("lambda1_tight_printed_cross_term".into(), json!(l1_star_printed));
    ev.insert("lambda2_tight_printed_cross_term".into(), json!(l2_star_printed));
    ev.insert("lambda2_refinement_order".into(), json!(order));
    ev.insert(
        "lambda2_by_elements".into(),
        json!(GRIDS
            .iter()
            .zip(&corrected)
            .map(|(n, t)| json!({"elements": n, "lambda2": t.lambda2, "lambda1": t.lambda1}))
            .collect::<Vec<_>>()),
    );
    ev.insert("a_over_b_max".into(), json!(ratio_max));
    ev.insert("a_over_b_max_printed_cross_term".into(), json!(ratio_max_printed));
    ev.insert("omega1_rad_s".into(), json!(omega1));
    ev.insert("sdp_lambda2_n2".into(), json!(sdp_l2));
    ev.insert("sdp_lambda1_n2".into(), json!(sdp_l1));
    ev.insert("eig_lambda2_n2".into(), json!(corrected[0].lambda2));
    ev.insert("eig_lambda1_n2".into(), json!(corrected[0].lambda1));
    ev.insert("sdp_seconds".into(), json!(sdp_seconds));
    if let Some((_, wx, kx)) = &witness {
        ev.insert("witness_w".into(), json!(wx));
        ev.insert("witness_kappa".into(), json!(kx));
    }

    let pd_here = ratio < ratio_max;
    let (verdict, basis, summary, correction) = if pd_here {
        (
            Verdict::HoldsAfterCorrection,
            Basis::FloatSolver,
            format!(
                "As printed, λ2 = y2 − y3 = {l2p:.4} < 0 (so '0 ≤ λ2 κ' is false) and the condition b > 2y3/min{{ρ,I_p,EI,GJ}} can never hold \
                 here: y3 ≥ bρx_c forces min{{…}} = {m} > 2ρx_c = {}. But at a/b = {ratio:.4} < a/b_max = {ratio_max:.5} (= ω₁ = {omega1:.5} rad/s with \
                 the corrected cross term) W is positive definite: tight λ2* = {l2_star:.5}, λ1* = {l1_star:.5} (Galerkin, extrapolated; SDP at N = 2 agrees).",
                2.0 * w.rho_xc
            ),
            Some(format!(
                "replace λ2 = y2 − y3 by the tight λ2* = inf W/κ = {l2_star:.5} and λ1 by λ1* = {l1_star:.5}; positive iff a/b < ω₁ (cross term −bρx_c∫q̇θ̇)"
            )),
        )
    } else {
        (
            Verdict::Fails,
            if witness.is_some() { Basis::ExactCertificate } else { Basis::FloatSolver },
            format!(
                "As printed, λ2 = y2 − y3 = {l2p:.4} < 0, so '0 ≤ λ2 κ' is false; λ2 < 0 for every a, b > 0 because y3 ≥ bρx_c and min{{ρ,I_p,EI,GJ}} = {m} < 2ρx_c = {} \
                 (all {grid_negative}/{grid_total} grid points agree), and the printed condition on b is unsatisfiable. Worse, at a/b = {ratio:.4} W itself is indefinite: \
                 tight λ2* = {l2_star:.4} < 0 (λ1* = {l1_star:.4}); an exact rational state with W = {:.4e} < 0 proves it. W ≻ 0 only for a/b < {ratio_max:.5} = ω₁.",
                2.0 * w.rho_xc,
                witness.as_ref().map(|w| w.1).unwrap_or(f64::NAN)
            ),
            Some(format!("choose a/b < ω₁ = {omega1:.5} rad/s and use the tight λ2* (positive there) instead of y2 − y3")),
        )
    };
    let plots = vec![PlotData {
        name: "w-bounds-refinement".into(),
        title: format!(
            "Tight bounds of W/κ vs elements (a = {a}, b = {b}); extrapolated λ2* = {l2_star:.4}, λ1* = {l1_star:.4}"
        ),
        x_label: "elements N".into(),
        y_label: "W/κ extremes".into(),
        log_x: true,
        log_y: false,
        lines: vec![
            Line {
                label: "λ2(N) = min W/κ".into(),
                x: GRIDS.iter().map(|&n| n as f64).collect(),
                y: corrected.iter().map(|t| t.lambda2).collect(),
                points: true,
            },
            Line {
                label: "λ1(N) = max W/κ".into(),
                x: GRIDS.iter().map(|&n| n as f64).collect(),
                y: corrected.iter().map(|t| t.lambda1).collect(),
                points: true,
            },
        ],
    }];
    let row = ClaimRow {
        id: "W-bounds".into(),
        equation: "(22)–(28), Theorem 1".into(),
        claim: "0 ≤ λ2 κ ≤ W ≤ λ1 κ with the printed λ1, λ2, y1–y3".into(),
        verdict,
        basis,
        summary,
        correction,
        evidence: ev,
        highlights: ["lambda2_printed", "lambda1_printed", "lambda2_tight", "lambda1_tight", "a_over_b_max"].iter().map(|s| s.to_string()).collect(),
        assumptions: vec![
            format!("a = {a}, b = {b} (the paper does not give them)"),
            "W_o's last term read as −b ρx_c ∫q̇θ̇ (the paper prints b x_c; the bound (27) uses bρx_c); the printed variant is reported too".into(),
            format!("state space discretised by cubic Hermite q, linear θ, discontinuous cubic velocities on N ∈ {GRIDS:?} uniform elements; infimum over velocities exact"),
        ],
        certificates: ["w-bounds-indefinite.json", "w-bounds-lower.json", "w-bounds-upper.json", "w-bounds-ratio-above.json", "w-bounds-ratio-below.json"]
            .iter()
            .map(|s| s.to_string())
            .collect(),
        plots,
        seconds: start.elapsed().as_secs_f64(),
    };
    Ok(WBounds {
        row,
        lambda1_tight: Some(l1_star),
        lambda2_tight: Some(l2_star),
        lambda1_printed: l1p,
        lambda2_printed: l2p,
    })
}
