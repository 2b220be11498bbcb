//! Theorem 1, (22)–(28): bounds 0 ≤ λ2 κ ≤ W ≤ λ1 κ of the Lyapunov function.
//!
//! 1. The printed constants y1, y2, y3, λ1 = y1 + y3, λ2 = y2 − y3 and the printed condition
//!    b > 2y3/min{ρ, I_p, EI, GJ}, evaluated exactly. Analytic argument: y3 ≥ b ρx_c, so
//!    λ2 ≤ b(m/2 − ρx_c) and the condition needs m > 2ρx_c (m = min{ρ, I_p, EI, GJ}),
//!    independently of a, b; for the paper m = 0.2 < 7, so λ2 < 0 for all a, b > 0.
//! 2. The tightest constants λ2* = inf W/κ, λ1* = sup W/κ from the exact Galerkin forms
//!    ([`wingcheck_theory::lyapunov`]), by a generalised eigenvalue computation (faer), with convergence
//!    under refinement; cross-checked at N = 2 … 32 by the SDPs `max λ s.t. W − λκ ⪰ 0` and
//!    `max μ s.t. −W − μκ ⪰ 0` in clarabel ([`wingcheck_theory::sdp::pencil_cross_check`]), re-verified.
//! 3. The largest a/b for which W is positive definite: W = b·W_b + a·W_a, so W ≻ 0 iff
//!    a/b < −1/μ_min(W_a, W_b). With the corrected cross term b ρx_c, minimising over the
//!    velocities gives W ≥ (b/2)[P − (a/b)² ∫ xᵀMx] ⇒ a/b_max = ω₁, the fundamental natural
//!    frequency of the undamped wing (closed form, checked against the FE modes). The decision
//!    rests on the certified enclosure ω̲₁ ≤ ω₁ ≤ ω̄₁ of the continuous model
//!    ([`crate::certify::omega1`], exact): W ≻ 0 for a/b < ω̲₁, W not ≻ 0 for a/b > ω̄₁. Inside
//!    the enclosure (or without one) it falls back to ω₁ converged over uniform FE meshes with
//!    its error estimate ([`theory::w_threshold`], evidence): a/b within that error is "at the
//!    threshold" (inconclusive).
//! 4. An exact witness: a state (rational coefficients) with W < 0 at the configured a, b
//!    when a/b exceeds the maximum, evaluated in rational arithmetic: a proof for the PDE,
//!    since the state lies in the true state space.

mod explain;
mod records;
mod text;

use crate::numerics::NumericsError;
use num_rational::BigRational;
use num_traits::{Signed, Zero};
use wingcheck_cert::exact::{parse_rational, to_f64};
use wingcheck_cert::fe::{ClampedMesh, Space};
use wingcheck_model::Config;

use crate::certify::omega1::{EnclosureSummary, Position};
use crate::settings::CheckSettings;
use crate::{ClaimsError, WallTime};
use wingcheck_theory::lyapunov::{self, Coupling, LyapunovParams};
use wingcheck_theory::sdp::PencilSdpRow;
use wingcheck_theory::{self as theory, Decision, Estimate};

pub use explain::{
    check, check_cancellable, evidence, evidence_cancellable, EnclosureEvidence, WBounds, WBoundsEvidence,
};
pub use records::SdpRecord;
pub use text::sdp_sentence;

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

/// The wing's part of the printed constants of (26)–(28), exactly: what [`PrintedWing::at`]
/// combines with each (a, b).
#[derive(Debug, Clone)]
pub struct PrintedWing {
    /// max{EI, I_p, GJ, ρ}.
    max: BigRational,
    /// min{EI, I_p, GJ, ρ}.
    min: BigRational,
    /// ρx_c.
    rho_xc: BigRational,
    /// ρ + ρx_c.
    rho_sum: BigRational,
    /// (ρ + ρx_c)s⁴.
    rho_sum_s4: BigRational,
    /// I_p + ρx_c.
    ip_sum: BigRational,
    /// (I_p + ρx_c)s².
    ip_sum_s2: BigRational,
}

