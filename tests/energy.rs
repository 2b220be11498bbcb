//! Energy: conservation without damping, control and disturbance, and the exact discrete
//! balance dE = work in − Kelvin–Voigt dissipation in the general closed loop.

mod common;

use common::paper_with;
use wingcheck_sim::Stepper;

const NO_DISTURBANCE: [&str; 5] = [
    "disturbance.distributed.mean=0",
    "disturbance.distributed.cos_amp=0",
    "disturbance.distributed.sin_amp=0",
    "disturbance.tip_bending.mean=0",
    "disturbance.tip_torsion.mean=0",
];

fn conservative(method: &str) -> Vec<String> {
    let mut sets: Vec<String> = NO_DISTURBANCE.iter().map(|s| s.to_string()).collect();
    sets.extend(
        ["wing.xi=0", "control.kind=none", "disturbance.tip_bending.amp=0", "disturbance.tip_torsion.amp=0"]
            .iter()
            .map(|s| s.to_string()),
    );
    sets.push(format!("discretisation.method={method}"));
    sets.push(uniform_if_fd(method));
    sets
}

/// FD refuses a graded grid; FE keeps the default grading.
fn uniform_if_fd(method: &str) -> String {
    let grading = if method == "fd" { 0.0 } else { paper_with(&[]).discretisation.grading };
    format!("discretisation.grading={grading}")
}

#[test]
fn undamped_uncontrolled_undisturbed_energy_is_conserved() {
    // Reference: E(t) = E(0) exactly for the PDE with ξ = 0, τ = g = 0; the trapezoidal rule
    // conserves the discrete quadratic energy exactly, so only round-off remains.
    for method in ["fe", "fd"] {
        let mut sets = conservative(method);
        sets.push("discretisation.stepper=trapezoid".into());
        let refs: Vec<&str> = sets.iter().map(|s| s.as_str()).collect();
        let cfg = paper_with(&refs);
        let mut st = Stepper::new(&cfg).unwrap();
        let e0 = st.sample().energy;
        let mut worst: f64 = 0.0;
        for _ in 0..5000 {
            st.advance_sample();
            worst = worst.max((st.sample().energy - e0).abs() / e0);
        }
        println!("{method}: E(0) = {e0:.6e} J, max relative drift over 5 s = {worst:.2e}");
        // round-off random walk over 5000 steps (banded Cholesky, no pivoting needed for SPD)
        assert!(worst < 5e-11, "{method}: relative energy drift {worst}");
    }
}

#[test]
fn discrete_energy_balance_holds_to_round_off_in_the_closed_loop() {
    // Reference: dE/dt = (τ1+g1)q̇(s) + (τ2+g2)θ̇(s) + ∫g_h(q̇ − x_ac θ̇) − ξ∫(EI q̇''² + GJ θ̇'²)
    // (spec), whose discrete counterpart E_{n+1} − E_n = h v̄ᵀf̄ − hξ v̄ᵀKv̄ the scheme satisfies
    // exactly; the ledger accumulates the right-hand side independently of E.
    for (method, controller, rule) in
        [("fe", "ftdo", "implicit"), ("fd", "ftdo", "explicit"), ("fe", "dobc", "implicit"), ("fd", "pd", "implicit")]
    {
        let cfg = paper_with(&[
            &format!("discretisation.method={method}"),
            &uniform_if_fd(method),
            &format!("control.kind={controller}"),
            &format!("observer.rule={rule}"),
            "discretisation.stepper=trapezoid",
        ]);
        let mut st = Stepper::new(&cfg).unwrap();
        st.track_energy(true);
        let e0 = st.sample().energy;
        let mut worst: f64 = 0.0;
        for _ in 0..3000 {
            st.advance_sample();
            let l = st.ledger();
            let scale = e0 + l.work_in.abs() + l.dissipated;
            worst = worst.max((st.sample().energy - e0 - l.work_in + l.dissipated).abs() / scale);
        }
        println!("{method}/{controller}/{rule}: max |ΔE − (work − dissipation)| / scale = {worst:.2e}");
        // round-off over 3000 samples on the graded default mesh (smallest element 0.3 × uniform)
        assert!(worst < 5e-11, "{method}/{controller}: balance residual {worst}");
    }
}

