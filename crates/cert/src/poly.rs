//! Exact univariate polynomials with rational coefficients.

use std::ops::{Add, Mul, Neg, Sub};

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Zero};

/// A polynomial `Σ c_k x^k` with exact rational coefficients, stored in
/// ascending order with no trailing zeros (the zero polynomial has no
/// coefficients). The variable `x` carries whatever unit the caller uses
/// (for FE shape functions: arc length along the element, in metres).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Poly {
    coeffs: Vec<BigRational>,
}

impl Poly {
    /// Builds a polynomial from ascending coefficients `[c0, c1, …]`.
    pub fn new(mut coeffs: Vec<BigRational>) -> Self {
        while coeffs.last().is_some_and(Zero::is_zero) {
            coeffs.pop();
        }
        Self { coeffs }
    }

    /// The zero polynomial.
    pub fn zero() -> Self {
        Self { coeffs: Vec::new() }
    }

    /// The constant polynomial `c`.
    pub fn constant(c: BigRational) -> Self {
        Self::new(vec![c])
    }

    /// The polynomial `x`.
    pub fn x() -> Self {
        Self::new(vec![BigRational::zero(), BigRational::one()])
    }

    /// The monomial `c · x^k`.
    pub fn monomial(c: BigRational, k: usize) -> Self {
        let mut coeffs = vec![BigRational::zero(); k];
        coeffs.push(c);
        Self::new(coeffs)
    }

    /// Ascending coefficients (empty for the zero polynomial).
    pub fn coeffs(&self) -> &[BigRational] {
        &self.coeffs
    }

    /// Degree; `None` for the zero polynomial.
    pub fn degree(&self) -> Option<usize> {
        self.coeffs.len().checked_sub(1)
    }

    /// Whether this is the zero polynomial.
    pub fn is_zero(&self) -> bool {
        self.coeffs.is_empty()
    }

    /// Value at `x` (Horner).
    pub fn eval(&self, x: &BigRational) -> BigRational {
        self.coeffs.iter().rev().fold(BigRational::zero(), |acc, c| acc * x + c)
    }

    /// `c · self`.
    pub fn scale(&self, c: &BigRational) -> Self {
        Self::new(self.coeffs.iter().map(|a| a * c).collect())
    }

    /// First derivative `d/dx`.
    pub fn derivative(&self) -> Self {
        Self::new(
            self.coeffs
                .iter()
                .enumerate()
                .skip(1)
                .map(|(k, c)| c * BigRational::from_integer(BigInt::from(k)))
                .collect(),
        )
    }

    /// The antiderivative vanishing at 0.
    pub fn antiderivative(&self) -> Self {
        let mut coeffs = Vec::with_capacity(self.coeffs.len() + 1);
        coeffs.push(BigRational::zero());
        for (k, c) in self.coeffs.iter().enumerate() {
            coeffs.push(c / BigRational::from_integer(BigInt::from(k + 1)));
        }
        Self::new(coeffs)
    }

    /// Exact definite integral `∫_{x0}^{x1} p(x) dx`.
    pub fn integrate(&self, x0: &BigRational, x1: &BigRational) -> BigRational {
        let anti = self.antiderivative();
        anti.eval(x1) - anti.eval(x0)
    }

    /// Composition `self(q(x))`.
    pub fn compose(&self, q: &Poly) -> Self {
        self.coeffs.iter().rev().fold(Poly::zero(), |acc, c| &(&acc * q) + &Poly::constant(c.clone()))
    }
}

impl Add for &Poly {
    type Output = Poly;
    fn add(self, rhs: &Poly) -> Poly {
        let n = self.coeffs.len().max(rhs.coeffs.len());
        let zero = BigRational::zero();
        Poly::new((0..n).map(|k| self.coeffs.get(k).unwrap_or(&zero) + rhs.coeffs.get(k).unwrap_or(&zero)).collect())
    }
}

impl Sub for &Poly {
    type Output = Poly;
    fn sub(self, rhs: &Poly) -> Poly {
        self + &(-rhs)
    }
}

impl Neg for &Poly {
    type Output = Poly;
    fn neg(self) -> Poly {
        Poly::new(self.coeffs.iter().map(|c| -c).collect())
    }
}

impl Mul for &Poly {
    type Output = Poly;
    fn mul(self, rhs: &Poly) -> Poly {
        if self.is_zero() || rhs.is_zero() {
            return Poly::zero();
        }
        let mut out = vec![BigRational::zero(); self.coeffs.len() + rhs.coeffs.len() - 1];
        for (i, a) in self.coeffs.iter().enumerate() {
            for (j, b) in rhs.coeffs.iter().enumerate() {
                out[i + j] += a * b;
            }
        }
        Poly::new(out)
    }
}