impl PrintedWing {
    /// The wing of `cfg`, its values read exactly from their shortest decimal texts.
    pub fn of(cfg: &Config) -> Self {
        let w = &cfg.wing;
        let (rho, rho_xc, ei, gj, ip, s) = (q(w.rho), q(w.rho_xc), q(w.ei), q(w.gj), q(w.ip), q(w.span));
        let all = [ei, ip.clone(), gj, rho.clone()];
        let s2 = &s * &s;
        let rho_sum = &rho + &rho_xc;
        let ip_sum = &ip + &rho_xc;
        PrintedWing {
            max: all.iter().max().expect("four values").clone(),
            min: all.iter().min().expect("four values").clone(),
            rho_sum_s4: &rho_sum * &s2 * &s2,
            ip_sum_s2: &ip_sum * &s2,
            rho_sum,
            ip_sum,
            rho_xc,
        }
    }

    /// The printed constants at weights (a, b), exactly.
    pub fn at(&self, a: f64, b: f64) -> PrintedConstants {
        let (a, b) = (q(a), q(b));
        let b_rho_xc = &b * &self.rho_xc;
        let y3 = [
            &a * &self.rho_sum + &b_rho_xc,
            &a * &self.rho_sum_s4,
            &a * &self.ip_sum + &b_rho_xc,
            &a * &self.ip_sum_s2,
        ]
        .into_iter()
        .max()
        .expect("four values");
        // b > 2y3/min ⇔ b·min > 2y3 (min > 0: the configuration's values are positive)
        let condition_holds = &b * &self.min > BigRational::from_integer(2.into()) * &y3;
        let half = BigRational::new(1.into(), 2.into());
        PrintedConstants { y1: &half * &b * &self.max, y2: &half * &b * &self.min, y3, condition_holds }
    }
}

/// Evaluate the printed constants exactly for the configuration's parameters and (a, b).
pub fn printed_constants(cfg: &Config, a: f64, b: f64) -> PrintedConstants {
    PrintedWing::of(cfg).at(a, b)
}

/// Tight constants on V_N for both cross-term variants.
fn study(cfg: &Config, coupling: Coupling, grids: &[usize]) -> Result<Vec<Extremes>, ClaimsError> {
    grids
        .iter()
        .map(|&n| {
            let f = lyapunov::assemble(&LyapunovParams::from_config(cfg, coupling, n)).map_err(num("assembly"))?;
            let t = lyapunov::tight_constants(&f).map_err(num("generalised eigenproblem"))?;
            Ok(Extremes::of(&f, &t))
        })
        .collect()
}

/// λ2(N) = min W/κ and λ1(N) = max W/κ on one Galerkin space as the exact Rayleigh quotients
/// ρ(x) = xᵀWx/xᵀκx of the float solver's extremal vectors x (W, κ exact rationals, x converted
/// exactly), so λ2(N) ≤ ρ(x_min) and ρ(x_max) ≤ λ1(N) hold exactly and their distance is second
/// order in the vectors' errors; with the round-off of each: the float eigenvalue's distance
/// from it (first order in the same errors, so an overestimate) plus 4 ulp. The float
/// eigenvalues alone are off by far more than a fixed multiple of max |W/κ| on stiff wings
/// (measured: 8.4e-6 at 5e6 on an SI-scale wing at N = 16, 7.4× 1024 ulp of the scale; 1.4e-3 at
/// 4e8 with a = 0.02, b = 80, 15×; 4.1e-12 at 9.9 on the paper's wing, 1.8×): κ's condition
/// grows like h⁻⁴.
#[derive(Debug, Clone, Copy)]
struct Extremes {
    lambda2: f64,
    lambda1: f64,
    roundoff2: f64,
    roundoff1: f64,
}

impl Extremes {
    fn of(f: &lyapunov::ExactForms, t: &lyapunov::TightConstants) -> Extremes {
        let quotient = |x: &[f64], float: f64| {
            let exact: Option<Vec<BigRational>> = x.iter().map(|v| BigRational::from_float(*v)).collect();
            let rho = exact.and_then(|x| {
                let k = lyapunov::quadratic_form(&f.kappa, &x);
                (!k.is_zero()).then(|| to_f64(&(lyapunov::quadratic_form(&f.w, &x) / k)))
            });
            match rho {
                Some(r) if r.is_finite() => (r, (float - r).abs() + 4.0 * f64::EPSILON * r.abs()),
                // no usable vector (a non-finite entry, κ(x) = 0): the float value, unresolved
                _ => (float, float.abs()),
            }
        };
        let (lambda2, roundoff2) = quotient(&t.argmin, t.lambda2);
        let (lambda1, roundoff1) = quotient(&t.argmax, t.lambda1);
        Extremes { lambda2, lambda1, roundoff2, roundoff1 }
    }
}

