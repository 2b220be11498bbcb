//! Symmetric eigensolver `dsyevr_` (Fortran ABI) on faer's self-adjoint EVD.

use crate::util::{ch, int, set_work_size, symmetrize, view, view_mut};
use faer::prelude::ReborrowMut;
use faer::Side;
use std::ffi::{c_char, c_int};

/// Minimum (and reported optimal) `lwork` for `n`: LAPACK's `max(1, 26 n)`.
pub(crate) fn syevr_lwork(n: usize) -> usize {
    (26 * n).max(1)
}

/// Minimum (and reported optimal) `liwork` for `n`: LAPACK's `max(1, 10 n)`.
pub(crate) fn syevr_liwork(n: usize) -> usize {
    (10 * n).max(1)
}

/// Selected eigenvalues (ascending) and optionally eigenvectors of a
/// symmetric `n x n` matrix whose `uplo` triangle is stored in `A`.
///
/// * `jobz`: `'N'` values only, `'V'` values and vectors (columns of `Z`).
/// * `range`: `'A'` all; `'V'` those in the half-open interval `(vl, vu]`;
///   `'I'` the `il`-th through `iu`-th (1-based, ascending).
/// * `m` receives the number found; `W[0..m]` the values; `Z[:, 0..m]` the
///   orthonormal vectors. `isuppz` (when `jobz = 'V'`) is filled trivially with
///   full support `[1, n]` per vector.
/// * `abstol` is ignored: faer computes to full working accuracy.
/// * Workspace query: `lwork == -1` or `liwork == -1` stores the minimum sizes
///   (`26n`, `10n`) in `work[0]`/`iwork[0]`; the arrays are otherwise unused.
/// * `A` is left unchanged (LAPACK says its triangle is destroyed).
/// * `info = -i` for an illegal `i`-th argument, `1` if faer fails to converge.
///
/// # Safety
/// All pointers must be valid Fortran arguments for `DSYEVR`.
#[no_mangle]
pub unsafe extern "C" fn dsyevr_(
    jobz: *const c_char,
    range: *const c_char,
    uplo: *const c_char,
    n: *const c_int,
    a: *mut f64,
    lda: *const c_int,
    vl: *const f64,
    vu: *const f64,
    il: *const c_int,
    iu: *const c_int,
    _abstol: *const f64,
    m: *mut c_int,
    w: *mut f64,
    z: *mut f64,
    ldz: *const c_int,
    isuppz: *mut c_int,
    work: *mut f64,
    lwork: *const c_int,
    iwork: *mut c_int,
    liwork: *const c_int,
    info: *mut c_int,
) {
    // SAFETY: the caller passes valid Fortran arguments (the `# Safety` section above), as the BLAS/LAPACK ABI requires of clarabel's calls.
    unsafe {
        let (jz, rg, up) = (ch(jobz), ch(range), ch(uplo));
        let (nn, lda, ldz, lwork, liwork) = (int(n), int(lda), int(ldz), int(lwork), int(liwork));
        let query = lwork == -1 || liwork == -1;
        let wantz = jz == b'V';
        let nu = nn.max(0) as usize;
        *info = if jz != b'N' && jz != b'V' {
            -1
        } else if !matches!(rg, b'A' | b'V' | b'I') {
            -2
        } else if up != b'U' && up != b'L' {
            -3
        } else if nn < 0 {
            -4
        } else if lda < nn.max(1) {
            -6
        } else if rg == b'V' && nn > 0 && *vu <= *vl {
            -8
        } else if rg == b'I' && (int(il) < 1 || int(il) > nn.max(1)) {
            -9
        } else if rg == b'I' && (int(iu) < nn.min(int(il)) || int(iu) > nn) {
            -10
        } else if ldz < 1 || (wantz && ldz < nn) {
            -15
        } else if !query && (lwork as i64) < syevr_lwork(nu) as i64 {
            -18
        } else if !query && (liwork as i64) < syevr_liwork(nu) as i64 {
            -20
        } else {
            0
        };
        if *info != 0 {
            return;
        }
        if query {
            set_work_size(work, syevr_lwork(nu));
            *iwork = syevr_liwork(nu) as c_int;
            return;
        }
        *m = 0;
        if nu == 0 {
            return;
        }
        let full = symmetrize(view(a, nu, nu, lda as usize), up == b'U');
        let (vals, vecs) = if wantz {
            match full.self_adjoint_eigen(Side::Lower) {
                Ok(e) => {
                    let s = e.S().column_vector().iter().copied().collect::<Vec<_>>();
                    (s, Some(e.U().to_owned()))
                }
                Err(_) => {
                    *info = 1;
                    return;
                }
            }
        } else {
            match full.self_adjoint_eigenvalues(Side::Lower) {
                Ok(s) => (s, None),
                Err(_) => {
                    *info = 1;
                    return;
                }
            }
        };
        let sel: Vec<usize> = match rg {
            b'A' => (0..nu).collect(),
            b'I' => ((int(il) - 1) as usize..int(iu) as usize).collect(),
            _ => (0..nu).filter(|&i| vals[i] > *vl && vals[i] <= *vu).collect(),
        };
        *m = sel.len() as c_int;
        for (out, &i) in sel.iter().enumerate() {
            *w.add(out) = vals[i];
        }
        if let Some(u) = vecs {
            let mut zv = view_mut(z, nu, sel.len(), ldz as usize);
            for (out, &i) in sel.iter().enumerate() {
                zv.rb_mut().col_mut(out).copy_from(u.col(i));
                *isuppz.add(2 * out) = 1;
                *isuppz.add(2 * out + 1) = nu as c_int;
            }
        }
    }
}
