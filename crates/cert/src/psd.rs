//! Exact positive-(semi)definiteness checks for symmetric rational matrices.
//!
//! [`check_positive_definite`] runs a symmetric, fraction-free (Bareiss)
//! elimination without pivoting on the integer matrix `M = c·A`, where `c` is
//! the lcm of all denominators. The `k`-th Bareiss pivot equals the leading
//! principal minor `Δ_{k+1}(M)`; by Sylvester's criterion `A ≻ 0` iff every
//! `Δ_k > 0`, and the LDLᵀ pivots of `A` are `d_k = Δ_{k+1} / (Δ_k · c)`.
//! Rows whose eliminating entry is zero are only rescaled by `Δ_{k+1}/Δ_k`;
//! that rescaling is deferred until the row is next touched, so banded FE
//! matrices cost `O(n · bandwidth²)` big-integer operations instead of `O(n³)`.
//!
//! [`check_psd_with_witness`] verifies a supplied factorisation `A = L D Lᵀ`
//! with unit lower-triangular `L` and `D ≥ 0`, which certifies `A ⪰ 0` even
//! when some pivots are zero.

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

use crate::exact::{abbreviated, denominator_lcm};
use crate::matrix::RationalMatrix;

/// Why a matrix was not accepted as positive (semi)definite.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum PsdError {
    /// The matrix is not square.
    #[error("matrix is not square ({rows}×{cols})")]
    NotSquare {
        /// Row count.
        rows: usize,
        /// Column count.
        cols: usize,
    },
    /// `A[i][j] ≠ A[j][i]`.
    #[error("matrix is not symmetric: entry ({i},{j}) differs from ({j},{i})")]
    NotSymmetric {
        /// Row of the first asymmetric entry.
        i: usize,
        /// Column of the first asymmetric entry.
        j: usize,
    },
    /// LDLᵀ pivot `index` (0-based) is `≤ 0`, so `A` is not positive definite.
    #[error("pivot {index} not positive: {}", abbreviated(value))]
    PivotNotPositive {
        /// 0-based index of the first non-positive pivot.
        index: usize,
        /// Its exact value `Δ_{k+1}/Δ_k` (in the units of `A`).
        value: BigRational,
    },
    /// A zero pivot whose column below is not zero: `A` is indefinite.
    #[error(
        "not PSD: pivot {index} is zero but entry ({row},{index}) of its Schur complement is {}",
        abbreviated(value)
    )]
    ZeroPivotNonzeroColumn {
        /// 0-based pivot index.
        index: usize,
        /// Row of the nonzero entry below the zero pivot.
        row: usize,
        /// That entry.
        value: BigRational,
    },
    /// A witness matrix/vector has the wrong size.
    #[error("witness {what} has size {found}, expected {expected}")]
    WitnessShape {
        /// Which part (`"L"` or `"D"`).
        what: &'static str,
        /// Expected size.
        expected: String,
        /// Size found.
        found: String,
    },
    /// `L` is not unit lower triangular at `(i, j)`.
    #[error("witness L is not unit lower triangular: L[{i}][{j}] = {}", abbreviated(value))]
    WitnessNotUnitLower {
        /// Row.
        i: usize,
        /// Column.
        j: usize,
        /// Offending value.
        value: BigRational,
    },
    /// `D[index] < 0`.
    #[error("witness D[{index}] = {} is negative", abbreviated(value))]
    WitnessNegativeD {
        /// Index into `D`.
        index: usize,
        /// Offending value.
        value: BigRational,
    },
    /// `(L D Lᵀ)[i][j] ≠ A[i][j]`.
    #[error(
        "witness does not reproduce A at ({i},{j}): A has {}, L·D·Lᵀ has {}",
        abbreviated(expected),
        abbreviated(found)
    )]
    WitnessMismatch {
        /// Row.
        i: usize,
        /// Column.
        j: usize,
        /// `A[i][j]` (boxed to keep the error small).
        expected: Box<BigRational>,
        /// `(L D Lᵀ)[i][j]`.
        found: Box<BigRational>,
    },
}

/// Outcome of a successful positive-definiteness check.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PdReport {
    /// Exact LDLᵀ pivots `d_0 … d_{n−1}` of `A` (all `> 0`).
    pub pivots: Vec<BigRational>,
}

impl PdReport {
    /// Smallest pivot (`None` for the empty matrix).
    pub fn min_pivot(&self) -> Option<&BigRational> {
        self.pivots.iter().min()
    }