/// Map a numerical failure to [`ClaimsError::Numerical`] for `what`.
pub(crate) fn num<E: Into<NumericsError>>(what: &'static str) -> impl Fn(E) -> ClaimsError {
    move |cause| ClaimsError::Numerical { what, cause: cause.into() }
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

/// Richardson extrapolation of an O(h²) value from meshes h and h/2.
fn richardson(c: f64, f: f64) -> f64 {
    (4.0 * f - c) / 3.0
}

/// SDP cross-check of λ2(N) = min W/κ and λ1(N) = max W/κ at N ∈ `grids`: clarabel on
/// max λ s.t. W − λκ ⪰ 0 and max μ s.t. −W − μκ ⪰ 0 (λ1 = −μ), with the velocities eliminated
/// exactly and the displacements in the hierarchical basis ([`wingcheck_theory::sdp::pencil_cross_check`]),
/// each answer re-verified and compared with the eigenvalues at the same N. A failure at one N
/// is recorded in its row, never fatal.
///
/// Bounded, deterministically: the whole cross-check spends at most
/// [`wingcheck_theory::sdp::SDP_ITERATION_BUDGET`] interior-point iterations (16–20 per N on the paper's
/// wing, far more on wings whose parameters span many decades); a solve at the budget stops
/// with status `MaxIterations` and the remaining N are not run, each saying why. The same
/// input gives the same rows whatever the machine's speed or load.
pub fn sdp_cross_check(cfg: &Config, coupling: Coupling, grids: &[usize]) -> Vec<PencilSdpRow> {
    sdp_cross_check_cancellable(cfg, coupling, grids, &wingcheck_model::Cancel::new())
}

/// [`sdp_cross_check`] stopped once `cancel` is set: the solve in flight ends at its next
/// interior-point iteration and the remaining N are not run (their rows say so).
pub fn sdp_cross_check_cancellable(
    cfg: &Config,
    coupling: Coupling,
    grids: &[usize],
    cancel: &wingcheck_model::Cancel,
) -> Vec<PencilSdpRow> {
    let mut budget = wingcheck_theory::sdp::SDP_ITERATION_BUDGET;
    grids
        .iter()
        .map(|&n| {
            if cancel.is_cancelled() {
                return PencilSdpRow::not_run(n, "not run: cancelled");
            }
            if budget == 0 {
                return PencilSdpRow::not_run(
                    n,
                    &format!(
                        "not run: the cross-check's budget of {} solver iterations was spent on the smaller N",
                        wingcheck_theory::sdp::SDP_ITERATION_BUDGET
                    ),
                );
            }
            let f = match lyapunov::assemble(&LyapunovParams::from_config(cfg, coupling, n)) {
                Ok(f) => f,
                Err(e) => return PencilSdpRow::not_run(n, &format!("assembly: {e}")),
            };
            let mesh = ClampedMesh::new(q(cfg.wing.span), n);
            let c1 = lyapunov::to_dense(&mesh.mass(Space::DgCubic, Space::Hermite));
            let c2 = lyapunov::to_dense(&mesh.mass(Space::DgCubic, Space::Linear));
            let (w, k) = (lyapunov::to_dense(&f.w), lyapunov::to_dense(&f.kappa));
            wingcheck_theory::sdp::pencil_cross_check_within(&w, &k, &c1, &c2, n, cfg.wing.span, &mut budget, cancel)
        })
        .collect()
}

/// The tight constants λ2* = inf W/κ and λ1* = sup W/κ, each Richardson-extrapolated from the
/// two finest meshes of the study with the error |extrapolated − finest| (O(h²) convergence,
/// observed order reported), the per-N values (λ2(N) ≥ λ2*, λ1(N) ≤ λ1*: Galerkin extremes on
/// a subspace), and the observed order of λ2(N).
#[derive(Debug, Clone)]
pub struct TightStudy {
    /// (N, λ2(N), λ1(N)).
    pub by_elements: Vec<(usize, f64, f64)>,
    /// λ2* with its error.
    pub lambda2: Estimate,
    /// λ1* with its error.
    pub lambda1: Estimate,
    /// Observed refinement order of λ2(N) (None when the differences vanish).
    pub order: Option<f64>,
}

/// The refinement study of W/κ on `grids` (coarse → fine, at least three meshes), each mesh's
/// extremes as exact Rayleigh quotients of the solver's vectors ([`Extremes`]).
/// The extrapolated λ's errors: the last refinement's change (grid, extrapolation) plus the
/// round-off of both meshes' values through the extrapolation.
pub fn tight_study(cfg: &Config, coupling: Coupling, grids: &[usize]) -> Result<TightStudy, ClaimsError> {
    let t = study(cfg, coupling, grids)?;
    let k = t.len();
    // the extrapolation (4f − c)/3 carries the round-off of both meshes' values: (4r_f + r_c)/3
    let ex = |c: f64, f: f64, rc: f64, rf: f64| {
        let v = richardson(c, f);
        Estimate { value: v, error: (v - f).abs() + (4.0 * rf + rc) / 3.0 }
    };
    let (c, f) = (t[k - 2], t[k - 1]);
    Ok(TightStudy {
        by_elements: grids.iter().zip(&t).map(|(n, x)| (*n, x.lambda2, x.lambda1)).collect(),
        lambda2: ex(c.lambda2, f.lambda2, c.roundoff2, f.roundoff2),
        lambda1: ex(c.lambda1, f.lambda1, c.roundoff1, f.roundoff1),
        order: wingcheck_sim::estimate::observed_order(t[k - 3].lambda2, c.lambda2, f.lambda2),
    })
}

/// Everything the W-bounds row computes, before it is put into words.
pub struct Computed {
    /// The printed constants at the configured (a, b).
    pub printed: PrintedConstants,
    /// Over the 25 × 25 (a, b) grid: (points, printed λ2 < 0, printed condition holds).
    pub printed_grid: (usize, usize, usize),
    /// Tight constants, corrected cross term.
    pub corrected: TightStudy,
    /// Tight constants, printed cross term.
    pub printed_cross: TightStudy,
    /// ω₁ (rad/s) converged, the W ≻ 0 threshold of a/b.
    pub omega1: Estimate,
    /// The threshold on the finest Galerkin space of the study (an upper bound of ω₁).
    pub ratio_galerkin: (usize, f64),
    /// The same with the printed cross term.
    pub ratio_printed_cross: f64,
    /// An exact witness of W(x) < 0 at the configured weights: (W(x), κ(x)).
    pub witness: Option<(f64, f64)>,
    /// The certified enclosure ω̲₁ ≤ ω₁ ≤ ω̄₁ of the continuous model, or why there is none.
    pub enclosure: EnclosureSummary,
    /// The SDP cross-check per N.
    pub sdp: Vec<PencilSdpRow>,
    /// Wall time of the SDP cross-check (s).
    pub sdp_seconds: f64,
    /// Wall time of the enclosure (s).
    pub enclosure_seconds: f64,
}

/// W ≻ 0 from the enclosure when a/b lies outside it (exact, for the continuous model), else
/// the float decision `float` against the converged ω₁.
pub fn decide(enclosure: &EnclosureSummary, float: Decision) -> Decision {
    match enclosure.position() {
        Some(Position::Below) => Decision::Yes,
        Some(Position::Above) => Decision::No,
        Some(Position::Inside) | None => float,
    }
}

/// Compute everything; the SDP cross-check and the ω₁ enclosure (independent of the rest) run
/// beside it on the thread pool ([`crate::beside`]), and their failure is recorded, never fatal.
pub fn compute(cfg: &Config, settings: &CheckSettings) -> Result<Computed, ClaimsError> {
    compute_cancellable(cfg, settings, &wingcheck_model::Cancel::new())
}

/// [`compute`] whose SDP cross-check stops once `cancel` is set.
pub fn compute_cancellable(
    cfg: &Config,
    settings: &CheckSettings,
    cancel: &wingcheck_model::Cancel,
) -> Result<Computed, ClaimsError> {
    let sdp = || crate::seconds(|| sdp_cross_check_cancellable(cfg, Coupling::Corrected, &settings.sdp_grids, cancel));
    let enclosure = || crate::seconds(|| EnclosureSummary::deciding(cfg));
    let rest = || -> Result<Computed, ClaimsError> {
        let (a, b) = (cfg.control.a, cfg.control.b);
        let (mut neg, mut cond, mut total) = (0usize, 0usize, 0usize);
        let wing = PrintedWing::of(cfg);
        for i in 0..25 {
            for j in 0..25 {
                let p = wing.at(10f64.powf(-4.0 + 0.35 * i as f64), 10f64.powf(-2.0 + 0.25 * j as f64));
                total += 1;
                neg += usize::from(p.y2 < p.y3);
                cond += usize::from(p.condition_holds);
            }
        }
        let grids = &settings.w_grids;
        let finest = grids[grids.len() - 1];
        let witness = indefinite_witness(cfg, 4)?.map(|w| (w.1, w.2));
        Ok(Computed {
            printed: wing.at(a, b),
            printed_grid: (total, neg, cond),
            corrected: tight_study(cfg, Coupling::Corrected, grids)?,
            printed_cross: tight_study(cfg, Coupling::Printed, grids)?,
            omega1: theory::w_threshold(cfg)?,
            ratio_galerkin: (finest, lyapunov::a_over_b_max(cfg, Coupling::Corrected, finest).map_err(num("pencil"))?),
            ratio_printed_cross: lyapunov::a_over_b_max(cfg, Coupling::Printed, finest).map_err(num("pencil"))?,
            witness,
            enclosure: EnclosureSummary::NotCertified { reason: "not computed".into() },
            enclosure_seconds: 0.0,
            sdp: Vec::new(),
            sdp_seconds: 0.0,
        })
    };
    // The SDP ladder is the ledger's longest sequential chain: it starts at once on this thread.
    let (sdp, (enclosure, computed)) = crate::first_beside(sdp, || crate::beside(enclosure, rest));
    let mut computed = computed?;
    (computed.sdp, computed.sdp_seconds) = sdp.unwrap_or_else(|p| {
        let why = format!("the SDP computation failed: {p}");
        (settings.sdp_grids.iter().map(|&n| PencilSdpRow::not_run(n, &why)).collect(), 0.0)
    });
    (computed.enclosure, computed.enclosure_seconds) = enclosure.unwrap_or_else(|p| {
        (EnclosureSummary::NotCertified { reason: format!("the enclosure computation failed: {p}") }, 0.0)
    });
    Ok(computed)
}

/// The SDP cross-check's and the enclosure's wall times (the SDP's per N too).
pub fn sdp_wall_times(c: &Computed) -> Vec<WallTime> {
    let mut out = vec![
        WallTime { what: crate::SDP_CROSS_CHECK.into(), seconds: c.sdp_seconds },
        WallTime { what: "W-bounds ω₁ enclosure".into(), seconds: c.enclosure_seconds },
    ];
    out.extend(c.sdp.iter().map(|r| WallTime { what: format!("W-bounds SDP N = {}", r.elements), seconds: r.seconds }));
    out
}

/// The sign of λ2* the certificate proves where the float extrapolation, with its error, does
/// not show it: a/b below the certified enclosure of ω₁ proves W ≻ 0, so λ2* > 0; above it,
/// λ2* < 0. λ2* → 0 as a/b → ω₁, so close to ω₁ the float value may straddle 0 or even show
/// the other sign; `None` where the float value agrees or nothing is certified.
pub(crate) fn certified_sign_unshown(
    lambda2: &wingcheck_model::Quantity,
    position: Option<Position>,
) -> Option<&'static str> {
    let error = lambda2.error().unwrap_or(0.0);
    match position {
        Some(Position::Below) if lambda2.value - error <= 0.0 => Some("> 0"),
        Some(Position::Above) if lambda2.value + error >= 0.0 => Some("< 0"),
        _ => None,
    }
}
