//! The closed loop in the wing's modal basis: the simulator's scheme ([`crate::Stepper`] on
//! M ẍ + C ẋ + K_c x = f̄ with C = ξK + b·T, K_c = K + a·T, T = diag(k1, k2) at the tip
//! unknowns; TR-BDF2 or the trapezoidal rule, every solve with the step matrix
//! S = M/α + C + αK_c) written in another basis, O(n) work per step:
//!
//! - **Modal basis** ([`ModalBasis`], per wing): K Φ = M Φ Ω², ΦᵀMΦ = I (Cholesky of M,
//!   symmetric eigenproblem of L⁻¹KL⁻ᵀ). With x = Φη, v = Φζ the step matrix becomes
//!   D + β UTUᵀ with D = diag(1/α + (ξ + α)ω_i²), β = b + αa and U the tip rows of Φ (n×2):
//!   diagonal plus rank 2, solved by the Woodbury identity ([`scheme`]); TR-BDF2's two
//!   solves in one pass over the modes per step (`trbdf2_pass`).
//! - **Observer signal** ([`ObserverSignal`]): σ obeys σ_{n+1} − σ_n = h(ḡ − ĝ_k) whatever the
//!   plant, for either scheme (the tip boundary condition cancels τ and w in the scheme's own
//!   quadrature, see `wingcheck_control::ChannelObserver`), so ĝ_k and the tip input ḡ − ĝ of
//!   every step follow from the disturbances and the observer alone.
//!
//! Same discrete equations, so the results agree with the nodal stepper to round-off (tests:
//! ≤ 4e-9 relative on FE wings, whose modal basis carries the round-off of a dense
//! eigenproblem with ω² spanning many decades; ≤ 3e-11 on FD wings), not bit for bit.
//! [`simulate_modal`] is `simulate` in this basis; `discretisation.basis` chooses.

mod diagonal;
mod drive;
mod eigen_solve;
#[cfg(test)]
mod eigenbasis_tests;
mod exact;
mod gemv;
mod layout;
mod lyapunov;
mod probe;
mod refine;
mod run;
pub mod scheme;
mod signal;
mod trbdf2_pass;
mod woodbury;

use faer::{Mat, Side};
use wingcheck_model::{Config, MODAL_MAX_UNKNOWNS};

use crate::{Discretisation, SimError};

pub use drive::{drive, Reads, Recorder, Signal};
pub use probe::{SubStepPeak, FINE_PER_OCTAVE, PROBED, PROBE_MARGIN};
pub use run::simulate_modal;
pub use scheme::{dot, ModalLoop, ModalState, StepInput};
pub use signal::{ObserverSignal, RecordedSignal, Replay, SampleInput};

/// The wing in its modal basis (units: ω² in 1/s², modal coordinates in √kg·m).
#[derive(Debug)]
pub struct ModalBasis {
    /// ω_i² (1/s²), ascending.
    pub omega2: Vec<f64>,
    /// Rows of Φ at the tip unknowns q(s) and θ(s).
    pub tip: [Vec<f64>; 2],
    /// Φᵀ f_h: the distributed load's shape in modal coordinates.
    pub load: Vec<f64>,
    /// η(0) = ΦᵀM x(0).
    pub eta0: Vec<f64>,
    /// Output-grid rows of Φ: q(z_j) = field_q[j]·η (m), θ(z_j) = field_theta[j]·η (rad).
    pub field_q: Vec<Vec<f64>>,
    /// See `field_q`.
    pub field_theta: Vec<Vec<f64>>,
    /// Output-grid points z_j (m).
    pub field_z: Vec<f64>,
}

impl ModalBasis {
    /// A text that is equal for two configurations exactly when their modal bases (and the
    /// choice of basis, [`crate::resolved_basis`]) are: everything [`Discretisation::new`]
    /// reads (wing, method, grid, grading, initial shape, distributed load, output grid),
    /// `discretisation.basis` and whether the stepper is `exponential` (which needs the modal
    /// basis where `auto` would step in the nodal one). The search's cache key.
    pub fn key(cfg: &Config) -> String {
        serde_json::to_string(&(
            &cfg.wing,
            &cfg.discretisation.method,
            &cfg.discretisation.basis,
            cfg.discretisation.stepper == wingcheck_model::TimeScheme::Exponential,
            cfg.discretisation.elements,
            cfg.discretisation.fd_points,
            cfg.discretisation.grading,
            &cfg.initial,
            &cfg.disturbance.distributed,
            cfg.horizon.field_points,
        ))
        .expect("a config serialises")
    }

