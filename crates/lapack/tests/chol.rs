//! Property tests of `dpotrf_`/`dpotrs_` against the definitions
//! `A = UᵀU` / `A = LLᵀ` and `A X = B` (LAPACK dpotrf/dpotrs documentation).

mod common;
use common::*;
use proptest::prelude::*;
use wingcheck_lapack::{dpotrf_, dpotrs_};

fn potrf(a: &mut Buf, upper: bool) -> i32 {
    let (n, mut info) = (a.rows as i32, 0);
    let uplo = if upper { b'U' } else { b'L' } as i8;
    unsafe { dpotrf_(&uplo, &n, a.data.as_mut_ptr(), &a.ld_i32(), &mut info) };
    info
}

/// Triangle of the factor as a dense matrix `R` with `A = RᵀR` (upper) or `A = R Rᵀ` (lower).
fn factor(a: &Buf, upper: bool) -> Dense {
    Dense::from_fn(a.rows, a.rows, |i, j| if (i <= j) == upper || i == j { a.at(i, j) } else { 0.0 })
}

proptest! {
    #![proptest_config(cases())]

    #[test]
    fn dpotrf_reconstructs_and_keeps_other_triangle(
        a0 in (0usize..14).prop_flat_map(spd), upper in any::<bool>(), p in pad(),
    ) {
        let n = a0.rows;
        // poison the unreferenced triangle: it must be neither read nor written
        let mut a = Buf::from_fn(n, n, p, |i, j| if (i <= j) == upper || i == j { a0.at(i, j) } else { f64::NAN });
        prop_assert_eq!(potrf(&mut a, upper), 0);
        let r = factor(&a, upper);
        let rec = if upper { r.t().mul(&r) } else { r.mul(&r.t()) };
        assert_close(&rec, &a0, 1e-12 * (1.0 + a0.norm()) * n.max(1) as f64, "A = RᵀR");
        for j in 0..n { prop_assert!(r.at(j, j) > 0.0); }
        for j in 0..n { for i in 0..n { if !((i <= j) == upper || i == j) { prop_assert!(a.at(i, j).is_nan()); } } }
        a.assert_padding_intact();
    }

    #[test]
    fn dpotrs_solves(
        (a0, x0) in (1usize..14, 0usize..5).prop_flat_map(|(n, r)| (spd(n), matrix(n, r))),
        upper in any::<bool>(), pads in (pad(), pad()),
    ) {
        let n = a0.rows;
        let mut a = Buf::from_dense(&a0, pads.0);
        prop_assert_eq!(potrf(&mut a, upper), 0);
        // B := A X0, solve and compare residual A X - B (backward-stable check)
        let b0 = a0.mul(&x0);
        let mut b = Buf::from_dense(&b0, pads.1);
        let (ni, nrhs, mut info) = (n as i32, x0.cols as i32, 0);
        let uplo = if upper { b'U' } else { b'L' } as i8;
        unsafe { dpotrs_(&uplo, &ni, &nrhs, a.data.as_ptr(), &a.ld_i32(), b.data.as_mut_ptr(), &b.ld_i32(), &mut info) };
        prop_assert_eq!(info, 0);
        let x = b.to_dense();
        assert_close(&a0.mul(&x), &b0, 1e-10 * (1.0 + a0.norm() * x.norm()), "A X = B");
        b.assert_padding_intact();
    }
}

/// diag(1, -1, 1): LAPACK reports the order of the first non-PD leading minor (2).
#[test]
fn dpotrf_reports_first_failing_minor() {
    for upper in [false, true] {
        let mut a = Buf::from_fn(3, 3, 1, |i, j| if i == j { [1.0, -1.0, 1.0][i] } else { 0.0 });
        assert_eq!(potrf(&mut a, upper), 2);
        // [[4,2,0],[2,1,0],[0,0,1]] has a zero 2x2 leading minor (4*1 - 2*2) -> info 2
        let m = [[4.0, 2.0, 0.0], [2.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let mut a = Buf::from_fn(3, 3, 0, |i, j| m[i][j]);
        assert_eq!(potrf(&mut a, upper), 2);
        let mut a = Buf::from_fn(2, 2, 0, |i, j| if i == j { f64::NAN } else { 0.0 });
        assert_eq!(potrf(&mut a, upper), 1, "NaN pivot");
    }
    // 2x2 closed form: chol([[4,2],[2,5]]) = [[2,0],[1,2]]
    let mut a = Buf::from_fn(2, 2, 0, |i, j| [[4.0, 2.0], [2.0, 5.0]][i][j]);
    assert_eq!(potrf(&mut a, false), 0);
    assert_eq!((a.at(0, 0), a.at(1, 0), a.at(1, 1)), (2.0, 1.0, 2.0));
}

/// Argument checks: info = -(position of the bad argument), per LAPACK docs.
#[test]
fn bad_arguments() {
    let mut a = Buf::from_fn(2, 2, 0, |i, j| f64::from(u8::from(i == j)));
    let (two, one, neg, mut info) = (2, 1, -1, 0);
    unsafe { dpotrf_(&(b'X' as i8), &two, a.data.as_mut_ptr(), &two, &mut info) };
    assert_eq!(info, -1);
    unsafe { dpotrf_(&(b'L' as i8), &neg, a.data.as_mut_ptr(), &two, &mut info) };
    assert_eq!(info, -2);
    unsafe { dpotrf_(&(b'L' as i8), &two, a.data.as_mut_ptr(), &one, &mut info) };
    assert_eq!(info, -4);
    let mut b = vec![1.0; 4];
    unsafe { dpotrs_(&(b'L' as i8), &two, &neg, a.data.as_ptr(), &two, b.as_mut_ptr(), &two, &mut info) };
    assert_eq!(info, -3);
    unsafe { dpotrs_(&(b'L' as i8), &two, &two, a.data.as_ptr(), &two, b.as_mut_ptr(), &one, &mut info) };
    assert_eq!(info, -7);
}
