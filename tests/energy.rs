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
    sets
}

#[test]
fn undamped_uncontrolled_undisturbed_energy_is_conserved() {
    // Reference: E(t) = E(0) exactly for the PDE with ξ = 0, τ = g = 0; the trapezoidal rule
    // conserves the discrete quadratic energy exactly, so only round-off remains.
    for method in ["fe", "fd"] {
        let sets = conservative(method);
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
        assert!(worst < 1e-11, "{method}: relative energy drift {worst}");
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
            &format!("control.kind={controller}"),
            &format!("observer.rule={rule}"),
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
        assert!(worst < 1e-12, "{method}/{controller}: balance residual {worst}");
    }
}
