//! The closed loop's real eigendecomposition for [`super::diagonal`], through faer's real
//! eigen-solver with its scratch space kept per thread (a search solves one such problem per
//! point; a fresh scratch of this size is a fresh mapping of pages the kernel zero-fills).

use std::cell::RefCell;

use faer::diag::Diag;
use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::evd::{self, ComputeEigenvectors, EvdParams};
use faer::{c64, Mat, Par, Spec};

thread_local! {
    static SCRATCH: RefCell<(MemBuffer, usize)> = RefCell::new((MemBuffer::new(StackReq::EMPTY), 0));
}

/// A = V diag(λ) V⁻¹ in faer's real form: for a real eigenvalue λ_j column j of `vectors` is
/// its eigenvector; for a conjugate pair (λ_j, λ_{j+1} = λ̄_j, Im λ_j > 0) columns j and j + 1
/// hold the real and imaginary parts of λ_j's eigenvector. `values` lists all N eigenvalues
/// in that order. The same numbers as `faer::Mat::eigen` (which converts this form to complex
/// vectors), without the conversion.
pub(crate) struct RealEigenvectors {
    pub(crate) values: Vec<c64>,
    pub(crate) vectors: Mat<f64>,
}

/// The right eigendecomposition of the square matrix `a` (sequential).
pub(crate) fn real_eigen(a: &Mat<f64>) -> Result<RealEigenvectors, evd::EvdError> {
    let n = a.nrows();
    let params: Spec<EvdParams, f64> = Default::default();
    let need = evd::evd_scratch::<f64>(n, ComputeEigenvectors::No, ComputeEigenvectors::Yes, Par::Seq, params);
    let mut vectors = Mat::<f64>::zeros(n, n);
    let mut re = Diag::<f64>::zeros(n);
    let mut im = Diag::<f64>::zeros(n);
    SCRATCH.with(|cell| {
        let mut held = cell.borrow_mut();
        let bytes = need.unaligned_bytes_required();
        if held.1 < bytes {
            *held = (MemBuffer::new(need), bytes);
        }
        let buf = &mut held.0;
        evd::evd_real(
            a.as_ref(),
            re.as_mut(),
            im.as_mut(),
            None,
            Some(vectors.as_mut()),
            Par::Seq,
            MemStack::new(buf),
            params,
        )
    })?;
    let mut values = Vec::with_capacity(n);
    let mut j = 0;
    while j < n {
        if im[j] == 0.0 {
            values.push(c64::new(re[j], 0.0));
            j += 1;
        } else {
            values.push(c64::new(re[j], im[j]));
            values.push(c64::new(re[j], -im[j]));
            j += 2;
        }
    }
    values.truncate(n);
    Ok(RealEigenvectors { values, vectors })
}
