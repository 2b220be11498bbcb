//! Typed failures of the theory's numerics: building the exact forms W, κ of (22)–(25)
//! ([`FormsError`]), and the float pencils, eigen-solves and convex solves on them
//! ([`PencilError`]). The claims crate's own numerical failures (its reaching times, Lemma
//! checks, digital runs, the ω₁ enclosure's float steps) are its `numerics::NumericsError`,
//! which wraps these.

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

/// A failed numerical step of the theory: on the pencil (W, κ) a factorisation, an eigen-solve,
/// a reduction or a convex solve.
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