    /// Modal basis of the configuration's discretised wing; refused above
    /// [`MODAL_MAX_UNKNOWNS`] unknowns (dense O(n³) eigenproblem).
    pub fn new(cfg: &Config) -> Result<ModalBasis, SimError> {
        Self::of(&Discretisation::new(cfg))
    }

    /// Modal basis of a given discretisation.
    /// Every failure is a [`SimError::NoModalBasis`] naming its reason.
    pub fn of(disc: &Discretisation) -> Result<ModalBasis, SimError> {
        let no_basis = |reason: String| SimError::NoModalBasis { reason };
        let n = disc.dim();
        if n > MODAL_MAX_UNKNOWNS {
            return Err(no_basis(format!(
                "{n} unknowns: above the modal basis's {MODAL_MAX_UNKNOWNS} (dense eigenproblem)"
            )));
        }
        let (omega2, phi) = modes(disc).map_err(|e| match e {
            SimError::Numerical(reason) => no_basis(reason),
            other => other,
        })?;
        let (mass, stiffness) = orthonormality_defect(disc, &omega2, &phi);
        if !(mass <= MASS_TOLERANCE && stiffness <= STIFFNESS_TOLERANCE) {
            return Err(no_basis(format!(
                "modal basis of {n} unknowns is orthonormal only to {mass:.1e} in M (tolerance \
                 {MASS_TOLERANCE:.0e}) and {stiffness:.1e} in K (tolerance {STIFFNESS_TOLERANCE:.0e})"
            )));
        }
        let tip = [disc.tip_q, disc.tip_theta].map(|d| (0..n).map(|i| phi[(d, i)]).collect::<Vec<f64>>());
        let load = (0..n).map(|i| (0..n).map(|r| phi[(r, i)] * disc.load[r]).sum()).collect();
        let mut mx0 = vec![0.0; n];
        disc.mass.mul_into(&disc.x0, &mut mx0);
        let eta0 = (0..n).map(|i| (0..n).map(|r| phi[(r, i)] * mx0[r]).sum()).collect();
        let rows = |rows: &[Vec<(usize, f64)>]| -> Vec<Vec<f64>> {
            rows.iter().map(|row| (0..n).map(|i| row.iter().map(|&(r, w)| w * phi[(r, i)]).sum()).collect()).collect()
        };
        Ok(ModalBasis {
            omega2,
            tip,
            load,
            eta0,
            field_q: rows(&disc.interp.q_rows),
            field_theta: rows(&disc.interp.theta_rows),
            field_z: disc.interp.z.clone(),
        })
    }

    /// Number of modes (= unknowns).
    pub fn len(&self) -> usize {
        self.omega2.len()
    }

    /// True if there are no modes (never for a valid wing).
    pub fn is_empty(&self) -> bool {
        self.omega2.is_empty()
    }

    /// Mechanical energy ½ Σ (ζ_i² + ω_i² η_i²) = ½(vᵀMv + xᵀKx) (J).
    /// Summed in [`woodbury::LANES`] partial sums, as [`dot`].
    pub fn energy(&self, eta: &[f64], zeta: &[f64]) -> f64 {
        use woodbury::{total, LANES};
        let n = self.len();
        let (eta, zeta, om) = (&eta[..n], &zeta[..n], &self.omega2[..]);
        let term = |z: f64, e: f64, w: f64| z * z + w * e * e;
        let mut s = [0.0; LANES];
        for ((z, e), w) in zeta.chunks_exact(LANES).zip(eta.chunks_exact(LANES)).zip(om.chunks_exact(LANES)) {
            for l in 0..LANES {
                s[l] += term(z[l], e[l], w[l]);
            }
        }
        let tail = n - n % LANES;
        0.5 * (tail..n).fold(total(&s), |acc, i| acc + term(zeta[i], eta[i], om[i]))
    }
}

