//! The second-order-cone cross-checks of the closed forms of (29)–(32) ([`crate::MuData`]).
//!
//! Scale-free formulation: every η is written as η_i = S_i·y_i with S_i an upper bound of η_i
//! read off the data (S1 = m3/b, S2 = m4/(b x), S3 = S4 = b/(2a), S5 = √(m3/m4),
//! S6 = EI/s⁴, S7 = GJ/(s² x), where m3 = bξEI/(2s⁴) + aρ and m4 = bξGJ/(2s²) + aI_p are the
//! magnitudes of the η-free parts of μ3, μ4), and each row μ_i ≥ t is divided by its magnitude
//! (m3, m4, aEI, aGJ). Under (a, b) → (ca, cb) every scaled coefficient is unchanged, so the
//! solver sees the same problem at every scale; no artificial bounds are imposed (the scaled
//! feasible sets are bounded by the rows themselves).
//!
//! A solver answer is accepted only with status `Solved` or `AlmostSolved` (recorded in the
//! evidence) and only after its η's are put back into the printed formulas of μ3..μ6 and ε:
//! each μ_i must be ≥ t − [`ROW_TOLERANCE`]·max(m_i, |t|), η ≥ 0, η3, η4 ≤ b/(2a) to the same
//! relative tolerance. Any other status is recorded and the answer is not used.

use serde::Serialize;

use crate::socp::Socp;
use crate::{Etas, MuData};

/// Relative tolerance of a re-verified row: μ_i(η) ≥ t − ROW_TOLERANCE · m_i.
pub const ROW_TOLERANCE: f64 = 1e-7;

/// The outcome of one cross-check.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
pub struct CrossCheck {
    /// Clarabel's status.
    pub status: crate::status::SolveStatus,
    /// Solved and re-verified against the printed constraints.
    pub accepted: bool,
    /// Largest violation of a row, relative to the row's magnitude (≤ 0: none).
    pub max_row_violation: f64,
    /// The solver's value, recomputed from its η's with the printed formulas.
    pub solver_value: f64,
    /// The closed form's value.
    pub closed_form_value: f64,
    /// |solver − closed form| relative to the problem's scale (ε: the value; λ3*: the largest
    /// row magnitude m_i, the scale to which the solver resolves a row).
    pub relative_difference: f64,
    /// Solve time (s); not reproducible content, so not serialised.
    #[serde(skip)]
    pub seconds: f64,
}

struct Scales {
    m: [f64; 4],
    s: [f64; 7],
}

fn scales(d: &MuData) -> Scales {
    let m3 = d.b * d.xi * d.ei / (2.0 * d.s.powi(4)) + d.a * d.rho;
    let m4 = d.b * d.xi * d.gj / (2.0 * d.s * d.s) + d.a * d.ip;
    let x = if d.x > 0.0 { d.x } else { 1.0 };
    Scales {
        m: [m3, m4, d.a * d.ei, d.a * d.gj],
        s: [
            m3 / d.b,
            m4 / (d.b * x),
            d.b / (2.0 * d.a),
            d.b / (2.0 * d.a),
            (m3 / m4).sqrt(),
            d.ei / d.s.powi(4),
            d.gj / (d.s * d.s * x),
        ],
    }
}

// variable layout: y1..y7 = 0..6, w3, w4, w5 (reciprocals of y3, y4, y5) = 7, 8, 9,
// v1, v2, v6, v7 (reciprocals of y1, y2, y6, y7) = 10..13, τ = 14
const W3: usize = 7;
const W4: usize = 8;
const W5: usize = 9;
const TAU: usize = 14;

