//! The wing's modal basis (`wingcheck_sim::modal::ModalBasis`, one SVD in the strain factor) on
//! refined grids — 576 unknowns (FE 192 graded elements) and 1 536 (FE 512 graded and uniform
//! elements, FD 768 intervals) — against values computed without it:
//!
//! - identities every complete M-orthonormal basis of the pencil obeys, evaluated from the
//!   matrices directly: Σ_i φ_i(a)φ_i(b)/ω_i² = (K⁻¹)_ab (the static compliance: s³/(3EI) and
//!   s/GJ at the tip for these elements, whose tip deflection under a tip load is exact, and 0
//!   between q(s) and θ(s) as K does not couple them), Σ_i φ_i(a)² = (M⁻¹)_aa (the stiff modes'
//!   share), Σ η_i(0)² = x₀ᵀMx₀ and Σ ω_i²η_i(0)² = x₀ᵀKx₀ (Parseval), tr(M⁻¹K) = Σ ω_i² and
//!   tr(K⁻¹M) = Σ ω_i⁻²;
//! - the lowest 40 frequencies against sparse shift-invert subspace iteration (`modes`'s
//!   solver: another algorithm, with its own error bound);
//! - the lowest five of the uniform wing, Romberg-extrapolated over 128, 256 and 512 elements
//!   (the last 1 536 unknowns), against the roots of the continuous problem's characteristic
//!   determinant.
//!
//! Every frequency i of the basis carries the printed relative bound `quality.frequency_error`
//! on |λ_i/ω_i² − 1|; a sum of positive terms each within it is within it too.

mod common;

use common::characteristic::roots;
use common::paper_with;
use faer::linalg::solvers::DenseSolveCore;
use faer::{Mat, Side};
use wingcheck_model::Config;
use wingcheck_sim::modal::{ModalBasis, MASS_TOLERANCE};
use wingcheck_sim::Discretisation;

/// The refined grids of the issue: (name, overrides).
const GRIDS: [(&str, &[&str]); 4] = [
    ("FE 192 graded (576 unknowns)", &["discretisation.elements=192"]),
    ("FE 512 graded (1 536 unknowns)", &["discretisation.elements=512"]),
    ("FE 512 uniform (1 536 unknowns)", &["discretisation.elements=512", "discretisation.grading=0"]),
    (
        "FD 768 intervals (1 536 unknowns)",
        &["discretisation.method=fd", "discretisation.fd_points=768", "discretisation.grading=0"],
    ),
];

fn dense(disc: &Discretisation, m: &wingcheck_sim::sparse::SymMatrix) -> Mat<f64> {
    let n = disc.dim();
    let v = m.to_dense();
    Mat::from_fn(n, n, |i, j| v[i * n + j])
}

/// |a/b − 1|.
fn rel(a: f64, b: f64) -> f64 {
    (a / b - 1.0).abs()
}

#[test]
fn the_basis_is_m_orthonormal_complete_and_its_sums_match_the_matrices() {
    for (name, sets) in GRIDS {
        let cfg = paper_with(sets);
        let disc = Discretisation::new(&cfg);
        let n = disc.dim();
        let t = std::time::Instant::now();
        let basis = ModalBasis::of(&disc).unwrap();
        let q = basis.quality;
        println!("{name}: built in {:.2} s, {q:?}", t.elapsed().as_secs_f64());
        // the tolerance on M-orthonormality; the frequency bound the basis prints
        assert!(q.mass_defect <= MASS_TOLERANCE, "{name}: {q:?}");
        let bound = q.frequency_error;
        assert!(bound <= 1e-6, "{name}: {q:?}");
        let w2 = &basis.omega2;
        // Each identity's terms are within `bound` (relative) of the exact ones, up to the
        // M-defect's share; round-off of the sums themselves is ≤ 1e-12 relative here.
        let tol = bound + 1e-12;
        // static compliance at the tip: s³/(3EI), s/GJ (exact for Hermite bending and linear
        // torsion elements under a tip load; FD's ghost-point stencil is checked against the
        // strain solve K⁻¹e, an independent substitution)
        let w = &cfg.wing;
        let [uq, ut] = &basis.tip;
        let sum = |f: &dyn Fn(usize) -> f64| (0..n).map(f).sum::<f64>();
        let cq = sum(&|i| uq[i] * uq[i] / w2[i]);
        let ct = sum(&|i| ut[i] * ut[i] / w2[i]);
        let cqt = sum(&|i| uq[i] * ut[i] / w2[i]);
        let solve_tip = |d: usize| {
            let mut e = vec![0.0; n];
            e[d] = 1.0;
            disc.strain.solve_in_place(&mut e, &mut Vec::new());
            e
        };
        let (kq, kt) = (solve_tip(disc.tip_q), solve_tip(disc.tip_theta));
        if cfg.discretisation.method == wingcheck_model::Method::Fe {
            assert!(rel(kq[disc.tip_q], w.span.powi(3) / (3.0 * w.ei)) < 1e-12, "{name}: the strain solve");
            assert!(rel(kt[disc.tip_theta], w.span / w.gj) < 1e-12, "{name}: the strain solve");
        }
        println!("  compliance: q {:.1e}, θ {:.1e} relative", rel(cq, kq[disc.tip_q]), rel(ct, kt[disc.tip_theta]));
        assert!(rel(cq, kq[disc.tip_q]) <= tol && rel(ct, kt[disc.tip_theta]) <= tol, "{name}");
        // K does not couple q and θ: the cross compliance is 0 (relative to √(cq ct))
        assert!(cqt.abs() <= tol * (cq * ct).sqrt(), "{name}: cross compliance {cqt:e}");
        // the stiff modes' share: Σ φ_i(s)² = (M⁻¹)_ss (dense inverse of M by faer's Cholesky)
        let m = dense(&disc, &disc.mass);
        let m_inv = m.llt(Side::Lower).unwrap().inverse();
        let (sq, st) = (sum(&|i| uq[i] * uq[i]), sum(&|i| ut[i] * ut[i]));
        let (mq, mt) = (m_inv[(disc.tip_q, disc.tip_q)], m_inv[(disc.tip_theta, disc.tip_theta)]);
        println!("  inverse mass: q {:.1e}, θ {:.1e} relative", rel(sq, mq), rel(st, mt));
        assert!(rel(sq, mq) <= tol && rel(st, mt) <= tol, "{name}");
        // Parseval on the initial state
        let e0 = &basis.eta0;
        let (mass0, stiff0) = (disc.mass.form(&disc.x0, &disc.x0), disc.strain.energy_form(&disc.x0));
        let (p0, p1) = (sum(&|i| e0[i] * e0[i]), sum(&|i| w2[i] * e0[i] * e0[i]));
        println!("  Parseval: {:.1e} (M), {:.1e} (K) relative", rel(p0, mass0), rel(p1, stiff0));
        assert!(rel(p0, mass0) <= tol && rel(p1, stiff0) <= tol, "{name}");
        // traces: tr(M⁻¹K) = Σ_c ‖R L⁻ᵀe_c‖² (every term a sum of squares), tr(K⁻¹M) by strain
        // solves of M's columns
        let l = m.llt(Side::Lower).unwrap().L().to_owned();
        let mut li = Mat::<f64>::identity(n, n);
        faer::linalg::triangular_solve::solve_upper_triangular_in_place(l.transpose(), li.as_mut(), faer::Par::Seq);
        let tr_mk: f64 = (0..n).map(|c| disc.strain.energy_form(li.col_as_slice(c))).sum();
        let tr_km: f64 = (0..n)
            .map(|c| {
                let mut col: Vec<f64> = (0..n).map(|r| m[(r, c)]).collect();
                disc.strain.solve_in_place(&mut col, &mut Vec::new());
                col[c]
            })
            .sum();
        let (s2, s_2) = (sum(&|i| w2[i]), sum(&|i| 1.0 / w2[i]));
        println!("  traces: Σω² {:.1e}, Σω⁻² {:.1e} relative", rel(s2, tr_mk), rel(s_2, tr_km));
        assert!(rel(s2, tr_mk) <= tol && rel(s_2, tr_km) <= tol, "{name}");
    }
}

