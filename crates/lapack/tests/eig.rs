//! Property tests of `dsyevr_` against the definition of a symmetric
//! eigendecomposition: `A V = V Λ`, `VᵀV = I`, eigenvalues ascending
//! (LAPACK dsyevr documentation), plus range 'I'/'V' selection semantics.

mod common;
use common::*;
use proptest::prelude::*;
use wingcheck_lapack::dsyevr_;

struct Out {
    info: i32,
    m: usize,
    w: Vec<f64>,
    z: Buf,
}

/// Call dsyevr with a workspace query first (as clarabel does), then the real call.
#[allow(clippy::too_many_arguments)]
fn syevr(a: &mut Buf, jobz: u8, range: u8, upper: bool, vl: f64, vu: f64, il: i32, iu: i32, zpad: usize) -> Out {
    let n = a.rows;
    let ni = n as i32;
    let uplo = if upper { b'U' } else { b'L' } as i8;
    let (mut m, mut info) = (0, 0);
    let mut w = vec![f64::NAN; n.max(1)];
    let mut z = Buf::from_fn(n, n, zpad, |_, _| f64::NAN);
    let mut isuppz = vec![0; 2 * n.max(1)];
    let (mut work, mut iwork) = (vec![0.0; 1], vec![0; 1]);
    let call = |lwork: i32,
                liwork: i32,
                work: &mut Vec<f64>,
                iwork: &mut Vec<i32>,
                w: &mut Vec<f64>,
                z: &mut Buf,
                m: &mut i32,
                info: &mut i32,
                isuppz: &mut Vec<i32>,
                a: &mut Buf| unsafe {
        dsyevr_(
            &(jobz as i8),
            &(range as i8),
            &uplo,
            &ni,
            a.data.as_mut_ptr(),
            &a.ld_i32(),
            &vl,
            &vu,
            &il,
            &iu,
            &-1.0,
            m,
            w.as_mut_ptr(),
            z.data.as_mut_ptr(),
            &z.ld_i32(),
            isuppz.as_mut_ptr(),
            work.as_mut_ptr(),
            &lwork,
            iwork.as_mut_ptr(),
            &liwork,
            info,
        )
    };
    call(-1, -1, &mut work, &mut iwork, &mut w, &mut z, &mut m, &mut info, &mut isuppz, a);
    assert_eq!(info, 0);
    // LAPACK documents LWORK >= max(1,26N), LIWORK >= max(1,10N)
    assert!(work[0] >= (26 * n).max(1) as f64 && iwork[0] >= (10 * n).max(1) as i32);
    let (lw, liw) = (work[0] as usize, iwork[0] as usize);
    work.resize(lw, 0.0);
    iwork.resize(liw, 0);
    call(lw as i32, liw as i32, &mut work, &mut iwork, &mut w, &mut z, &mut m, &mut info, &mut isuppz, a);
    Out { info, m: m as usize, w, z }
}

fn check_pairs(a0: &Dense, o: &Out) {
    let n = a0.rows;
    let v = Dense::from_fn(n, o.m, |i, j| o.z.at(i, j));
    let lam = Dense::from_fn(o.m, o.m, |i, j| if i == j { o.w[i] } else { 0.0 });
    assert_close(&a0.mul(&v), &v.mul(&lam), 1e-11 * (1.0 + a0.norm()) * n as f64, "A V = V Λ");
    assert_close(&v.t().mul(&v), &Dense::eye(o.m), 1e-11 * n as f64, "VᵀV = I");
    assert!(o.w[..o.m].windows(2).all(|p| p[0] <= p[1]), "ascending");
}

proptest! {
    #![proptest_config(cases())]

    #[test]
    fn dsyevr_all_eigenpairs(a0 in (0usize..16).prop_flat_map(symmetric), upper in any::<bool>(), pads in (pad(), pad())) {
        let n = a0.rows;
        // garbage in the unreferenced triangle must not matter
        let mut a = Buf::from_fn(n, n, pads.0, |i, j| if (i <= j) == upper || i == j { a0.at(i, j) } else { 1e30 });
        let o = syevr(&mut a, b'V', b'A', upper, 0.0, 0.0, 0, 0, pads.1);
        prop_assert_eq!(o.info, 0);
        prop_assert_eq!(o.m, n);
        check_pairs(&a0, &o);
        // trace = sum of eigenvalues (similarity invariant)
        let tr: f64 = (0..n).map(|i| a0.at(i, i)).sum();
        prop_assert!((o.w[..n].iter().sum::<f64>() - tr).abs() <= 1e-11 * (1.0 + a0.norm()) * n as f64);
        a.assert_padding_intact();
        o.z.assert_padding_intact();
        // jobz = 'N' gives the same values
        let mut a2 = Buf::from_dense(&a0, 0);
        let o2 = syevr(&mut a2, b'N', b'A', upper, 0.0, 0.0, 0, 0, 0);
        for i in 0..n { prop_assert!((o2.w[i] - o.w[i]).abs() <= 1e-11 * (1.0 + a0.norm())); }
    }

    #[test]
    fn dsyevr_index_and_value_ranges(a0 in (1usize..16).prop_flat_map(symmetric), il0 in 0usize..16, cnt in 0usize..16, upper in any::<bool>()) {
        let n = a0.rows;
        let all = syevr(&mut Buf::from_dense(&a0, 0), b'N', b'A', upper, 0.0, 0.0, 0, 0, 0);
        let il = il0 % n + 1;
        let iu = il + cnt % (n - il + 1);
        let o = syevr(&mut Buf::from_dense(&a0, 1), b'V', b'I', upper, 0.0, 0.0, il as i32, iu as i32, 2);
        prop_assert_eq!(o.info, 0);
        prop_assert_eq!(o.m, iu + 1 - il);
        check_pairs(&a0, &o);
        for k in 0..o.m { prop_assert!((o.w[k] - all.w[il - 1 + k]).abs() <= 1e-11 * (1.0 + a0.norm())); }
        // range 'V': half-open (vl, vu] placed between distinct eigenvalues
        let (vl, vu) = (all.w[il - 1] - 1e-3, all.w[iu.max(il) - 1] + 1e-3);
        let want = all.w[..n].iter().filter(|&&x| x > vl && x <= vu).count();
        let o = syevr(&mut Buf::from_dense(&a0, 0), b'V', b'V', upper, vl, vu, 0, 0, 0);
        prop_assert_eq!(o.info, 0);
        prop_assert_eq!(o.m, want);
        check_pairs(&a0, &o);
    }
}

