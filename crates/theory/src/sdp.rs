//! SDP cross-checks of generalised eigenvalues: max λ s.t. A − λB ⪰ 0 (B ≻ 0).
//!
//! * [`max_lambda`]: dense pencils, posed on the congruent, well-scaled problem
//!   max λ s.t. C − λI ⪰ 0 with C = L⁻¹AL⁻ᵀ (B = LLᵀ, both symmetrised first). Posed on (A, B)
//!   directly, clarabel stops with NumericalError when cond(B) ~ 1e8 or when B carries
//!   rounding-level asymmetry; the congruent form has the same answer and condition number 1 in
//!   its constraint matrix. The returned λ is re-verified: the smallest eigenvalue of C − λI
//!   (faer) must be ≥ −[`SDP_TOLERANCE`]·max(1, ‖C‖_max). Its cost grows like the dimension⁶
//!   (clarabel's dense PSD block): ~76 s at dimension 120.
//! * [`pencil_cross_check`]: the W-bounds pencil (W, κ) of [`crate::lyapunov`] at N elements
//!   (dimension 11N, N = 2 … 32), kept sparse: the velocities are eliminated exactly (a 2 × 2
//!   multiplier and a 4 × 4 LMI), the displacement LMI (3N) is posed in the hierarchical basis
//!   ([`hierarchical_basis`]), where κ is the identity and the matrix stays chordal with cliques
//!   of ~3(log₂N + 1), and clarabel's chordal decomposition solves it (N = 32: ~0.1 s a side).
//!   Measured before this formulation: on the nodal forms with chordal decomposition clarabel
//!   gave AlmostSolved at N = 16 and NumericalError at N = 32 (cond(κ) ~ N⁴ even after Jacobi
//!   scaling); the hierarchical basis on the full 11N forms was accurate but ~7× slower
//!   (cliques of 25). Every returned λ is re-verified by Cholesky against the original
//!   constraint and compared with the eigenvalues at the same N.
//!
//! Both are posed through [`problem`], the modelling layer over clarabel's PSD triangle cone
//! (its BLAS/LAPACK symbols come from `wingcheck-lapack`).
//!
//! A float SDP is evidence, not proof.

use faer::{Mat, Side};
use serde::Serialize;

use crate::numerics::PencilError;

pub mod problem;
mod reduce;

pub use reduce::hierarchical_basis;
use reduce::{reduce, ReducedPencil};

/// Relative tolerance of the re-verification of an SDP answer.
pub const SDP_TOLERANCE: f64 = 1e-7;

/// Outcome of one SDP cross-check.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
pub struct SdpCheck {
    /// clarabel's status (simplified).
    #[serde(serialize_with = "debug_name")]
    #[schemars(with = "String")]
    pub status: problem::SdpStatus,
    /// The SDP's λ (0 when not accepted).
    pub lambda_sdp: f64,
    /// λ_min of the pencil from the symmetric eigenvalue solver.
    pub lambda_eig: f64,
    /// Solved/AlmostSolved and C − λI ⪰ 0 re-verified to the tolerance.
    pub accepted: bool,
    /// Solve time (s); not reproducible content.
    pub seconds: f64,
}

fn debug_name<T: std::fmt::Debug, S: serde::Serializer>(v: &T, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(&format!("{v:?}"))
}

fn symmetrise(m: &Mat<f64>) -> Mat<f64> {
    Mat::from_fn(m.nrows(), m.ncols(), |i, j| 0.5 * (m[(i, j)] + m[(j, i)]))
}

