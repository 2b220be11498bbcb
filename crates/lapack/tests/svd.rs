//! Property tests of `dgesdd_`/`dgesvd_` against the definition of the SVD:
//! `U Σ Vᵀ = A`, orthonormal `U`/`V`, `σ` non-negative and non-increasing
//! (LAPACK dgesdd/dgesvd documentation), for every job option.

mod common;
use common::*;
use proptest::prelude::*;
use wingcheck_lapack::{dgesdd_, dgesvd_};

/// Output of one SVD call: singular values, U (m x ucols), Vᵀ (vrows x n).
struct Out {
    s: Vec<f64>,
    u: Option<Dense>,
    vt: Option<Dense>,
}

fn job_cols(job: u8, m: usize, mn: usize) -> usize {
    match job {
        b'A' => m,
        b'S' | b'O' => mn,
        _ => 0,
    }
}

/// Run dgesvd (sdd = false) or dgesdd (sdd = true, jobu is jobz) with a
/// workspace query first, as clarabel does.
fn run(sdd: bool, jobu: u8, jobvt: u8, a0: &Dense, pads: (usize, usize, usize)) -> Out {
    let (m, n) = (a0.rows, a0.cols);
    let mn = m.min(n);
    let mut a = Buf::from_dense(a0, pads.0);
    let mut u = Buf::from_fn(m, m, pads.1, |_, _| f64::NAN);
    let mut vt = Buf::from_fn(n, n, pads.2, |_, _| f64::NAN);
    let mut s = vec![f64::NAN; mn.max(1)];
    let (mi, ni, mut info) = (m as i32, n as i32, 0);
    let mut work = vec![0.0; 1];
    let mut iwork = vec![0; 8 * mn.max(1)];
    for lwork in [-1, 0] {
        let lw = if lwork == -1 { -1 } else { work[0] as i32 };
        if lwork == 0 {
            work.resize(lw as usize, 0.0);
        }
        unsafe {
            if sdd {
                dgesdd_(
                    &(jobu as i8),
                    &mi,
                    &ni,
                    a.data.as_mut_ptr(),
                    &a.ld_i32(),
                    s.as_mut_ptr(),
                    u.data.as_mut_ptr(),
                    &u.ld_i32(),
                    vt.data.as_mut_ptr(),
                    &vt.ld_i32(),
                    work.as_mut_ptr(),
                    &lw,
                    iwork.as_mut_ptr(),
                    &mut info,
                );
            } else {
                dgesvd_(
                    &(jobu as i8),
                    &(jobvt as i8),
                    &mi,
                    &ni,
                    a.data.as_mut_ptr(),
                    &a.ld_i32(),
                    s.as_mut_ptr(),
                    u.data.as_mut_ptr(),
                    &u.ld_i32(),
                    vt.data.as_mut_ptr(),
                    &vt.ld_i32(),
                    work.as_mut_ptr(),
                    &lw,
                    &mut info,
                );
            }
        }
        assert_eq!(info, 0, "info");
    }
    a.assert_padding_intact();
    u.assert_padding_intact();
    vt.assert_padding_intact();
    // where each factor lives, per the LAPACK job semantics
    let (ucols, vrows, u_in_a, vt_in_a) = if sdd {
        match jobu {
            b'O' if m >= n => (n, n, true, false),
            b'O' => (m, m, false, true),
            j => (job_cols(j, m, mn), job_cols(j, n, mn), false, false),
        }
    } else {
        (job_cols(jobu, m, mn), job_cols(jobvt, n, mn), jobu == b'O', jobvt == b'O')
    };
    let want_u = jobu != b'N';
    let want_v = if sdd { jobu != b'N' } else { jobvt != b'N' };
    let ub = if u_in_a { &a } else { &u };
    let vb = if vt_in_a { &a } else { &vt };
    Out {
        s: s[..mn].to_vec(),
        u: want_u.then(|| Dense::from_fn(m, ucols, |i, j| ub.at(i, j))),
        vt: want_v.then(|| Dense::from_fn(vrows, n, |i, j| vb.at(i, j))),
    }
}

fn check(a0: &Dense, o: &Out) {
    let (m, n) = (a0.rows, a0.cols);
    let mn = m.min(n);
    let tol = 1e-11 * (1.0 + a0.norm()) * (m + n + 1) as f64;
    assert!(o.s.iter().all(|&x| x >= 0.0), "σ ≥ 0");
    assert!(o.s.windows(2).all(|p| p[0] >= p[1]), "σ non-increasing");
    // ‖A‖_F² = Σ σ² (orthogonal invariance)
    let fro2: f64 = o.s.iter().map(|x| x * x).sum();
    assert!((fro2.sqrt() - a0.norm()).abs() <= tol, "Σσ² = ‖A‖²");
    if mn == 0 {
        return; // LAPACK quick-returns without touching U/Vᵀ when m or n is 0
    }
    if let Some(u) = &o.u {
        assert_close(&u.t().mul(u), &Dense::eye(u.cols), 1e-11 * (m + 1) as f64, "UᵀU = I");
    }
    if let Some(vt) = &o.vt {
        assert_close(&vt.mul(&vt.t()), &Dense::eye(vt.rows), 1e-11 * (n + 1) as f64, "VᵀV = I");
    }
    if let (Some(u), Some(vt)) = (&o.u, &o.vt) {
        let us = Dense::from_fn(m, mn, |i, j| u.at(i, j) * o.s[j]);
        let v1 = Dense::from_fn(mn, n, |i, j| vt.at(i, j));
        assert_close(&us.mul(&v1), a0, tol, "U Σ Vᵀ = A");
    }
}

