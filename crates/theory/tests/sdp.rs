//! The SDP cross-check max λ s.t. A − λB ⪰ 0 on hard inputs: cond(B) = 1e8, repeated
//! eigenvalues, rounding-level asymmetry. Reference: for diagonal A, B (rotated by an
//! orthogonal Q, which leaves the pencil's eigenvalues unchanged) λ = min a_i/b_i.

use faer::Mat;
use wingcheck_theory::sdp::max_lambda;

/// A Householder reflection Q = I − 2vvᵀ/vᵀv (orthogonal, dense).
fn householder(n: usize) -> Mat<f64> {
    let v: Vec<f64> = (0..n).map(|i| 1.0 + (i as f64 * 0.7).sin()).collect();
    let vv: f64 = v.iter().map(|x| x * x).sum();
    Mat::from_fn(n, n, |i, j| if i == j { 1.0 } else { 0.0 } - 2.0 * v[i] * v[j] / vv)
}

fn rotated(q: &Mat<f64>, d: &[f64]) -> Mat<f64> {
    let n = d.len();
    Mat::from_fn(n, n, |i, j| (0..n).map(|k| q[(i, k)] * d[k] * q[(j, k)]).sum())
}

#[test]
fn ill_conditioned_b() {
    let n = 8;
    let q = householder(n);
    // b_i from 1 to 1e-8 (cond(B) = 1e8); a_i = 1 + i/10 ⇒ min a_i/b_i = a_0/b_0 = 1
    let b: Vec<f64> = (0..n).map(|i| 10f64.powf(-8.0 * i as f64 / (n - 1) as f64)).collect();
    let a: Vec<f64> = (0..n).map(|i| 1.0 + i as f64 / 10.0).collect();
    let r = max_lambda(&rotated(&q, &a), &rotated(&q, &b)).unwrap();
    assert!(r.accepted, "{r:?}");
    assert!((r.lambda_sdp - 1.0).abs() < 1e-6, "{r:?}");
    assert!((r.lambda_eig - 1.0).abs() < 1e-6, "{r:?}");
}

#[test]
fn repeated_eigenvalues() {
    let n = 10;
    let q = householder(n);
    // a_i/b_i = 2 for five indices, larger for the rest ⇒ λ = 2 with multiplicity 5
    let a: Vec<f64> = (0..n).map(|i| if i < 5 { 2.0 } else { 3.0 + i as f64 }).collect();
    let r = max_lambda(&rotated(&q, &a), &Mat::identity(n, n)).unwrap();
    assert!(r.accepted && (r.lambda_sdp - 2.0).abs() < 1e-6, "{r:?}");
}

#[test]
fn rounding_level_asymmetry() {
    let n = 12;
    // B = I + 5e-16 asymmetric noise, A = diag(1..n) ⇒ λ = 1 (to 1e-15)
    let b = Mat::from_fn(n, n, |i, j| {
        if i == j {
            1.0
        } else if i < j {
            5e-16
        } else {
            0.0
        }
    });
    let a = Mat::from_fn(n, n, |i, j| if i == j { 1.0 + i as f64 } else { 0.0 });
    let r = max_lambda(&a, &b).unwrap();
    assert!(r.accepted && (r.lambda_sdp - 1.0).abs() < 1e-6, "{r:?}");
    // indefinite A: λ < 0 is an answer too
    let a2 = Mat::from_fn(n, n, |i, j| if i == j { i as f64 - 3.0 } else { 0.0 });
    let r2 = max_lambda(&a2, &b).unwrap();
    assert!(r2.accepted && (r2.lambda_sdp + 3.0).abs() < 1e-6, "{r2:?}");
}
