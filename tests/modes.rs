//! Natural frequencies: both discretisations against the analytic uncoupled frequencies, their
//! convergence order under refinement, and FD/FE agreement in the coupled case.

mod common;

use common::{orders, paper_with};
use wingcheck_model::Method;
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
