//! The observer identities, whatever the plant: σ_{k+1} − σ_k = ∫g − T ĝ_k (FTDO, (16)–(19)
//! with the tip boundary conditions ⇒ σ̇ = g − ĝ) and ĝ_{k+1} − ĝ_k = ∫g − T ĝ (DOBC ⇒
//! d ĝ/dt = g − ĝ), checked per sample against the exact integral of g (analytic).

mod common;

use common::paper_with;
use proptest::prelude::*;
use wingcheck_model::{Config, TipDisturbance};
use wingcheck_sim::Stepper;

/// ∫_{t0}^{t1} (mean + amp sin(ω t)) dt, analytically.
fn integral(g: &TipDisturbance, t0: f64, t1: f64) -> f64 {
    g.mean * (t1 - t0) + g.amp * ((g.freq * t0).cos() - (g.freq * t1).cos()) / g.freq
}

/// Largest per-sample violation of σ_{k+1} − σ_k = ∫g − T ĝ_k, relative to the size of the
/// terms that cancel (round-off scale).
fn ftdo_identity_residual(cfg: &Config, samples: usize) -> f64 {
    let mut st = Stepper::new(cfg).unwrap();
    let period = cfg.observer.sample_period;
    let g = [&cfg.disturbance.tip_bending, &cfg.disturbance.tip_torsion];
    let mut worst: f64 = 0.0;
    for _ in 0..samples {
        let t0 = st.time();
        let before: Vec<(f64, f64, f64)> = st.channels.iter().map(|c| (c.sigma, c.g_hat, c.observer.nu)).collect();
        st.advance_sample();
        for (i, c) in st.channels.iter().enumerate() {
            let (sigma0, ghat0, nu0) = before[i];
            let expected = integral(g[i], t0, t0 + period) - period * ghat0;
            let scale = 1.0 + nu0.abs() + c.observer.nu.abs() + sigma0.abs() + c.sigma.abs();
            worst = worst.max(((c.sigma - sigma0) - expected).abs() / scale);
        }
    }
    worst
}

#[test]
fn ftdo_sigma_identity_holds_per_sample_for_both_rules_and_methods() {
    for rule in ["implicit", "explicit"] {
        for method in ["fe", "fd"] {
            let cfg = paper_with(&[&format!("observer.rule={rule}"), &format!("discretisation.method={method}")]);
            let r = ftdo_identity_residual(&cfg, 2000);
            println!("{rule}/{method}: max relative residual {r:.2e}");
            assert!(r < 1e-13, "{rule}/{method}: {r}");
        }
    }
}

#[test]
fn dobc_estimate_obeys_its_filter_equation_per_sample() {
    for rule in ["explicit", "implicit"] {
        let cfg = paper_with(&["control.kind=dobc", &format!("observer.rule={rule}")]);
        let period = cfg.observer.sample_period;
        let g = [&cfg.disturbance.tip_bending, &cfg.disturbance.tip_torsion];
        let mut st = Stepper::new(&cfg).unwrap();
        let mut worst: f64 = 0.0;
        for _ in 0..2000 {
            let t0 = st.time();
            let before: Vec<f64> = st.channels.iter().map(|c| c.g_hat).collect();
            st.advance_sample();
            for (i, c) in st.channels.iter().enumerate() {
                let int_g = integral(g[i], t0, t0 + period);
                // explicit (forward Euler): ĝ_{k+1} − ĝ_k = ∫g − T ĝ_k;
                // implicit (backward Euler): ĝ_{k+1} − ĝ_k = ∫g − T ĝ_{k+1}.
                let lhs = c.g_hat - before[i];
                let rhs = if rule == "explicit" { int_g - period * before[i] } else { int_g - period * c.g_hat };
                worst = worst.max((lhs - rhs).abs() / (1.0 + c.observer.nu.abs()));
            }
        }
        println!("dobc/{rule}: max residual {worst:.2e}");
        assert!(worst < 1e-13, "dobc/{rule}: {worst}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]
    /// Whatever the plant (stiffness, damping, coupling, gains, initial shape), the observer
    /// error dynamics do not depend on it.
    #[test]
    fn sigma_identity_is_plant_independent(
        ei in 0.05f64..2.0, gj in 0.1f64..2.0, xi in 0.0f64..1.5, coupling in 0.0f64..0.9,
        k1 in 0.0f64..10.0, k2 in 0.0f64..10.0, a in 0.0f64..5.0, b in 0.0f64..5.0,
        q_tip in -2.0f64..2.0, cantilever in any::<bool>(), explicit in any::<bool>(),
    ) {
        let rho_xc = coupling * (10.0f64 * 1.5).sqrt(); // keeps ρ I_p > (ρx_c)²
        let cfg = paper_with(&[
            &format!("wing.ei={ei}"), &format!("wing.gj={gj}"), &format!("wing.xi={xi}"),
            &format!("wing.rho_xc={rho_xc}"), &format!("control.k1={k1}"), &format!("control.k2={k2}"),
            &format!("control.a={a}"), &format!("control.b={b}"), &format!("initial.q_tip={q_tip}"),
            &format!("initial.shape={}", if cantilever { "cantilever" } else { "linear" }),
            &format!("observer.rule={}", if explicit { "explicit" } else { "implicit" }),
            "discretisation.elements=8",
        ]);
        let r = ftdo_identity_residual(&cfg, 300);
        prop_assert!(r < 1e-12, "residual {}", r);
    }
}