/// TR-BDF2 energy, undamped and unforced: A-stable (|R(iy)| ≤ 1 in every mode, and E is the
/// modal norm), so E never increases; its numerical dissipation vanishes under dt refinement
/// (reference: E(t) = E(0) for the PDE). Measured orders 1.2–1.5 on the graded FE mesh (the
/// asymptotic 3 of the scheme needs every excited mode resolved in time) and 3.0 on FD; the loss
/// over 2 s at the default dt is < 1e-4 of E(0).
#[test]
fn trbdf2_energy_never_increases_and_its_dissipation_vanishes_under_refinement() {
    for method in ["fe", "fd"] {
        let mut losses = Vec::new();
        for dt in ["1e-3", "5e-4", "2.5e-4"] {
            let mut sets = conservative(method);
            sets.push(format!("discretisation.dt={dt}"));
            sets.push("discretisation.stepper=trbdf2".into());
            // smooth initial shape: the linear one violates the clamp and puts energy in modes
            // no dt here resolves, which TR-BDF2 damps at any of these steps
            sets.push("initial.shape=cantilever".into());
            let refs: Vec<&str> = sets.iter().map(|s| s.as_str()).collect();
            let cfg = paper_with(&refs);
            let mut st = Stepper::new(&cfg).unwrap();
            let e0 = st.sample().energy;
            let mut prev = e0;
            for _ in 0..2000 {
                st.advance_sample();
                let e = st.sample().energy;
                assert!(e <= prev * (1.0 + 1e-13), "{method} dt {dt}: energy rose {prev} -> {e}");
                prev = e;
            }
            losses.push((e0 - prev) / e0);
        }
        let orders: Vec<f64> = losses.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
        println!("{method}: TR-BDF2 relative energy loss over 2 s {losses:?}, orders {orders:.2?}");
        assert!(orders.iter().all(|&p| p > 1.0), "{method}: orders {orders:?}");
        assert!(losses[0] < 1e-4, "{method}: loss {} at the default dt", losses[0]);
    }
}

/// TR-BDF2 energy balance in the closed loop: the ledger integrates the power and the
/// Kelvin–Voigt dissipation with the scheme's own stage quadrature; ΔE − (work − dissipation)
/// is the scheme's numerical dissipation, which vanishes under dt refinement (reference:
/// dE/dt = power in − ξ∫(EI q̇''² + GJ θ̇'²) for the PDE, spec). Measured order ≈ 1.8, not 2:
/// every sample's jump of ĝ excites stiff, physically overdamped modes, whose energy the
/// L-stable scheme removes numerically instead of through ξ (the price of not ringing); the
/// residual is ≤ 2e-3 of the energy scale at the default dt.
#[test]
fn trbdf2_energy_balance_residual_vanishes_under_refinement() {
    for method in ["fe", "fd"] {
        let mut residuals = Vec::new();
        for dt in ["1e-3", "5e-4", "2.5e-4"] {
            let cfg = paper_with(&[
                &format!("discretisation.method={method}"),
                &uniform_if_fd(method),
                &format!("discretisation.dt={dt}"),
                // smooth initial shape: the linear one violates the clamp and puts energy in
                // modes no dt here resolves, which TR-BDF2 damps at any of these steps
                "initial.shape=cantilever",
                "discretisation.stepper=trbdf2",
            ]);
            let mut st = Stepper::new(&cfg).unwrap();
            st.track_energy(true);
            let e0 = st.sample().energy;
            let mut worst: f64 = 0.0;
            let mut worst_late: f64 = 0.0;
            let mut at_half = 0.0;
            for k in 1..=2000 {
                st.advance_sample();
                let l = st.ledger();
                let scale = e0 + l.work_in.abs() + l.dissipated;
                let r = (st.sample().energy - e0 - l.work_in + l.dissipated) / scale;
                worst = worst.max(r.abs());
                if k == 1000 {
                    at_half = r;
                }
                if k > 1000 {
                    worst_late = worst_late.max((r - at_half).abs());
                }
            }
            println!("{method} dt {dt}: max residual over [0, 2] s {worst:.3e}, growth over [1, 2] s {worst_late:.3e}");
            if dt == "1e-3" {
                assert!(worst < 2e-3, "{method}: residual {worst} at the default dt");
            }
            residuals.push(worst);
        }
        let orders: Vec<f64> = residuals.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
        println!("{method}: TR-BDF2 balance residuals {residuals:?}, orders {orders:.2?}");
        assert!(orders.iter().all(|&p| p > 1.25), "{method}: orders {orders:?}");
    }
}
