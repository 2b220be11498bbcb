//! Singular value decompositions `dgesdd_` and `dgesvd_` (Fortran ABI) on
//! faer's SVD. Both compute the same factorisation `A = U diag(S) V^T` with
//! `S` non-negative and non-increasing; only the job/argument conventions differ.

use crate::util::{ch, int, set_work_size, view, view_mut};
use faer::diag::Diag;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::svd::{svd, svd_scratch, ComputeSvdVectors};
use faer::{Mat, MatRef, Par};
use std::ffi::{c_char, c_int};

/// Result of the shared SVD kernel.
struct SvdOut {
    s: Vec<f64>,
    u: Option<Mat<f64>>,
    v: Option<Mat<f64>>,
}

fn compute(a: MatRef<'_, f64>, cu: ComputeSvdVectors, cv: ComputeSvdVectors) -> Option<SvdOut> {
    let (m, n) = a.shape();
    let mn = m.min(n);
    let cols = |c: ComputeSvdVectors, full: usize| match c {
        ComputeSvdVectors::No => None,
        ComputeSvdVectors::Thin => Some(mn),
        ComputeSvdVectors::Full => Some(full),
    };
    let mut u = cols(cu, m).map(|c| Mat::<f64>::zeros(m, c));
    let mut v = cols(cv, n).map(|c| Mat::<f64>::zeros(n, c));
    let mut s = Diag::<f64>::zeros(mn);
    let mut mem = MemBuffer::new(svd_scratch::<f64>(m, n, cu, cv, Par::Seq, Default::default()));
    let stack = MemStack::new(&mut mem);
    let res = svd(
        a,
        s.as_mut(),
        u.as_mut().map(|x| x.as_mut()),
        v.as_mut().map(|x| x.as_mut()),
        Par::Seq,
        stack,
        Default::default(),
    );
    res.ok()?;
    let s: Vec<f64> = s.column_vector().iter().copied().collect();
    if s.iter().any(|x| !x.is_finite()) {
        return None;
    }
    Some(SvdOut { s, u, v })
}

/// Write the first `cols` columns of `u` into the column-major buffer `dst`.
///
/// # Safety
/// `dst` must be writable for `ld * (cols - 1) + u.nrows()` `f64`s, not aliased ([`view_mut`]).
unsafe fn put_u(dst: *mut f64, ld: usize, u: &Mat<f64>, cols: usize) {
    // SAFETY: the caller upholds the `# Safety` section above, which is view_mut's.
    unsafe {
        view_mut(dst, u.nrows(), cols, ld).copy_from(u.as_ref().subcols(0, cols));
    }
}

/// Write the first `rows` rows of `V^T` into the column-major buffer `dst`.
///
/// # Safety
/// `dst` must be writable for `ld * (v.nrows() - 1) + rows` `f64`s, not aliased ([`view_mut`]).
unsafe fn put_vt(dst: *mut f64, ld: usize, v: &Mat<f64>, rows: usize) {
    // SAFETY: the caller upholds the `# Safety` section above, which is view_mut's.
    unsafe {
        view_mut(dst, rows, v.nrows(), ld).copy_from(v.as_ref().subcols(0, rows).transpose());
    }
}

/// Minimum (and reported optimal) `lwork` of `dgesdd` (LAPACK 3.x docs).
pub(crate) fn gesdd_lwork(jobz: u8, m: usize, n: usize) -> usize {
    let (mn, mx) = (m.min(n), m.max(n));
    let w = match jobz {
        b'N' => 3 * mn + mx.max(7 * mn),
        b'O' => 3 * mn + mx.max(5 * mn * mn + 4 * mn),
        b'S' => 4 * mn * mn + 7 * mn,
        _ => 4 * mn * mn + 6 * mn + mx,
    };
    w.max(1)
}

