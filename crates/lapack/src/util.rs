//! Shared helpers for the Fortran-ABI entry points: argument decoding,
//! strided faer views over caller buffers, and `xerbla`-style error reporting.

use faer::{MatMut, MatRef};
use std::cell::Cell;
use std::ffi::{c_char, c_int};

/// A BLAS argument error, as reference BLAS would report through `XERBLA`.
///
/// BLAS level-3 routines have no `info` argument; reference BLAS prints a
/// message and stops the program. This crate instead prints the same message
/// to stderr, leaves every output untouched, and records the error in a
/// thread-local slot that [`take_blas_error`] reads (mainly for tests).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BlasArgError {
    /// Routine name in upper case, e.g. `"DGEMM"`.
    pub routine: &'static str,
    /// 1-based position of the first illegal argument.
    pub arg: i32,
}

thread_local! {
    static LAST_ERROR: Cell<Option<BlasArgError>> = const { Cell::new(None) };
}

/// Returns (and clears) the last BLAS argument error raised on this thread.
pub fn take_blas_error() -> Option<BlasArgError> {
    LAST_ERROR.with(|c| c.take())
}

/// Report an illegal BLAS argument like reference `XERBLA`, without aborting.
pub(crate) fn xerbla(routine: &'static str, arg: i32) {
    eprintln!(" ** On entry to {routine} parameter number {arg} had an illegal value");
    LAST_ERROR.with(|c| c.set(Some(BlasArgError { routine, arg })));
}

/// Read a Fortran CHARACTER*1 argument, upper-cased.
///
/// # Safety
/// `p` must be valid for reads.
#[inline]
pub(crate) unsafe fn ch(p: *const c_char) -> u8 {
    // SAFETY: the caller upholds the `# Safety` section above.
    unsafe { (*p as u8).to_ascii_uppercase() }
}

/// Read a Fortran INTEGER argument.
///
/// # Safety
/// `p` must be valid for reads.
#[inline]
pub(crate) unsafe fn int(p: *const c_int) -> i32 {
    // SAFETY: the caller upholds the `# Safety` section above.
    unsafe { *p }
}

/// Column-major strided read-only view of `rows x cols` entries at `ptr`.
///
/// # Safety
/// If `rows > 0 && cols > 0`, `ptr` must point to at least
/// `ld * (cols - 1) + rows` readable `f64`s that outlive `'a`.
#[inline]
pub(crate) unsafe fn view<'a>(ptr: *const f64, rows: usize, cols: usize, ld: usize) -> MatRef<'a, f64> {
    // SAFETY: the caller upholds the `# Safety` section above.
    unsafe {
        if rows == 0 || cols == 0 {
            return MatRef::from_column_major_slice(&[], rows, cols);
        }
        MatRef::from_raw_parts(ptr, rows, cols, 1, ld as isize)
    }
}

/// Column-major strided mutable view of `rows x cols` entries at `ptr`.
///
/// # Safety
/// As for [`view`], plus the region must be writable and not aliased.
#[inline]
pub(crate) unsafe fn view_mut<'a>(ptr: *mut f64, rows: usize, cols: usize, ld: usize) -> MatMut<'a, f64> {
    // SAFETY: the caller upholds the `# Safety` section above.
    unsafe {
        if rows == 0 || cols == 0 {
            return MatMut::from_column_major_slice_mut(&mut [], rows, cols);
        }
        MatMut::from_raw_parts_mut(ptr, rows, cols, 1, ld as isize)
    }
}

/// Scale the `uplo` triangle (`b'U'` or `b'L'`) of an `n x n` view by `beta`,
/// writing exact zeros when `beta == 0` (so NaN/Inf in `C` do not propagate).
pub(crate) fn scale_triangle(mut c: MatMut<'_, f64>, upper: bool, beta: f64) {
    if beta == 1.0 {
        return;
    }
    let n = c.nrows();
    for j in 0..n {
        let (lo, hi) = if upper { (0, j + 1) } else { (j, n) };
        for i in lo..hi {
            c[(i, j)] = if beta == 0.0 { 0.0 } else { beta * c[(i, j)] };
        }
    }
}

/// Scale every entry of a view by `beta` (exact zeros when `beta == 0`).
pub(crate) fn scale_all(mut c: MatMut<'_, f64>, beta: f64) {
    if beta == 1.0 {
        return;
    }
    for j in 0..c.ncols() {
        for i in 0..c.nrows() {
            c[(i, j)] = if beta == 0.0 { 0.0 } else { beta * c[(i, j)] };
        }
    }
}

/// Store a workspace size in `work[0]` as LAPACK does.
///
/// # Safety
/// `work` must be valid for one write.
#[inline]
pub(crate) unsafe fn set_work_size(work: *mut f64, size: usize) {
    // SAFETY: the caller upholds the `# Safety` section above.
    unsafe {
        *work = size.max(1) as f64;
    }
}

/// Copy the `upper`/lower triangle of a square view into a full symmetric
/// owned matrix (the other triangle of the source is never read).
pub(crate) fn symmetrize(a: MatRef<'_, f64>, upper: bool) -> faer::Mat<f64> {
    let n = a.nrows();
    faer::Mat::from_fn(n, n, |i, j| {
        let (r, c) = if (i <= j) == upper { (i, j) } else { (j, i) };
        a[(r, c)]
    })
}
