//! The search's modal runner against the simulator: the same discrete scheme in another basis
//! (Woodbury solve of diagonal + rank 2 vs sparse Cholesky of the step matrix, observer signal
//! precomputed vs integrated with the plant), so every recorded tip quantity must agree to
//! round-off, far below the simulator's discretisation error (≥ 1e-4).

use wingcheck_model::{apply_overrides, Config};
use wingcheck_search::modal::{RunCache, TipTrace};
use wingcheck_search::point::closed_loop;
use wingcheck_sim::{simulate, RunOptions};

fn cfg(sets: &[&str]) -> Config {
    let mut all = vec!["horizon.t_end=2".to_string()];
    all.extend(sets.iter().map(|s| s.to_string()));
    apply_overrides(&Config::paper(), &all).unwrap()
}

/// max_k |x_k − y_k| / max_k |y_k| over a column.
fn rel(x: &[f64], y: &[f64]) -> f64 {
    assert_eq!(x.len(), y.len());
    let scale = y.iter().fold(0.0f64, |m, v| m.max(v.abs())).max(1e-300);
    x.iter().zip(y).fold(0.0f64, |m, (a, b)| m.max((a - b).abs())) / scale
}

fn compare(sets: &[&str], tol: f64) {
    compare_with(sets, tol, 1e-9)
}

/// As [`compare`] with an absolute tolerance on g̃ (N, N m).
fn compare_with(sets: &[&str], tol: f64, g_tol: f64) {
    let c = cfg(sets);
    let fast = closed_loop(&c, &RunCache::new()).unwrap();
    let reference = TipTrace::from_series(&simulate(&c, RunOptions::default()).unwrap().series);
    assert_eq!(fast.t, reference.t, "{sets:?}: same sample times");
    for (name, a, b) in [
        ("q_tip", &fast.q_tip, &reference.q_tip),
        ("theta_tip", &fast.theta_tip, &reference.theta_tip),
        ("tau1", &fast.tau1, &reference.tau1),
        ("tau2", &fast.tau2, &reference.tau2),
    ] {
        let e = rel(a, b);
        assert!(e <= tol, "{sets:?}: {name} differs by {e:e} relative");
    }
    // g̃ is small after convergence; compare against the disturbance scale |g| + |ĝ| instead.
    for (a, b) in [(&fast.g1_tilde, &reference.g1_tilde), (&fast.g2_tilde, &reference.g2_tilde)] {
        let d = a.iter().zip(b.iter()).fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
        assert!(d <= g_tol, "{sets:?}: g̃ differs by {d:e}");
    }
    let e = (fast.energy_end - reference.energy_end).abs() / reference.energy_end.abs().max(1e-300);
    assert!(e <= tol, "{sets:?}: E(T) differs by {e:e} relative");
}

#[test]
fn paper_point_and_its_controllers() {
    for kind in ["ftdo", "dobc", "pd", "none"] {
        compare(&[&format!("control.kind={kind}")], 1e-9);
    }
}

#[test]
fn extreme_gains_and_weights() {
    compare(&["control.a=1e-4", "control.b=1e4"], 1e-9);
    compare(&["control.a=10", "control.b=1e-2"], 1e-9);
    compare(&["control.k1=50", "control.k2=0.01"], 1e-9);
}

#[test]
fn other_discretisations_and_wings() {
    // FD (lumped mass), no Kelvin–Voigt damping, two integrator steps per observer sample,
    // the cantilever initial shape.
    compare(&["discretisation.method=fd", "discretisation.elements=24"], 1e-9);
    compare(&["wing.xi=0"], 1e-8);
    compare(&["discretisation.dt=5e-4", "initial.shape=cantilever"], 1e-9);
    // An SI-scale wing. The simulator forms σ = s ξ S w − ν as a difference of terms of size
    // ξ·EI·|q'''| ~ 1e3–1e5 here, so its own g̃ carries round-off ~1e-16 × that × steps.
    compare_with(
        &[
            "wing.span=6",
            "wing.ei=1e7",
            "wing.gj=1e6",
            "wing.rho=100",
            "wing.rho_xc=5",
            "wing.ip=10",
            "wing.xi=0.01",
            "control.k1=1e4",
            "control.k2=1e3",
        ],
        1e-8,
        1e-7,
    );
}

#[test]
fn large_wings_run_the_simulator_itself() {
    // FE with 240 elements = 720 unknowns > MODAL_MAX_UNKNOWNS: the fallback path is the
    // simulator, so the trace equals simulate's exactly.
    let c = cfg(&["horizon.t_end=0.02", "discretisation.elements=240"]);
    assert!(wingcheck_search::modal::ModalBasis::new(&c).is_err());
    let fast = closed_loop(&c, &RunCache::new()).unwrap();
    let reference = TipTrace::from_series(&simulate(&c, RunOptions::default()).unwrap().series);
    assert_eq!(fast, reference);
}
