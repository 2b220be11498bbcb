//! Tests for exact PD/PSD checks.

use std::time::Instant;

use num_rational::BigRational;
use num_traits::Zero;
use proptest::prelude::*;
use wingcheck_cert::exact::{frac, int};
use wingcheck_cert::fe::{ClampedMesh, Space};
use wingcheck_cert::psd::*;
use wingcheck_cert::RationalMatrix;

fn from_ints(rows: &[Vec<i64>]) -> RationalMatrix {
    RationalMatrix::from_rows(rows.iter().map(|r| r.iter().map(|&v| int(v)).collect()).collect()).unwrap()
}

/// Laplace (cofactor) expansion along the first row — independent reference.
fn cofactor_det(a: &RationalMatrix) -> BigRational {
    let n = a.rows();
    if n == 0 {
        return int(1);
    }
    let mut det = int(0);
    for j in 0..n {
        let minor = RationalMatrix::from_fn(n - 1, n - 1, |r, c| a.get(r + 1, if c < j { c } else { c + 1 }).clone());
        let term = a.get(0, j) * cofactor_det(&minor);
        det = if j % 2 == 0 { det + term } else { det - term };
    }
    det
}

#[test]
fn tridiagonal_pivots() {
    // [[2,−1,0],[−1,2,−1],[0,−1,2]]: pivots 2, 3/2, 4/3, det 4 (hand elimination).
    let a = from_ints(&[vec![2, -1, 0], vec![-1, 2, -1], vec![0, -1, 2]]);
    let r = check_positive_definite(&a).unwrap();
    assert_eq!(r.pivots, vec![int(2), frac(3, 2), frac(4, 3)]);
    assert_eq!(r.determinant(), int(4));
    // Same matrix divided by 7: pivots scale by 1/7 (denominator clearing).
    let r7 = check_positive_definite(&a.scale(&frac(1, 7))).unwrap();
    assert_eq!(r7.pivots, vec![frac(2, 7), frac(3, 14), frac(4, 21)]);
}

#[test]
fn rejects_indefinite_and_singular() {
    // [[1,2],[2,1]]: second pivot 1 − 4 = −3.
    let a = from_ints(&[vec![1, 2], vec![2, 1]]);
    assert_eq!(check_positive_definite(&a), Err(PsdError::PivotNotPositive { index: 1, value: int(-3) }));
    // [[1,1],[1,1]] is PSD, singular: pivot 1 is 0.
    let s = from_ints(&[vec![1, 1], vec![1, 1]]);
    let e = check_positive_definite(&s).unwrap_err();
    assert_eq!(e, PsdError::PivotNotPositive { index: 1, value: int(0) });
    assert!(e.to_string().contains("pivot 1 not positive"));
    // Non-symmetric and non-square are refused.
    assert!(matches!(
        check_positive_definite(&from_ints(&[vec![1, 2], vec![0, 1]])),
        Err(PsdError::NotSymmetric { i: 0, j: 1 })
    ));
    assert!(matches!(check_positive_definite(&from_ints(&[vec![1, 2]])), Err(PsdError::NotSquare { .. })));
    // First pivot negative.
    assert!(matches!(
        check_positive_definite(&from_ints(&[vec![-1]])),
        Err(PsdError::PivotNotPositive { index: 0, .. })
    ));
    assert!(check_positive_definite(&RationalMatrix::zeros(0, 0)).is_ok());
}

#[test]
fn psd_witness() {
    let s = from_ints(&[vec![1, 1, 0], vec![1, 1, 0], vec![0, 0, 2]]);
    let (l, d) = ldlt_witness(&s).unwrap();
    assert_eq!(d, vec![int(1), int(0), int(2)]);
    check_psd_with_witness(&s, &l, &d).unwrap();
    // Wrong D value → mismatch naming the entry.
    let mut d_bad = d.clone();
    d_bad[2] = int(3);
    assert!(matches!(check_psd_with_witness(&s, &l, &d_bad), Err(PsdError::WitnessMismatch { i: 2, j: 2, .. })));
    // Negative D → rejected even if the product matched.
    let neg = vec![int(1), int(-1), int(2)];
    assert!(matches!(check_psd_with_witness(&s, &l, &neg), Err(PsdError::WitnessNegativeD { index: 1, .. })));
    // L not unit lower.
    let mut l_bad = l.clone();
    l_bad.set(0, 1, int(1));
    assert!(matches!(check_psd_with_witness(&s, &l_bad, &d), Err(PsdError::WitnessNotUnitLower { i: 0, j: 1, .. })));
    // Indefinite [[0,1],[1,0]] has no witness.
    assert!(matches!(
        ldlt_witness(&from_ints(&[vec![0, 1], vec![1, 0]])),
        Err(PsdError::ZeroPivotNonzeroColumn { index: 0, row: 1, .. })
    ));
}

fn bbt(b: &RationalMatrix) -> RationalMatrix {
    b.mul(&b.transpose()).unwrap()
}

