//! Property tests of `dgemm_`, `dsyrk_`, `dsyr2k_` against naive triple-loop
//! definitions (reference: BLAS reference-implementation documentation of
//! the operations `C := alpha op(A) op(B) + beta C` etc.).

mod common;
use common::*;
use proptest::prelude::*;
use wingcheck_lapack::{dgemm_, dsyr2k_, dsyrk_, take_blas_error, BlasArgError};

fn tr(t: bool) -> i8 {
    if t {
        b'T' as i8
    } else {
        b'N' as i8
    }
}

#[allow(clippy::too_many_arguments)]
fn gemm(ta: bool, tb: bool, alpha: f64, a: &Buf, b: &Buf, beta: f64, c: &mut Buf, k: usize) {
    let (m, n, k) = (c.rows as i32, c.cols as i32, k as i32);
    unsafe {
        dgemm_(
            &tr(ta),
            &tr(tb),
            &m,
            &n,
            &k,
            &alpha,
            a.data.as_ptr(),
            &a.ld_i32(),
            b.data.as_ptr(),
            &b.ld_i32(),
            &beta,
            c.data.as_mut_ptr(),
            &c.ld_i32(),
        );
    }
}

fn dims() -> impl Strategy<Value = (usize, usize, usize)> {
    (0usize..12, 0usize..12, 0usize..12)
}

proptest! {
    #![proptest_config(cases())]

    #[test]
    fn dgemm_matches_triple_loop(
        (a, b, c0, ta, tb) in dims().prop_flat_map(|(m, n, k)| (matrix(m, k), matrix(k, n), matrix(m, n), any::<bool>(), any::<bool>())),
        alpha in -2.0f64..2.0, beta in prop_oneof![Just(0.0), Just(1.0), -2.0f64..2.0],
        pads in (pad(), pad(), pad()),
    ) {
        // store op(A) = a, i.e. A = aᵀ when transposed
        let abuf = Buf::from_dense(&if ta { a.t() } else { a.clone() }, pads.0);
        let bbuf = Buf::from_dense(&if tb { b.t() } else { b.clone() }, pads.1);
        let mut c = Buf::from_dense(&c0, pads.2);
        gemm(ta, tb, alpha, &abuf, &bbuf, beta, &mut c, a.cols);
        // reference: definition alpha*A*B + beta*C with a naive product
        let want = Dense::from_fn(c0.rows, c0.cols, |i, j| alpha * a.mul(&b).at(i, j) + beta * c0.at(i, j));
        assert_close(&c.to_dense(), &want, 1e-12 * (1.0 + want.norm()) * (1 + a.cols) as f64, "gemm");
        c.assert_padding_intact();
        abuf.assert_padding_intact();
    }

    #[test]
    fn dsyrk_matches_definition_and_keeps_other_triangle(
        (a, c0, t, upper) in (0usize..12, 0usize..12).prop_flat_map(|(n, k)| (matrix(n, k), matrix(n, n), any::<bool>(), any::<bool>())),
        alpha in -2.0f64..2.0, beta in prop_oneof![Just(0.0), Just(1.0), -2.0f64..2.0],
        pads in (pad(), pad()),
    ) {
        let n = c0.rows;
        let abuf = Buf::from_dense(&if t { a.t() } else { a.clone() }, pads.0);
        let mut c = Buf::from_dense(&c0, pads.1);
        let (ni, ki) = (n as i32, a.cols as i32);
        let uplo = if upper { b'U' } else { b'L' } as i8;
        unsafe { dsyrk_(&uplo, &tr(t), &ni, &ki, &alpha, abuf.data.as_ptr(), &abuf.ld_i32(), &beta, c.data.as_mut_ptr(), &c.ld_i32()) };
        // reference: alpha*A*Aᵀ + beta*C on the uplo triangle, C unchanged elsewhere
        let aat = a.mul(&a.t());
        let want = Dense::from_fn(n, n, |i, j| {
            if (i <= j) == upper || i == j { alpha * aat.at(i, j) + beta * c0.at(i, j) } else { c0.at(i, j) }
        });
        assert_close(&c.to_dense(), &want, 1e-12 * (1.0 + want.norm()) * (1 + a.cols) as f64, "syrk");
        c.assert_padding_intact();
    }

    #[test]
    fn dsyr2k_matches_definition_and_keeps_other_triangle(
        (a, b, c0, t, upper) in (0usize..12, 0usize..12).prop_flat_map(|(n, k)| (matrix(n, k), matrix(n, k), matrix(n, n), any::<bool>(), any::<bool>())),
        alpha in -2.0f64..2.0, beta in prop_oneof![Just(0.0), Just(1.0), -2.0f64..2.0],
        pads in (pad(), pad(), pad()),
    ) {
        let n = c0.rows;
        let abuf = Buf::from_dense(&if t { a.t() } else { a.clone() }, pads.0);
        let bbuf = Buf::from_dense(&if t { b.t() } else { b.clone() }, pads.1);
        let mut c = Buf::from_dense(&c0, pads.2);
        let (ni, ki) = (n as i32, a.cols as i32);
        let uplo = if upper { b'U' } else { b'L' } as i8;
        unsafe { dsyr2k_(&uplo, &tr(t), &ni, &ki, &alpha, abuf.data.as_ptr(), &abuf.ld_i32(), bbuf.data.as_ptr(), &bbuf.ld_i32(), &beta, c.data.as_mut_ptr(), &c.ld_i32()) };
        // reference: alpha*(A Bᵀ + B Aᵀ) + beta*C on the uplo triangle
        let s = a.mul(&b.t());
        let want = Dense::from_fn(n, n, |i, j| {
            if (i <= j) == upper || i == j { alpha * (s.at(i, j) + s.at(j, i)) + beta * c0.at(i, j) } else { c0.at(i, j) }
        });
        assert_close(&c.to_dense(), &want, 1e-12 * (1.0 + want.norm()) * (1 + a.cols) as f64, "syr2k");
        c.assert_padding_intact();
    }
}