/// Largest accepted mass defect of the modal basis, max_ij |φ_iᵀMφ_j − δ_ij|: the modal
/// equations take ΦᵀMΦ = I. The largest entries are between stiff, heavily damped
/// (quasi-static) modes, which barely move the response. Measured against the nodal run
/// (2-s paper runs): defects up to 1e-9 (FE ≤ 48 elements, FD ≤ 96 intervals) left every series
/// within 1e-10 relative; 4e-7–1.5e-6 (FE 96–192 elements) within 1e-8 (tips) and 4e-7
/// (energy); 2.3e-4 (FE 192 graded elements) is refused.
pub const MASS_TOLERANCE: f64 = 1e-6;

/// Largest accepted stiffness defect, max_ij |φ_iᵀKφ_j − δ_ij ω_i²|/(ω_i ω_j): the modal
/// equations take ΦᵀKΦ = Ω². Measured as for [`MASS_TOLERANCE`]: ≤ 8e-8 at FE ≤ 48 elements
/// and FD ≤ 192 intervals, 3e-5–2.6e-4 at FE 96–192 elements, 9e-3 at FE 192 graded.
pub const STIFFNESS_TOLERANCE: f64 = 1e-3;

/// All modes, each from the form in which it is accurate: with κ = ω_max²/ω₁², the
/// compliance form gives ω_i² to ≈ ε·ω_i²/ω₁² relative and the stiffness form to
/// ≈ ε·ω_max²/ω_i²; modes up to ω_i² = ω₁·ω_max come from the first, the rest from the second,
/// so every mode is within ≈ ε√κ. Without a square strain factorisation, the stiffness form.
fn modes(disc: &Discretisation) -> Result<(Vec<f64>, Mat<f64>), SimError> {
    let n = disc.dim();
    let (mut omega2, mut phi) = stiffness_modes(disc)?;
    if disc.strain.rows.len() == n {
        let (low_omega2, low_phi) = compliance_modes(disc)?;
        // split in the widest relative gap within a factor 30 of ω₁·ω_max, so that a cluster of
        // close frequencies (which the two solves may mix differently) is never cut
        let middle = (low_omega2[0] * omega2[n - 1]).sqrt();
        let p = (1..n)
            .filter(|&p| low_omega2[p - 1] >= middle / 30.0 && low_omega2[p - 1] <= middle * 30.0)
            .max_by(|&p, &q| (low_omega2[p] / low_omega2[p - 1]).total_cmp(&(low_omega2[q] / low_omega2[q - 1])))
            .unwrap_or_else(|| low_omega2.iter().take_while(|w| **w <= middle).count());

        for i in 0..p {
            omega2[i] = low_omega2[i];
            for r in 0..n {
                phi[(r, i)] = low_phi[(r, i)];
            }
        }
    }
    if omega2.iter().any(|w| !(w.is_finite() && *w > 0.0)) {
        return Err(SimError::Numerical("stiffness matrix is not positive definite".into()));
    }
    Ok((omega2, phi))
}

/// The basis's defects (max_ij |φ_iᵀMφ_j − δ_ij|, max_ij |φ_iᵀKφ_j − δ_ij ω_i²|/(ω_i ω_j)); NaN
/// becomes ∞ (see [`MASS_TOLERANCE`], [`STIFFNESS_TOLERANCE`]).
fn orthonormality_defect(disc: &Discretisation, omega2: &[f64], phi: &Mat<f64>) -> (f64, f64) {
    let n = disc.dim();
    let (mut mphi, mut kphi) = (Mat::<f64>::zeros(n, n), Mat::<f64>::zeros(n, n));
    let (mut out_m, mut out_k) = (vec![0.0; n], vec![0.0; n]);
    for c in 0..n {
        let col: Vec<f64> = (0..n).map(|r| phi[(r, c)]).collect();
        disc.mass.mul_into(&col, &mut out_m);
        disc.stiffness.mul_into(&col, &mut out_k);
        for r in 0..n {
            mphi[(r, c)] = out_m[r];
            kphi[(r, c)] = out_k[r];
        }
    }
    let (gm, gk) = (phi.transpose() * &mphi, phi.transpose() * &kphi);
    let (mut mass, mut stiffness) = (0.0f64, 0.0f64);
    for i in 0..n {
        for j in 0..n {
            let delta = if i == j { 1.0 } else { 0.0 };
            mass = mass.max((gm[(i, j)] - delta).abs());
            stiffness = stiffness.max((gk[(i, j)] - delta * omega2[i]).abs() / (omega2[i] * omega2[j]).sqrt());
        }
    }
    let finite = |d: f64| if d.is_nan() { f64::INFINITY } else { d };
    (finite(mass), finite(stiffness))
}