fn shape() -> impl Strategy<Value = Dense> {
    (0usize..12, 0usize..12).prop_flat_map(|(m, n)| matrix(m, n))
}

fn pads() -> impl Strategy<Value = (usize, usize, usize)> {
    (pad(), pad(), pad())
}

proptest! {
    #![proptest_config(cases())]

    #[test]
    fn dgesdd_all_jobs(a0 in shape(), p in pads()) {
        for job in [b'A', b'S', b'O', b'N'] {
            let o = run(true, job, job, &a0, p);
            check(&a0, &o);
        }
    }

    #[test]
    fn dgesvd_all_jobs(a0 in shape(), p in pads(), ju in 0usize..4, jv in 0usize..4) {
        let jobs = [b'A', b'S', b'O', b'N'];
        let (ju, jv) = (jobs[ju], if jobs[ju] == b'O' && jobs[jv] == b'O' { b'S' } else { jobs[jv] });
        let o = run(false, ju, jv, &a0, p);
        check(&a0, &o);
        // singular values agree with dgesdd
        let o2 = run(true, b'N', b'N', &a0, p);
        for (x, y) in o.s.iter().zip(&o2.s) { prop_assert!((x - y).abs() <= 1e-11 * (1.0 + a0.norm())); }
    }
}

/// Closed form: [[3,0],[4,5]] has σ = (3√5, √5) (AᵀA = [[25,20],[20,25]] → 45, 5).
#[test]
fn closed_form_2x2() {
    let a = Dense::from_fn(2, 2, |i, j| [[3.0, 0.0], [4.0, 5.0]][i][j]);
    for sdd in [true, false] {
        let o = run(sdd, b'S', b'S', &a, (1, 0, 2));
        assert!((o.s[0] - 3.0 * 5f64.sqrt()).abs() < 1e-13 && (o.s[1] - 5f64.sqrt()).abs() < 1e-13);
    }
}

/// Bad arguments give info = -(argument position) per the LAPACK interface.
#[test]
fn bad_arguments() {
    let mut a = vec![1.0; 12];
    let (mut s, mut u, mut vt, mut w, mut iw) =
        (vec![0.0; 4], vec![0.0; 16], vec![0.0; 16], vec![0.0; 200], vec![0; 32]);
    let mut sdd = |jobz: u8, m: i32, n: i32, lda: i32, ldu: i32, ldvt: i32, lwork: i32| {
        let mut info = 0;
        unsafe {
            dgesdd_(
                &(jobz as i8),
                &m,
                &n,
                a.as_mut_ptr(),
                &lda,
                s.as_mut_ptr(),
                u.as_mut_ptr(),
                &ldu,
                vt.as_mut_ptr(),
                &ldvt,
                w.as_mut_ptr(),
                &lwork,
                iw.as_mut_ptr(),
                &mut info,
            )
        };
        info
    };
    assert_eq!(sdd(b'X', 3, 4, 3, 3, 4, 200), -1);
    assert_eq!(sdd(b'A', -3, 4, 3, 3, 4, 200), -2);
    assert_eq!(sdd(b'A', 3, -4, 3, 3, 4, 200), -3);
    assert_eq!(sdd(b'A', 3, 4, 2, 3, 4, 200), -5);
    assert_eq!(sdd(b'A', 3, 4, 3, 2, 4, 200), -8);
    assert_eq!(sdd(b'A', 3, 4, 3, 3, 3, 200), -10);
    assert_eq!(sdd(b'S', 3, 4, 3, 3, 2, 200), -10);
    assert_eq!(sdd(b'A', 3, 4, 3, 3, 4, 1), -12);
    assert_eq!(sdd(b'A', 3, 4, 3, 3, 4, 200), 0);
    let mut a = vec![1.0; 12];
    let mut svd = |ju: u8, jv: u8, m: i32, n: i32, lda: i32, ldu: i32, ldvt: i32, lwork: i32| {
        let mut info = 0;
        unsafe {
            dgesvd_(
                &(ju as i8),
                &(jv as i8),
                &m,
                &n,
                a.as_mut_ptr(),
                &lda,
                s.as_mut_ptr(),
                u.as_mut_ptr(),
                &ldu,
                vt.as_mut_ptr(),
                &ldvt,
                w.as_mut_ptr(),
                &lwork,
                &mut info,
            )
        };
        info
    };
    assert_eq!(svd(b'X', b'A', 3, 4, 3, 3, 4, 200), -1);
    assert_eq!(svd(b'O', b'O', 3, 4, 3, 3, 4, 200), -2);
    assert_eq!(svd(b'A', b'A', -1, 4, 3, 3, 4, 200), -3);
    assert_eq!(svd(b'A', b'A', 3, -1, 3, 3, 4, 200), -4);
    assert_eq!(svd(b'A', b'A', 3, 4, 2, 3, 4, 200), -6);
    assert_eq!(svd(b'A', b'A', 3, 4, 3, 2, 4, 200), -9);
    assert_eq!(svd(b'A', b'A', 3, 4, 3, 3, 3, 200), -11);
    assert_eq!(svd(b'A', b'A', 3, 4, 3, 3, 4, 14), -13);
    assert_eq!(svd(b'A', b'A', 3, 4, 3, 3, 4, 15), 0);
}
