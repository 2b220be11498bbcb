//! The one dense congruence of the workspace: the symmetric eigenproblem of a pencil (A, B),
//! B ≻ 0, posed on C = L⁻¹AL⁻ᵀ with B = LLᵀ. Used by the modal basis (K, M) and by the claims'
//! Lyapunov pencils and SDP cross-checks (W, κ).

use faer::{Mat, MatRef, Par};

/// C = L⁻¹AL⁻ᵀ, symmetrised as ½(C + Cᵀ), for the lower Cholesky factor `l` of B: its
/// eigenvalues are those of the pencil (A, B), its eigenvectors y give the pencil's as
/// x = L⁻ᵀy. Two triangular solves, O(n³).
pub fn congruence(l: MatRef<'_, f64>, a: &Mat<f64>) -> Mat<f64> {
    let mut y = a.clone();
    faer::linalg::triangular_solve::solve_lower_triangular_in_place(l, y.as_mut(), Par::Seq);
    let mut c = y.transpose().to_owned();
    faer::linalg::triangular_solve::solve_lower_triangular_in_place(l, c.as_mut(), Par::Seq);
    let n = c.nrows();
    Mat::from_fn(n, n, |i, j| 0.5 * (c[(i, j)] + c[(j, i)]))
}
