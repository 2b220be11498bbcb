//! The real vectors of the eigenbasis step ([`super::diagonal`]): which slot holds which part
//! of which representative eigenvalue.

use faer::Mat;

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
