//! The search's modal runner against the simulator. In the modal basis both run the one driver
//! (`wingcheck_sim::modal::drive`) on the same inputs, so the search's trace equals
//! `simulate`'s bit for bit (first test), except that the search steps the exponential scheme
//! in the closed loop's eigenbasis where its checks pass (within its round-off estimate,
//! second test). Against the nodal stepper: the same discrete scheme (TR-BDF2 or the
//! trapezoidal rule, as `discretisation.stepper` selects) in another basis (Woodbury solve of
//! diagonal + rank 2 vs sparse Cholesky of the step matrix, observer signal precomputed vs
//! integrated with the plant), so every recorded tip quantity must agree to round-off.
//!
//! Basis of the tolerances (each case's is ~3–10× the largest difference measured on this
//! machine, over both schemes): on FE wings the modal basis comes from a dense symmetric
//! eigenproblem whose ω² span ~10 decades, and the two runs differ by 1e-11–4e-9 relative
//! (the same for both schemes, so it is the change of basis, not the scheme); on the FD wing
//! (lumped, diagonal M, 24 intervals) by ≤ 3e-12. A scheme that is not the simulator's shows far above
//! that: the trapezoid against TR-BDF2 differs by 2.5e-3 relative at the paper point (τ1; q(s,t)
//! by 7e-7) and by a factor 9 in τ1 at a = 1e-4, b = 1e4 (checked below).

use wingcheck_model::{apply_overrides, Config};
use wingcheck_search::modal::{RunCache, TipTrace};
use wingcheck_search::point::closed_loop;
use wingcheck_sim::{simulate, simulate_base, RunOptions};

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

/// The simulator in the nodal basis (banded Cholesky of the step matrix): the independent
/// implementation of the same scheme. At the configured step only (`simulate_base`): the search
/// runs the same discrete equations and does not re-run the initial layer at finer steps, which
/// `simulate` does for its full-rate peaks (at b = 1e4 the layer raises peak |τ| by 41 %).
fn reference(c: &Config) -> TipTrace {
    let mut nodal = c.clone();
    nodal.discretisation.basis = wingcheck_model::StepBasis::Nodal;
    TipTrace::from_output(&simulate_base(&nodal, RunOptions::default()).unwrap())
}

/// Largest relative difference over q(s,t), θ(s,t), τ1, τ2 and E(T), and largest absolute
/// difference of g̃ (N, N m): g̃ is small after convergence, so it is compared absolutely.
fn differences(fast: &TipTrace, reference: &TipTrace) -> (f64, f64) {
    assert_eq!(fast.t, reference.t, "same sample times");
    let columns = [
        (&fast.q_tip, &reference.q_tip),
        (&fast.theta_tip, &reference.theta_tip),
        (&fast.tau1, &reference.tau1),
        (&fast.tau2, &reference.tau2),
    ];
    let energy = (fast.energy_end - reference.energy_end).abs() / reference.energy_end.abs().max(1e-300);
    // and the full-rate τ peaks (the simulator's `Peaks`), not the output samples'
    let peaks = rel(&fast.tau_peak[..], &reference.tau_peak[..]);
    let rel_max = columns.iter().map(|(a, b)| rel(a, b)).fold(energy.max(peaks), f64::max);
    let g = [(&fast.g1_tilde, &reference.g1_tilde), (&fast.g2_tilde, &reference.g2_tilde)];
    let g_max = g.iter().flat_map(|(a, b)| a.iter().zip(b.iter()).map(|(x, y)| (x - y).abs())).fold(0.0, f64::max);
    (rel_max, g_max)
}

/// Modal runner vs simulator under both schemes: relative tolerance `tol`, g̃ within `g_tol`.
fn compare(sets: &[&str], tol: f64, g_tol: f64) {
    for scheme in ["trbdf2", "trapezoid"] {
        let stepper = format!("discretisation.stepper={scheme}");
        let c = cfg(&[sets, &[stepper.as_str()]].concat());
        let fast = closed_loop(&c, &RunCache::new(), None).unwrap();
        let (d, g) = differences(&fast, &reference(&c));
        assert!(d <= tol, "{sets:?} ({scheme}): differs by {d:e} relative (tolerance {tol:e})");
        assert!(g <= g_tol, "{sets:?} ({scheme}): g̃ differs by {g:e} (tolerance {g_tol:e})");
    }
}

/// `simulate` in the modal basis, as the search's trace.
fn modal_simulation(c: &Config) -> TipTrace {
    let mut modal = c.clone();
    modal.discretisation.basis = wingcheck_model::StepBasis::Modal;
    TipTrace::from_output(&simulate(&modal, RunOptions::default()).unwrap())
}

