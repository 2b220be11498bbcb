//! Level-3 BLAS: `dgemm_`, `dsyrk_`, `dsyr2k_` (Fortran ABI, column-major).
//!
//! Argument checking follows reference BLAS (argument numbers as in the
//! Fortran interface); an illegal argument is reported via
//! [`crate::take_blas_error`] and the call returns without touching `C`.

use crate::util::{ch, int, scale_all, scale_triangle, view, view_mut, xerbla};
use faer::linalg::matmul::matmul;
use faer::linalg::matmul::triangular::{self, BlockStructure};
use faer::prelude::ReborrowMut;
use faer::{Accum, MatRef, Par};
use std::ffi::{c_char, c_int};

fn is_trans(t: u8) -> Option<bool> {
    match t {
        b'N' => Some(false),
        b'T' | b'C' => Some(true),
        _ => None,
    }
}

/// `C := alpha * op(A) * op(B) + beta * C` with `op(X) = X` or `X^T`.
///
/// `C` is `m x n`, `op(A)` is `m x k`, `op(B)` is `k x n`. When `beta == 0`
/// the input `C` is not read (NaN/Inf in it do not propagate); when
/// `alpha == 0` neither `A` nor `B` is read.
///
/// # Safety
/// All pointers must be valid Fortran arguments for `DGEMM`.
#[no_mangle]
pub unsafe extern "C" fn dgemm_(
    transa: *const c_char,
    transb: *const c_char,
    m: *const c_int,
    n: *const c_int,
    k: *const c_int,
    alpha: *const f64,
    a: *const f64,
    lda: *const c_int,
    b: *const f64,
    ldb: *const c_int,
    beta: *const f64,
    c: *mut f64,
    ldc: *const c_int,
) {
    // SAFETY: the caller passes valid Fortran arguments (the `# Safety` section above), as the BLAS/LAPACK ABI requires of clarabel's calls.
    unsafe {
        let (ta, tb) = (is_trans(ch(transa)), is_trans(ch(transb)));
        let (m, n, k) = (int(m), int(n), int(k));
        let (lda, ldb, ldc) = (int(lda), int(ldb), int(ldc));
        let nrowa = if ta == Some(false) { m } else { k };
        let nrowb = if tb == Some(false) { k } else { n };
        let bad = if ta.is_none() {
            1
        } else if tb.is_none() {
            2
        } else if m < 0 {
            3
        } else if n < 0 {
            4
        } else if k < 0 {
            5
        } else if lda < nrowa.max(1) {
            8
        } else if ldb < nrowb.max(1) {
            10
        } else if ldc < m.max(1) {
            13
        } else {
            0
        };
        if bad != 0 {
            return xerbla("DGEMM", bad);
        }
        let (alpha, beta) = (*alpha, *beta);
        if m == 0 || n == 0 || ((alpha == 0.0 || k == 0) && beta == 1.0) {
            return;
        }
        let (m, n, k) = (m as usize, n as usize, k as usize);
        let mut cv = view_mut(c, m, n, ldc as usize);
        scale_all(cv.rb_mut(), beta);
        if alpha == 0.0 || k == 0 {
            return;
        }
        let av = op(view(a, nrowa as usize, if ta == Some(false) { k } else { m }, lda as usize), ta);
        let bv = op(view(b, nrowb as usize, if tb == Some(false) { n } else { k }, ldb as usize), tb);
        matmul(cv, Accum::Add, av, bv, alpha, Par::Seq);
    }
}