    /// `det A`, the product of the pivots.
    pub fn determinant(&self) -> BigRational {
        self.pivots.iter().fold(BigRational::one(), |acc, d| acc * d)
    }
}

fn check_square_symmetric(a: &RationalMatrix) -> Result<(), PsdError> {
    if !a.is_square() {
        return Err(PsdError::NotSquare { rows: a.rows(), cols: a.cols() });
    }
    match a.first_asymmetry() {
        Some((i, j)) => Err(PsdError::NotSymmetric { i, j }),
        None => Ok(()),
    }
}

/// Upper triangle of `c·A` as integers, `rows[i][j - i]`, and the scale `c`.
fn integer_upper(a: &RationalMatrix) -> (Vec<Vec<BigInt>>, BigInt) {
    let n = a.rows();
    let c = denominator_lcm((0..n).flat_map(|i| a.row(i)[i..].iter()));
    let rows = (0..n)
        .map(|i| {
            a.row(i)[i..]
                .iter()
                .map(|v| if v.is_zero() { BigInt::zero() } else { v.numer() * (&c / v.denom()) })
                .collect()
        })
        .collect();
    (rows, c)
}

/// The deferred rescaling of fraction-free LDLᵀ (Bareiss): row `row`, last updated by step
/// `*upto` − 1, is brought to step `k` by multiplying its nonzero entries by Δ_k/Δ_upto (exact:
/// the division is exact by Sylvester's identity). Shared by [`check_positive_definite`] and the
/// banded inertia ([`crate::banded::inertia`]).
pub(crate) fn bring_row(row: &mut [BigInt], upto: &mut usize, k: usize, minors: &[BigInt]) {
    if *upto < k {
        let (num, den) = (&minors[k], &minors[*upto]);
        for e in row.iter_mut().filter(|e| !e.is_zero()) {
            *e = &*e * num / den;
        }
        *upto = k;
    }
}

/// Exact positive-definiteness test (Sylvester via fraction-free LDLᵀ).
///
/// Returns all LDLᵀ pivots on success; otherwise the first pivot that is not
/// positive, with its exact value, or a shape/symmetry error. The empty
/// matrix is positive definite.
pub fn check_positive_definite(a: &RationalMatrix) -> Result<PdReport, PsdError> {
    check_square_symmetric(a)?;
    let n = a.rows();
    let (mut rows, c) = integer_upper(a);
    // minors[k] = Δ_k (leading principal minor of order k of c·A); Δ_0 = 1.
    let mut minors: Vec<BigInt> = vec![BigInt::one()];
    // upto[i] = s means row i currently holds M^(s) (updated by steps < s).
    let mut upto = vec![0usize; n];
    let bring = bring_row;
    let mut pivots = Vec::with_capacity(n);
    for k in 0..n {
        let (head, tail) = rows.split_at_mut(k + 1);
        let row_k = &mut head[k];
        bring(row_k, &mut upto[k], k, &minors);
        let pk = row_k[0].clone();
        let prev = &minors[k];
        let d = BigRational::new(pk.clone(), prev * &c);
        if !pk.is_positive() {
            return Err(PsdError::PivotNotPositive { index: k, value: d });
        }
        pivots.push(d);
        for (off, row_i) in tail.iter_mut().enumerate() {
            let i = k + 1 + off;
            let cik = &row_k[i - k];
            if cik.is_zero() {
                continue; // pure rescaling, deferred
            }
            bring(row_i, &mut upto[i], k, &minors);
            for (jj, e) in row_i.iter_mut().enumerate() {
                let mkj = &row_k[i - k + jj];
                if mkj.is_zero() {
                    if !e.is_zero() {
                        *e = &*e * &pk / prev;
                    }
                } else {
                    *e = (&pk * &*e - cik * mkj) / prev;
                }
            }
            upto[i] = k + 1;
        }
        minors.push(pk);
    }
    Ok(PdReport { pivots })
}

