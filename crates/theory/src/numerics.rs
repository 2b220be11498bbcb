//! Typed failures of the theory's and the claim checker's numerics: building the exact forms
//! W, κ of (22)–(25) ([`FormsError`]), and the float pencils, eigen-solves and convex solves on
//! them ([`PencilError`]). The claims crate's `ClaimsError::Numerical` and
//! `certify::CertifyError::Numerical` carry a [`PencilError`] as their cause.

use std::sync::Arc;

use faer::linalg::cholesky::llt::factor::LltError;
use faer::linalg::evd::EvdError;
use wingcheck_cert::exact::ExactError;

/// Why the exact forms W, κ (or a certificate recipe's matrix built from them) could not be
/// assembled from their parameters.
#[derive(Debug, Clone, thiserror::Error)]
pub enum FormsError {
    /// The Galerkin space's element count is outside the exact assembly's range.
    #[error("elements = {0} out of range [1, 64]")]
    Elements(usize),
    /// The span or ρ is zero or negative.
    #[error("span and rho must be positive")]
    NonPositive,
    /// A parameter is not an exact decimal or fraction.
    #[error("{field}: {cause}")]
    Rational {
        /// The parameter.
        field: &'static str,
        /// The parser's reason.
        #[source]
        cause: ExactError,
    },
    /// A recipe lacks a field.
    #[error("missing `{0}`")]
    Missing(&'static str),
    /// A recipe's `forms` do not parse.
    #[error("{0}")]
    Json(#[source] Arc<serde_json::Error>),
    /// Two matrices of a recipe have different dimensions.
    #[error("dimension mismatch")]
    DimensionMismatch,
    /// A recipe's direction x has the wrong length.
    #[error("x has {got} entries, the state space {dim}")]
    DirectionLength {
        /// Entries of x.
        got: usize,
        /// Dimension of the state space (11N).
        dim: usize,
    },
    /// A recipe names a form that does not exist.
    #[error("unknown form `{0}`")]
    UnknownForm(String),
}

/// A failed numerical step of the claim checker: on the pencil (W, κ) a factorisation, an
/// eigen-solve, a reduction or a convex solve; a bound's or run's inputs outside its hypotheses.
#[derive(Debug, Clone, thiserror::Error)]
pub enum PencilError {
    /// The exact forms could not be assembled.
    #[error(transparent)]
    Forms(#[from] FormsError),
    /// A matrix that must be positive definite is not (its Cholesky factorisation failed).
    #[error("{what} is not positive definite: {cause:?}")]
    NotPositiveDefinite {
        /// The matrix (`κ`, `κ (B)`).
        what: &'static str,
        /// faer's reason (the failing pivot).
        cause: LltError,
    },
    /// A symmetric eigen-solve did not converge.
    #[error("{what}: {cause:?}")]
    Eigen {
        /// The step (`eigenvalues`, `eigen solver failed`).
        what: &'static str,
        /// faer's reason.
        cause: EvdError,
    },
    /// The two matrices of a pencil differ in shape.
    #[error("A is {}x{}, B is {}x{}", a.0, a.1, b.0, b.1)]
    Shape {
        /// Rows and columns of A.
        a: (usize, usize),
        /// Rows and columns of B.
        b: (usize, usize),
    },
    /// The hierarchical reduction needs a power-of-two element count.
    #[error("elements = {0} is not a power of two")]
    NotPowerOfTwo(usize),
    /// W, κ lack the velocity structure the reduction relies on.
    #[error("W, κ do not have the velocity structure the reduction needs (residual {residual:.1e} of max |W|)")]
    VelocityStructure {
        /// The largest residual over max |W|.
        residual: f64,
    },
    /// The hierarchical basis's congruence is not the identity on κ to 1e-10.
    #[error("the hierarchical basis did not orthonormalise κ (error {0:.1e})")]
    NotOrthonormal(f64),
    /// Building or solving an SDP failed (infeasibility is a status, not this).
    #[error("{0}")]
    Sdp(#[source] Arc<crate::sdp::problem::SdpError>),
    /// clarabel panicked inside a solve.
    #[error("clarabel failed ({0})")]
    SolverPanicked(#[source] wingcheck_io::Panicked),
    /// No solver tolerance to try.
    #[error("no solver tolerance configured")]
    NoTolerance,
    /// clarabel rejected its settings.
    #[error("{0:?}")]
    SolverSettings(Arc<clarabel::solver::DefaultSettingsBuilderError>),
    /// clarabel rejected the problem's data.
    #[error("{0:?}")]
    SolverSetup(Arc<clarabel::solver::SolverError>),
    /// The f64 LDLᵀ of K − σM met a zero or non-finite pivot.
    #[error("the f64 LDLᵀ broke down at σ = {0:e}")]
    LdltBreakdown(f64),
    /// K − σM is not positive definite just below the fundamental eigenvalue.
    #[error("K − σM is not positive definite just below μ₁")]
    ShiftNotDefinite,
    /// A vector that must be nonzero and finite is not.
    #[error("{0}")]
    DegenerateVector(&'static str),
    /// A value whose sign is to be certified is too close to 0 for either sign.
    #[error("{what} = {value:.3e} is too close to 0 to certify either sign")]
    NearZero {
        /// The quantity.
        what: &'static str,
        /// Its float value.
        value: f64,
    },
    /// A run needed for a bound recorded no fields.
    #[error("the run recorded no fields")]
    NoFields,
    /// Lemma 3's time (14) outside its hypotheses.
    #[error("need φ1, φ2 > 0, 0 < φ3 < 1, Q0 ≥ 0; got {phi1}, {phi2}, {phi3}, {q0}")]
    Lemma3Inputs {
        /// φ1 (1/s).
        phi1: f64,
        /// φ2.
        phi2: f64,
        /// φ3.
        phi3: f64,
        /// Q0.
        q0: f64,
    },
    /// The bound (38) outside its hypotheses.
    #[error("need κ_lin, κ_frac > 0, a1 < a2 < 2a1; got {linear}, {fractional}, {a1}, {a2}")]
    Bound38Inputs {
        /// κ_lin.
        linear: f64,
        /// κ_frac.
        fractional: f64,
        /// a1.
        a1: u32,
        /// a2.
        a2: u32,
    },
    /// The Filippov reaching solve's inputs are out of range.
    #[error("bad input σ0 = {sigma0}, r = {exponent}")]
    FilippovInputs {
        /// σ(0).
        sigma0: f64,
        /// The exponent r.
        exponent: f64,
    },
    /// A digital run's timing is out of range.
    #[error("need T > 0, t_end > T, window > 0; got {period}, {t_end}, {window}")]
    DigitalRunInputs {
        /// The hold period T (s).
        period: f64,
        /// The end time (s).
        t_end: f64,
        /// The window (s).
        window: f64,
    },
    /// The finite-time runs at the reference hold period are missing.
    #[error("the runs at the reference hold period are missing")]
    MissingReferenceRuns,
    /// Lemma 3's reaching time by RK4 has a non-finite error.
    #[error("the RK4 reaching time did not converge")]
    ReachingTimeNotConverged,
    /// A Gram matrix's Cholesky pivot is not positive.
    #[error("not positive definite at {0}")]
    GramPivot(usize),
    /// Lemma 2's ratio outside its hypotheses.
    #[error("need f > 0, K ≥ 1; got {span}, {degree}")]
    Lemma2Inputs {
        /// The span f (m).
        span: f64,
        /// The degree K.
        degree: usize,
    },
    /// The span is not an exact decimal.
    #[error("span {span} not a decimal: {cause}")]
    SpanNotDecimal {
        /// The span (m).
        span: f64,
        /// The parser's reason.
        #[source]
        cause: ExactError,
    },
    /// The span is not positive.
    #[error("span {0} must be > 0")]
    SpanNotPositive(f64),
    /// A simulation's own numerics failed (ω₁ from the simulator's modes).
    #[error(transparent)]
    Sim(Arc<wingcheck_sim::SimError>),
}

impl From<wingcheck_sim::SimError> for PencilError {
    fn from(e: wingcheck_sim::SimError) -> Self {
        PencilError::Sim(Arc::new(e))
    }
}

impl From<crate::sdp::problem::SdpError> for PencilError {
    fn from(e: crate::sdp::problem::SdpError) -> Self {
        PencilError::Sdp(Arc::new(e))
    }
}