/// max λ s.t. A − λB ⪰ 0 by SDP on the congruent problem, re-verified.
pub fn max_lambda(a: &Mat<f64>, b: &Mat<f64>) -> Result<SdpCheck, PencilError> {
    let n = a.nrows();
    if a.ncols() != n || b.nrows() != n || b.ncols() != n {
        return Err(PencilError::Shape { a: (a.nrows(), a.ncols()), b: (b.nrows(), b.ncols()) });
    }
    let (c, eig) = congruent_to_identity(a, b)?;
    let rows: Vec<Vec<f64>> = (0..n).map(|i| (0..n).map(|j| c[(i, j)]).collect()).collect();
    let id: Vec<Vec<f64>> = (0..n).map(|i| (0..n).map(|j| if i == j { 1.0 } else { 0.0 }).collect()).collect();
    let out = problem::max_generalized_lambda(&rows, &id)?;
    let scale = (0..n).flat_map(|i| (0..n).map(move |j| (i, j))).fold(1.0f64, |m, (i, j)| m.max(c[(i, j)].abs()));
    let (accepted, lambda_sdp) = match out.lambda {
        Some(lam) if lam.is_finite() => {
            // C − λI ⪰ 0 ⟺ λ_min(C) − λ ≥ 0
            (eig[0] - lam >= -SDP_TOLERANCE * scale, lam)
        }
        _ => (false, 0.0),
    };
    Ok(SdpCheck {
        status: out.status,
        lambda_sdp: if accepted { lambda_sdp } else { 0.0 },
        lambda_eig: eig[0],
        accepted,
        seconds: out.solve_time,
    })
}

// ---------------------------------------------------------------------------------------------
// The SDP cross-check of the W-bounds pencil at N = 2 … 32 elements.
// ---------------------------------------------------------------------------------------------

/// Element counts of the SDP cross-check of the W-bounds row.
pub const SDP_GRIDS: [usize; 5] = [2, 4, 8, 16, 32];

/// clarabel's gap and feasibility tolerances for the pencil SDPs (relative, on data scaled to
/// O(1) by the pencil scale σ): 1e-9 first; when that does not end Solved, once more at
/// clarabel's default 1e-8 (measured: a few small-N problems with nearly repeated eigenvalues
/// stop AlmostSolved at 1e-9 and Solved at 1e-8).
pub const PENCIL_SOLVER_TOLERANCES: [f64; 2] = [1e-9, 1e-8];

/// Interior-point iterations the whole SDP cross-check of one ledger may spend (every N, both
/// sides, every attempt): a deterministic work bound, so the same input gives the same rows on
/// any machine and under any load. Measured: 16–20 iterations per N at the paper's point and at
/// a = 1, b = 3000 (both sides, two formulations); wings whose parameters span many decades
/// need hundreds per solve and stop at the budget (status `MaxIterations`, not accepted; the
/// larger N then not run).
pub const SDP_ITERATION_BUDGET: u32 = 600;

/// Wall-clock guard of one clarabel solve (s), far above what the iteration budget allows on
/// any machine this tool runs on (≈ 0.05 s per iteration at N = 32): a solve stopped by it is
/// recorded as `MaxTime` and not accepted. It exists only against a machine stalled for
/// minutes; the iteration budget is what bounds the work.
pub const SDP_SOLVE_GUARD_SECONDS: f64 = 120.0;

/// One side of the pencil SDP at one N: λ2 = max λ s.t. W − λκ ⪰ 0, or λ1 = −max μ s.t.
/// −W − μκ ⪰ 0 (units of W/κ).
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
pub struct PencilSide {
    /// clarabel's status (`not run` when the problem could not be posed).
    pub status: crate::status::SolveStatus,
    /// Interior-point iterations (of the last solve).
    pub iterations: u32,
    /// Formulations tried: 1, or 2 when the first point was not Solved or not re-verified
    /// and the 4×4 LMI was rescaled from it (0: not run).
    pub attempts: u32,
    /// clarabel's tolerance of the last solve (one of [`PENCIL_SOLVER_TOLERANCES`]; 0: not run).
    pub solver_tolerance: f64,
    /// The SDP's λ (absent when clarabel returned no point).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lambda_sdp: Option<f64>,
    /// The eigenvalue answer at the same N: extreme eigenvalue of L⁻¹WL⁻ᵀ (κ = LLᵀ, faer).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lambda_eig: Option<f64>,
    /// |λ_sdp − λ_eig|.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub difference: Option<f64>,
    /// Status Solved *and* the original constraint re-verified at λ ∓ δ (see [`SDP_TOLERANCE`]).
    pub accepted: bool,
    /// |λ_sdp − λ_eig| ≤ δ.
    pub agrees: bool,
    /// Why the answer was not accepted, or why it disagrees.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
}

