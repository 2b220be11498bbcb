//! Natural frequencies: both discretisations against the analytic uncoupled frequencies, their
//! convergence order under refinement, and FD/FE agreement in the coupled case.

mod common;

use common::{orders, paper_with};
use wingcheck_model::{Config, Method};
use wingcheck_sim::{modes, Discretisation};

fn frequencies(method: Method, elements: usize, sets: &[&str], count: usize) -> Vec<f64> {
    // uniform meshes: the refinement orders below are for uniform grids
    let mut cfg = paper_with(sets);
    cfg.discretisation.grading = 0.0;
    modes::natural_frequencies(&Discretisation::with(&cfg, method, elements), count).unwrap()
}

#[test]
fn cantilever_roots_match_tabulated_values() {
    // Reference: β_n s for a clamped–free Euler–Bernoulli beam, 1.875104, 4.694091, 7.854757,
    // 10.995541 (e.g. Blevins, Formulas for Natural Frequency and Mode Shape, Table 8-1).
    let expected = [1.875_104_069, 4.694_091_133, 7.854_757_438, 10.995_540_735];
    for (n, e) in expected.iter().enumerate() {
        assert!((modes::cantilever_root(n + 1) - e).abs() < 1e-8, "root {}", n + 1);
    }
}

/// Uncoupled (ρx_c = 0): every computed frequency must match an analytic one of the right
/// family. Bending from Hermite cubics converges at O(h⁴) (eigenvalue error O(h^{2(p+1−m)}),
/// p = 3, m = 2), torsion from linear elements at O(h²); the FD scheme at O(h²).
#[test]
fn uncoupled_frequencies_converge_to_analytic_at_the_expected_order() {
    let w = paper_with(&[]).wing;
    let bend = modes::bending_frequencies(w.span, w.ei, w.rho, 3);
    let tors = modes::torsion_frequencies(w.span, w.gj, w.ip, 3);
    let analytic = modes::uncoupled_frequencies(w.span, w.ei, w.rho, w.gj, w.ip, 5);
    for method in [Method::Fe, Method::Fd] {
        let grids = [8usize, 16, 32, 64];
        // errors of the third bending and the second torsion frequency
        let mut bend_err: Vec<f64> = Vec::new();
        let mut tors_err: Vec<f64> = Vec::new();
        for &n in &grids {
            let f = frequencies(method, n, &["wing.rho_xc=0"], 8);
            let nearest = |target: f64| f.iter().map(|x| (x - target).abs()).fold(f64::INFINITY, f64::min);
            bend_err.push(nearest(bend[2]) / bend[2]);
            tors_err.push(nearest(tors[1]) / tors[1]);
            if n == 64 {
                for (k, a) in analytic.iter().enumerate() {
                    // O(h²) torsion error at N = 64: (ωh)²/24-sized, below 3e-3 for these modes
                    assert!((f[k] - a).abs() / a < 3e-3, "{method:?} mode {k}: {} vs analytic {a}", f[k]);
                }
            }
        }
        let pb = orders(&bend_err);
        let pt = orders(&tors_err);
        println!("{method:?}: bending-3 rel. errors {bend_err:?} orders {pb:.2?}; torsion-2 errors {tors_err:?} orders {pt:.2?}");
        let (bend_order, tors_order) = match method {
            Method::Fe => (4.0, 2.0),
            Method::Fd => (2.0, 2.0),
        };
        assert!((pb[1] - bend_order).abs() < 0.3, "{method:?} bending order {pb:?}");
        assert!((pt[2] - tors_order).abs() < 0.2, "{method:?} torsion order {pt:?}");
    }
}