/// Minimum (and reported optimal) `lwork` of `dgesvd`: `max(1, 3mn+mx, 5mn)`.
pub(crate) fn gesvd_lwork(m: usize, n: usize) -> usize {
    let (mn, mx) = (m.min(n), m.max(n));
    (3 * mn + mx).max(5 * mn).max(1)
}

/// Divide-and-conquer style SVD of the `m x n` matrix `A`.
///
/// `jobz`: `'A'` all of `U` (`m x m`) and `V^T` (`n x n`); `'S'` the leading
/// `min(m,n)` columns of `U` / rows of `V^T`; `'O'` like `'S'` but with `U`
/// (if `m >= n`) or `V^T` (if `m < n`) overwriting `A` and the other factor
/// full-size in `U`/`VT` as LAPACK specifies; `'N'` singular values only.
/// `lwork == -1` is a workspace query (size in `work[0]`); `iwork` is unused.
/// `info = -i` for an illegal `i`-th argument, `1` on non-convergence.
/// `A` is left unchanged unless `jobz = 'O'`.
///
/// # Safety
/// All pointers must be valid Fortran arguments for `DGESDD`.
#[no_mangle]
pub unsafe extern "C" fn dgesdd_(
    jobz: *const c_char,
    m: *const c_int,
    n: *const c_int,
    a: *mut f64,
    lda: *const c_int,
    s: *mut f64,
    u: *mut f64,
    ldu: *const c_int,
    vt: *mut f64,
    ldvt: *const c_int,
    work: *mut f64,
    lwork: *const c_int,
    _iwork: *mut c_int,
    info: *mut c_int,
) {
    // SAFETY: the caller passes valid Fortran arguments (the `# Safety` section above), as the BLAS/LAPACK ABI requires of clarabel's calls.
    unsafe {
        let jz = ch(jobz);
        let (mi, ni, lda, ldu, ldvt, lwork) = (int(m), int(n), int(lda), int(ldu), int(ldvt), int(lwork));
        let mni = mi.min(ni);
        let (wa, ws, wo) = (jz == b'A', jz == b'S', jz == b'O');
        let lw_min = gesdd_lwork(jz, mi.max(0) as usize, ni.max(0) as usize);
        *info = if !matches!(jz, b'A' | b'S' | b'O' | b'N') {
            -1
        } else if mi < 0 {
            -2
        } else if ni < 0 {
            -3
        } else if lda < mi.max(1) {
            -5
        } else if ldu < 1 || ((wa || ws) && ldu < mi) || (wo && mi < ni && ldu < mi) {
            -8
        } else if ldvt < 1 || (wa && ldvt < ni) || (ws && ldvt < mni) || (wo && mi >= ni && ldvt < ni) {
            -10
        } else if lwork != -1 && (lwork as i64) < lw_min as i64 {
            -12
        } else {
            0
        };
        if *info != 0 {
            return;
        }
        if lwork == -1 {
            return set_work_size(work, lw_min);
        }
        if mi == 0 || ni == 0 {
            return;
        }
        let (m, n, mn) = (mi as usize, ni as usize, mni as usize);
        let (lda, ldu, ldvt) = (lda as usize, ldu as usize, ldvt as usize);
        use ComputeSvdVectors::{Full, No, Thin};
        let (cu, cv) = match jz {
            b'N' => (No, No),
            b'S' => (Thin, Thin),
            b'A' => (Full, Full),
            _ if m >= n => (Thin, Full),
            _ => (Full, Thin),
        };
        let Some(r) = compute(view(a, m, n, lda), cu, cv) else {
            *info = 1;
            return;
        };
        std::ptr::copy_nonoverlapping(r.s.as_ptr(), s, mn);
        let (Some(uu), Some(vv)) = (r.u, r.v) else {
            return;
        };
        match jz {
            b'O' if m >= n => {
                put_u(a, lda, &uu, n);
                put_vt(vt, ldvt, &vv, n);
            }
            b'O' => {
                put_u(u, ldu, &uu, m);
                put_vt(a, lda, &vv, m);
            }
            _ => {
                put_u(u, ldu, &uu, uu.ncols());
                put_vt(vt, ldvt, &vv, vv.ncols());
            }
        }
    }
}

