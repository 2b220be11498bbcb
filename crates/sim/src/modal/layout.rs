//! The vectors of the eigenbasis step ([`super::diagonal`]): the complex vectors over the
//! representative eigenvalues its construction works with ([`Half`]), and the real vectors it
//! carries (which slot holds which part of which representative, [`Layout`]).

use faer::{c64, Mat};

use super::woodbury::dot;

/// The real vectors the step carries: the k representatives' (re, im) pairs of the
/// construction with the imaginary parts of the real eigenvalues dropped (they are 0 in every
/// vector and multiply 0 in every row), N reals in all: the real eigenvalues' values, the
/// pairs' real parts, the pairs' imaginary parts.
#[derive(Debug)]
pub(crate) struct Layout {
    /// Real eigenvalues.
    pub(crate) real: usize,
    /// Conjugate pairs.
    pub(crate) pairs: usize,
    /// For each slot, its index in the (re 0..k, im k..2k) layout of the construction.
    from: Vec<usize>,
}

impl Layout {
    pub(crate) fn new(reps: &[(usize, f64)]) -> Layout {
        let k = reps.len();
        let is_pair = |r: &usize| reps[*r].1 == 2.0;
        let real: Vec<usize> = (0..k).filter(|r| !is_pair(r)).collect();
        let pairs: Vec<usize> = (0..k).filter(is_pair).collect();
        let from = real.iter().chain(&pairs).copied().chain(pairs.iter().map(|r| k + r)).collect();
        Layout { real: real.len(), pairs: pairs.len(), from }
    }

    /// Number of slots (N).
    pub(crate) fn len(&self) -> usize {
        self.from.len()
    }

    /// The slot of index `i` of the (re 0..k, im k..2k) layout, `None` for the imaginary part
    /// of a real eigenvalue (dropped).
    pub(crate) fn slot(&self, i: usize) -> Option<usize> {
        self.from.iter().position(|&f| f == i)
    }

    /// The entries of a (re, im) vector in this layout.
    pub(crate) fn vector(&self, full: &[f64]) -> Vec<f64> {
        self.from.iter().map(|&i| full[i]).collect()
    }

    /// The columns of a matrix over (re, im) in this layout.
    pub(crate) fn columns(&self, full: &Mat<f64>) -> Mat<f64> {
        Mat::from_fn(full.nrows(), self.from.len(), |i, j| full[(i, self.from[j])])
    }

    /// The rows of a matrix over (re, im) in this layout.
    pub(crate) fn rows(&self, full: &Mat<f64>) -> Mat<f64> {
        Mat::from_fn(self.from.len(), full.ncols(), |i, j| full[(self.from[i], j)])
    }
}

/// A complex vector over the eigenvalue representatives (one per real eigenvalue, one per
/// conjugate pair), real and imaginary parts apart. As a row it carries the weight of its
/// representative (1 real, 2 pair), so Σ over all N eigenvalues of a_i x_i for conjugate-closed
/// a, x is [`Half::re_dot`].
#[derive(Debug, Clone)]
pub(crate) struct Half {
    pub(crate) re: Vec<f64>,
    pub(crate) im: Vec<f64>,
}

impl Half {
    pub(crate) fn zeros(k: usize) -> Half {
        Half { re: vec![0.0; k], im: vec![0.0; k] }
    }
    pub(crate) fn from_fn(k: usize, f: impl Fn(usize) -> c64) -> Half {
        let v: Vec<c64> = (0..k).map(f).collect();
        Half { re: v.iter().map(|c| c.re).collect(), im: v.iter().map(|c| c.im).collect() }
    }
    /// Re Σ a_i x_i = Σ (a_re x_re − a_im x_im).
    #[inline]
    pub(crate) fn re_dot(&self, x: &Half) -> f64 {
        dot(&self.re, &x.re) - dot(&self.im, &x.im)
    }
}

/// The rows Re(a · x̂) of the [`Half`] vectors `rows` as a matrix over (x̂_re, x̂_im):
/// [a_re, −a_im].
pub(crate) fn stack(rows: &[Half]) -> Mat<f64> {
    let k = rows.first().map_or(0, |r| r.re.len());
    Mat::from_fn(rows.len(), 2 * k, |i, j| if j < k { rows[i].re[j] } else { -rows[i].im[j - k] })
}
