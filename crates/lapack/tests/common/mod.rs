//! Shared helpers for the integration tests: padded column-major buffers,
//! random test-matrix families, and naive reference products.
#![allow(dead_code)]

use proptest::prelude::*;

/// Sentinel written into the padding rows `rows..ld` of every column.
pub const PAD: f64 = -7.777e77;

/// A column-major `rows x cols` matrix stored with leading dimension `ld >= rows`.
#[derive(Debug, Clone)]
pub struct Buf {
    pub rows: usize,
    pub cols: usize,
    pub ld: usize,
    pub data: Vec<f64>,
}

impl Buf {
    /// Fill the logical entries from `f(i, j)`; padding rows get [`PAD`].
    pub fn from_fn(rows: usize, cols: usize, pad: usize, f: impl Fn(usize, usize) -> f64) -> Self {
        let ld = (rows + pad).max(1);
        let mut data = vec![PAD; ld * cols.max(1)];
        for j in 0..cols {
            for i in 0..rows {
                data[i + j * ld] = f(i, j);
            }
        }
        Self { rows, cols, ld, data }
    }
    pub fn from_dense(m: &Dense, pad: usize) -> Self {
        Self::from_fn(m.rows, m.cols, pad, |i, j| m.at(i, j))
    }
    pub fn at(&self, i: usize, j: usize) -> f64 {
        self.data[i + j * self.ld]
    }
    pub fn to_dense(&self) -> Dense {
        Dense::from_fn(self.rows, self.cols, |i, j| self.at(i, j))
    }
    /// Assert the padding rows of every column still hold [`PAD`].
    pub fn assert_padding_intact(&self) {
        for j in 0..self.cols {
            for i in self.rows..self.ld {
                assert_eq!(self.data[i + j * self.ld].to_bits(), PAD.to_bits(), "padding ({i},{j}) touched");
            }
        }
    }
    pub fn ld_i32(&self) -> i32 {
        self.ld as i32
    }
}

/// Plain dense row-major matrix for reference computations.
#[derive(Debug, Clone, PartialEq)]
pub struct Dense {
    pub rows: usize,
    pub cols: usize,
    pub v: Vec<f64>,
}

impl Dense {
    pub fn from_fn(rows: usize, cols: usize, f: impl Fn(usize, usize) -> f64) -> Self {
        let mut v = Vec::with_capacity(rows * cols);
        for i in 0..rows {
            for j in 0..cols {
                v.push(f(i, j));
            }
        }
        Self { rows, cols, v }
    }
    pub fn zeros(rows: usize, cols: usize) -> Self {
        Self::from_fn(rows, cols, |_, _| 0.0)
    }
    pub fn eye(n: usize) -> Self {
        Self::from_fn(n, n, |i, j| f64::from(u8::from(i == j)))
    }
    pub fn at(&self, i: usize, j: usize) -> f64 {
        self.v[i * self.cols + j]
    }
    pub fn t(&self) -> Self {
        Self::from_fn(self.cols, self.rows, |i, j| self.at(j, i))
    }
    /// Naive triple-loop product (the reference definition of matmul).
    pub fn mul(&self, o: &Dense) -> Dense {
        assert_eq!(self.cols, o.rows);
        Dense::from_fn(self.rows, o.cols, |i, j| (0..self.cols).map(|k| self.at(i, k) * o.at(k, j)).sum())
    }
    pub fn sub(&self, o: &Dense) -> Dense {
        Dense::from_fn(self.rows, self.cols, |i, j| self.at(i, j) - o.at(i, j))
    }
    pub fn norm(&self) -> f64 {
        self.v.iter().map(|x| x * x).sum::<f64>().sqrt()
    }
    pub fn sym(&self) -> Dense {
        Dense::from_fn(self.rows, self.cols, |i, j| 0.5 * (self.at(i, j) + self.at(j, i)))
    }
    pub fn to_rows(&self) -> Vec<Vec<f64>> {
        (0..self.rows).map(|i| (0..self.cols).map(|j| self.at(i, j)).collect()).collect()
    }
}

