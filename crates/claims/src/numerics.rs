//! A claim's own numerical failures — its reaching times, Lemma checks, digital runs and the ω₁
//! enclosure's float steps — beside the theory's ([`PencilError`], [`FormsError`]), which they
//! wrap. `ClaimsError::Numerical` and `certify::CertifyError::Numerical` carry a
//! [`NumericsError`] as their cause.

use wingcheck_cert::exact::ExactError;
use wingcheck_theory::numerics::{FormsError, PencilError};

/// A failed numerical step of a claim's check or of a certificate's float search.
#[derive(Debug, Clone, thiserror::Error)]
pub enum NumericsError {
    /// The theory's computation failed (the exact forms, the pencil, an eigen-solve, a solver).
    #[error(transparent)]
    Theory(#[from] PencilError),
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
}

impl From<FormsError> for NumericsError {
    fn from(e: FormsError) -> Self {
        NumericsError::Theory(e.into())
    }
}

impl From<wingcheck_sim::SimError> for NumericsError {
    fn from(e: wingcheck_sim::SimError) -> Self {
        NumericsError::Theory(e.into())
    }
}