/// Coupled case: FD and FE converge to the same frequencies, each at O(h²) or better.
#[test]
fn coupled_frequencies_fd_and_fe_agree_and_converge() {
    let grids = [16usize, 32, 64, 128];
    let mut limit = Vec::new();
    for method in [Method::Fe, Method::Fd] {
        let runs: Vec<Vec<f64>> = grids.iter().map(|&n| frequencies(method, n, &[], 5)).collect();
        for k in 0..5 {
            let p = common::order_from_three(runs[1][k], runs[2][k], runs[3][k]);
            println!(
                "{method:?} coupled mode {k}: {:.8} {:.8} {:.8} {:.8} order {p:.2}",
                runs[0][k], runs[1][k], runs[2][k], runs[3][k]
            );
            assert!(p > 1.8, "{method:?} mode {k} converges at order {p}");
        }
        limit.push((0..5).map(|k| common::richardson(runs[2][k], runs[3][k], 2.0)).collect::<Vec<f64>>());
    }
    for k in 0..5 {
        let rel = (limit[0][k] - limit[1][k]).abs() / limit[0][k];
        println!("mode {k}: FE limit {:.8} FD limit {:.8} rel diff {rel:.2e}", limit[0][k], limit[1][k]);
        assert!(rel < 1e-4, "mode {k}: FD and FE extrapolations differ by {rel}");
    }
}

/// Wings of very different scales (EI, GJ, ρ, I_p, s), all uncoupled (ρx_c = 0), incl. an SI-scale one.
const WINGS: [[&str; 5]; 7] = [
    ["wing.span=2", "wing.ei=0.2", "wing.gj=0.5", "wing.rho=10", "wing.ip=1.5"],
    ["wing.span=6", "wing.ei=1e7", "wing.gj=1e6", "wing.rho=100", "wing.ip=10"],
    ["wing.span=15", "wing.ei=4e7", "wing.gj=2e6", "wing.rho=250", "wing.ip=30"],
    ["wing.span=0.5", "wing.ei=3", "wing.gj=0.02", "wing.rho=0.7", "wing.ip=0.05"],
    ["wing.span=1", "wing.ei=1", "wing.gj=1", "wing.rho=1", "wing.ip=1"],
    ["wing.span=3", "wing.ei=50", "wing.gj=400", "wing.rho=2", "wing.ip=0.3"],
    ["wing.span=8", "wing.ei=2e5", "wing.gj=9e3", "wing.rho=40", "wing.ip=4"],
];

fn uncoupled_config(wing: &[&str]) -> Config {
    let mut sets = wing.to_vec();
    sets.push("wing.rho_xc=0");
    paper_with(&sets)
}

/// Converged frequencies at the default tolerance against the analytic uncoupled ones
/// (reference: cantilever roots of 1 + cos βs cosh βs = 0 for bending, (2n−1)π/(2s)·√(GJ/I_p)
/// for torsion): ≤ 1e-7 relative, and every estimate bounds its actual error, for FE and FD.
#[test]
fn converged_uncoupled_frequencies_match_analytic_within_their_estimates() {
    for wing in &WINGS {
        let cfg = uncoupled_config(wing);
        let w = &cfg.wing;
        let analytic = modes::uncoupled_frequencies(w.span, w.ei, w.rho, w.gj, w.ip, 5);
        for method in [Method::Fe, Method::Fd] {
            let c = modes::converged_frequencies(&cfg, method, 5, modes::DEFAULT_MODE_TOLERANCE).unwrap();
            assert!(c.converged, "{wing:?} {method:?}: not converged, meshes {:?}", c.meshes);
            for (m, a) in c.modes.iter().zip(&analytic) {
                let err = (m.omega - a).abs();
                println!(
                    "{wing:?} {method:?}: {:.12e} ± {:.1e} vs analytic {a:.12e}: actual {:.1e} (rel {:.1e}), meshes {:?}",
                    m.omega,
                    m.error,
                    err,
                    err / a,
                    c.meshes
                );
                assert!(err / a <= 1e-7, "{wing:?} {method:?}: relative error {} > 1e-7", err / a);
                assert!(err <= m.error, "{wing:?} {method:?}: actual error {err:e} exceeds the estimate {:e}", m.error);
            }
        }
    }
}

