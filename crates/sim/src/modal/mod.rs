//! The closed loop in the wing's modal basis: the simulator's scheme ([`crate::Stepper`] on
//! M ẍ + C ẋ + K_c x = f̄ with C = ξK + b·T, K_c = K + a·T, T = diag(k1, k2) at the tip
//! unknowns; TR-BDF2 or the trapezoidal rule, every solve with the step matrix
//! S = M/α + C + αK_c) written in another basis, O(n) work per step:
//!
//! - **Modal basis** ([`ModalBasis`], per wing): K Φ = M Φ Ω², ΦᵀMΦ = I (one SVD of
//!   LᵀR⁻¹, M = LLᵀ and K = RᵀR the strain factor, [`wing_modes`]: M-orthonormal to round-off and
//!   every frequency within its measured bound at any grid). With x = Φη, v = Φζ the step matrix becomes
//!   D + β UTUᵀ with D = diag(1/α + (ξ + α)ω_i²), β = b + αa and U the tip rows of Φ (n×2):
//!   diagonal plus rank 2, solved by the Woodbury identity ([`scheme`]); TR-BDF2's two
//!   solves in one pass over the modes per step (`trbdf2_pass`).
//! - **Observer signal** ([`ObserverSignal`]): σ obeys σ_{n+1} − σ_n = h(ḡ − ĝ_k) whatever the
//!   plant, for either scheme (the tip boundary condition cancels τ and w in the scheme's own
//!   quadrature, see `wingcheck_control::ChannelObserver`), so ĝ_k and the tip input ḡ − ĝ of
//!   every step follow from the disturbances and the observer alone.
//!
//! - **Controllers of any origin** ([`ControlledSignal`]): a user's held inputs depend on the
//!   plant, so they are sampled from the modal state at every t_k instead (the built-ins keep
//!   the precomputed signal and its bits).
//!
//! Same discrete equations, so the results agree with the nodal stepper to round-off
//! (`tests/basis.rs`), not bit for bit.
//! [`simulate_modal`] is `simulate` in this basis; `discretisation.basis` chooses.

mod closed_loop;
mod controlled;
mod diagonal;
mod drive;
mod eigen_solve;
#[cfg(test)]
mod eigenbasis_tests;
mod exact;
mod gemv;
mod layout;
mod loop_eigen;
mod lyapunov;
pub(crate) mod memo;
mod probe;
mod refine;
mod run;
pub mod scheme;
mod signal;
mod trbdf2_pass;
mod wing_modes;
mod woodbury;

use wingcheck_model::{Config, MODAL_MAX_UNKNOWNS};

use crate::{Discretisation, ModalBasisError, SimError};

pub use controlled::{controlled_loop, measurement, ControlledSignal, StepQuadrature};
pub use drive::{drive, Reads, Recorder, Signal};
pub use probe::{ProbedStep, SubStepPeak, FINE_PER_OCTAVE, PROBED, PROBE_MARGIN};
pub use run::simulate_modal;
pub use scheme::{ModalLoop, ModalState, StepInput};
pub use signal::{ObserverSignal, RecordedSignal, Replay, SampleInput};
use wing_modes::wing_modes;
pub use wing_modes::BasisQuality;
pub use woodbury::dot;

/// The modal bases kept for the next run of the same wing and grid ([`ModalBasis::of_config`]):
/// four, a ledger's grid and its doubled grid with and without the exponential scheme (which
/// [`ModalBasis::key`] tells apart); a few MB each at the basis's 3 072-unknown limit.
static BASES: memo::Memo<ModalBasis, String> = memo::Memo::keeping(4);

/// The wing in its modal basis (units: ω² in 1/s², modal coordinates in √kg·m).
#[derive(Debug, Clone)]
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
    /// How well Φ diagonalises the pencil, measured after the solve.
    pub quality: BasisQuality,
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
    /// [`MODAL_MAX_UNKNOWNS`] unknowns (one dense O(n³) SVD, [`wing_modes`]).
    pub fn new(cfg: &Config) -> Result<ModalBasis, SimError> {
        Self::of(&Discretisation::new(cfg))
    }

    /// [`ModalBasis::of`] `disc`, which must be `cfg`'s discretisation
    /// (`Discretisation::new(cfg)`), or a copy of the basis kept from an earlier run under the
    /// same [`ModalBasis::key`]: the same bits, the basis being a deterministic function of the
    /// key's inputs (a ledger makes 17 runs at 96 elements of one wing; four bases are kept). Failures are not kept.
    pub fn of_config(cfg: &Config, disc: &Discretisation) -> Result<ModalBasis, SimError> {
        debug_assert_eq!(disc.dim(), Discretisation::new(cfg).dim(), "the discretisation of another config");
        BASES.get_or_try(ModalBasis::key(cfg), || ModalBasis::of(disc)).map(|kept| (*kept).clone())
    }

    /// Modal basis of a given discretisation.
    /// Every failure is a [`SimError::NoModalBasis`] naming its reason.
    pub fn of(disc: &Discretisation) -> Result<ModalBasis, SimError> {
        let no_basis = |reason: ModalBasisError| SimError::NoModalBasis { reason };
        let n = disc.dim();
        if n > MODAL_MAX_UNKNOWNS {
            return Err(no_basis(ModalBasisError::TooManyUnknowns { n, max: MODAL_MAX_UNKNOWNS }));
        }
        let (omega2, phi, quality) = wing_modes(disc).map_err(|e| no_basis(e.into()))?;
        if !(quality.mass_defect <= MASS_TOLERANCE && quality.frequency_error <= FREQUENCY_TOLERANCE) {
            return Err(no_basis(ModalBasisError::Unchecked {
                n,
                mass_defect: quality.mass_defect,
                mass_tolerance: MASS_TOLERANCE,
                frequency_error: quality.frequency_error,
                frequency_tolerance: FREQUENCY_TOLERANCE,
            }));
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
            quality,
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

/// Largest accepted mass defect of the modal basis, max_ij |φ_iᵀMφ_j − δ_ij|
/// ([`BasisQuality::mass_defect`]): the modal equations take ΦᵀMΦ = I. The SVD basis
/// ([`wing_modes`]) measures ≤ 2e-14 up to 1 536 unknowns (FE 512 graded elements, FD 768
/// intervals).
pub const MASS_TOLERANCE: f64 = 1e-10;

/// Largest accepted bound on the frequencies' relative error, |λ_i/ω_i² − 1|
/// ([`BasisQuality::frequency_error`]): the modal equations take ΦᵀKΦ = Ω², and a basis that
/// diagonalises K only to E (scaled) steps a wing whose stiffness differs from K by at most this
/// relative amount in the energy norm, so every frequency, and with it the trajectory, moves by
/// at most this relative amount — far below the grid's and the time step's errors (≥ 1e-6
/// relative on the default grids).
pub const FREQUENCY_TOLERANCE: f64 = 1e-6;