#[test]
fn the_search_records_the_simulators_own_run() {
    // One driver, one signal (replayed vs generated while stepping: the same numbers), one
    // step per scheme: equal bits, not a tolerance (but for the run's RMS τ, summed another
    // way) — every controller, both observer rules and every scheme, off the paper point too.
    for sets in [
        &["control.kind=ftdo"][..],
        &["control.kind=dobc", "discretisation.stepper=trapezoid"],
        &["control.kind=pd", "control.a=10", "control.b=1e-2"],
        &["observer.rule=explicit", "discretisation.stepper=trbdf2", "wing.xi=0"],
        &["discretisation.method=fd", "discretisation.grading=0", "discretisation.fd_points=24", "control.k1=50"],
        // the exponential scheme where the eigenbasis refuses (no Kelvin–Voigt damping: an
        // eigenvalue on the imaginary axis to round-off) is the dense one in both
        &["observer.rule=explicit", "wing.xi=0", "control.b=2"],
    ] {
        let c = cfg(&[sets, &["horizon.t_end=0.5"]].concat());
        let cache = RunCache::new();
        let (mut searched, mut simulated) = (closed_loop(&c, &cache, None).unwrap(), modal_simulation(&c));
        // but RMS τ over the run: the search forms √(∫τ²/T) from the steps' ∫τ² in one sum,
        // the simulator √(Σ_k rms_k² Δt_k / T) from its intervals' RMS (a square root and a
        // square per interval): the same integral to round-off, ≤ (intervals + 2) ε relative
        let bound = (simulated.t.len() + 2) as f64 * f64::EPSILON;
        for ch in 0..2 {
            let (a, b) = (searched.tau_rms[ch], simulated.tau_rms[ch]);
            assert!((a - b).abs() <= bound * b.abs(), "{sets:?}: RMS τ{} {a:e} vs {b:e}", ch + 1);
        }
        (searched.tau_rms, simulated.tau_rms) = ([0.0; 2], [0.0; 2]);
        assert_eq!(searched, simulated, "{sets:?}");
    }
}

#[test]
fn the_search_steps_the_exponential_scheme_in_the_eigenbasis_within_its_roundoff() {
    // The search steps the exponential scheme in the closed loop's eigenbasis where its checks
    // pass (ModalLoop::with_eigenbasis), `simulate` by the dense scaling and squaring: the same
    // exact transition computed two ways. Reference: `simulate` in the modal basis; the
    // eigenbasis's round-off estimate is ≤ 1e-6 relative of the state (its acceptance limit;
    // 4.0e-8 at the paper point over this 2-s horizon), so 1e-6 relative on every sampled value, peak and RMS. g̃ is
    // the replayed observer signal, independent of the plant: equal.
    for sets in [
        &["observer.rule=explicit"][..],
        &["observer.rule=explicit", "control.k1=3", "control.a=0.5", "wing.xi=0.3"],
        &[
            "observer.rule=explicit",
            "discretisation.method=fd",
            "discretisation.grading=0",
            "discretisation.fd_points=24",
        ],
        // slow loops (slowest decay rates 3.5e-4, 2e-4 and 3.8e-6 1/s), whose solver eigenvalues
        // the refinement corrects; in the last the telescoped ∫τ² terms are 2.7e8 steps' integrals
        &["observer.rule=explicit", "control.a=1", "control.b=3000"],
        &["observer.rule=explicit", "control.a=0.014", "control.b=190"],
        &["observer.rule=explicit", "control.a=1e-4", "control.b=1e4"],
    ] {
        let c = cfg(&[sets, &["horizon.t_end=2"]].concat());
        let basis = wingcheck_sim::modal::ModalBasis::new(&c).unwrap();
        let lp = wingcheck_sim::modal::ModalLoop::with_eigenbasis(&c, &basis).unwrap();
        assert!(lp.eigenbasis_roundoff().is_some(), "{sets:?}: the eigenbasis was refused");
        let fast = closed_loop(&c, &RunCache::new(), None).unwrap();
        let reference = modal_simulation(&c);
        let (d, g) = differences(&fast, &reference);
        let rms = rel(&fast.tau_rms, &reference.tau_rms);
        println!("{sets:?}: {d:.1e} relative, RMS τ {rms:.1e}");
        assert!(d <= 1e-6 && rms <= 1e-6, "{sets:?}: differs by {d:e} / RMS {rms:e} relative");
        assert_eq!(g, 0.0, "{sets:?}");
    }
}

#[test]
fn paper_point_and_its_controllers() {
    // measured ≤ 1.6e-9 (E(T) of the uncontrolled `none` run), g̃ ≤ 2e-13
    for kind in ["ftdo", "dobc", "pd", "none"] {
        compare(&[&format!("control.kind={kind}")], 1e-8, 2e-12);
    }
}