/// Coupled case (paper's and SI-scale wings): the default estimate against an independent,
/// much finer reference — raw frequencies on 256…2048-element uniform meshes, Richardson in
/// h² then h⁴ (common::richardson) — and FE against FD: the differences lie within the
/// stated errors.
#[test]
fn coupled_default_estimates_bound_the_difference_to_a_much_finer_extrapolation() {
    for sets in
        [&[][..], &["wing.span=6", "wing.ei=1e7", "wing.gj=1e6", "wing.rho=100", "wing.ip=10", "wing.rho_xc=20"][..]]
    {
        let fe = modes::converged_frequencies(&paper_with(sets), Method::Fe, 5, modes::DEFAULT_MODE_TOLERANCE).unwrap();
        let fd = modes::converged_frequencies(&paper_with(sets), Method::Fd, 5, modes::DEFAULT_MODE_TOLERANCE).unwrap();
        let fine: Vec<Vec<f64>> =
            [256usize, 512, 1024, 2048].iter().map(|&n| frequencies(Method::Fe, n, sets, 5)).collect();
        for k in 0..5 {
            let r1: Vec<f64> = (0..3).map(|i| common::richardson(fine[i][k], fine[i + 1][k], 2.0)).collect();
            let r2: Vec<f64> = (0..2).map(|i| common::richardson(r1[i], r1[i + 1], 4.0)).collect();
            let reference = r2[1];
            // the reference's own uncertainty: its last correction
            let ref_err = (r2[1] - r2[0]).abs();
            let (e, d) = (fe.modes[k], fd.modes[k]);
            println!(
                "{sets:?} mode {k}: FE {:.13} ± {:.1e}, FD {:.13} ± {:.1e}, fine reference {reference:.13} (± {ref_err:.1e})",
                e.omega, e.error, d.omega, d.error
            );
            assert!(e.error <= 1e-7 * e.omega && d.error <= 1e-7 * d.omega);
            assert!((e.omega - reference).abs() <= e.error + ref_err, "FE mode {k} vs reference");
            assert!((d.omega - reference).abs() <= d.error + ref_err, "FD mode {k} vs reference");
            assert!((e.omega - d.omega).abs() <= e.error + d.error, "FE vs FD mode {k}");
        }
    }
}

/// The eigen-solve's round-off does not grow with refinement: on uniform meshes up to 1024
/// elements the raw error against the converged value keeps falling at the observed order 2
/// (a dense L⁻¹KL⁻ᵀ solve or a Cholesky of the assembled K stalls and reverses past ~256).
#[test]
fn no_loss_of_accuracy_with_refinement_up_to_1024_elements() {
    for sets in
        [&[][..], &["wing.span=6", "wing.ei=1e7", "wing.gj=1e6", "wing.rho=100", "wing.ip=10", "wing.rho_xc=20"][..]]
    {
        let conv = modes::converged_frequencies(&paper_with(sets), Method::Fe, 3, 1e-12).unwrap();
        let grids = [128usize, 256, 512, 1024];
        for k in 0..3 {
            let errs: Vec<f64> =
                grids.iter().map(|&n| (frequencies(Method::Fe, n, sets, 3)[k] - conv.modes[k].omega).abs()).collect();
            let p = orders(&errs);
            println!("{sets:?} mode {k}: errors {errs:?} orders {p:.3?}");
            for q in &p {
                assert!((q - 2.0).abs() < 0.05, "{sets:?} mode {k}: order {q} (round-off growth?)");
            }
        }
    }
}

/// The strain factorisation is the assembled stiffness: xᵀKx = Σ w (g·x)² and K (K⁻¹ b) = b, to round-off.
#[test]
fn strain_form_reproduces_the_assembled_stiffness() {
    for method in [Method::Fe, Method::Fd] {
        for grading in [0.0, 0.3] {
            let mut cfg = paper_with(&[]);
            cfg.discretisation.grading = grading;
            let disc = Discretisation::with(&cfg, method, 40);
            let n = disc.dim();
            let x: Vec<f64> = (0..n).map(|i| ((i * 7919) % 113) as f64 / 113.0 - 0.5).collect();
            let a = disc.stiffness.form(&x, &x);
            let b = disc.strain.energy_form(&x);
            assert!((a - b).abs() <= 1e-12 * a.abs(), "{method:?}: {a} vs {b}");
            let mut y = x.clone();
            disc.strain.solve_in_place(&mut y, &mut Vec::new());
            let mut ky = vec![0.0; n];
            disc.stiffness.mul_into(&y, &mut ky);
            let worst = ky.iter().zip(&x).map(|(u, v)| (u - v).abs()).fold(0.0, f64::max);
            assert!(worst < 1e-10, "{method:?} grading {grading}: residual {worst}");
        }
    }
}