/// The scaled rows μ_i ≥ t (t = τ·t_scale if `tau`, else the fixed `t`).
fn rows(d: &MuData, sc: &Scales, p: &mut Socp, t: Option<f64>, t_scale: f64) {
    let [m3, m4, m5, m6] = sc.m;
    let s = &sc.s;
    let c = d.c();
    let x = d.x;
    let tcol = |p: &mut Socp, mut row: Vec<(usize, f64)>, m: f64, rhs: f64| {
        match t {
            Some(t) => {
                p.le(row, rhs - t / m);
            }
            None => {
                row.push((TAU, t_scale / m));
                p.le(row, rhs);
            }
        };
    };
    let a3 = d.b * d.xi * d.ei / (2.0 * d.s.powi(4)) - d.a * d.rho;
    let a4 = d.b * d.xi * d.gj / (2.0 * d.s * d.s) - d.a * d.ip;
    tcol(p, vec![(0, d.b * s[0] / m3), (4, c * s[4] / m3)], m3, a3 / m3);
    tcol(p, vec![(1, d.b * x * s[1] / m4), (W5, c / (s[4] * m4))], m4, a4 / m4);
    tcol(p, vec![(W3, d.a * d.xi * d.ei / (s[2] * m5)), (5, d.a * d.s.powi(4) * s[5] / m5)], m5, 1.0);
    tcol(p, vec![(W4, d.a * d.xi * d.gj / (s[3] * m6)), (6, d.a * d.s * d.s * x * s[6] / m6)], m6, 1.0);
    let cap = d.b / (2.0 * d.a);
    p.le(vec![(2, 1.0)], cap / s[2]).le(vec![(3, 1.0)], cap / s[3]);
    // a variable that enters no row (x = 0: y2, y7; c = 0: y5, w5; ξ = 0: w3, w4) is pinned
    // to ≤ 1, so that no direction of the feasible set is unbounded
    let entered: Vec<usize> =
        p.le.iter().flat_map(|(r, _)| r.iter().filter(|(_, v)| *v > 0.0).map(|(c, _)| *c)).collect();
    for var in [1, 4, 5, 6, W3, W4, W5] {
        if !entered.contains(&var) {
            p.le(vec![(var, 1.0)], 1.0);
        }
    }
    for i in 0..7 {
        p.le(vec![(i, -1.0)], 0.0);
    }
    p.hyperbolic(W3, 2, 1.0).hyperbolic(W4, 3, 1.0).hyperbolic(W5, 4, 1.0);
}

fn etas_of(sc: &Scales, y: &[f64]) -> Etas {
    // interior-point iterates may sit a rounding error below 0 on y ≥ 0; the rows are
    // re-verified with the clamped values
    let mut e = [0.0; 7];
    for i in 0..7 {
        e[i] = sc.s[i] * y[i].max(0.0);
    }
    Etas(e)
}

fn epsilon_objective(d: &MuData, sc: &Scales, p: &mut Socp) {
    let x = d.x;
    let coef = [d.b / sc.s[0], d.b * x / sc.s[1], d.a / sc.s[5], d.a * x / sc.s[6]];
    let total: f64 = coef.iter().sum();
    for (k, (v, y)) in [(10, 0), (11, 1), (12, 5), (13, 6)].into_iter().enumerate() {
        if coef[k] > 0.0 {
            p.hyperbolic(v, y, 1.0);
            p.cost[v] = coef[k] / total;
        } else {
            p.le(vec![(v, 1.0)], 0.0).le(vec![(v, -1.0)], 0.0);
        }
    }
    p.le(vec![(TAU, 1.0)], 0.0).le(vec![(TAU, -1.0)], 0.0);
}

fn violation(d: &MuData, sc: &Scales, e: &Etas, t: f64) -> f64 {
    let mus = d.mus(e);
    let mut worst = f64::NEG_INFINITY;
    for i in 0..4 {
        worst = worst.max((t - mus[i]) / sc.m[i].max(t.abs()));
    }
    let cap = d.b / (2.0 * d.a);
    worst = worst.max((e.0[2] - cap) / cap).max((e.0[3] - cap) / cap);
    if e.0.iter().any(|v| !v.is_finite() || *v < 0.0) {
        return f64::INFINITY;
    }
    worst
}

/// A point worth re-verifying ([`crate::status::worth_reverifying`]); used only if it passes
/// the re-verification, and the status is recorded.
fn usable(out: &crate::socp::SocpOutcome) -> bool {
    crate::status::worth_reverifying(out.status, &out.x)
}

/// Passes of re-scaling: after each solve every η scale is multiplied by the solver's y, so
/// that the next solve sees its optimum near y = 1 (a rotated cone u·η ≥ 1 is resolved to a
/// relative accuracy only when u and η are of similar size).
pub const RESCALE_PASSES: usize = 6;

