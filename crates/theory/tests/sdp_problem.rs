//! clarabel end to end through the faer-backed BLAS/LAPACK symbols, on SDPs
//! with independently known answers.

use faer::linalg::triangular_solve::solve_lower_triangular_in_place;
use faer::{Mat, Par, Side};
use wingcheck_theory::sdp::problem::{
    max_generalized_lambda, smat, svec, PsdConstraint, SdpError, SdpProblem, SdpStatus,
};

/// Deterministic xorshift64* stream in [-1, 1).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

fn random_sym(n: usize, rng: &mut Rng) -> Vec<Vec<f64>> {
    let g: Vec<Vec<f64>> = (0..n).map(|_| (0..n).map(|_| rng.next()).collect()).collect();
    (0..n).map(|i| (0..n).map(|j| 0.5 * (g[i][j] + g[j][i])).collect()).collect()
}

/// `G Gᵀ / n + I`: SPD with eigenvalues in [1, ~5].
fn random_spd(n: usize, rng: &mut Rng) -> Vec<Vec<f64>> {
    let g: Vec<Vec<f64>> = (0..n).map(|_| (0..n).map(|_| rng.next()).collect()).collect();
    (0..n)
        .map(|i| {
            (0..n)
                .map(|j| (0..n).map(|k| g[i][k] * g[j][k]).sum::<f64>() / n as f64 + f64::from(u8::from(i == j)))
                .collect()
        })
        .collect()
}

fn to_mat(a: &[Vec<f64>]) -> Mat<f64> {
    Mat::from_fn(a.len(), a.len(), |i, j| a[i][j])
}

/// Reference: smallest eigenvalue of L⁻¹ A L⁻ᵀ with B = L Lᵀ (faer Cholesky +
/// faer symmetric eigensolver, independent of clarabel and of our symbols).
fn smallest_generalized_eigenvalue(a: &[Vec<f64>], b: &[Vec<f64>]) -> f64 {
    let l = to_mat(b).llt(Side::Lower).expect("B SPD").L().to_owned();
    let mut x = to_mat(a);
    solve_lower_triangular_in_place(l.as_ref(), x.as_mut(), Par::Seq); // L⁻¹ A
    let mut y = x.transpose().to_owned();
    solve_lower_triangular_in_place(l.as_ref(), y.as_mut(), Par::Seq); // L⁻¹ (L⁻¹ A)ᵀ = L⁻¹ A L⁻ᵀ
    let c = Mat::from_fn(y.nrows(), y.ncols(), |i, j| 0.5 * (y[(i, j)] + y[(j, i)]));
    c.self_adjoint_eigenvalues(Side::Lower).expect("evd")[0]
}

fn trace_prod(a: &[Vec<f64>], z: &[Vec<f64>]) -> f64 {
    (0..a.len()).map(|i| (0..a.len()).map(|j| a[i][j] * z[j][i]).sum::<f64>()).sum()
}

#[test]
fn generalized_lambda_matches_eigenvalue_at_5_20_60() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    for n in [5, 20, 60] {
        let (a, b) = (random_sym(n, &mut rng), random_spd(n, &mut rng));
        let want = smallest_generalized_eigenvalue(&a, &b);
        let out = max_generalized_lambda(&a, &b).expect("solve");
        assert_eq!(out.status, SdpStatus::Solved, "n = {n}");
        let got = out.lambda.unwrap();
        eprintln!("n={n}: λ={got:.10} ref={want:.10} iters={} time={:.4}s", out.iterations, out.solve_time);
        assert!((got - want).abs() <= 1e-6 * (1.0 + want.abs()), "n={n}: {got} vs {want}");
        // dual certificate: Z ⪰ 0, tr(BZ) = 1, tr(AZ) = λ (strong duality)
        assert!((trace_prod(&b, &out.dual) - 1.0).abs() < 1e-6);
        assert!((trace_prod(&a, &out.dual) - got).abs() < 1e-6 * (1.0 + got.abs()));
        let zmin = to_mat(&out.dual).self_adjoint_eigenvalues(Side::Lower).unwrap()[0];
        assert!(zmin > -1e-7, "Z not PSD: {zmin}");
    }
}

/// Closed form: A = [[2,1],[1,2]], B = I ⇒ λ = λ_min(A) = 1; and
/// A = [[1,0],[0,4]], B = [[1,0],[0,2]] ⇒ λ = min(1/1, 4/2) = 1... use B = diag(2,1): min(1/2, 4) = 0.5.
#[test]
fn closed_form_2x2() {
    let out = max_generalized_lambda(&[vec![2.0, 1.0], vec![1.0, 2.0]], &[vec![1.0, 0.0], vec![0.0, 1.0]]).unwrap();
    assert_eq!(out.status, SdpStatus::Solved);
    assert!((out.lambda.unwrap() - 1.0).abs() < 1e-7);
    // dual: Z = v vᵀ with v = (1,-1)/√2, the λ_min eigenvector
    assert!((out.dual[0][0] - 0.5).abs() < 1e-5 && (out.dual[0][1] + 0.5).abs() < 1e-5);
    let out = max_generalized_lambda(&[vec![1.0, 0.0], vec![0.0, 4.0]], &[vec![2.0, 0.0], vec![0.0, 1.0]]).unwrap();
    assert!((out.lambda.unwrap() - 0.5).abs() < 1e-7);
}