/// The SDP cross-check at one element count N.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
pub struct PencilSdpRow {
    /// Elements N.
    pub elements: usize,
    /// Dimension 11N of the Galerkin state space (the SDP itself is posed on 3N + 4 after the
    /// exact elimination of the velocities).
    pub dimension: usize,
    /// Pencil scale σ = max |W/κ| = max(|λ2|, |λ1|) = ‖L⁻¹WL⁻ᵀ‖₂ (eigenvalues; units of W/κ);
    /// δ = [`SDP_TOLERANCE`]·σ.
    pub scale: f64,
    /// λ2 = min W/κ.
    pub lambda2: PencilSide,
    /// λ1 = max W/κ.
    pub lambda1: PencilSide,
    /// Both sides accepted and agreeing with the eigenvalues.
    pub accepted: bool,
    /// Wall time of this N (s: eigenvalues, formulation, both SDPs, re-verification; not the
    /// exact assembly); not reproducible content.
    pub seconds: f64,
}

/// `v`, or 0 for a subnormal: the SDP's data are scaled to O(1), so an entry below the smallest
/// normal f64 (≈ 2.2e-308) is zero to 300 digits, and clarabel's eigen-decompositions fail on
/// such entries (it panicked at a = 1e12, b = 1e-300, where W's reduced block scaled by σ ≈ 6e12
/// is ≈ 4e-314).
fn flush_subnormal(v: f64) -> f64 {
    if v.abs() < f64::MIN_POSITIVE {
        0.0
    } else {
        v
    }
}

fn dense_rows(m: &Mat<f64>, scale: f64) -> Vec<Vec<f64>> {
    // symmetrised exactly; entries below 1e-13 of the largest are round-off of exact zeros
    let max = m.norm_max();
    (0..m.nrows())
        .map(|i| {
            (0..m.ncols())
                .map(|j| {
                    let v = 0.5 * (m[(i, j)] + m[(j, i)]);
                    if v.abs() <= 1e-13 * max {
                        0.0
                    } else {
                        flush_subnormal(v / scale)
                    }
                })
                .collect()
        })
        .collect()
}

/// The SDP of one side of the cross-check at N: max λ with the 4×4 LMI in the congruent form
/// diag(1, 1, β, β)·[[A, B], [Bᵀ, P]]·diag(1, 1, β, β) and the big LMI on the eliminated
/// displacements, and the variables' scales m_k (variable k is p̃_k = m_k β² P_k/σ, m_k =
/// max(1, max|G_k|/β²), so that its coefficients in both LMIs are ≤ 1 in size).
fn side_problem(
    r: &ReducedPencil,
    sign: f64,
    sigma: f64,
    beta: f64,
) -> Result<(problem::SdpProblem, Vec<f64>), PencilError> {
    use problem::{PsdConstraint, SdpProblem};
    let b2 = beta * beta;
    let m: Vec<f64> = r.g.iter().map(|g| (g.norm_max() / b2).max(1.0)).collect();
    let mut f0 = vec![vec![0.0; 4]; 4];
    for i in 0..2 {
        for j in 0..2 {
            f0[i][j] = flush_subnormal(sign * r.a_b[i][j] / sigma);
            f0[i][2 + j] = flush_subnormal(beta * sign * r.b[i][j] / sigma);
            f0[2 + j][i] = flush_subnormal(beta * sign * r.b[i][j] / sigma);
        }
    }
    let unit = |pairs: &[(usize, usize)], s: f64| {
        let mut e = vec![vec![0.0; 4]; 4];
        for &(i, j) in pairs {
            e[i][j] = s;
            e[j][i] = s;
        }
        e
    };
    let small = PsdConstraint::new(&f0)
        .and_then(|c| c.term(0, &unit(&[(0, 0), (1, 1)], -1.0)))
        .and_then(|c| c.term(1, &unit(&[(2, 2)], 1.0 / m[0])))
        .and_then(|c| c.term(2, &unit(&[(2, 3)], 1.0 / m[1])))
        .and_then(|c| c.term(3, &unit(&[(3, 3)], 1.0 / m[2])))?;
    let big = PsdConstraint::new(&dense_rows(&r.w_dd, sign * sigma))
        .and_then(|c| c.term(0, &dense_rows(&r.kappa_dd, -1.0)))
        .and_then(|c| c.term(1, &dense_rows(&r.g[0], -b2 * m[0])))
        .and_then(|c| c.term(2, &dense_rows(&r.g[1], -b2 * m[1])))
        .and_then(|c| c.term(3, &dense_rows(&r.g[2], -b2 * m[2])))?;
    let problem =
        SdpProblem::new(4).minimize(vec![-1.0, 0.0, 0.0, 0.0]).and_then(|p| p.psd(small)).and_then(|p| p.psd(big))?;
    Ok((problem, m))
}

