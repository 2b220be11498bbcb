//! Symmetric banded matrices for the time stepper: both discretisations number their unknowns
//! node by node, so M, K and the step matrix have a half-bandwidth of 4–5 whatever the mesh
//! size. A banded Cholesky factor and a fused banded product A u − B w are contiguous loops
//! over a fixed band; for these small bands they are several times faster per step than the
//! general sparse (faer) kernels with their indirect indexing, which dominated the step cost.
//! Written by hand because no maintained crate offers a banded SPD factorisation in pure Rust.

use crate::sparse::SymMatrix;
use crate::NumericalError;

/// Half-bandwidth max |i − j| over the stored entries of `a`.
pub fn half_bandwidth(a: &SymMatrix) -> usize {
    let d = a.to_sparse_entries();
    d.iter().map(|&(i, j, _)| i.abs_diff(j)).max().unwrap_or(0)
}

/// Σ a_k b_k with four independent accumulators (short dot products are latency-bound).
#[inline]
fn dot4(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let mut ca = a.chunks_exact(4);
    let mut cb = b.chunks_exact(4);
    for (x, y) in (&mut ca).zip(&mut cb) {
        for k in 0..4 {
            acc[k] += x[k] * y[k];
        }
    }
    for (k, (x, y)) in ca.remainder().iter().zip(cb.remainder()).enumerate() {
        acc[k] += x * y;
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3])
}

/// Cholesky factor A = LLᵀ of a symmetric positive definite banded matrix.
#[derive(Debug, Clone)]
pub struct BandedCholesky {
    n: usize,
    bw: usize,
    /// Row i: L[i][i−bw..i] (bw entries, zero outside the matrix).
    lower: Vec<f64>,
    /// Row i: L[i+1..=i+bw][i] (bw entries, zero outside the matrix): the band of Lᵀ.
    upper: Vec<f64>,
    /// 1 / L[i][i].
    inv_diag: Vec<f64>,
    /// Work vector with bw zeros of padding at both ends.
    work: Vec<f64>,
}

impl BandedCholesky {
    /// Factorise `a` (bandwidth from its pattern). Errors if `a` is not positive definite.
    pub fn new(a: &SymMatrix) -> Result<BandedCholesky, NumericalError> {
        let n = a.dim();
        let bw = half_bandwidth(a).max(1);
        // Dense band l[i][k] = L[i][i − bw + k], k = 0..=bw (k = bw is the diagonal).
        let w = bw + 1;
        let mut l = vec![0.0; n * w];
        for (i, j, v) in a.to_sparse_entries() {
            if j <= i {
                l[i * w + (j + bw - i)] = v;
            }
        }
        for j in 0..n {
            let row_j = j * w;
            let k0 = j.saturating_sub(bw);
            let mut d = l[row_j + bw];
            for k in k0..j {
                let v = l[row_j + (k + bw - j)];
                d -= v * v;
            }
            if !(d > 0.0 && d.is_finite()) {
                return Err(NumericalError::Pivot { what: "step matrix", pivot: d, row: j });
            }
            let ljj = d.sqrt();
            l[row_j + bw] = ljj;
            for i in j + 1..n.min(j + bw + 1) {
                let row_i = i * w;
                let k0 = i.saturating_sub(bw);
                let mut s = l[row_i + (j + bw - i)];
                for k in k0..j {
                    s -= l[row_i + (k + bw - i)] * l[row_j + (k + bw - j)];
                }
                l[row_i + (j + bw - i)] = s / ljj;
            }
        }
        let mut lower = vec![0.0; n * bw];
        let mut upper = vec![0.0; n * bw];
        let mut inv_diag = vec![0.0; n];
        for i in 0..n {
            inv_diag[i] = 1.0 / l[i * w + bw];
            for k in 0..bw {
                // L[i][i − bw + k]
                if i + k >= bw {
                    lower[i * bw + k] = l[i * w + k];
                }
                // L[i + 1 + k][i]
                let r = i + 1 + k;
                if r < n {
                    upper[i * bw + k] = l[r * w + (i + bw - r)];
                }
            }
        }
        Ok(BandedCholesky { n, bw, lower, upper, inv_diag, work: vec![0.0; n + 2 * bw] })
    }

    /// Overwrite `b` with A⁻¹ b.
    pub fn solve_in_place(&mut self, b: &mut [f64]) {
        let (n, bw) = (self.n, self.bw);
        let y = &mut self.work;
        // Forward: y[bw + i] = (b_i − L[i][i−bw..i]·y[i..i+bw]) / L_ii; y[0..bw] = 0. The term
        // with the newest y is subtracted last, so the others overlap with its latency.
        for i in 0..n {
            let l = &self.lower[i * bw..(i + 1) * bw];
            let prev = &y[i..i + bw];
            let older = dot4(&l[..bw - 1], &prev[..bw - 1]);
            y[bw + i] = (b[i] - older - l[bw - 1] * prev[bw - 1]) * self.inv_diag[i];
        }
        // Backward: x_i = (y_i − L[i+1..=i+bw][i]·x[i+1..=i+bw]) / L_ii; x[n..n+bw] = 0.
        for i in (0..n).rev() {
            let u = &self.upper[i * bw..(i + 1) * bw];
            let next = &y[bw + i + 1..2 * bw + i + 1];
            let older = dot4(&u[1..], &next[1..]);
            y[bw + i] = (y[bw + i] - older - u[0] * next[0]) * self.inv_diag[i];
        }
        b.copy_from_slice(&y[bw..bw + n]);
    }