fn solve_rescaled(
    d: &MuData,
    build: impl Fn(&Scales) -> Socp,
    read: impl Fn(&Scales, &[f64]) -> (Etas, f64, f64),
    closed: f64,
    scale: f64,
) -> CrossCheck {
    let mut sc = scales(d);
    let mut seconds = 0.0;
    let mut last = None;
    for _ in 0..RESCALE_PASSES {
        let out = match build(&sc).solve() {
            Ok(o) => o,
            Err(e) => {
                return CrossCheck {
                    status: crate::status::SolveStatus::NotRun(format!("setup error: {e}")),
                    accepted: false,
                    max_row_violation: 0.0,
                    solver_value: 0.0,
                    closed_form_value: closed,
                    relative_difference: 0.0,
                    seconds,
                }
            }
        };
        seconds += out.seconds;
        let solved = usable(&out);
        if !solved {
            // keep the last solved pass, if any (its point is re-verified below)
            if last.is_none() {
                last = Some((out, sc.s));
            }
            break;
        }
        let mut converged = true;
        let mut next = sc.s;
        for i in 0..7 {
            let y = out.x[i];
            if y > 0.0 {
                converged &= y.ln().abs() < 1e-3;
                next[i] = sc.s[i] * y;
            }
        }
        last = Some((out, sc.s));
        if converged {
            break;
        }
        sc.s = next;
    }
    let (out, used) = last.expect("at least one pass");
    sc.s = used;
    let solved = usable(&out);
    let (e, t, value) = if solved { read(&sc, &out.x) } else { (Etas([0.0; 7]), 0.0, 0.0) };
    let viol = if solved { violation(d, &sc, &e, t) } else { 0.0 };
    let accepted = solved && viol <= ROW_TOLERANCE && value.is_finite();
    let rel = if accepted { (value - closed).abs() / scale.abs().max(f64::MIN_POSITIVE) } else { 0.0 };
    CrossCheck {
        status: crate::status::SolveStatus::Clarabel(out.status),
        accepted,
        max_row_violation: if viol.is_finite() { viol } else { f64::MAX },
        solver_value: if accepted { value } else { 0.0 },
        closed_form_value: closed,
        relative_difference: rel,
        seconds,
    }
}

/// Cross-check λ3* = sup min{μ3..μ6} (a, b > 0) by `max τ` in clarabel.
pub fn check_lambda3(d: &MuData) -> CrossCheck {
    let m = scales(d).m;
    let t_scale = m.iter().cloned().fold(f64::INFINITY, f64::min);
    // the solver resolves each row to a fraction of its largest term: compare on that scale
    let accuracy_scale = m.iter().cloned().fold(0.0, f64::max);
    let closed = d.lambda3_sup();
    solve_rescaled(
        d,
        |sc| {
            let mut p = Socp::new(15);
            rows(d, sc, &mut p, None, t_scale);
            p.cost[TAU] = -1.0;
            for v in 10..14 {
                p.le(vec![(v, 1.0)], 0.0).le(vec![(v, -1.0)], 0.0);
            }
            p
        },
        |sc, x| {
            let e = etas_of(sc, x);
            let t = x[TAU] * t_scale;
            (e, t, d.mus(&e).iter().cloned().fold(f64::INFINITY, f64::min))
        },
        closed,
        accuracy_scale,
    )
}

/// Cross-check min ε_η subject to μ3..μ6 ≥ t (0 < t < λ3*) in clarabel; values are
/// ε_η/(s g²) = b/η1 + bx/η2 + a/η6 + ax/η7.
pub fn check_epsilon(d: &MuData, t: f64) -> CrossCheck {
    let closed = d.epsilon_eta_min(t, 1.0) / d.s;
    solve_rescaled(
        d,
        |sc| {
            let mut p = Socp::new(15);
            rows(d, sc, &mut p, Some(t), 1.0);
            epsilon_objective(d, sc, &mut p);
            p
        },
        |sc, xs| {
            let e = etas_of(sc, xs);
            (e, t, d.epsilon_eta_part(&e, 1.0) / d.s)
        },
        closed,
        closed.abs(),
    )
}