/// clarabel's point for one side: max λ s.t. sign·W − λκ ⪰ 0 in the reduced form, with data
/// divided by σ, the 4×4 LMI rescaled by β and each P entry scaled by the size of its
/// coefficients.
fn solve_side(
    r: &ReducedPencil,
    sign: f64,
    sigma: f64,
    beta: f64,
    budget: &mut u32,
    cancel: &wingcheck_model::Cancel,
) -> Result<SideSolution, PencilError> {
    let b2 = beta * beta;
    let (problem, m) = side_problem(r, sign, sigma, beta)?;
    let bmax = r.b.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs())) / sigma;
    let mut out = None;
    for tol in PENCIL_SOLVER_TOLERANCES {
        if *budget == 0 && out.is_some() {
            break;
        }
        let mut settings = problem::prescaled_chordal_settings(tol);
        // clarabel stops with status MaxIterations at the budget (recorded, not accepted)
        settings.max_iter = (*budget).max(1);
        settings.time_limit = SDP_SOLVE_GUARD_SECONDS;
        // clarabel panics on some ill-scaled data (an eigen-decomposition failure inside its
        // cone margins): that solve becomes this side's reason, never the process's end
        let stop = cancel.clone();
        let sol = wingcheck_io::catch(|| problem.solve_with_stop(settings, move || stop.is_cancelled()))
            .map_err(PencilError::SolverPanicked)??;
        *budget = budget.saturating_sub(sol.iterations.max(1));
        use problem::SdpStatus;
        // λ only from a point clarabel calls optimal (an interrupted solve's point means nothing)
        let optimal = crate::status::worth_reverifying(sol.raw_status, &sol.x) && !sol.x.is_empty();
        let lambda = optimal.then(|| sign * sigma * sol.x[0]);
        let solved = sol.status == SdpStatus::Solved;
        // P/σ back from the scaled variables (p̃_k = m_k β² P_k/σ)
        let p_over_sigma =
            (1..4).map(|k| sol.x.get(k).copied().unwrap_or(0.0) / (m[k - 1] * b2)).fold(0.0f64, |a, v| a.max(v.abs()));
        out = Some(SideSolution {
            status: crate::status::SolveStatus::Clarabel(sol.raw_status),
            iterations: sol.iterations,
            tolerance: tol,
            lambda,
            p_over_sigma,
            b_over_sigma: bmax,
        });
        if solved {
            break;
        }
    }
    out.ok_or(PencilError::NoTolerance)
}

struct SideSolution {
    status: crate::status::SolveStatus,
    iterations: u32,
    tolerance: f64,
    lambda: Option<f64>,
    /// max |P/σ| of the returned point.
    p_over_sigma: f64,
    /// max |B/σ|.
    b_over_sigma: f64,
}

/// The SDP cross-check of min/max W/κ at N elements (forms assembled exactly, converted to
/// f64): reduced SDP (velocities eliminated exactly, hierarchical basis) solved by clarabel for
/// each side, every returned λ re-verified against the original W − λκ ⪰ 0 (Cholesky of
/// L⁻¹(W − (λ2 − δ)κ)L⁻ᵀ, resp. of L⁻¹((λ1 + δ)κ − W)L⁻ᵀ, δ = [`SDP_TOLERANCE`]·σ) and compared
/// with the eigenvalues of L⁻¹WL⁻ᵀ. A float SDP is evidence, not proof.
pub fn pencil_cross_check(
    w: &Mat<f64>,
    kappa: &Mat<f64>,
    c1: &Mat<f64>,
    c2: &Mat<f64>,
    n: usize,
    span: f64,
) -> PencilSdpRow {
    let mut budget = SDP_ITERATION_BUDGET;
    pencil_cross_check_within(w, kappa, c1, c2, n, span, &mut budget, &wingcheck_model::Cancel::new())
}

