//! Exact checks for linear systems `{x : A x ≤ b, A_eq x = b_eq}`.
//!
//! * [`check_farkas`]: a Farkas certificate `(y ≥ 0, w free)` with
//!   `yᵀA + wᵀA_eq = 0` and `yᵀb + wᵀb_eq < 0` proves the system infeasible
//!   (any feasible `x` would give `0 = (yᵀA + wᵀA_eq)x ≤ yᵀb + wᵀb_eq < 0`).
//! * [`check_feasible_point`]: verifies that a rational `x` satisfies every
//!   constraint exactly.

use num_rational::BigRational;
use num_traits::{Signed, Zero};

use crate::exact::abbreviated;
use crate::matrix::RationalMatrix;

/// Failure of an exact LP check.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum LpError {
    /// Sizes of the system or certificate do not fit together.
    #[error("dimension mismatch: {what} has {found}, expected {expected}")]
    Dimension {
        /// Which object.
        what: &'static str,
        /// Expected size.
        expected: usize,
        /// Size found.
        found: usize,
    },
    /// An inequality multiplier `y[index] < 0`.
    #[error("Farkas multiplier y[{index}] = {} is negative", abbreviated(value))]
    NegativeMultiplier {
        /// Index into `y`.
        index: usize,
        /// Offending value.
        value: BigRational,
    },
    /// `(yᵀA + wᵀA_eq)[column] ≠ 0`.
    #[error("Farkas combination nonzero at column {column}: {}", abbreviated(value))]
    CombinationNonzero {
        /// Column (variable) index.
        column: usize,
        /// Value of the combination there.
        value: BigRational,
    },
    /// `yᵀb + wᵀb_eq ≥ 0`, so nothing is proved.
    #[error("Farkas right-hand side yᵀb + wᵀb_eq = {} is not negative", abbreviated(value))]
    RhsNotNegative {
        /// The value of `yᵀb + wᵀb_eq`.
        value: BigRational,
    },
    /// Inequality row violated: `(A x)[row] > b[row]`.
    #[error("inequality {row} violated: (A x) = {} > b = {}", abbreviated(lhs), abbreviated(rhs))]
    InequalityViolated {
        /// Row index.
        row: usize,
        /// `(A x)[row]` (boxed to keep the error small).
        lhs: Box<BigRational>,
        /// `b[row]`.
        rhs: Box<BigRational>,
    },
    /// Equality row violated: `(A_eq x)[row] ≠ b_eq[row]`.
    #[error("equality {row} violated: (A_eq x) = {} ≠ b_eq = {}", abbreviated(lhs), abbreviated(rhs))]
    EqualityViolated {
        /// Row index.
        row: usize,
        /// `(A_eq x)[row]` (boxed to keep the error small).
        lhs: Box<BigRational>,
        /// `b_eq[row]`.
        rhs: Box<BigRational>,
    },
}

/// The system `{x ∈ ℚⁿ : A x ≤ b, A_eq x = b_eq}` with `n = a.cols()`.
/// Either block may have zero rows (but must still have `n` columns).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LinearSystem {
    /// Inequality matrix `A` (`m × n`).
    pub a: RationalMatrix,
    /// Inequality right-hand side `b` (length `m`).
    pub b: Vec<BigRational>,
    /// Equality matrix `A_eq` (`p × n`).
    pub a_eq: RationalMatrix,
    /// Equality right-hand side `b_eq` (length `p`).
    pub b_eq: Vec<BigRational>,
}

impl LinearSystem {
    /// Number of variables `n`.
    pub fn n_vars(&self) -> usize {
        self.a.cols()
    }

    /// Checks that all blocks have consistent sizes.
    pub fn check_shape(&self) -> Result<(), LpError> {
        let dim = |what, expected, found| {
            if expected == found {
                Ok(())
            } else {
                Err(LpError::Dimension { what, expected, found })
            }
        };
        dim("b", self.a.rows(), self.b.len())?;
        dim("A_eq columns", self.a.cols(), self.a_eq.cols())?;
        dim("b_eq", self.a_eq.rows(), self.b_eq.len())
    }
}

/// Multipliers of a Farkas infeasibility certificate.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FarkasCertificate {
    /// Multipliers for `A x ≤ b` (must be `≥ 0`; length `m`).
    pub y: Vec<BigRational>,
    /// Multipliers for `A_eq x = b_eq` (free sign; length `p`).
    pub w: Vec<BigRational>,
}

fn dot(a: &[BigRational], b: &[BigRational]) -> BigRational {
    a.iter().zip(b).filter(|(x, y)| !x.is_zero() && !y.is_zero()).fold(BigRational::zero(), |acc, (x, y)| acc + x * y)
}

/// Verifies a Farkas certificate; on success returns `yᵀb + wᵀb_eq` (< 0).
pub fn check_farkas(sys: &LinearSystem, cert: &FarkasCertificate) -> Result<BigRational, LpError> {
    sys.check_shape()?;
    let dim = |what, expected: usize, found: usize| {
        if expected == found {
            Ok(())
        } else {
            Err(LpError::Dimension { what, expected, found })
        }
    };
    dim("y", sys.a.rows(), cert.y.len())?;
    dim("w", sys.a_eq.rows(), cert.w.len())?;
    if let Some((index, value)) = cert.y.iter().enumerate().find(|(_, v)| v.is_negative()) {
        return Err(LpError::NegativeMultiplier { index, value: value.clone() });
    }
    let ya = sys.a.vec_mul(&cert.y).expect("shape checked");
    let wa = sys.a_eq.vec_mul(&cert.w).expect("shape checked");
    for (column, (u, v)) in ya.iter().zip(&wa).enumerate() {
        let s = u + v;
        if !s.is_zero() {
            return Err(LpError::CombinationNonzero { column, value: s });
        }
    }
    let value = dot(&cert.y, &sys.b) + dot(&cert.w, &sys.b_eq);
    if !value.is_negative() {
        return Err(LpError::RhsNotNegative { value });
    }
    Ok(value)
}

/// Verifies that `x` satisfies `A x ≤ b` and `A_eq x = b_eq` exactly.
pub fn check_feasible_point(sys: &LinearSystem, x: &[BigRational]) -> Result<(), LpError> {
    sys.check_shape()?;
    if x.len() != sys.n_vars() {
        return Err(LpError::Dimension { what: "x", expected: sys.n_vars(), found: x.len() });
    }
    let ax = sys.a.mul_vec(x).expect("shape checked");
    for (row, (lhs, rhs)) in ax.into_iter().zip(&sys.b).enumerate() {
        if &lhs > rhs {
            return Err(LpError::InequalityViolated { row, lhs: Box::new(lhs), rhs: Box::new(rhs.clone()) });
        }
    }
    let ax = sys.a_eq.mul_vec(x).expect("shape checked");
    for (row, (lhs, rhs)) in ax.into_iter().zip(&sys.b_eq).enumerate() {
        if &lhs != rhs {
            return Err(LpError::EqualityViolated { row, lhs: Box::new(lhs), rhs: Box::new(rhs.clone()) });
        }
    }
    Ok(())
}
