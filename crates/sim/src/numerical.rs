//! Typed failures of the simulator's linear algebra and numerics ([`NumericalError`]), carried
//! by [`crate::SimError::Numerical`]; `what` names the matrix or step that failed.

use thiserror::Error;

/// A failed linear-algebra or numerical step of the simulator.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum NumericalError {
    /// A Cholesky pivot of a matrix that must be positive definite is not positive and finite.
    #[error("{what} is not positive definite (pivot {pivot:e} at row {row})")]
    Pivot {
        /// The matrix.
        what: &'static str,
        /// The failing pivot (before its square root).
        pivot: f64,
        /// Its row (0-based).
        row: usize,
    },
    /// A matrix that must be positive definite is not (its factorisation failed).
    #[error("{what} is not positive definite")]
    NotPositiveDefinite {
        /// The matrix.
        what: &'static str,
    },
    /// A matrix that must be positive definite has a zero (or non-finite) singular value.
    #[error("{what} is not positive definite (a zero singular value)")]
    ZeroSingularValue {
        /// The matrix.
        what: &'static str,
    },
    /// A small matrix to invert has a determinant that is zero, negative or not finite.
    #[error("{what} is singular (det {det:e})")]
    Singular {
        /// The matrix.
        what: &'static str,
        /// Its determinant.
        det: f64,
    },
    /// A factor that must be square is not.
    #[error("{what} has {rows} rows for {unknowns} unknowns (must be square)")]
    NotSquare {
        /// The factor.
        what: &'static str,
        /// Its rows.
        rows: usize,
        /// The unknowns of the discretisation.
        unknowns: usize,
    },
    /// A dense decomposition (faer's eigen-solver or SVD, whose one failure is reaching its
    /// iteration limit) did not converge.
    #[error("{what} did not converge")]
    Decomposition {
        /// The decomposition.
        what: &'static str,
    },
    /// The work space of a dense decomposition could not be allocated.
    #[error("no memory for {what} of a {n} x {n} matrix")]
    NoMemory {
        /// The decomposition.
        what: &'static str,
        /// The matrix's dimension.
        n: usize,
    },
    /// More eigenvalues asked for than the pencil has, or none.
    #[error("asked for {count} eigenvalues of a pencil of dimension {dim}")]
    EigenCount {
        /// Eigenvalues asked for.
        count: usize,
        /// Dimension of the pencil.
        dim: usize,
    },
    /// The subspace iteration's block lost rank.
    #[error("subspace iteration lost rank (degenerate start block)")]
    LostRank,
    /// A Ritz value μ = 1/λ of K φ = λ M φ that is not positive.
    #[error("non-positive Ritz value {value:e} (K not positive definite?)")]
    NonPositiveRitz {
        /// The Ritz value μ.
        value: f64,
    },
    /// An iteration did not meet its tolerance within its limit.
    #[error("{what} did not converge in {iterations} iterations")]
    NoConvergence {
        /// The iteration.
        what: &'static str,
        /// Its limit.
        iterations: usize,
    },
    /// A tolerance of the converged frequencies below what double precision resolves.
    #[error("mode tolerance {tol:e} out of range: use a value >= {min:e}")]
    ModeTolerance {
        /// The tolerance asked for (relative).
        tol: f64,
        /// The smallest allowed.
        min: f64,
    },
    /// A number of converged frequencies outside 1..=`max`.
    #[error("mode count {count} out of range: use 1..={max}")]
    ModeCount {
        /// The count asked for.
        count: usize,
        /// The largest allowed.
        max: usize,
    },
    /// The exponential scheme met a mode with ω² ≤ 0 (or not finite).
    #[error("exponential scheme: a mode with ω² ≤ 0")]
    NonPositiveMode,
    /// The exponential scheme's ‖A‖₁ or step h (s) is not finite and positive.
    #[error("exponential scheme: ‖A‖₁ = {norm:e}, h = {h:e}")]
    StepNorm {
        /// ‖A‖₁ of the closed loop's matrix (1/s).
        norm: f64,
        /// The step (s).
        h: f64,
    },
    /// The exponential scheme's ‖A‖₁h needs more than 200 doublings.
    #[error("exponential scheme: ‖A‖₁h = {norm_h:e} is out of range")]
    StepNormRange {
        /// ‖A‖₁h.
        norm_h: f64,
    },
    /// A computed quantity is not finite.
    #[error("{what} is not finite")]
    NotFinite {
        /// The quantity.
        what: &'static str,
    },
}

/// Why a discretisation has no modal basis ([`crate::SimError::NoModalBasis`]).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ModalBasisError {
    /// More unknowns than one dense O(n³) SVD is allowed
    /// ([`wingcheck_model::MODAL_MAX_UNKNOWNS`]).
    #[error("{n} unknowns: above the modal basis's {max} (one dense O(n³) SVD)")]
    TooManyUnknowns {
        /// The discretisation's unknowns.
        n: usize,
        /// The limit.
        max: usize,
    },
    /// The modes could not be computed.
    #[error(transparent)]
    Numerical(#[from] NumericalError),
    /// The basis failed its check ([`crate::modal::MASS_TOLERANCE`],
    /// [`crate::modal::FREQUENCY_TOLERANCE`]).
    #[error(
        "modal basis of {n} unknowns is orthonormal only to {mass_defect:.1e} in M (tolerance \
         {mass_tolerance:.0e}), its frequencies bounded only to {frequency_error:.1e} relative (tolerance \
         {frequency_tolerance:.0e})"
    )]
    Unchecked {
        /// The discretisation's unknowns.
        n: usize,
        /// max |ΦᵀMΦ − I| measured.
        mass_defect: f64,
        /// Its tolerance.
        mass_tolerance: f64,
        /// The bound on the frequencies' relative error.
        frequency_error: f64,
        /// Its tolerance.
        frequency_tolerance: f64,
    },
}

/// `discretisation.stepper = exponential` without a modal basis (the scheme runs in the modal
/// basis only).
#[derive(Debug, Clone, PartialEq, Error)]
#[error(
    "discretisation.stepper = exponential needs the modal basis: {reason}; \
     use discretisation.stepper=trbdf2 (or auto) or a coarser grid"
)]
pub struct ExponentialNeedsModal {
    /// Why there is no modal basis.
    pub reason: ModalBasisError,
}

/// Why a refined run cannot use the base run's time scheme
/// ([`crate::SimError::RefinementScheme`]).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SchemeObstacle {
    /// A numerical step of the refined run's set-up failed.
    #[error(transparent)]
    Numerical(#[from] NumericalError),
    /// The refined discretisation has no modal basis.
    #[error(transparent)]
    NoModalBasis(#[from] ModalBasisError),
    /// The exponential scheme needs a modal basis the refined discretisation has not.
    #[error(transparent)]
    ExponentialNeedsModal(#[from] ExponentialNeedsModal),
}