/// [`pencil_cross_check`] spending at most `budget` interior-point iterations (decremented by
/// what the solves use); a solve stopped by it ends `MaxIterations`, recorded in the row and
/// not accepted. Once `cancel` is set, a solve stops at its next interior-point iteration
/// (clarabel's termination callback) and is not accepted.
#[allow(clippy::too_many_arguments)]
pub fn pencil_cross_check_within(
    w: &Mat<f64>,
    kappa: &Mat<f64>,
    c1: &Mat<f64>,
    c2: &Mat<f64>,
    n: usize,
    span: f64,
    budget: &mut u32,
    cancel: &wingcheck_model::Cancel,
) -> PencilSdpRow {
    let start = std::time::Instant::now();
    let dimension = w.nrows();
    let (c, eig) = match congruent_to_identity(w, kappa) {
        Ok(x) => x,
        Err(e) => {
            return PencilSdpRow { seconds: start.elapsed().as_secs_f64(), ..PencilSdpRow::not_run(n, &e.to_string()) }
        }
    };
    let sigma = eig[0].abs().max(eig[dimension - 1].abs()).max(f64::MIN_POSITIVE);
    let reduced = reduce(w, kappa, c1, c2, n, span / n as f64);
    let lambda2 = pencil_side(&reduced, &c, 1.0, sigma, eig[0], n, budget, cancel);
    let lambda1 = pencil_side(&reduced, &c, -1.0, sigma, eig[dimension - 1], n, budget, cancel);
    PencilSdpRow {
        elements: n,
        dimension,
        scale: sigma,
        accepted: lambda2.agrees && lambda1.agrees,
        lambda2,
        lambda1,
        seconds: start.elapsed().as_secs_f64(),
    }
}

/// One side of the cross-check at N (sign 1: λ2 = min W/κ; −1: λ1 = max W/κ): clarabel on the
/// reduced pencil, once more rescaled if the first point is not Solved or not re-verified, then
/// re-verified against the original constraint and compared with the eigenvalue.
#[allow(clippy::too_many_arguments)]
fn pencil_side(
    reduced: &Result<ReducedPencil, PencilError>,
    c: &Mat<f64>,
    sign: f64,
    sigma: f64,
    lambda_eig: f64,
    n: usize,
    budget: &mut u32,
    cancel: &wingcheck_model::Cancel,
) -> PencilSide {
    let not_run = |reason: &str| PencilSdpRow::not_run(n, reason).lambda2;
    let delta = SDP_TOLERANCE * sigma;
    let r = match &reduced {
        Ok(r) => r,
        Err(e) => return PencilSide { lambda_eig: Some(lambda_eig), ..not_run(&e.to_string()) },
    };
    // the one acceptance rule (status::worth_reverifying), then the original constraint
    let verify = |x: &SideSolution| {
        x.status.is_candidate() && x.lambda.is_some_and(|l| l.is_finite() && pencil_feasible(c, sign, l - sign * delta))
    };
    let first = match solve_side(r, sign, sigma, 1.0, budget, cancel) {
        Ok(x) => x,
        Err(e) => return PencilSide { lambda_eig: Some(lambda_eig), ..not_run(&format!("SDP: {e}")) },
    };
    // Not a candidate or not re-verified (never because of the eigenvalue comparison): once more
    // with the 4×4 LMI rescaled by β = 1/√max(|P/σ|, |B/σ|²) from the first point, which
    // makes its P-block O(1) (measured: on an SI-scale wing at a/b ≈ 5 the first point has
    // P ≈ 0, violating the 4×4 LMI by ~|B/σ|² ≈ 2e-9, and λ1 fails re-verification).
    let mut attempts = 1;
    let chosen = if verify(&first) {
        first
    } else {
        let scale = first.p_over_sigma.max(first.b_over_sigma * first.b_over_sigma);
        match (scale > 0.0 && *budget > 0).then(|| solve_side(r, sign, sigma, 1.0 / scale.sqrt(), budget, cancel)) {
            Some(Ok(second)) => {
                attempts = 2;
                second
            }
            _ => first,
        }
    };
    let verified = verify(&chosen);
    let SideSolution { status, iterations, tolerance, lambda, .. } = chosen;
    let difference = lambda.map(|l| (l - lambda_eig).abs());
    let accepted = verified;
    let agrees = accepted && difference.is_some_and(|d| d <= delta);
    let reason = if !status.is_candidate() {
        Some(format!("clarabel status {status} (only Solved and AlmostSolved points are re-verified)"))
    } else if !verified {
        let constraint = if sign > 0.0 { "W − λκ ⪰ 0" } else { "λκ − W ⪰ 0" };
        Some(format!("re-verification failed: the returned λ violates {constraint} by more than δ = {delta:.1e}"))
    } else if !agrees {
        Some(format!("feasible but {:.1e} from the eigenvalue, more than δ = {delta:.1e}", difference.unwrap_or(0.0)))
    } else {
        None
    };
    PencilSide {
        status,
        iterations,
        attempts,
        solver_tolerance: tolerance,
        lambda_sdp: lambda,
        lambda_eig: Some(lambda_eig),
        difference,
        accepted,
        agrees,
        reason,
    }
}

