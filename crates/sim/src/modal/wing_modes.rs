//! The wing's modes K Φ = M Φ Ω², ΦᵀMΦ = I, for the modal basis, by one singular value
//! decomposition in the strain factor — and how well the result diagonalises the pencil,
//! measured after the solve ([`BasisQuality`]).
//!
//! **Method.** With K = RᵀR (R = D^½G, the strain factorisation of [`crate::strain`]: square,
//! triangular in its pivot order) and M = LLᵀ (banded Cholesky), the pencil's eigenvalues are
//! ω_i² = 1/σ_i² for the singular values σ_i of F = LᵀR⁻¹ (FᵀF = R⁻ᵀMR⁻¹, the compliance), and
//! with F = UΣVᵀ the basis Φ = L⁻ᵀU satisfies ΦᵀMΦ = UᵀU = I and ΦᵀKΦ = Uᵀ(FFᵀ)⁻¹U = Σ⁻².
//! R⁻¹ is formed column by column by forward substitution (round-off relative to the result,
//! whatever the mesh), Lᵀ and L⁻ᵀ are banded products and back-substitutions, and the SVD is
//! faer's (Householder bidiagonalisation, divide and conquer; left vectors only).
//!
//! **Accuracy.** The SVD is backward stable: its σ_i err by ≈ ε‖F‖ = ε/ω₁, so ω_i carries a
//! relative error ≈ ε·ω_i/ω₁ (≤ ε√κ, κ = ω_max²/ω₁²): the low modes, which carry the tip
//! response, to round-off, the stiffest ones to ε√κ — the square root of what a symmetric
//! eigen-solve of either L⁻¹KL⁻ᵀ (ε κ on ω₁²) or R⁻ᵀMR⁻¹ (ε κ on ω_max²) leaves. U is
//! orthogonal to round-off whatever the spectrum, so ΦᵀMΦ = I to round-off (measured ≤ 2e-14
//! up to 1 536 unknowns); ΦᵀKΦ is diagonal to ≈ ε ω_max/ω₁ scaled (measured ≤ 2e-8 on 512
//! graded FE elements, κ = 2.6e15). The splice of a stiffness and a compliance eigen-solve it
//! replaces was orthonormal only to 2.3e-4 in M at 192 graded FE elements (11 at 512).
//!
//! **Cost.** R⁻¹ O(n²·row), F and Φ O(n²·band), the SVD ≈ 60 ms CPU at n = 576 and ≈ 2 s at
//! n = 1 536 (O(n³)); the check ([`BasisQuality::measure`]) two n³ products.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::svd::{self, ComputeSvdVectors};
use faer::{Mat, Par};
use serde::Serialize;

use crate::banded::BandedCholesky;
use crate::{Discretisation, NumericalError};

/// How well a modal basis Φ (columns M-normalised, ω_i² ascending) diagonalises the pencil
/// (K, M), measured after the solve from the Gram matrices ΦᵀMΦ = I + G and
/// ΦᵀKΦ = Ω(I + E)Ω (K applied through the strain factor, (RΦ)ᵀ(RΦ), which keeps the low
/// modes' products relative to their size).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, schemars::JsonSchema)]
pub struct BasisQuality {
    /// max_ij |G_ij| = max_ij |φ_iᵀMφ_j − δ_ij| (dimensionless).
    pub mass_defect: f64,
    /// max_ij |E_ij| = max_ij |φ_iᵀKφ_j − δ_ij ω_i²|/(ω_i ω_j) (dimensionless).
    pub stiffness_defect: f64,
    /// Bound on |λ_i/ω_i² − 1| for every mode i, λ_i the i-th eigenvalue of the discrete pencil
    /// (dimensionless; ω_i's relative error is at most half of it): the pencil (ΦᵀKΦ, ΦᵀMΦ) has
    /// λ_i as its eigenvalues (a congruence), and by Ostrowski's theorem, applied to the
    /// congruence by (I + G)^-½ and to Ω(I + E)Ω = Ω²'s congruence by (I + E)^½,
    /// λ_i ∈ ω_i²[(1 − ‖E‖)/(1 + ‖G‖), (1 + ‖E‖)/(1 − ‖G‖)]; the norms are bounded by the largest
    /// row sums of |E| and |G| plus a bound on the round-off of forming them.
    pub frequency_error: f64,
}