/// Householder reflector `I - 2 v vᵀ / vᵀv` (orthogonal by construction).
pub fn householder(v: &[f64]) -> Dense {
    let n = v.len();
    let nn: f64 = v.iter().map(|x| x * x).sum::<f64>().max(1e-300);
    Dense::from_fn(n, n, |i, j| f64::from(u8::from(i == j)) - 2.0 * v[i] * v[j] / nn)
}

/// Families of test matrices.
#[derive(Debug, Clone, Copy)]
pub enum Kind {
    /// i.i.d. uniform entries in [-1, 1].
    Random,
    /// Product of `m x r` and `r x n` random factors (rank ≤ r).
    RankDeficient(usize),
    /// `H₁ diag(σ) H₂` with σ geometric from 1 down to `10^-e` (cond ≈ 10^e).
    IllConditioned(u32),
}

/// Strategy for an `m x n` matrix of the given family (entries from a flat
/// random pool so that shrinking works).
pub fn matrix(m: usize, n: usize) -> impl Strategy<Value = Dense> {
    let kind = prop_oneof![
        Just(Kind::Random),
        (0..=m.min(n)).prop_map(Kind::RankDeficient),
        (4u32..=12).prop_map(Kind::IllConditioned),
    ];
    let pool = proptest::collection::vec(-1.0f64..1.0, 2 * (m + n) * (m + n) + 2);
    (kind, pool).prop_map(move |(k, p)| build(m, n, k, &p))
}

fn build(m: usize, n: usize, kind: Kind, p: &[f64]) -> Dense {
    match kind {
        Kind::Random => Dense::from_fn(m, n, |i, j| p[i * n + j]),
        Kind::RankDeficient(r) => {
            let x = Dense::from_fn(m, r, |i, j| p[i * r + j]);
            let y = Dense::from_fn(r, n, |i, j| p[m * r + i * n + j]);
            x.mul(&y)
        }
        Kind::IllConditioned(e) => {
            let mn = m.min(n);
            let h1 = householder(&p[..m]);
            let h2 = householder(&p[m..m + n]);
            let s = Dense::from_fn(m, n, |i, j| {
                if i == j {
                    10f64.powf(-(e as f64) * i as f64 / (mn.max(2) - 1) as f64)
                } else {
                    0.0
                }
            });
            h1.mul(&s).mul(&h2)
        }
    }
}

/// Strategy for a symmetric `n x n` matrix of any family.
pub fn symmetric(n: usize) -> impl Strategy<Value = Dense> {
    matrix(n, n).prop_map(|a| a.sym())
}

/// Strategy for an SPD `n x n` matrix `G Gᵀ + δ I` (δ small for ill-conditioning).
pub fn spd(n: usize) -> impl Strategy<Value = Dense> {
    (matrix(n, n), prop_oneof![Just(1e-8), Just(1e-3), Just(1.0)])
        .prop_map(move |(g, d)| g.mul(&g.t()).sym().sub(&Dense::from_fn(n, n, |i, j| if i == j { -d } else { 0.0 })))
}

/// Padding (`ld - rows`) strategy: usually some, sometimes none.
pub fn pad() -> impl Strategy<Value = usize> {
    prop_oneof![Just(0usize), 1usize..4]
}

/// `|got - want| ≤ tol` entrywise-in-norm helper with a readable message.
pub fn assert_close(got: &Dense, want: &Dense, tol: f64, what: &str) {
    let err = got.sub(want).norm();
    assert!(err <= tol, "{what}: error {err:e} > tol {tol:e}");
}

/// Default CI-friendly number of proptest cases.
pub fn cases() -> proptest::test_runner::Config {
    proptest::test_runner::Config { cases: 48, failure_persistence: None, ..Default::default() }
}
