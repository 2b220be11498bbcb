//! Cholesky: `dpotrf_` (factor) and `dpotrs_` (solve), Fortran ABI.

use crate::util::{ch, int, view, view_mut};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::{cholesky_in_place, cholesky_in_place_scratch, LltError};
use faer::linalg::triangular_solve::{solve_lower_triangular_in_place, solve_upper_triangular_in_place};
use faer::prelude::{Reborrow, ReborrowMut};
use faer::{Mat, MatRef, Par};
use std::ffi::{c_char, c_int};

/// Copy the `uplo` triangle of `a` into an owned lower-triangular `L` such that
/// `A = L L^T` (for `'U'`, `L = U^T`). The other triangle of `a` is not read.
fn lower_copy(a: MatRef<'_, f64>, upper: bool) -> Mat<f64> {
    let n = a.nrows();
    Mat::from_fn(n, n, |i, j| match (i >= j, upper) {
        (false, _) => 0.0,
        (true, false) => a[(i, j)],
        (true, true) => a[(j, i)],
    })
}

/// Cholesky factorisation of a symmetric positive definite `n x n` matrix:
/// `A = U^T U` (uplo `'U'`) or `A = L L^T` (uplo `'L'`), overwriting only the
/// `uplo` triangle of `A`.
///
/// `info = -i` for an illegal `i`-th argument; `info = k > 0` if the leading
/// minor of order `k` is not positive definite (then `A` is left unchanged,
/// which LAPACK permits: its contents are unspecified on failure).
///
/// # Safety
/// All pointers must be valid Fortran arguments for `DPOTRF`.
#[no_mangle]
pub unsafe extern "C" fn dpotrf_(
    uplo: *const c_char,
    n: *const c_int,
    a: *mut f64,
    lda: *const c_int,
    info: *mut c_int,
) {
    // SAFETY: the caller passes valid Fortran arguments (the `# Safety` section above), as the BLAS/LAPACK ABI requires of clarabel's calls.
    unsafe {
        let u = ch(uplo);
        let (n, lda) = (int(n), int(lda));
        *info = if u != b'U' && u != b'L' {
            -1
        } else if n < 0 {
            -2
        } else if lda < n.max(1) {
            -4
        } else {
            0
        };
        if *info != 0 || n == 0 {
            return;
        }
        let (n, upper) = (n as usize, u == b'U');
        let mut av = view_mut(a, n, n, lda as usize);
        let mut l = lower_copy(av.rb(), upper);
        let mut mem = MemBuffer::new(cholesky_in_place_scratch::<f64>(n, Par::Seq, Default::default()));
        let stack = MemStack::new(&mut mem);
        let res = cholesky_in_place(l.as_mut(), Default::default(), Par::Seq, stack, Default::default());
        if let Err(LltError::NonPositivePivot { index }) = res {
            *info = index as c_int + 1;
            return;
        }
        // faer does not flag NaN pivots in every code path; LAPACK does.
        if let Some(j) = (0..n).find(|&j| l[(j, j)].is_nan()) {
            *info = j as c_int + 1;
            return;
        }
        for j in 0..n {
            for i in j..n {
                if upper {
                    av[(j, i)] = l[(i, j)];
                } else {
                    av[(i, j)] = l[(i, j)];
                }
            }
        }
    }
}

/// Solve `A X = B` given the Cholesky factor from [`dpotrf_`] stored in the
/// `uplo` triangle of `A` (`n x n`); `B` (`n x nrhs`) is overwritten by `X`.
///
/// # Safety
/// All pointers must be valid Fortran arguments for `DPOTRS`.
#[no_mangle]
pub unsafe extern "C" fn dpotrs_(
    uplo: *const c_char,
    n: *const c_int,
    nrhs: *const c_int,
    a: *const f64,
    lda: *const c_int,
    b: *mut f64,
    ldb: *const c_int,
    info: *mut c_int,
) {
    // SAFETY: the caller passes valid Fortran arguments (the `# Safety` section above), as the BLAS/LAPACK ABI requires of clarabel's calls.
    unsafe {
        let u = ch(uplo);
        let (n, nrhs, lda, ldb) = (int(n), int(nrhs), int(lda), int(ldb));
        *info = if u != b'U' && u != b'L' {
            -1
        } else if n < 0 {
            -2
        } else if nrhs < 0 {
            -3
        } else if lda < n.max(1) {
            -5
        } else if ldb < n.max(1) {
            -7
        } else {
            0
        };
        if *info != 0 || n == 0 || nrhs == 0 {
            return;
        }
        let (n, nrhs) = (n as usize, nrhs as usize);
        let l = lower_copy(view(a, n, n, lda as usize), u == b'U');
        let mut bv = view_mut(b, n, nrhs, ldb as usize);
        solve_lower_triangular_in_place(l.as_ref(), bv.rb_mut(), Par::Seq);
        solve_upper_triangular_in_place(l.transpose(), bv, Par::Seq);
    }
}