/// Reference BLAS: "when BETA is supplied as zero then C need not be set on
/// input" — NaN in C must not leak; likewise alpha = 0 must not read A/B.
#[test]
fn beta_zero_ignores_nan_in_c_and_alpha_zero_ignores_a() {
    let a = Buf::from_fn(3, 2, 1, |i, j| (i + 2 * j) as f64);
    let b = Buf::from_fn(2, 3, 0, |i, j| (i * j) as f64 + 1.0);
    let mut c = Buf::from_fn(3, 3, 2, |_, _| f64::NAN);
    gemm(false, false, 1.0, &a, &b, 0.0, &mut c, 2);
    // expected: naive product of the two small integer matrices above
    let want = a.to_dense().mul(&b.to_dense());
    assert_eq!(c.to_dense(), want);
    let nan_a = Buf::from_fn(3, 2, 0, |_, _| f64::NAN);
    let mut c2 = Buf::from_fn(3, 3, 0, |i, j| (i + j) as f64);
    gemm(false, false, 0.0, &nan_a, &b, 2.0, &mut c2, 2);
    // expected: 2*C exactly (A never read)
    assert_eq!(c2.to_dense(), Dense::from_fn(3, 3, |i, j| 2.0 * (i + j) as f64));

    let mut cs = Buf::from_fn(3, 3, 0, |_, _| f64::NAN);
    let (n, k) = (3, 2);
    unsafe {
        dsyrk_(
            &(b'L' as i8),
            &(b'N' as i8),
            &n,
            &k,
            &1.0,
            a.data.as_ptr(),
            &a.ld_i32(),
            &0.0,
            cs.data.as_mut_ptr(),
            &cs.ld_i32(),
        )
    };
    let aat = a.to_dense().mul(&a.to_dense().t());
    for j in 0..3 {
        for i in j..3 {
            assert_eq!(cs.at(i, j), aat.at(i, j));
        }
        for i in 0..j {
            assert!(cs.at(i, j).is_nan(), "upper triangle must be untouched");
        }
    }
}

/// Argument numbers follow the reference BLAS XERBLA calls.
#[test]
fn illegal_arguments_are_reported_and_c_untouched() {
    let a = Buf::from_fn(2, 2, 0, |_, _| 1.0);
    let mut c = Buf::from_fn(2, 2, 0, |_, _| 5.0);
    let _ = take_blas_error();
    let (two, one) = (2, 1);
    unsafe {
        dgemm_(
            &(b'X' as i8),
            &(b'N' as i8),
            &two,
            &two,
            &two,
            &1.0,
            a.data.as_ptr(),
            &two,
            a.data.as_ptr(),
            &two,
            &0.0,
            c.data.as_mut_ptr(),
            &two,
        )
    };
    assert_eq!(take_blas_error(), Some(BlasArgError { routine: "DGEMM", arg: 1 }));
    unsafe {
        dgemm_(
            &(b'N' as i8),
            &(b'N' as i8),
            &two,
            &two,
            &two,
            &1.0,
            a.data.as_ptr(),
            &one,
            a.data.as_ptr(),
            &two,
            &0.0,
            c.data.as_mut_ptr(),
            &two,
        )
    };
    assert_eq!(take_blas_error(), Some(BlasArgError { routine: "DGEMM", arg: 8 }));
    unsafe {
        dsyrk_(&(b'Q' as i8), &(b'N' as i8), &two, &two, &1.0, a.data.as_ptr(), &two, &0.0, c.data.as_mut_ptr(), &two)
    };
    assert_eq!(take_blas_error(), Some(BlasArgError { routine: "DSYRK", arg: 1 }));
    unsafe {
        dsyr2k_(
            &(b'U' as i8),
            &(b'N' as i8),
            &two,
            &two,
            &1.0,
            a.data.as_ptr(),
            &two,
            a.data.as_ptr(),
            &two,
            &0.0,
            c.data.as_mut_ptr(),
            &one,
        )
    };
    assert_eq!(take_blas_error(), Some(BlasArgError { routine: "DSYR2K", arg: 12 }));
    assert!(c.data.iter().all(|&x| x == 5.0));
}