/// 2x2 closed form: [[2,1],[1,2]] has eigenvalues 1 and 3, vectors (1,∓1)/√2.
#[test]
fn closed_form_2x2() {
    let mut a = Buf::from_fn(2, 2, 0, |i, j| if i == j { 2.0 } else { 1.0 });
    let o = syevr(&mut a, b'V', b'A', false, 0.0, 0.0, 0, 0, 0);
    assert!((o.w[0] - 1.0).abs() < 1e-14 && (o.w[1] - 3.0).abs() < 1e-14);
    assert!((o.z.at(0, 0).abs() - 0.5f64.sqrt()).abs() < 1e-14);
    assert!((o.z.at(0, 0) + o.z.at(1, 0)).abs() < 1e-14);
}

/// Bad arguments give info = -(argument position) per the LAPACK interface.
#[test]
fn bad_arguments() {
    let mut a = Buf::from_fn(3, 3, 0, |i, j| (i + j) as f64);
    let mut base = |jobz: u8,
                    range: u8,
                    uplo: u8,
                    n: i32,
                    lda: i32,
                    vl: f64,
                    vu: f64,
                    il: i32,
                    iu: i32,
                    ldz: i32,
                    lwork: i32,
                    liwork: i32|
     -> i32 {
        let (mut m, mut info) = (0, 0);
        let (mut w, mut z, mut is, mut wk, mut iw) =
            (vec![0.0; 3], vec![0.0; 9], vec![0; 6], vec![0.0; 100], vec![0; 100]);
        unsafe {
            dsyevr_(
                &(jobz as i8),
                &(range as i8),
                &(uplo as i8),
                &n,
                a.data.as_mut_ptr(),
                &lda,
                &vl,
                &vu,
                &il,
                &iu,
                &0.0,
                &mut m,
                w.as_mut_ptr(),
                z.as_mut_ptr(),
                &ldz,
                is.as_mut_ptr(),
                wk.as_mut_ptr(),
                &lwork,
                iw.as_mut_ptr(),
                &liwork,
                &mut info,
            )
        };
        info
    };
    assert_eq!(base(b'X', b'A', b'U', 3, 3, 0.0, 0.0, 0, 0, 3, 78, 30), -1);
    assert_eq!(base(b'V', b'X', b'U', 3, 3, 0.0, 0.0, 0, 0, 3, 78, 30), -2);
    assert_eq!(base(b'V', b'A', b'X', 3, 3, 0.0, 0.0, 0, 0, 3, 78, 30), -3);
    assert_eq!(base(b'V', b'A', b'U', -1, 3, 0.0, 0.0, 0, 0, 3, 78, 30), -4);
    assert_eq!(base(b'V', b'A', b'U', 3, 2, 0.0, 0.0, 0, 0, 3, 78, 30), -6);
    assert_eq!(base(b'V', b'V', b'U', 3, 3, 1.0, 0.0, 0, 0, 3, 78, 30), -8);
    assert_eq!(base(b'V', b'I', b'U', 3, 3, 0.0, 0.0, 0, 2, 3, 78, 30), -9);
    assert_eq!(base(b'V', b'I', b'U', 3, 3, 0.0, 0.0, 2, 4, 3, 78, 30), -10);
    assert_eq!(base(b'V', b'A', b'U', 3, 3, 0.0, 0.0, 0, 0, 2, 78, 30), -15);
    assert_eq!(base(b'V', b'A', b'U', 3, 3, 0.0, 0.0, 0, 0, 3, 77, 30), -18);
    assert_eq!(base(b'V', b'A', b'U', 3, 3, 0.0, 0.0, 0, 0, 3, 78, 29), -20);
    assert_eq!(base(b'V', b'A', b'U', 3, 3, 0.0, 0.0, 0, 0, 3, 78, 30), 0);
}