#[test]
fn the_lowest_forty_frequencies_agree_with_subspace_iteration() {
    for (name, sets) in GRIDS {
        let disc = Discretisation::new(&paper_with(sets));
        let basis = ModalBasis::of(&disc).unwrap();
        // reference: shift-invert subspace iteration through the strain factor, with its own
        // residual bound (wingcheck_sim::modes::lowest_eigenvalues)
        let reference = wingcheck_sim::modes::lowest_eigenvalues(&disc, 40).unwrap();
        let mut worst = 0.0f64;
        for (i, r) in reference.iter().enumerate() {
            let d = (basis.omega2[i] - r.lambda).abs();
            let allowed = basis.quality.frequency_error * r.lambda + r.solver_error;
            worst = worst.max(d / allowed);
            assert!(d <= allowed, "{name}, mode {}: {} vs {} ± {}", i + 1, basis.omega2[i], r.lambda, allowed);
        }
        println!("{name}: largest difference {worst:.2e} of what the two bounds allow");
    }
}

/// The lowest `count` frequencies (rad/s) of the modal basis of `cfg` at `elements`.
fn frequencies(cfg: &Config, elements: usize, count: usize) -> (Vec<f64>, f64) {
    let mut c = cfg.clone();
    c.discretisation.elements = elements;
    let basis = ModalBasis::new(&c).unwrap();
    (basis.omega2[..count].iter().map(|w| w.sqrt()).collect(), basis.quality.frequency_error)
}

#[test]
fn the_uniform_wing_converges_to_its_characteristic_roots() {
    // The uniform wing (grading 0): the continuous frequencies are the roots of the
    // characteristic determinant (tests/common/characteristic.rs, computed here without any
    // discretisation). The FE frequencies converge to them like h² (linear torsion elements)
    // then h⁴ (Hermite bending): Romberg over 128, 256, 512 elements, as `modes` does.
    let cfg = paper_with(&["discretisation.grading=0"]);
    let exact = roots(&cfg, 5);
    let meshes = [128, 256, 512];
    let runs: Vec<(Vec<f64>, f64)> = meshes.iter().map(|&e| frequencies(&cfg, e, 5)).collect();
    for (k, root) in exact.iter().enumerate() {
        let values: Vec<f64> = runs.iter().map(|r| r.0[k]).collect();
        let table = wingcheck_sim::estimate::romberg_table(&values, &[2.0, 4.0]);
        let best = table[2][2];
        // the Romberg estimate's error: its last correction, plus each value's bound from the
        // basis (ω within half the bound on ω², through Romberg weights summing to < 2)
        let estimate = (best - table[2][1]).abs() + runs.iter().map(|r| r.1).fold(0.0, f64::max) * best;
        let raw = (values[2] - root).abs() / root;
        let err = (best - root).abs() / root;
        println!(
            "mode {}: root {root:.12}, at 512 elements {:.1e}, extrapolated {err:.1e} (estimate {:.1e})",
            k + 1,
            raw,
            estimate / root
        );
        assert!((best - root).abs() <= estimate.max(1e-12 * root), "mode {}: {best} vs root {root}", k + 1);
        assert!(err < 1e-3 * raw, "mode {}: the extrapolation gained little ({err:e} vs {raw:e})", k + 1);
    }
}
