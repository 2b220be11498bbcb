//! The SDP cross-check of a generalised eigenvalue: max λ s.t. A − λB ⪰ 0 (B ≻ 0), posed on
//! the congruent, well-scaled problem max λ s.t. C − λI ⪰ 0 with C = L⁻¹AL⁻ᵀ (B = LLᵀ,
//! both symmetrised first). Posed on (A, B) directly, clarabel stops with NumericalError when
//! cond(B) ~ 1e8 or when B carries rounding-level asymmetry; the congruent form has the same
//! answer (λ_min of the pencil) and condition number 1 in its constraint matrix.
//!
//! The returned λ is re-verified: the smallest eigenvalue of C − λI (faer) must be ≥
//! −[`SDP_TOLERANCE`]·max(1, ‖C‖_max); the eigenvalue answer λ_min(C) is reported beside it.

use faer::{Mat, Side};
use serde::{Deserialize, Serialize};

/// Relative tolerance of the re-verification of an SDP answer.
pub const SDP_TOLERANCE: f64 = 1e-7;

/// Outcome of one SDP cross-check.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SdpCheck {
    /// clarabel's status.
    pub status: String,
    /// The SDP's λ (0 when not accepted).
    pub lambda_sdp: f64,
    /// λ_min of the pencil from the symmetric eigenvalue solver.
    pub lambda_eig: f64,
    /// Solved/AlmostSolved and C − λI ⪰ 0 re-verified to the tolerance.
    pub accepted: bool,
    /// Solve time (s); not reproducible content.
    pub seconds: f64,
}

fn symmetrise(m: &Mat<f64>) -> Mat<f64> {
    Mat::from_fn(m.nrows(), m.ncols(), |i, j| 0.5 * (m[(i, j)] + m[(j, i)]))
}

/// max λ s.t. A − λB ⪰ 0 by SDP on the congruent problem, re-verified.
pub fn max_lambda(a: &Mat<f64>, b: &Mat<f64>) -> Result<SdpCheck, String> {
    let n = a.nrows();
    if a.ncols() != n || b.nrows() != n || b.ncols() != n {
        return Err(format!("A is {}x{}, B is {}x{}", a.nrows(), a.ncols(), b.nrows(), b.ncols()));
    }
    let (a, b) = (symmetrise(a), symmetrise(b));
    let llt = b.llt(Side::Lower).map_err(|e| format!("B is not positive definite: {e:?}"))?;
    let l = llt.L();
    let mut y = a.clone();
    faer::linalg::triangular_solve::solve_lower_triangular_in_place(l, y.as_mut(), faer::Par::Seq);
    let mut c = y.transpose().to_owned();
    faer::linalg::triangular_solve::solve_lower_triangular_in_place(l, c.as_mut(), faer::Par::Seq);
    let c = symmetrise(&c);
    let mut eig = c.self_adjoint_eigenvalues(Side::Lower).map_err(|e| format!("eigenvalues: {e:?}"))?;
    eig.sort_by(f64::total_cmp);
    let rows: Vec<Vec<f64>> = (0..n).map(|i| (0..n).map(|j| c[(i, j)]).collect()).collect();
    let id: Vec<Vec<f64>> = (0..n).map(|i| (0..n).map(|j| if i == j { 1.0 } else { 0.0 }).collect()).collect();
    let out = wingcheck_lapack::sdp::max_generalized_lambda(&rows, &id).map_err(|e| e.to_string())?;
    let scale = (0..n).flat_map(|i| (0..n).map(move |j| (i, j))).fold(1.0f64, |m, (i, j)| m.max(c[(i, j)].abs()));
    let (accepted, lambda_sdp) = match out.lambda {
        Some(lam) if lam.is_finite() => {
            // C − λI ⪰ 0 ⟺ λ_min(C) − λ ≥ 0
            (eig[0] - lam >= -SDP_TOLERANCE * scale, lam)
        }
        _ => (false, 0.0),
    };
    Ok(SdpCheck {
        status: format!("{:?}", out.status),
        lambda_sdp: if accepted { lambda_sdp } else { 0.0 },
        lambda_eig: eig[0],
        accepted,
        seconds: out.solve_time,
    })
}