fn int_matrix(n: usize, vals: &[i64]) -> RationalMatrix {
    RationalMatrix::from_fn(n, n, |i, j| int(vals[i * n + j]))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn spd_accepted_and_pivots_match_det(n in 1usize..=6, vals in prop::collection::vec(-9i64..=9, 36), den in 1i64..=12) {
        let b = int_matrix(n, &vals);
        let a = bbt(&b).add(&RationalMatrix::identity(n)).unwrap().scale(&frac(1, den));
        let r = check_positive_definite(&a).unwrap();
        // Independent determinants: cofactor expansion and pivoting Bareiss.
        prop_assert_eq!(r.determinant(), cofactor_det(&a));
        prop_assert_eq!(determinant(&a).unwrap(), cofactor_det(&a));
        // Plain rational LDLᵀ gives the same pivots, and its witness checks.
        let (l, d) = ldlt_witness(&a).unwrap();
        prop_assert_eq!(&d, &r.pivots);
        prop_assert!(check_psd_with_witness(&a, &l, &d).is_ok());
    }

    #[test]
    fn negative_eigenvalue_rejected(n in 1usize..=6, vals in prop::collection::vec(-9i64..=9, 36), extra in 1i64..=50) {
        let b = int_matrix(n, &vals);
        let g = bbt(&b);
        // c > trace(BBᵀ) ≥ λ_max(BBᵀ) makes every eigenvalue of BBᵀ − cI negative.
        let tr: BigRational = (0..n).map(|i| g.get(i, i).clone()).sum();
        let c = tr + int(extra);
        let a = g.sub(&RationalMatrix::identity(n).scale(&c)).unwrap();
        let e = check_positive_definite(&a);
        prop_assert!(matches!(e, Err(PsdError::PivotNotPositive { index: 0, .. })), "{:?}", e);
        prop_assert!(ldlt_witness(&a).is_err());
    }

    #[test]
    fn decision_matches_plain_elimination(n in 1usize..=6, vals in prop::collection::vec(-6i64..=6, 36), shift in -8i64..=8) {
        // Random symmetric matrix S + Sᵀ + shift·I, sometimes PD, often not.
        let s = int_matrix(n, &vals);
        let a = s.add(&s.transpose()).unwrap().add(&RationalMatrix::identity(n).scale(&int(shift))).unwrap();
        let det = cofactor_det(&a);
        match check_positive_definite(&a) {
            Ok(r) => {
                prop_assert_eq!(r.determinant(), det);
                prop_assert!(r.pivots.iter().all(|p| p > &BigRational::zero()));
            }
            Err(PsdError::PivotNotPositive { index, value }) => {
                // Leading principal minors up to `index` are positive, the next is not:
                // value = Δ_{index+1}/Δ_index computed from cofactor expansions.
                let minor = |k: usize| cofactor_det(&RationalMatrix::from_fn(k, k, |i, j| a.get(i, j).clone()));
                prop_assert_eq!(value, minor(index + 1) / minor(index));
                for k in 1..=index {
                    prop_assert!(minor(k) > BigRational::zero());
                }
            }
            Err(e) => prop_assert!(false, "unexpected {:?}", e),
        }
    }
}

#[test]
fn hermite_assembly_timings() {
    // Clamped beam on [0, 7/2] (a rational semi-span); stiffness and mass are SPD.
    for n_el in [30usize, 60] {
        let mesh = ClampedMesh::new(frac(7, 2), n_el);
        let k = mesh.hermite_stiffness();
        let m = mesh.mass(Space::Hermite, Space::Hermite);
        let t = Instant::now();
        let rk = check_positive_definite(&k).unwrap();
        let tk = t.elapsed();
        let t = Instant::now();
        check_positive_definite(&m).unwrap();
        let tm = t.elapsed();
        // A combined "Lyapunov-like" matrix K + M/3 with full rational entries.
        let p = k.add(&m.scale(&frac(1, 3))).unwrap();
        let t = Instant::now();
        check_positive_definite(&p).unwrap();
        let tp = t.elapsed();
        let t = Instant::now();
        let (l, d) = ldlt_witness(&k).unwrap();
        check_psd_with_witness(&k, &l, &d).unwrap();
        let tw = t.elapsed();
        assert_eq!(d, rk.pivots);
        eprintln!("n = {}: PD(K) {:?}, PD(M) {:?}, PD(K+M/3) {:?}, witness build+check {:?}", 2 * n_el, tk, tm, tp, tw);
    }
}

#[test]
fn dense_timings() {
    // Dense B Bᵀ + I with B entries in −9..9 (deterministic LCG) and rational scaling.
    for n in [60usize, 120] {
        let mut state = 12345u64;
        let vals: Vec<i64> = (0..n * n)
            .map(|_| {
                state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                ((state >> 33) % 19) as i64 - 9
            })
            .collect();
        let a = bbt(&int_matrix(n, &vals)).add(&RationalMatrix::identity(n)).unwrap().scale(&frac(3, 11));
        let t = Instant::now();
        let r = check_positive_definite(&a).unwrap();
        eprintln!("dense n = {n}: PD check {:?}", t.elapsed());
        assert_eq!(r.pivots.len(), n);
    }
}
