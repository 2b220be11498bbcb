//! Closed-loop tip trajectories: convergence under refinement in space and time, FD/FE
//! agreement, and the accuracy of the default settings against a Richardson-extrapolated
//! solution (the independent reference: two finer grids of the same scheme, order measured).

mod common;

use common::paper_with;
use wingcheck_sim::{simulate, simulate_with_error, RunOptions, Series};

fn run(sets: &[&str]) -> Series {
    simulate(&paper_with(sets), RunOptions::default()).unwrap().series
}

/// The control switches on at t = 0 against an initial state that violates the clamp and the
/// tip boundary conditions; the resulting boundary layer dominates the error for t < 0.1 s.
const TRANSIENT: f64 = 0.1;

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
}

/// Max |a − b| over the samples with t ≥ t0.
fn max_diff_after(t: &[f64], a: &[f64], b: &[f64], t0: f64) -> f64 {
    t.iter().zip(a.iter().zip(b)).filter(|(t, _)| **t >= t0).map(|(_, (x, y))| (x - y).abs()).fold(0.0, f64::max)
}

/// Max over the sampled trajectory of |q_tip| and |θ_tip| differences.
fn tip_diff(a: &Series, b: &Series) -> f64 {
    max_diff(&a.q_tip, &b.q_tip).max(max_diff(&a.theta_tip, &b.theta_tip))
}

fn extrapolate(coarse: &Series, fine: &Series, p: f64) -> (Vec<f64>, Vec<f64>) {
    let r = |c: &[f64], f: &[f64]| c.iter().zip(f).map(|(c, f)| common::richardson(*c, *f, p)).collect();
    (r(&coarse.q_tip, &fine.q_tip), r(&coarse.theta_tip, &fine.theta_tip))
}

fn spatial_study(method: &str) -> (Vec<Series>, f64) {
    let grids = [8usize, 16, 32, 64];
    let runs: Vec<Series> = grids
        .iter()
        .map(|n| {
            run(&[
                &format!("discretisation.method={method}"),
                &format!("discretisation.elements={n}"),
                &format!("discretisation.fd_points={n}"),
                "discretisation.grading=0",
            ])
        })
        .collect();
    let d: Vec<f64> = runs.windows(2).map(|w| tip_diff(&w[0], &w[1])).collect();
    let order = (d[1] / d[2]).log2();
    println!("{method}: successive tip differences {d:?}, observed order {order:.2}");
    (runs, order)
}

#[test]
fn fe_and_fd_tip_trajectories_converge_at_second_order_and_agree() {
    let (fe, p_fe) = spatial_study("fe");
    let (fd, p_fd) = spatial_study("fd");
    assert!(p_fe > 1.8, "FE spatial order {p_fe}");
    assert!(p_fd > 1.8, "FD spatial order {p_fd}");
    let (fe_q, fe_t) = extrapolate(&fe[2], &fe[3], 2.0);
    let (fd_q, fd_t) = extrapolate(&fd[2], &fd[3], 2.0);
    let gap_all = max_diff(&fe_q, &fd_q).max(max_diff(&fe_t, &fd_t));
    let t = &fe[0].t;
    let gap = max_diff_after(t, &fe_q, &fd_q, TRANSIENT).max(max_diff_after(t, &fe_t, &fd_t, TRANSIENT));
    println!("FE vs FD extrapolated tip trajectories: max difference {gap:.3e} for t >= {TRANSIENT} s, {gap_all:.3e} overall");
    // Two independent discretisations agree far below the 2e-4 accuracy target.
    assert!(gap < 2e-5, "FE and FD limits differ by {gap}");
    assert!(gap_all < 1e-4, "FE and FD limits differ by {gap_all} in the start-up transient");
}

/// FD's default settings (the FD grid is uniform).
const FD: [&str; 2] = ["discretisation.method=fd", "discretisation.grading=0"];

#[test]
fn default_settings_are_within_2e_4_of_the_extrapolated_solution_over_the_whole_horizon() {
    // Reference: FE on uniform grids (grading 0) of 64 and 128 elements, Richardson-extrapolated
    // at the measured order 2: independent of the default graded FE mesh and of FD.
    let fine = run(&["discretisation.elements=64", "discretisation.grading=0"]);
    let finer = run(&["discretisation.elements=128", "discretisation.grading=0"]);
    let (q_ref, t_ref) = extrapolate(&fine, &finer, 2.0);
    for (name, sets) in [("fe", &[][..]), ("fd", &FD[..])] {
        let default = run(sets);
        let t = &default.t;
        let err_all = max_diff(&default.q_tip, &q_ref).max(max_diff(&default.theta_tip, &t_ref));
        let err_late = max_diff_after(t, &default.q_tip, &q_ref, TRANSIENT).max(max_diff_after(
            t,
            &default.theta_tip,
            &t_ref,
            TRANSIENT,
        ));
        let cfg = paper_with(sets);
        println!(
            "{name} default ({} grid, grading {}, dt = {} s): max tip error {err_all:.3e} over [0, 20] s, {err_late:.3e} for t >= {TRANSIENT} s",
            cfg.discretisation.grid_size(),
            cfg.discretisation.grading,
            cfg.discretisation.dt
        );
        assert!(err_all <= 2e-4, "{name} default tip error {err_all}");
    }
    // the time-step part of the error, from a run with dt/4 on the default grid
    let dt_fine = run(&["discretisation.dt=0.00025"]);
    let dt_err = tip_diff(&run(&[]), &dt_fine);
    println!("time-step contribution (dt vs dt/4): {dt_err:.3e}");
    assert!(dt_err < 2e-5);
}