/// C = L⁻¹AL⁻ᵀ (B = LLᵀ, both symmetrised) and its eigenvalues ascending.
fn congruent_to_identity(a: &Mat<f64>, b: &Mat<f64>) -> Result<(Mat<f64>, Vec<f64>), PencilError> {
    let (a, b) = (symmetrise(a), symmetrise(b));
    let llt = b.llt(Side::Lower).map_err(|cause| PencilError::NotPositiveDefinite { what: "κ (B)", cause })?;
    let c = wingcheck_sim::dense::congruence(llt.L(), &a);
    let mut eig =
        c.self_adjoint_eigenvalues(Side::Lower).map_err(|cause| PencilError::Eigen { what: "eigenvalues", cause })?;
    eig.sort_by(f64::total_cmp);
    Ok((c, eig))
}

/// Whether sign·(C − λI) is positive definite (Cholesky succeeds): with C = L⁻¹WL⁻ᵀ this is
/// W − λκ ≻ 0 (sign = 1) or λκ − W ≻ 0 (sign = −1), by congruence.
pub fn pencil_feasible(c: &Mat<f64>, sign: f64, lambda: f64) -> bool {
    let n = c.nrows();
    let m = Mat::from_fn(n, n, |i, j| sign * (c[(i, j)] - if i == j { lambda } else { 0.0 }));
    m.llt(Side::Lower).is_ok()
}

/// The re-verification on the forms themselves: C = L⁻¹WL⁻ᵀ and the test of [`pencil_feasible`]
/// for W − λκ ≻ 0 (sign = 1) or λκ − W ≻ 0 (sign = −1).
pub fn forms_feasible(w: &Mat<f64>, kappa: &Mat<f64>, sign: f64, lambda: f64) -> Result<bool, PencilError> {
    Ok(pencil_feasible(&congruent_to_identity(w, kappa)?.0, sign, lambda))
}

impl PencilSdpRow {
    /// A row for an N whose SDP could not be posed (e.g. the assembly failed), saying why.
    pub fn not_run(elements: usize, reason: &str) -> Self {
        let side = PencilSide {
            status: crate::status::SolveStatus::NotRun(reason.to_string()),
            iterations: 0,
            attempts: 0,
            solver_tolerance: 0.0,
            lambda_sdp: None,
            lambda_eig: None,
            difference: None,
            accepted: false,
            agrees: false,
            reason: Some(reason.to_string()),
        };
        PencilSdpRow {
            elements,
            dimension: 11 * elements,
            scale: 0.0,
            lambda2: side.clone(),
            lambda1: side,
            accepted: false,
            seconds: 0.0,
        }
    }
}