/// Verifies `A = L D Lᵀ` exactly with `L` unit lower triangular and every
/// `D[k] ≥ 0`; together these prove `A ⪰ 0` (`xᵀAx = Σ D_k (Lᵀx)_k²`).
pub fn check_psd_with_witness(a: &RationalMatrix, l: &RationalMatrix, d: &[BigRational]) -> Result<(), PsdError> {
    check_square_symmetric(a)?;
    let n = a.rows();
    if l.rows() != n || l.cols() != n {
        return Err(PsdError::WitnessShape {
            what: "L",
            expected: format!("{n}×{n}"),
            found: format!("{}×{}", l.rows(), l.cols()),
        });
    }
    if d.len() != n {
        return Err(PsdError::WitnessShape { what: "D", expected: n.to_string(), found: d.len().to_string() });
    }
    for i in 0..n {
        for j in i..n {
            let v = l.get(i, j);
            let ok = if i == j { v.is_one() } else { v.is_zero() };
            if !ok {
                return Err(PsdError::WitnessNotUnitLower { i, j, value: v.clone() });
            }
        }
    }
    if let Some((index, value)) = d.iter().enumerate().find(|(_, v)| v.is_negative()) {
        return Err(PsdError::WitnessNegativeD { index, value: value.clone() });
    }
    // Column indices of the nonzeros in each row of L (lower part incl. diagonal).
    let nz: Vec<Vec<usize>> = (0..n).map(|i| (0..=i).filter(|&k| !l.get(i, k).is_zero()).collect()).collect();
    for i in 0..n {
        for (j, nz_j) in nz.iter().enumerate().take(i + 1) {
            let mut s = BigRational::zero();
            for &k in nz_j {
                let lik = l.get(i, k);
                if !lik.is_zero() && !d[k].is_zero() {
                    s += lik * &d[k] * l.get(j, k);
                }
            }
            if &s != a.get(i, j) {
                return Err(PsdError::WitnessMismatch {
                    i,
                    j,
                    expected: Box::new(a.get(i, j).clone()),
                    found: Box::new(s),
                });
            }
        }
    }
    Ok(())
}

/// Plain rational LDLᵀ without pivoting, producing a witness for
/// [`check_psd_with_witness`]. Zero pivots are allowed when the rest of their
/// column is zero (then `L` gets a unit column), so PSD-but-singular matrices
/// succeed. Independent of the fraction-free code path (used to cross-check it).
pub fn ldlt_witness(a: &RationalMatrix) -> Result<(RationalMatrix, Vec<BigRational>), PsdError> {
    check_square_symmetric(a)?;
    let n = a.rows();
    let mut w = a.clone();
    let mut l = RationalMatrix::identity(n);
    let mut d = Vec::with_capacity(n);
    for k in 0..n {
        let dk = w.get(k, k).clone();
        if dk.is_negative() {
            return Err(PsdError::PivotNotPositive { index: k, value: dk });
        }
        if dk.is_zero() {
            if let Some(row) = (k + 1..n).find(|&i| !w.get(i, k).is_zero()) {
                return Err(PsdError::ZeroPivotNonzeroColumn { index: k, row, value: w.get(row, k).clone() });
            }
            d.push(dk);
            continue;
        }
        let below: Vec<usize> = (k + 1..n).filter(|&i| !w.get(i, k).is_zero()).collect();
        for &i in &below {
            l.set(i, k, w.get(i, k) / &dk);
        }
        for &i in &below {
            let lik = l.get(i, k).clone();
            for &j in below.iter().filter(|&&j| j <= i) {
                let v = w.get(i, j) - &lik * w.get(j, k);
                w.set(i, j, v.clone());
                w.set(j, i, v);
            }
        }
        d.push(dk);
    }
    Ok((l, d))
}

/// Exact determinant of a square matrix by Bareiss elimination with row
/// pivoting (general, not necessarily symmetric). `None` if not square.
pub fn determinant(a: &RationalMatrix) -> Option<BigRational> {
    if !a.is_square() {
        return None;
    }
    let n = a.rows();
    let c = denominator_lcm(a.entries());
    let mut m: Vec<Vec<BigInt>> =
        (0..n).map(|i| a.row(i).iter().map(|v| v.numer() * (&c / v.denom())).collect()).collect();
    let mut prev = BigInt::one();
    let mut negate = false;
    for k in 0..n {
        let Some(p) = (k..n).find(|&i| !m[i][k].is_zero()) else {
            return Some(BigRational::zero());
        };
        if p != k {
            m.swap(p, k);
            negate = !negate;
        }
        for i in k + 1..n {
            for j in k + 1..n {
                let v = &m[k][k] * &m[i][j] - &m[i][k] * &m[k][j];
                let (q, r) = v.div_rem(&prev);
                debug_assert!(r.is_zero(), "Bareiss division must be exact");
                m[i][j] = q;
            }
            m[i][k] = BigInt::zero();
        }
        prev = m[k][k].clone();
    }
    let det_m = if n == 0 { BigInt::one() } else { prev };
    let det = BigRational::new(det_m, num_traits::pow(c, n));
    Some(if negate { -det } else { det })
}