/// The error estimate of `simulate_with_error` (one refinement in h and in dt) against the
/// actual error measured from an independent reference: Richardson extrapolation of the same
/// scheme on the two next finer grids (2N, 4N) at dt/2. Checked as the maximum over each 1-s
/// window of [0, 10] s (switch-on included; 10 s keeps the test quick), for FE and FD; and FE
/// and FD agree within the sum of their stated errors.
#[test]
fn error_estimates_bound_the_error_against_richardson_on_finer_grids_for_fe_and_fd() {
    const HORIZON: &str = "horizon.t_end=10";
    let mut estimated = Vec::new();
    for (name, sets) in [("fe", &["discretisation.method=fe", HORIZON][..]), ("fd", &[FD[0], FD[1], HORIZON][..])] {
        let cfg = paper_with(sets);
        let est = simulate_with_error(&cfg, RunOptions::default()).unwrap();
        let n = cfg.discretisation.grid_size();
        let key = if name == "fe" { "elements" } else { "fd_points" };
        let dt = format!("discretisation.dt={}", cfg.discretisation.dt / 2.0);
        let mut fine_sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        fine_sets.push(dt);
        let at = |m: usize| {
            let mut v = fine_sets.clone();
            v.push(format!("discretisation.{key}={m}"));
            let refs: Vec<&str> = v.iter().map(|s| s.as_str()).collect();
            run(&refs)
        };
        let (q_ref, t_ref) = extrapolate(&at(2 * n), &at(4 * n), 2.0);
        let s = &est.output.series;
        let mut worst_ratio: f64 = 0.0;
        for w in 0..10 {
            let idx: Vec<usize> = (0..s.len()).filter(|&k| s.t[k] >= w as f64 && s.t[k] < (w + 1) as f64).collect();
            let actual = idx.iter().map(|&k| (s.q_tip[k] - q_ref[k]).abs()).fold(0.0, f64::max);
            let bound = idx.iter().map(|&k| est.q_tip_error[k]).fold(0.0, f64::max);
            let actual_t = idx.iter().map(|&k| (s.theta_tip[k] - t_ref[k]).abs()).fold(0.0, f64::max);
            let bound_t = idx.iter().map(|&k| est.theta_tip_error[k]).fold(0.0, f64::max);
            worst_ratio = worst_ratio.max(actual / bound).max(actual_t / bound_t);
            assert!(actual <= bound, "{name} window {w} s: q error {actual:e} > estimate {bound:e}");
            assert!(actual_t <= bound_t, "{name} window {w} s: θ error {actual_t:e} > estimate {bound_t:e}");
        }
        println!(
            "{name}: max estimated error q {:.2e} θ {:.2e}; worst actual/estimate over 1-s windows {worst_ratio:.2}",
            est.max_q_tip_error, est.max_theta_tip_error
        );
        assert!(est.meets_tolerance, "{name}: defaults exceed the stated tolerance");
        estimated.push(est);
    }
    let (fe, fd) = (&estimated[0], &estimated[1]);
    let (a, b) = (&fe.output.series, &fd.output.series);
    let mut worst: f64 = 0.0;
    for k in 0..a.len() {
        let gap_q = (a.q_tip[k] - b.q_tip[k]).abs() / (fe.q_tip_error[k] + fd.q_tip_error[k]);
        let gap_t = (a.theta_tip[k] - b.theta_tip[k]).abs() / (fe.theta_tip_error[k] + fd.theta_tip_error[k]);
        worst = worst.max(gap_q).max(gap_t);
    }
    println!("FE vs FD: worst |difference| / (sum of stated errors) = {worst:.2}");
    assert!(worst <= 1.0, "FE and FD differ by more than their stated errors ({worst})");
}

#[test]
fn time_stepping_is_second_order() {
    // Fixed observer sample period 4 ms, integrator steps 4, 2, 1, 0.5 ms: the controller is
    // the same digital controller, so the differences measure the integrator alone.
    let dts = ["0.004", "0.002", "0.001", "0.0005"];
    let runs: Vec<Series> = dts
        .iter()
        .map(|dt| {
            run(&["observer.sample_period=0.004", "horizon.sample_every=0.02", &format!("discretisation.dt={dt}")])
        })
        .collect();
    let d: Vec<f64> = runs.windows(2).map(|w| tip_diff(&w[0], &w[1])).collect();
    let p = (d[1] / d[2]).log2();
    println!("time refinement differences {d:?}, observed order {p:.2}");
    assert!((p - 2.0).abs() < 0.25, "time order {p}");
}

/// FD refuses a graded grid (naming the key) instead of silently ignoring it; an error
/// estimate whose refinement the validation would refuse is refused before any work.
#[test]
fn fd_refuses_grading_and_estimates_refuse_an_invalid_refinement() {
    let sets = ["discretisation.method=fd".to_string(), "discretisation.grading=0.3".to_string()];
    let e = wingcheck_model::apply_overrides(&wingcheck_model::Config::paper(), &sets).unwrap_err().to_string();
    assert!(e.contains("discretisation.grading") && e.contains("fe only"), "{e}");
    let cfg = paper_with(&["discretisation.elements=3000", "horizon.t_end=0.01"]);
    let e = simulate_with_error(&cfg, RunOptions::default()).unwrap_err().to_string();
    assert!(e.contains("discretisation.elements"), "{e}");
}
