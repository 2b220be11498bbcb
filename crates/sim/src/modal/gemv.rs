//! y = A x for the exponential scheme's per-step operator: a small dense matrix (≈ 190 × 150 on
//! the default grid) applied once per step. Written by hand because a general matrix product
//! (faer's `matmul` with one column) pays its dispatch and packing on every call, which at this
//! size is most of the product: rows are stored contiguously, padded with zeros to a multiple
//! of [`LANES`], and each row's dot product is accumulated in [`LANES`] partial sums combined in
//! one fixed order ([`total`]), as the Woodbury step's sums are. The AVX loop performs the same
//! operations in the same order (no fused multiply-add), so both give the same bits.

use faer::Mat;

use super::woodbury::{padded_len, total, LANES};

/// A dense matrix in padded row-major storage, for [`RowMajor::mul_into`].
#[derive(Debug)]
pub(crate) struct RowMajor {
    rows: usize,
    /// Row length in storage: the column count rounded up to a multiple of [`LANES`].
    stride: usize,
    data: Vec<f64>,
    /// Run the AVX loop (the CPU has AVX).
    avx: bool,
}

impl RowMajor {
    /// The matrix `m`, padded.
    pub(crate) fn new(m: &Mat<f64>) -> RowMajor {
        let (rows, cols) = (m.nrows(), m.ncols());
        let stride = padded_len(cols);
        let mut data = vec![0.0; rows * stride];
        for i in 0..rows {
            for j in 0..cols {
                data[i * stride + j] = m[(i, j)];
            }
        }
        #[cfg(target_arch = "x86_64")]
        let avx = std::arch::is_x86_feature_detected!("avx");
        #[cfg(not(target_arch = "x86_64"))]
        let avx = false;
        RowMajor { rows, stride, data, avx }
    }

    /// Number of rows.
    pub(crate) fn rows(&self) -> usize {
        self.rows
    }

    /// Length a right-hand side must have: the padded column count (entries past the matrix's
    /// columns must be 0).
    pub(crate) fn stride(&self) -> usize {
        self.stride
    }

    /// Row i, padded to [`RowMajor::stride`] with zeros.
    pub(crate) fn row(&self, i: usize) -> &[f64] {
        &self.data[i * self.stride..(i + 1) * self.stride]
    }

    /// Every entry finite.
    pub(crate) fn is_finite(&self) -> bool {
        self.data.iter().all(|v| v.is_finite())
    }

    /// y = A x (`x` of length [`RowMajor::stride`], `y` of at least [`RowMajor::rows`]).
    pub(crate) fn mul_into(&self, x: &[f64], y: &mut [f64]) {
        assert!(x.len() == self.stride && y.len() >= self.rows, "gemv: operand of the wrong length");
        #[cfg(target_arch = "x86_64")]
        if self.avx {
            // SAFETY: the CPU has AVX (`avx`), and the lengths are checked above.
            return unsafe { avx::mul_into(self, x, y) };
        }
        for (i, yi) in y.iter_mut().enumerate().take(self.rows) {
            let row = &self.data[i * self.stride..(i + 1) * self.stride];
            let mut s = [0.0; LANES];
            for (a, b) in row.chunks_exact(LANES).zip(x.chunks_exact(LANES)) {
                for l in 0..LANES {
                    s[l] += a[l] * b[l];
                }
            }
            *yi = total(&s);
        }
    }

    /// Run the portable loop even where AVX is available (tests).
    #[cfg(test)]
    pub(crate) fn without_avx(mut self) -> Self {
        self.avx = false;
        self
    }
}

/// The loop above with AVX instructions: lanes 0–3 and 4–7 of the partial sums in two
/// registers, four rows per pass (each x chunk loaded once for all four, and eight independent
/// chains of additions, so the loop is not bound by the addition's latency; the last rows of
/// a matrix whose row count is not a multiple of four in passes of two and one), the same
/// operations in the same order per row.
#[cfg(target_arch = "x86_64")]
mod avx {
    use std::arch::x86_64::{
        __m256d, _mm256_add_pd, _mm256_loadu_pd, _mm256_mul_pd, _mm256_setzero_pd, _mm256_storeu_pd,
    };

    use super::{total, RowMajor, LANES};

