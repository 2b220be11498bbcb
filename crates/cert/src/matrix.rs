//! Dense row-major matrices of exact rationals.

use num_rational::BigRational;
use num_traits::Zero;

/// A dense `rows × cols` matrix of exact rationals, stored row-major.
///
/// Used for element/global FE matrices, certificate witnesses and linear
/// systems. Zero-row matrices with a positive column count are allowed (an
/// empty constraint block over `cols` variables).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RationalMatrix {
    rows: usize,
    cols: usize,
    data: Vec<BigRational>,
}

impl RationalMatrix {
    /// The `rows × cols` zero matrix.
    pub fn zeros(rows: usize, cols: usize) -> Self {
        Self { rows, cols, data: vec![BigRational::zero(); rows * cols] }
    }

    /// The `n × n` identity.
    pub fn identity(n: usize) -> Self {
        let mut m = Self::zeros(n, n);
        for i in 0..n {
            m.set(i, i, BigRational::from_integer(1.into()));
        }
        m
    }

    /// Builds a matrix from rows; `None` if the rows have different lengths.
    /// An empty `rows` gives the 0 × 0 matrix.
    pub fn from_rows(rows: Vec<Vec<BigRational>>) -> Option<Self> {
        let cols = rows.first().map_or(0, Vec::len);
        if rows.iter().any(|r| r.len() != cols) {
            return None;
        }
        let n = rows.len();
        Some(Self { rows: n, cols, data: rows.into_iter().flatten().collect() })
    }

    /// Builds a matrix from a closure `f(i, j)`.
    pub fn from_fn(rows: usize, cols: usize, mut f: impl FnMut(usize, usize) -> BigRational) -> Self {
        let mut data = Vec::with_capacity(rows * cols);
        for i in 0..rows {
            for j in 0..cols {
                data.push(f(i, j));
            }
        }
        Self { rows, cols, data }
    }

    /// Number of rows.
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Number of columns.
    pub fn cols(&self) -> usize {
        self.cols
    }

    /// Whether the matrix is square.
    pub fn is_square(&self) -> bool {
        self.rows == self.cols
    }

    /// Entry `(i, j)`. Panics when out of range.
    pub fn get(&self, i: usize, j: usize) -> &BigRational {
        assert!(i < self.rows && j < self.cols, "index ({i},{j}) out of range");
        &self.data[i * self.cols + j]
    }

    /// Overwrites entry `(i, j)`. Panics when out of range.
    pub fn set(&mut self, i: usize, j: usize, v: BigRational) {
        assert!(i < self.rows && j < self.cols, "index ({i},{j}) out of range");
        self.data[i * self.cols + j] = v;
    }

    /// Adds `v` to entry `(i, j)`. Panics when out of range.
    pub fn add_to(&mut self, i: usize, j: usize, v: &BigRational) {
        assert!(i < self.rows && j < self.cols, "index ({i},{j}) out of range");
        self.data[i * self.cols + j] += v;
    }

    /// Row `i` as a slice.
    pub fn row(&self, i: usize) -> &[BigRational] {
        &self.data[i * self.cols..(i + 1) * self.cols]
    }

    /// Rows as owned vectors (for serialisation).
    pub fn to_rows(&self) -> Vec<Vec<BigRational>> {
        (0..self.rows).map(|i| self.row(i).to_vec()).collect()
    }

    /// All entries, row-major.
    pub fn entries(&self) -> &[BigRational] {
        &self.data
    }

    /// The transpose.
    pub fn transpose(&self) -> Self {
        Self::from_fn(self.cols, self.rows, |i, j| self.get(j, i).clone())
    }

    /// `self · other`; `None` on a dimension mismatch.
    pub fn mul(&self, other: &Self) -> Option<Self> {
        if self.cols != other.rows {
            return None;
        }
        let mut out = Self::zeros(self.rows, other.cols);
        for i in 0..self.rows {
            for k in 0..self.cols {
                let a = self.get(i, k);
                if a.is_zero() {
                    continue;
                }
                for j in 0..other.cols {
                    let b = other.get(k, j);
                    if !b.is_zero() {
                        out.data[i * other.cols + j] += a * b;
                    }
                }
            }
        }
        Some(out)
    }

    /// `self + other`; `None` on a dimension mismatch.
    pub fn add(&self, other: &Self) -> Option<Self> {
        if (self.rows, self.cols) != (other.rows, other.cols) {
            return None;
        }
        Some(Self {
            rows: self.rows,
            cols: self.cols,
            data: self.data.iter().zip(&other.data).map(|(a, b)| a + b).collect(),
        })
    }

    /// `self − other`; `None` on a dimension mismatch.
    pub fn sub(&self, other: &Self) -> Option<Self> {
        if (self.rows, self.cols) != (other.rows, other.cols) {
            return None;
        }
        Some(Self {
            rows: self.rows,
            cols: self.cols,
            data: self.data.iter().zip(&other.data).map(|(a, b)| a - b).collect(),
        })
    }

    /// `c · self`.
    pub fn scale(&self, c: &BigRational) -> Self {
        Self { rows: self.rows, cols: self.cols, data: self.data.iter().map(|a| a * c).collect() }
    }

    /// `self · x` for a vector `x`; `None` on a dimension mismatch.
    pub fn mul_vec(&self, x: &[BigRational]) -> Option<Vec<BigRational>> {
        if x.len() != self.cols {
            return None;
        }
        Some(
            (0..self.rows)
                .map(|i| {
                    self.row(i)
                        .iter()
                        .zip(x)
                        .filter(|(a, b)| !a.is_zero() && !b.is_zero())
                        .fold(BigRational::zero(), |acc, (a, b)| acc + a * b)
                })
                .collect(),
        )
    }

    /// `xᵀ · self` for a vector `x`; `None` on a dimension mismatch.
    pub fn vec_mul(&self, x: &[BigRational]) -> Option<Vec<BigRational>> {
        if x.len() != self.rows {
            return None;
        }
        let mut out = vec![BigRational::zero(); self.cols];
        for (i, xi) in x.iter().enumerate() {
            if xi.is_zero() {
                continue;
            }
            for (o, a) in out.iter_mut().zip(self.row(i)) {
                if !a.is_zero() {
                    *o += xi * a;
                }
            }
        }
        Some(out)
    }

    /// First `(i, j)` with `A[i][j] ≠ A[j][i]`, or `None` when symmetric.
    /// Non-square matrices report `Some((rows, cols))`.
    pub fn first_asymmetry(&self) -> Option<(usize, usize)> {
        if !self.is_square() {
            return Some((self.rows, self.cols));
        }
        for i in 0..self.rows {
            for j in (i + 1)..self.cols {
                if self.get(i, j) != self.get(j, i) {
                    return Some((i, j));
                }
            }
        }
        None
    }

    /// Whether the matrix is square and exactly symmetric.
    pub fn is_symmetric(&self) -> bool {
        self.first_asymmetry().is_none()
    }
}