/// Modes from the compliance form (K = RᵀR, R = D^½G the strain factorisation): the symmetric
/// eigenproblem B y = μ y of B = R⁻ᵀMR⁻¹, μ = 1/ω², φ = R⁻¹y/√μ. Its round-off is
/// ε·μ_max = ε/ω₁² absolute, so the low modes — which carry the tip response — keep relative
/// accuracy ε under refinement; the stiffness form L⁻¹KL⁻ᵀ puts ε·ω_max² (∝ h⁻⁴) on every ω²,
/// which at 192 uniform FE elements moved the tip trajectory by 1.4e-4 relative. Its high
/// modes are the inaccurate ones (ε·ω_i²/ω₁² relative): see [`modes`].
fn compliance_modes(disc: &Discretisation) -> Result<(Vec<f64>, Mat<f64>), SimError> {
    let n = disc.dim();
    let rows = &disc.strain.rows;
    // X = R⁻¹ = G⁻¹ D^-½, column by column.
    let mut x = Mat::<f64>::zeros(n, n);
    let (mut z, mut col) = (vec![0.0; n], vec![0.0; n]);
    for c in 0..n {
        z.iter_mut().for_each(|v| *v = 0.0);
        z[c] = 1.0 / rows[c].weight.sqrt();
        disc.strain.integrate(&z, &mut col);
        for (r, v) in col.iter().enumerate() {
            x[(r, c)] = *v;
        }
    }
    // M X, then B = Xᵀ(MX) (symmetrised).
    let mut mx = Mat::<f64>::zeros(n, n);
    let mut out = vec![0.0; n];
    for c in 0..n {
        let xc: Vec<f64> = (0..n).map(|r| x[(r, c)]).collect();
        disc.mass.mul_into(&xc, &mut out);
        for (r, v) in out.iter().enumerate() {
            mx[(r, c)] = *v;
        }
    }
    let b = x.transpose() * &mx;
    let b = Mat::from_fn(n, n, |i, j| 0.5 * (b[(i, j)] + b[(j, i)]));
    let evd = b
        .self_adjoint_eigen(Side::Lower)
        .map_err(|e| SimError::Numerical(format!("modal eigenproblem failed: {e:?}")))?;
    // ascending ω² = descending μ
    let mu: Vec<f64> = (0..n).map(|i| evd.S()[n - 1 - i]).collect();
    if mu.iter().any(|m| !(m.is_finite() && *m > 0.0)) {
        return Err(SimError::Numerical("mass matrix is not positive definite in the compliance form".into()));
    }
    let y = evd.U();
    let xy = &x * y;
    let phi = Mat::from_fn(n, n, |r, i| xy[(r, n - 1 - i)] / mu[i].sqrt());
    Ok((mu.iter().map(|m| 1.0 / m).collect(), phi))
}

/// Modes from the stiffness form (ΦᵀMΦ = I: Cholesky M = LLᵀ, eigenproblem of L⁻¹KL⁻ᵀ), for a
/// discretisation without a square strain factorisation.
fn stiffness_modes(disc: &Discretisation) -> Result<(Vec<f64>, Mat<f64>), SimError> {
    let n = disc.dim();
    let dense = |v: Vec<f64>| Mat::from_fn(n, n, |i, j| v[i * n + j]);
    let (m, k) = (dense(disc.mass.to_dense()), dense(disc.stiffness.to_dense()));
    let llt =
        m.llt(Side::Lower).map_err(|e| SimError::Numerical(format!("mass matrix is not positive definite: {e:?}")))?;
    let l = llt.L();
    let evd = crate::dense::congruence(l, &k)
        .self_adjoint_eigen(Side::Lower)
        .map_err(|e| SimError::Numerical(format!("modal eigenproblem failed: {e:?}")))?;
    let omega2: Vec<f64> = (0..n).map(|i| evd.S()[i]).collect();
    // Φ = L⁻ᵀ V
    let mut phi = evd.U().to_owned();
    faer::linalg::triangular_solve::solve_upper_triangular_in_place(l.transpose(), phi.as_mut(), faer::Par::Seq);
    Ok((omega2, phi))
}