    /// Rows per pass.
    const BLOCK: usize = 4;

    #[inline(always)]
    unsafe fn sum(lo: __m256d, hi: __m256d) -> f64 {
        // SAFETY: the caller upholds this function's contract (the CPU has AVX; every lane read or written lies inside its slice).
        unsafe {
            let mut a = [0.0; LANES];
            _mm256_storeu_pd(a.as_mut_ptr(), lo);
            _mm256_storeu_pd(a.as_mut_ptr().add(4), hi);
            total(&a)
        }
    }

    #[target_feature(enable = "avx")]
    pub(super) unsafe fn mul_into(m: &RowMajor, x: &[f64], y: &mut [f64]) {
        // SAFETY: the caller upholds this function's contract (the CPU has AVX; every lane read or written lies inside its slice).
        unsafe {
            let full = m.rows - m.rows % BLOCK;
            for i in (0..full).step_by(BLOCK) {
                rows::<BLOCK>(m, x, y, i);
            }
            // the last rows in blocks of two and one: none is computed twice
            let mut i = full;
            if m.rows - i >= 2 {
                rows::<2>(m, x, y, i);
                i += 2;
            }
            if i < m.rows {
                rows::<1>(m, x, y, i);
            }
        }
    }

    /// Rows i..i + R of the product (R ≤ [`BLOCK`]), each x chunk loaded once for all of them.
    #[inline(always)]
    unsafe fn rows<const R: usize>(m: &RowMajor, x: &[f64], y: &mut [f64], i: usize) {
        // SAFETY: the caller upholds this function's contract (the CPU has AVX; every lane read or written lies inside its slice).
        unsafe {
            let (stride, xp) = (m.stride, x.as_ptr());
            let r: [*const f64; R] = std::array::from_fn(|b| m.data.as_ptr().add((i + b) * stride));
            let mut lo = [_mm256_setzero_pd(); R];
            let mut hi = [_mm256_setzero_pd(); R];
            let mut j = 0;
            while j < stride {
                let (xl, xh) = (_mm256_loadu_pd(xp.add(j)), _mm256_loadu_pd(xp.add(j + 4)));
                for b in 0..R {
                    lo[b] = _mm256_add_pd(lo[b], _mm256_mul_pd(_mm256_loadu_pd(r[b].add(j)), xl));
                    hi[b] = _mm256_add_pd(hi[b], _mm256_mul_pd(_mm256_loadu_pd(r[b].add(j + 4)), xh));
                }
                j += LANES;
            }
            for b in 0..R {
                y[i + b] = sum(lo[b], hi[b]);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn matrix(rows: usize, cols: usize) -> Mat<f64> {
        Mat::from_fn(rows, cols, |i, j| ((i * 31 + j * 17) % 23) as f64 / 7.0 - 1.5 + 1e-3 * (i as f64 - j as f64))
    }

    #[test]
    fn the_product_matches_faer_and_both_loops_give_the_same_bits() {
        for (rows, cols) in [(1, 1), (2, 3), (3, 8), (5, 20), (6, 146), (7, 9), (12, 146), (192, 151), (351, 295)] {
            let m = matrix(rows, cols);
            let a = RowMajor::new(&m);
            let mut x = vec![0.0; a.stride()];
            for (j, v) in x.iter_mut().enumerate().take(cols) {
                *v = (j as f64 * 0.37).sin();
            }
            let xm = Mat::from_fn(cols, 1, |j, _| x[j]);
            let reference = &m * &xm;
            let (mut y, mut yp) = (vec![0.0; rows], vec![0.0; rows]);
            a.mul_into(&x, &mut y);
            RowMajor::new(&m).without_avx().mul_into(&x, &mut yp);
            let scale: f64 = (0..cols).map(|j| x[j].abs()).sum::<f64>() * 3.0;
            for i in 0..rows {
                // a sum of `cols` products in another order: round-off ≤ cols·ε·Σ|a||x|
                assert!(
                    (y[i] - reference[(i, 0)]).abs() <= cols as f64 * f64::EPSILON * scale,
                    "{rows}×{cols} row {i}"
                );
                assert_eq!(y[i].to_bits(), yp[i].to_bits(), "{rows}×{cols} row {i}: AVX and portable differ");
            }
        }
    }
}