/// A − λB = diag(λ−1, −1−λ) ⪰ 0 needs λ ≥ 1 and λ ≤ −1: infeasible (an answer, not an error).
#[test]
fn infeasible_is_a_status() {
    let a = [vec![-1.0, 0.0], vec![0.0, -1.0]];
    let b = [vec![-1.0, 0.0], vec![0.0, 1.0]];
    let out = max_generalized_lambda(&a, &b).expect("not an error");
    assert_eq!(out.status, SdpStatus::Infeasible);
    assert_eq!(out.lambda, None);
}

/// B = −I: A + λI ⪰ 0 for all large λ, so max λ is unbounded.
#[test]
fn unbounded_is_a_status() {
    let a = [vec![1.0, 0.0], vec![0.0, 1.0]];
    let b = [vec![-1.0, 0.0], vec![0.0, -1.0]];
    assert_eq!(max_generalized_lambda(&a, &b).unwrap().status, SdpStatus::Unbounded);
}

#[test]
fn bad_input_is_an_error() {
    let sq = [vec![1.0, 0.0], vec![0.0, 1.0]];
    assert!(matches!(
        max_generalized_lambda(&[vec![1.0, 2.0], vec![0.0, 1.0]], &sq),
        Err(SdpError::NotSymmetric { .. })
    ));
    assert!(matches!(max_generalized_lambda(&[vec![1.0, 2.0]], &sq), Err(SdpError::NotSquare { .. })));
    assert!(matches!(max_generalized_lambda(&[vec![f64::NAN]], &[vec![1.0]]), Err(SdpError::NonFinite)));
    assert!(matches!(max_generalized_lambda(&[vec![1.0]], &sq), Err(SdpError::Dimension(_))));
}

/// clarabel's svec: upper triangle column-wise, off-diagonals × √2
/// (clarabel src/algebra/dense/matrix_math.rs `mat_to_svec`).
#[test]
fn svec_convention() {
    let m = [vec![1.0, 2.0, 4.0], vec![2.0, 3.0, 5.0], vec![4.0, 5.0, 6.0]];
    let r = std::f64::consts::SQRT_2;
    let want = [1.0, 2.0 * r, 3.0, 4.0 * r, 5.0 * r, 6.0];
    assert!(svec(&m).iter().zip(want).all(|(x, y)| (x - y).abs() < 1e-14));
    let back = smat(&svec(&m), 3);
    for i in 0..3 {
        for j in 0..3 {
            assert!((back[i][j] - m[i][j]).abs() < 1e-15);
        }
    }
}

/// Generic builder: min x₀ + x₁ s.t. [[x₀, 1],[1, x₁]] ⪰ 0, x₀ ≤ 4, x₀ = x₁.
/// By AM-GM (x₀x₁ ≥ 1 with x₀ = x₁) the optimum is x₀ = x₁ = 1, value 2.
#[test]
fn builder_with_equality_and_inequality() {
    let lmi = PsdConstraint::new(&[vec![0.0, 1.0], vec![1.0, 0.0]])
        .unwrap()
        .term(0, &[vec![1.0, 0.0], vec![0.0, 0.0]])
        .unwrap()
        .term(1, &[vec![0.0, 0.0], vec![0.0, 1.0]])
        .unwrap();
    let p = SdpProblem::new(2)
        .minimize(vec![1.0, 1.0])
        .unwrap()
        .eq(vec![1.0, -1.0], 0.0)
        .unwrap()
        .le(vec![1.0, 0.0], 4.0)
        .unwrap()
        .psd(lmi)
        .unwrap();
    let sol = p.solve().unwrap();
    assert_eq!(sol.status, SdpStatus::Solved);
    assert!((sol.objective - 2.0).abs() < 1e-6 && (sol.x[0] - 1.0).abs() < 1e-5);
    assert_eq!(sol.psd_duals.len(), 1);
    assert!(matches!(
        SdpProblem::new(1).psd(PsdConstraint::zero(2).term(3, &[vec![1.0, 0.0], vec![0.0, 1.0]]).unwrap()),
        Err(SdpError::Dimension(_))
    ));
}

/// Solve times at sizes 20, 60, 120 (run with `--ignored --nocapture`).
#[test]
#[ignore = "timing only"]
fn timing_20_60_120() {
    let mut rng = Rng(42);
    for n in [20, 60, 120] {
        let (a, b) = (random_sym(n, &mut rng), random_spd(n, &mut rng));
        let t = std::time::Instant::now();
        let out = max_generalized_lambda(&a, &b).unwrap();
        let want = smallest_generalized_eigenvalue(&a, &b);
        println!(
            "n={n:4} status={:?} iters={} clarabel_solve_time={:.3}s wall={:.3}s |λ-ref|={:.1e}",
            out.status,
            out.iterations,
            out.solve_time,
            t.elapsed().as_secs_f64(),
            (out.lambda.unwrap_or(f64::NAN) - want).abs()
        );
    }
}
