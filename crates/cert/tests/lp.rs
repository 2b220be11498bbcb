//! Tests for exact Farkas and feasible-point checks on hand-made systems.

use num_rational::BigRational;
use wingcheck_cert::exact::{frac, int};
use wingcheck_cert::lp::*;
use wingcheck_cert::RationalMatrix;

fn mat(rows: &[&[i64]], cols: usize) -> RationalMatrix {
    if rows.is_empty() {
        return RationalMatrix::zeros(0, cols);
    }
    RationalMatrix::from_rows(rows.iter().map(|r| r.iter().map(|&v| int(v)).collect()).collect()).unwrap()
}

fn v(xs: &[i64]) -> Vec<BigRational> {
    xs.iter().map(|&x| int(x)).collect()
}

/// x ≤ 1 and −x ≤ −2 (i.e. x ≥ 2): obviously infeasible.
fn interval_system() -> LinearSystem {
    LinearSystem { a: mat(&[&[1], &[-1]], 1), b: v(&[1, -2]), a_eq: mat(&[], 1), b_eq: vec![] }
}

#[test]
fn farkas_interval() {
    let sys = interval_system();
    // y = (1, 1): 1·x − 1·x = 0 and 1·1 + 1·(−2) = −1 < 0.
    let value = check_farkas(&sys, &FarkasCertificate { y: v(&[1, 1]), w: vec![] }).unwrap();
    assert_eq!(value, int(-1));
    // Wrong multipliers: combination x·(1 − 2) ≠ 0 at column 0.
    let e = check_farkas(&sys, &FarkasCertificate { y: v(&[1, 2]), w: vec![] }).unwrap_err();
    assert_eq!(e, LpError::CombinationNonzero { column: 0, value: int(-1) });
    assert!(e.to_string().contains("nonzero at column 0"));
    // Negative multiplier refused.
    let e = check_farkas(&sys, &FarkasCertificate { y: v(&[-1, -1]), w: vec![] }).unwrap_err();
    assert!(matches!(e, LpError::NegativeMultiplier { index: 0, .. }));
    // Zero multipliers prove nothing.
    let e = check_farkas(&sys, &FarkasCertificate { y: v(&[0, 0]), w: vec![] }).unwrap_err();
    assert_eq!(e, LpError::RhsNotNegative { value: int(0) });
    // Wrong length.
    assert!(matches!(
        check_farkas(&sys, &FarkasCertificate { y: v(&[1]), w: vec![] }),
        Err(LpError::Dimension { what: "y", expected: 2, found: 1 })
    ));
}

#[test]
fn farkas_with_equalities() {
    // x + y = 1, x − y = 1 (so x = 1, y = 0) together with y ≥ 1/2 (−y ≤ −1/2): infeasible.
    let sys = LinearSystem {
        a: mat(&[&[0, -1]], 2),
        b: vec![frac(-1, 2)],
        a_eq: mat(&[&[1, 1], &[1, -1]], 2),
        b_eq: v(&[1, 1]),
    };
    // y = 2, w = (1, −1): 2·(0,−1) + (1,1) − (1,−1) = (0, 0); rhs 2·(−1/2) + 1 − 1 = −1.
    let cert = FarkasCertificate { y: v(&[2]), w: v(&[1, -1]) };
    assert_eq!(check_farkas(&sys, &cert).unwrap(), int(-1));
    // The point (1, 0) satisfies the equalities but not the inequality.
    assert!(matches!(check_feasible_point(&sys, &v(&[1, 0])), Err(LpError::InequalityViolated { row: 0, .. })));
}

#[test]
fn feasible_points() {
    // Triangle x ≥ 0, y ≥ 0, x + y ≤ 1 with x = y (equality): (1/3, 1/3) is inside.
    let sys = LinearSystem {
        a: mat(&[&[-1, 0], &[0, -1], &[1, 1]], 2),
        b: v(&[0, 0, 1]),
        a_eq: mat(&[&[1, -1]], 2),
        b_eq: v(&[0]),
    };
    check_feasible_point(&sys, &[frac(1, 3), frac(1, 3)]).unwrap();
    // Boundary point (1/2, 1/2) is feasible (≤ is not strict).
    check_feasible_point(&sys, &[frac(1, 2), frac(1, 2)]).unwrap();
    // (1/3, 1/2) breaks the equality; (2/3, 2/3) breaks x + y ≤ 1.
    assert!(matches!(
        check_feasible_point(&sys, &[frac(1, 3), frac(1, 2)]),
        Err(LpError::EqualityViolated { row: 0, .. })
    ));
    let e = check_feasible_point(&sys, &[frac(2, 3), frac(2, 3)]).unwrap_err();
    assert_eq!(e, LpError::InequalityViolated { row: 2, lhs: Box::new(frac(4, 3)), rhs: Box::new(int(1)) });
    assert!(matches!(check_feasible_point(&sys, &v(&[1])), Err(LpError::Dimension { what: "x", .. })));
}