/// The modes of `disc`: ω_i² ascending and Φ (n × n, column i the mode of ω_i²), with the
/// measured quality of the basis. Fails with a [`NumericalError`] if a factor is not
/// positive definite, the strain factorisation is not square, or the SVD fails.
pub(crate) fn wing_modes(disc: &Discretisation) -> Result<(Vec<f64>, Mat<f64>, BasisQuality), NumericalError> {
    let n = disc.dim();
    if disc.strain.rows.len() != n {
        return Err(NumericalError::NotSquare {
            what: "the strain factorisation",
            rows: disc.strain.rows.len(),
            unknowns: n,
        });
    }
    let chol =
        BandedCholesky::new(&disc.mass).map_err(|_| NumericalError::NotPositiveDefinite { what: "mass matrix" })?;
    let f = compliance_factor(disc, &chol);
    let (sigma, u) = left_singular(&f)?;
    if sigma.iter().any(|s| !(s.is_finite() && *s > 0.0)) {
        return Err(NumericalError::ZeroSingularValue { what: "stiffness matrix" });
    }
    // σ descending = ω² ascending
    let omega2: Vec<f64> = sigma.iter().map(|s| 1.0 / (s * s)).collect();
    let mut phi = u;
    for c in 0..n {
        chol.transpose_solve_in_place(phi.col_as_slice_mut(c));
    }
    let quality = BasisQuality::measure(disc, &omega2, &phi);
    Ok((omega2, phi, quality))
}

/// F = LᵀR⁻¹, column c = Lᵀ G⁻¹ e_c/√w_c (one forward substitution and one banded product).
fn compliance_factor(disc: &Discretisation, chol: &BandedCholesky) -> Mat<f64> {
    let n = disc.dim();
    let rows = &disc.strain.rows;
    let mut f = Mat::<f64>::zeros(n, n);
    let (mut z, mut x) = (vec![0.0; n], vec![0.0; n]);
    for (c, row) in rows.iter().enumerate() {
        z[c] = 1.0 / row.weight.sqrt();
        disc.strain.integrate(&z, &mut x);
        z[c] = 0.0;
        chol.transpose_mul_into(&x, f.col_as_slice_mut(c));
    }
    f
}

/// The singular values (descending) and left singular vectors of the square `f`.
fn left_singular(f: &Mat<f64>) -> Result<(Vec<f64>, Mat<f64>), NumericalError> {
    let n = f.nrows();
    let params = Default::default();
    let need = svd::svd_scratch::<f64>(n, n, ComputeSvdVectors::Full, ComputeSvdVectors::No, Par::Seq, params);
    let mut buf = MemBuffer::try_new(need).map_err(|_| NumericalError::NoMemory { what: "the SVD", n })?;
    let mut s = faer::diag::Diag::<f64>::zeros(n);
    let mut u = Mat::<f64>::zeros(n, n);
    svd::svd(f.as_ref(), s.as_mut(), Some(u.as_mut()), None, Par::Seq, MemStack::new(&mut buf), params)
        .map_err(|_| NumericalError::Decomposition { what: "the modal SVD" })?;
    Ok(((0..n).map(|i| s[i]).collect(), u))
}

impl BasisQuality {
    /// The defects of the basis (ω², Φ) of `disc` and the frequency bound they give. NaN
    /// becomes ∞.
    pub(crate) fn measure(disc: &Discretisation, omega2: &[f64], phi: &Mat<f64>) -> BasisQuality {
        let n = disc.dim();
        let mut mphi = Mat::<f64>::zeros(n, n);
        for c in 0..n {
            disc.mass.mul_into(phi.col_as_slice(c), mphi.col_as_slice_mut(c));
        }
        let rphi = strains(disc, phi);
        let gm = phi.transpose() * &mphi;
        let gk = rphi.transpose() * &rphi;
        let (mut mass, mut stiffness, mut row_m, mut row_k) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for i in 0..n {
            let (mut sm, mut sk) = (0.0, 0.0);
            for j in 0..n {
                let delta = if i == j { 1.0 } else { 0.0 };
                let dm = (gm[(i, j)] - delta).abs();
                let dk = (gk[(i, j)] - delta * omega2[i]).abs() / (omega2[i] * omega2[j]).sqrt();
                (mass, stiffness) = (mass.max(dm), stiffness.max(dk));
                (sm, sk) = (sm + dm, sk + dk);
            }
            (row_m, row_k) = (row_m.max(sm), row_k.max(sk));
        }
        let frequency_error = (row_k + row_m) / (1.0 - row_m);
        let finite = |d: f64| if d.is_nan() || d < 0.0 { f64::INFINITY } else { d };
        BasisQuality {
            mass_defect: finite(mass),
            stiffness_defect: finite(stiffness),
            frequency_error: finite(frequency_error),
        }
    }
}

/// RΦ: the strains of each mode, scaled by √weight.
fn strains(disc: &Discretisation, phi: &Mat<f64>) -> Mat<f64> {
    let n = disc.dim();
    let rows = &disc.strain.rows;
    let mut rphi = Mat::<f64>::zeros(n, n);
    for c in 0..n {
        let col = phi.col_as_slice(c);
        let out = rphi.col_as_slice_mut(c);
        for (r, row) in rows.iter().enumerate() {
            out[r] = row.weight.sqrt() * row.entries.iter().map(|&(j, g)| g * col[j]).sum::<f64>();
        }
    }
    rphi
}
