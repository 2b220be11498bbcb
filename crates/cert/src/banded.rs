//! Symmetric banded rational matrices and their exact inertia.
//!
//! [`inertia`] counts the negative and positive LDLᵀ pivots of a symmetric banded matrix by a
//! fraction-free (Bareiss) elimination without pivoting on the integer matrix `c·A` (`c` the
//! lcm of the denominators), the banded analogue of [`crate::psd::check_positive_definite`]:
//! after step `k` every active entry is a minor of order `k + 2` of `c·A`, the `k`-th pivot is
//! the leading principal minor `Δ_{k+1}`, and the LDLᵀ pivot is `d_k = Δ_{k+1}/(c·Δ_k)`. By
//! Sylvester's law of inertia (`A = L D Lᵀ` with `L` unit lower triangular is a congruence) the
//! number of negative `d_k` is the number of negative eigenvalues of `A`. Without pivoting the
//! elimination needs every leading principal minor to be nonzero; a zero one is reported
//! ([`ZeroLeadingMinor`]) rather than worked around, and the caller chooses another shift.
//!
//! Work: no fill outside the band, so `n · bandwidth²` big-integer multiply–divides on numbers
//! of up to `n · b` bits (`b` the bits of one integerised entry).

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

use crate::exact::denominator_lcm;

/// A symmetric matrix of dimension `n` with upper bandwidth `bw`: `A[i][j] = 0` for
/// `|i − j| > bw`. Row `i` stores `A[i][i], A[i][i+1], …, A[i][min(i+bw, n−1)]`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SymBand {
    bw: usize,
    rows: Vec<Vec<BigRational>>,
}

impl SymBand {
    /// The zero matrix of dimension `n` and upper bandwidth `bw`.
    pub fn zeros(n: usize, bw: usize) -> Self {
        let rows = (0..n).map(|i| vec![BigRational::zero(); (bw + 1).min(n - i)]).collect();
        SymBand { bw, rows }
    }

    /// Dimension.
    pub fn dim(&self) -> usize {
        self.rows.len()
    }

    /// Upper bandwidth.
    pub fn bandwidth(&self) -> usize {
        self.bw
    }

    /// `A[i][j]` (zero outside the band).
    ///
    /// # Panics
    /// If `i` or `j` is out of range.
    pub fn get(&self, i: usize, j: usize) -> BigRational {
        let (i, j) = if i <= j { (i, j) } else { (j, i) };
        assert!(j < self.dim(), "index out of range");
        self.rows[i].get(j - i).cloned().unwrap_or_else(BigRational::zero)
    }

    /// Adds `v` to `A[i][j]` (and so to `A[j][i]`).
    ///
    /// # Panics
    /// If `(i, j)` lies outside the band or the matrix.
    pub fn add_to(&mut self, i: usize, j: usize, v: &BigRational) {
        let (i, j) = if i <= j { (i, j) } else { (j, i) };
        assert!(j - i <= self.bw && j < self.dim(), "entry ({i},{j}) outside the band");
        self.rows[i][j - i] += v;
    }

    /// `self + c · other` (same dimension and bandwidth).
    ///
    /// # Panics
    /// If the shapes differ.
    pub fn add_scaled(&self, c: &BigRational, other: &SymBand) -> SymBand {
        assert!(self.dim() == other.dim() && self.bw == other.bw, "shape mismatch");
        let rows = self
            .rows
            .iter()
            .zip(&other.rows)
            .map(|(a, b)| a.iter().zip(b).map(|(x, y)| if y.is_zero() { x.clone() } else { x + c * y }).collect())
            .collect();
        SymBand { bw: self.bw, rows }
    }

    /// The stored upper band, row by row (`row(i)[d] = A[i][i+d]`).
    pub fn row(&self, i: usize) -> &[BigRational] {
        &self.rows[i]
    }
}

/// Numbers of negative and positive eigenvalues of a symmetric matrix (no zero eigenvalue:
/// [`inertia`] refuses singular leading minors).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Inertia {
    /// Negative LDLᵀ pivots = negative eigenvalues.
    pub negative: usize,
    /// Positive LDLᵀ pivots = positive eigenvalues.
    pub positive: usize,
}

/// A leading principal minor is zero, so LDLᵀ without pivoting does not exist.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("the leading principal minor of order {order} is exactly zero (LDLᵀ without pivoting breaks down)")]
pub struct ZeroLeadingMinor {
    /// Order of the vanishing minor (1-based).
    pub order: usize,
}

/// Exact inertia of a symmetric banded rational matrix by fraction-free LDLᵀ without
/// pivoting (see the module documentation). The empty matrix has inertia (0, 0).
///
/// # Errors
/// [`ZeroLeadingMinor`] if some leading principal minor vanishes.
pub fn inertia(a: &SymBand) -> Result<Inertia, ZeroLeadingMinor> {
    let n = a.dim();
    let c = denominator_lcm(a.rows.iter().flatten());
    let mut rows: Vec<Vec<BigInt>> = a
        .rows
        .iter()
        .map(|r| r.iter().map(|v| if v.is_zero() { BigInt::zero() } else { v.numer() * (&c / v.denom()) }).collect())
        .collect();
    // minors[k] = Δ_k of c·A (Δ_0 = 1); upto[i] = s: row i holds its values after step s − 1.
    let mut minors: Vec<BigInt> = vec![BigInt::one()];
    let mut upto = vec![0usize; n];
    let bring = crate::psd::bring_row;
    let mut negative = 0;
    for k in 0..n {
        let (head, tail) = rows.split_at_mut(k + 1);
        let row_k = &mut head[k];
        bring(row_k, &mut upto[k], k, &minors);
        let pk = row_k[0].clone();
        if pk.is_zero() {
            return Err(ZeroLeadingMinor { order: k + 1 });
        }
        let prev = &minors[k];
        if pk.is_negative() != prev.is_negative() {
            negative += 1;
        }
        for off in 1..row_k.len() {
            let cik = &row_k[off];
            if cik.is_zero() {
                continue; // pure rescaling of row k + off, deferred
            }
            let i = k + off;
            let row_i = &mut tail[off - 1];
            bring(row_i, &mut upto[i], k, &minors);
            for (jj, e) in row_i.iter_mut().enumerate() {
                match row_k.get(off + jj) {
                    Some(mkj) if !mkj.is_zero() => *e = (&pk * &*e - cik * mkj) / prev,
                    _ => {
                        if !e.is_zero() {
                            *e = &*e * &pk / prev;
                        }
                    }
                }
            }
            upto[i] = k + 1;
        }
        minors.push(pk);
    }
    Ok(Inertia { negative, positive: n - negative })
}