fn job_mode(c: u8) -> Option<ComputeSvdVectors> {
    match c {
        b'A' => Some(ComputeSvdVectors::Full),
        b'S' | b'O' => Some(ComputeSvdVectors::Thin),
        b'N' => Some(ComputeSvdVectors::No),
        _ => None,
    }
}

/// QR-iteration style SVD of the `m x n` matrix `A` (same maths as [`dgesdd_`]).
///
/// `jobu`: `'A'` all `m` columns of `U`; `'S'` the first `min(m,n)`; `'O'` the
/// first `min(m,n)` columns overwrite `A`; `'N'` none. `jobvt` likewise for
/// the rows of `V^T` (`'O'` overwrites the first `min(m,n)` rows of `A`).
/// `jobu` and `jobvt` cannot both be `'O'`. `lwork == -1` is a workspace
/// query. `info = -i` for an illegal `i`-th argument, `1` on non-convergence.
///
/// # Safety
/// All pointers must be valid Fortran arguments for `DGESVD`.
#[no_mangle]
pub unsafe extern "C" fn dgesvd_(
    jobu: *const c_char,
    jobvt: *const c_char,
    m: *const c_int,
    n: *const c_int,
    a: *mut f64,
    lda: *const c_int,
    s: *mut f64,
    u: *mut f64,
    ldu: *const c_int,
    vt: *mut f64,
    ldvt: *const c_int,
    work: *mut f64,
    lwork: *const c_int,
    info: *mut c_int,
) {
    // SAFETY: the caller passes valid Fortran arguments (the `# Safety` section above), as the BLAS/LAPACK ABI requires of clarabel's calls.
    unsafe {
        let (ju, jv) = (ch(jobu), ch(jobvt));
        let (mi, ni, lda, ldu, ldvt, lwork) = (int(m), int(n), int(lda), int(ldu), int(ldvt), int(lwork));
        let mni = mi.min(ni);
        let lw_min = gesvd_lwork(mi.max(0) as usize, ni.max(0) as usize);
        *info = if job_mode(ju).is_none() {
            -1
        } else if job_mode(jv).is_none() || (ju == b'O' && jv == b'O') {
            -2
        } else if mi < 0 {
            -3
        } else if ni < 0 {
            -4
        } else if lda < mi.max(1) {
            -6
        } else if ldu < 1 || (matches!(ju, b'A' | b'S') && ldu < mi) {
            -9
        } else if ldvt < 1 || (jv == b'A' && ldvt < ni) || (jv == b'S' && ldvt < mni) {
            -11
        } else if lwork != -1 && (lwork as i64) < lw_min as i64 {
            -13
        } else {
            0
        };
        if *info != 0 {
            return;
        }
        if lwork == -1 {
            return set_work_size(work, lw_min);
        }
        if mi == 0 || ni == 0 {
            return;
        }
        let (m, n, mn) = (mi as usize, ni as usize, mni as usize);
        let (lda, ldu, ldvt) = (lda as usize, ldu as usize, ldvt as usize);
        let (cu, cv) = (job_mode(ju).unwrap(), job_mode(jv).unwrap());
        let Some(r) = compute(view(a, m, n, lda), cu, cv) else {
            *info = 1;
            return;
        };
        std::ptr::copy_nonoverlapping(r.s.as_ptr(), s, mn);
        if let Some(uu) = &r.u {
            let (dst, ld) = if ju == b'O' { (a, lda) } else { (u, ldu) };
            put_u(dst, ld, uu, uu.ncols());
        }
        if let Some(vv) = &r.v {
            let (dst, ld) = if jv == b'O' { (a, lda) } else { (vt, ldvt) };
            put_vt(dst, ld, vv, vv.ncols());
        }
    }
}