#[test]
fn extreme_gains_and_weights() {
    // measured ≤ 2.8e-9 (τ1 at b = 1e4: b·k1·q̇ amplifies the tip-rate round-off), g̃ ≤ 7e-13
    compare(&["control.a=1e-4", "control.b=1e4"], 1e-8, 5e-12);
    compare(&["control.a=10", "control.b=1e-2"], 1e-8, 5e-12);
    compare(&["control.k1=50", "control.k2=0.01"], 1e-8, 5e-12);
}

#[test]
fn other_discretisations_and_wings() {
    // FD (lumped mass, uniform grid): measured ≤ 2.8e-12, g̃ ≤ 2.3e-13.
    compare(&["discretisation.method=fd", "discretisation.grading=0", "discretisation.fd_points=24"], 2e-11, 2e-12);
    // No Kelvin–Voigt damping (algebraic tip states): measured ≤ 1.1e-10.
    compare(&["wing.xi=0"], 1e-9, 2e-12);
    // Two integrator steps per observer sample, the cantilever initial shape: ≤ 3.9e-10.
    compare(&["discretisation.dt=5e-4", "initial.shape=cantilever"], 4e-9, 2e-12);
    // An SI-scale wing: measured ≤ 3.6e-9 relative and g̃ ≤ 3.7e-9 N. The simulator forms
    // σ = s ξ S w − ν as a difference of terms of size ξ·EI·|q'''| ~ 1e3–1e5 here, so its
    // own g̃ carries round-off ~1e-16 × that × steps.
    compare(
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
        2e-8,
        2e-8,
    );
}

#[test]
fn the_runner_follows_the_configured_scheme() {
    // The tolerances above discriminate the scheme: the modal runner's TR-BDF2 against the
    // simulator's trapezoid (and the other way round) differs by far more than round-off —
    // measured 2.5e-3 relative at the paper point (τ1; q(s,t) by 7e-7), and τ1 by a factor
    // ~9 at a = 1e-4, b = 1e4 (the trapezoid rings on the stiff tip feedback).
    for sets in [&[][..], &["control.a=1e-4", "control.b=1e4"][..]] {
        let trbdf2 = cfg(&[sets, &["discretisation.stepper=trbdf2"]].concat());
        let trapezoid = cfg(&[sets, &["discretisation.stepper=trapezoid"]].concat());
        let cache = RunCache::new();
        let fast = [closed_loop(&trbdf2, &cache, None).unwrap(), closed_loop(&trapezoid, &cache, None).unwrap()];
        let (d, _) = differences(&fast[0], &reference(&trapezoid));
        assert!(d > 1e-5, "{sets:?}: modal TR-BDF2 vs simulator trapezoid differ by only {d:e}");
        let (d, _) = differences(&fast[1], &reference(&trbdf2));
        assert!(d > 1e-5, "{sets:?}: modal trapezoid vs simulator TR-BDF2 differ by only {d:e}");
    }
}

#[test]
fn one_cache_serves_wings_of_different_grids() {
    // The basis cache is keyed by every key the discretisation reads (fd_points included):
    // FD wings of 24 and 48 intervals through one cache each match their own simulator run
    // (measured 2.8e-12 and 3.0e-11: ω²_max grows as N⁴, and with it the round-off; a basis
    // of the wrong grid would not even have the right number of modes).
    let cache = RunCache::new();
    for points in ["24", "48"] {
        let c = cfg(&[
            "discretisation.method=fd",
            "discretisation.grading=0",
            &format!("discretisation.fd_points={points}"),
        ]);
        let (d, _) = differences(&closed_loop(&c, &cache, None).unwrap(), &reference(&c));
        assert!(d <= 3e-10, "fd_points={points}: differs by {d:e} relative");
    }
}

#[test]
fn large_wings_run_the_simulator_itself() {
    // FE with 1 025 elements = 3 075 unknowns > MODAL_MAX_UNKNOWNS, and 370 elements = 1 110
    // unknowns, above MODAL_AUTO_UNKNOWNS where a 0.02-s run's steps do not repay the modal
    // basis's setup (Config::expected_modal): the fallback path is the simulator's nodal
    // stepper, so the trace equals the nodal run exactly.
    for elements in ["discretisation.elements=1025", "discretisation.elements=370"] {
        let c = cfg(&["horizon.t_end=0.02", elements]);
        assert!(RunCache::new().basis(&c).is_none(), "{elements}");
        let fast = closed_loop(&c, &RunCache::new(), None).unwrap();
        assert_eq!(fast, reference(&c), "{elements}");
    }
    // an explicit `nodal` is kept by the search too
    let c = cfg(&["horizon.t_end=0.02", "discretisation.basis=nodal"]);
    assert!(RunCache::new().basis(&c).is_none());
}