fn op(x: MatRef<'_, f64>, t: Option<bool>) -> MatRef<'_, f64> {
    if t == Some(true) {
        x.transpose()
    } else {
        x
    }
}

fn uplo_flag(u: u8) -> Option<bool> {
    match u {
        b'U' => Some(true),
        b'L' => Some(false),
        _ => None,
    }
}

fn tri(upper: bool) -> BlockStructure {
    if upper {
        BlockStructure::TriangularUpper
    } else {
        BlockStructure::TriangularLower
    }
}

/// Symmetric rank-k update of one triangle of `C` (`n x n`):
/// `C := alpha*A*A^T + beta*C` (trans `'N'`, `A` is `n x k`) or
/// `C := alpha*A^T*A + beta*C` (trans `'T'`/`'C'`, `A` is `k x n`).
/// Only the `uplo` triangle of `C` is read or written.
///
/// # Safety
/// All pointers must be valid Fortran arguments for `DSYRK`.
#[no_mangle]
pub unsafe extern "C" fn dsyrk_(
    uplo: *const c_char,
    trans: *const c_char,
    n: *const c_int,
    k: *const c_int,
    alpha: *const f64,
    a: *const f64,
    lda: *const c_int,
    beta: *const f64,
    c: *mut f64,
    ldc: *const c_int,
) {
    // SAFETY: the caller passes valid Fortran arguments (the `# Safety` section above), as the BLAS/LAPACK ABI requires of clarabel's calls.
    unsafe {
        let (up, tr) = (uplo_flag(ch(uplo)), is_trans(ch(trans)));
        let (n, k, lda, ldc) = (int(n), int(k), int(lda), int(ldc));
        let nrowa = if tr == Some(false) { n } else { k };
        let bad = if up.is_none() {
            1
        } else if tr.is_none() {
            2
        } else if n < 0 {
            3
        } else if k < 0 {
            4
        } else if lda < nrowa.max(1) {
            7
        } else if ldc < n.max(1) {
            10
        } else {
            0
        };
        if bad != 0 {
            return xerbla("DSYRK", bad);
        }
        let (alpha, beta) = (*alpha, *beta);
        if n == 0 || ((alpha == 0.0 || k == 0) && beta == 1.0) {
            return;
        }
        let (upper, (n, k)) = (up == Some(true), (n as usize, k as usize));
        let mut cv = view_mut(c, n, n, ldc as usize);
        scale_triangle(cv.rb_mut(), upper, beta);
        if alpha == 0.0 || k == 0 {
            return;
        }
        // opA is n x k in both cases.
        let opa = if tr == Some(false) { view(a, n, k, lda as usize) } else { view(a, k, n, lda as usize).transpose() };
        let rect = BlockStructure::Rectangular;
        triangular::matmul(cv, tri(upper), Accum::Add, opa, rect, opa.transpose(), rect, alpha, Par::Seq);
    }
}

/// Symmetric rank-2k update of one triangle of `C` (`n x n`):
/// `C := alpha*A*B^T + alpha*B*A^T + beta*C` (trans `'N'`, `A`,`B` are `n x k`)
/// or `C := alpha*A^T*B + alpha*B^T*A + beta*C` (trans `'T'`/`'C'`, `k x n`).
/// Only the `uplo` triangle of `C` is read or written.
///
/// # Safety
/// All pointers must be valid Fortran arguments for `DSYR2K`.
#[no_mangle]
pub unsafe extern "C" fn dsyr2k_(
    uplo: *const c_char,
    trans: *const c_char,
    n: *const c_int,
    k: *const c_int,
    alpha: *const f64,
    a: *const f64,
    lda: *const c_int,
    b: *const f64,
    ldb: *const c_int,
    beta: *const f64,
    c: *mut f64,
    ldc: *const c_int,
) {
    // SAFETY: the caller passes valid Fortran arguments (the `# Safety` section above), as the BLAS/LAPACK ABI requires of clarabel's calls.
    unsafe {
        let (up, tr) = (uplo_flag(ch(uplo)), is_trans(ch(trans)));
        let (n, k, lda, ldb, ldc) = (int(n), int(k), int(lda), int(ldb), int(ldc));
        let nrowa = if tr == Some(false) { n } else { k };
        let bad = if up.is_none() {
            1
        } else if tr.is_none() {
            2
        } else if n < 0 {
            3
        } else if k < 0 {
            4
        } else if lda < nrowa.max(1) {
            7
        } else if ldb < nrowa.max(1) {
            9
        } else if ldc < n.max(1) {
            12
        } else {
            0
        };
        if bad != 0 {
            return xerbla("DSYR2K", bad);
        }
        let (alpha, beta) = (*alpha, *beta);
        if n == 0 || ((alpha == 0.0 || k == 0) && beta == 1.0) {
            return;
        }
        let (upper, (n, k)) = (up == Some(true), (n as usize, k as usize));
        let mut cv = view_mut(c, n, n, ldc as usize);
        scale_triangle(cv.rb_mut(), upper, beta);
        if alpha == 0.0 || k == 0 {
            return;
        }
        let (opa, opb) = if tr == Some(false) {
            (view(a, n, k, lda as usize), view(b, n, k, ldb as usize))
        } else {
            (view(a, k, n, lda as usize).transpose(), view(b, k, n, ldb as usize).transpose())
        };
        let rect = BlockStructure::Rectangular;
        let s = tri(upper);
        triangular::matmul(cv.rb_mut(), s, Accum::Add, opa, rect, opb.transpose(), rect, alpha, Par::Seq);
        triangular::matmul(cv, s, Accum::Add, opb, rect, opa.transpose(), rect, alpha, Par::Seq);
    }
}