    /// y = Lᵀ x (the factor's transpose times a vector).
    pub fn transpose_mul_into(&self, x: &[f64], y: &mut [f64]) {
        let (n, bw) = (self.n, self.bw);
        for i in 0..n {
            let hi = n.min(i + bw + 1);
            let u = &self.upper[i * bw..i * bw + (hi - i - 1)];
            y[i] = x[i] / self.inv_diag[i] + u.iter().zip(&x[i + 1..hi]).map(|(a, b)| a * b).sum::<f64>();
        }
    }

    /// Overwrite `b` with L⁻ᵀ b (the backward half of [`BandedCholesky::solve_in_place`]).
    pub fn transpose_solve_in_place(&self, b: &mut [f64]) {
        let (n, bw) = (self.n, self.bw);
        for i in (0..n).rev() {
            let hi = n.min(i + bw + 1);
            let u = &self.upper[i * bw..i * bw + (hi - i - 1)];
            let s: f64 = u.iter().zip(&b[i + 1..hi]).map(|(a, x)| a * x).sum();
            b[i] = (b[i] - s) * self.inv_diag[i];
        }
    }

    /// Stored band entries of L.
    pub fn stored(&self) -> usize {
        self.n * (self.bw + 1)
    }
}

/// Two symmetric banded matrices A, B stored as full bands, for the fused product A u − B w
/// (the right-hand side of every stage).
#[derive(Debug, Clone)]
pub struct BandedPair {
    n: usize,
    bw: usize,
    /// A_ij for j = i−bw..=i+bw, row-major (zero outside the matrix).
    a: Vec<f64>,
    /// B_ij, same layout.
    b: Vec<f64>,
}

impl BandedPair {
    /// Pair `a` and `b` (same dimension).
    pub fn new(a: &SymMatrix, b: &SymMatrix) -> BandedPair {
        let n = a.dim();
        let bw = half_bandwidth(a).max(half_bandwidth(b));
        let w = 2 * bw + 1;
        let mut band = [vec![0.0; n * w], vec![0.0; n * w]];
        for (which, m) in [(0, a), (1, b)] {
            for (i, j, v) in m.to_sparse_entries() {
                band[which][i * w + (j + bw - i)] += v;
            }
        }
        let [a, b] = band;
        BandedPair { n, bw, a, b }
    }

    /// out = A u − B w.
    pub fn mul_diff_into(&self, u: &[f64], w: &[f64], out: &mut [f64]) {
        let (n, bw) = (self.n, self.bw);
        let width = 2 * bw + 1;
        for (i, o) in out.iter_mut().enumerate().take(n) {
            let j0 = i.saturating_sub(bw);
            let j1 = n.min(i + bw + 1);
            let r = i * width + (j0 + bw - i)..i * width + (j1 + bw - i);
            *o = dot4(&self.a[r.clone()], &u[j0..j1]) - dot4(&self.b[r], &w[j0..j1]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sparse::SymBuilder;

    #[test]
    fn banded_solve_and_product_match_the_definitions() {
        // A banded SPD matrix (bandwidth 3): A x = b by definition, and the fused product
        // against the sparse one.
        let n = 30;
        let mut bld = SymBuilder::new(n);
        for i in 0..n {
            bld.add(i, i, 6.0 + 0.1 * i as f64);
            if i + 1 < n {
                bld.add(i, i + 1, -1.5);
            }
            if i + 3 < n {
                bld.add(i, i + 3, 0.7);
            }
        }
        let a = bld.build();
        let mut chol = BandedCholesky::new(&a).unwrap();
        let rhs: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).cos()).collect();
        let mut x = rhs.clone();
        chol.solve_in_place(&mut x);
        let mut ax = vec![0.0; n];
        a.mul_into(&x, &mut ax);
        for i in 0..n {
            assert!((ax[i] - rhs[i]).abs() < 1e-13, "row {i}");
        }
        let pair = BandedPair::new(&SymMatrix::combine(&[(2.0, &a)]), &a);
        let mut fused = vec![0.0; n];
        pair.mul_diff_into(&x, &x, &mut fused);
        for i in 0..n {
            assert!((fused[i] - ax[i]).abs() < 1e-13);
        }
    }

    #[test]
    fn indefinite_matrix_is_an_error() {
        let mut b = SymBuilder::new(2);
        b.add(0, 0, 1.0);
        b.add(1, 1, -1.0);
        assert!(matches!(BandedCholesky::new(&b.build()), Err(NumericalError::Pivot { .. })));
    }
}
