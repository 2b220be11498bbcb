//! Property tests of what Theorems 3–4 promise where their hypotheses hold: σ reaches 0 no
//! later than the bound (38)/(39) in the Filippov limit, and (up to one sample) with the
//! implicit digital observer, which then stays in |σ| ≤ T·ζ; the tip response stays bounded.
//! Cases: `PROPTEST_CASES` (default 24); shrunk failures persist in `proptest-regressions/`.

use proptest::prelude::*;
use wingcheck_claims::finite_time::reach::{bound_38, digital_run, filippov_reach, zeta};
use wingcheck_control::ObserverGain;
use wingcheck_model::{apply_overrides, Config, ObserverRule};
use wingcheck_sim::{simulate, RunOptions};

fn cases() -> u32 {
    std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(24)
}

/// Odd (a1, a2) with a1 < a2 < 2 a1.
const PAIRS: [(u32, u32); 6] = [(3, 5), (5, 7), (5, 9), (7, 9), (7, 13), (9, 17)];

proptest! {
    #![proptest_config(ProptestConfig { cases: cases() * 8, ..ProptestConfig::default() })]

    /// Filippov limit: reaching time ≤ bound for any gains and any g with sup|g| ≤ κ_sw.
    #[test]
    fn filippov_reaching_time_is_within_the_bound(
        lin in 0.05f64..5.0, sw in 0.1f64..3.0, frac in 0.1f64..10.0, pair in 0usize..PAIRS.len(),
        s0 in 1e-4f64..100.0, neg in any::<bool>(), share in 0.0f64..1.0, split in 0.0f64..1.0,
        freq in 0.0f64..30.0, phase_sign in any::<bool>(),
    ) {
        let (a1, a2) = PAIRS[pair];
        let gain = ObserverGain { linear: lin, switching: sw, fractional: frac,
            exponent: (2 * a1 - a2) as f64 / a2 as f64 };
        // sup|g| = |mean| + |amp| = share·κ_sw ≤ κ_sw (Assumption 1 with the hypothesis of Thm 3).
        let (mean, amp) = (share * sw * split, share * sw * (1.0 - split) * if phase_sign { 1.0 } else { -1.0 });
        let sigma0 = if neg { -s0 } else { s0 };
        let f = filippov_reach(&gain, &|t| mean + amp * (freq * t).sin(), sigma0, 100.0, 400).unwrap();
        let bound = bound_38(lin, frac, a1, a2, sigma0).unwrap();
        let t = f.reach_s.expect("reaches 0");
        prop_assert_eq!(f.method, wingcheck_claims::finite_time::reach::SIGMA_DOMAIN);
        prop_assert!(t <= bound * (1.0 + 1e-6) + f.error_s, "t = {} > bound {}", t, bound);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: cases(), ..ProptestConfig::default() })]

    /// Closed loop with the implicit digital observer: reaching within bound + one sample, then
    /// |σ_k| ≤ T ζ; g̃ at the samples O(T ġ); tip response bounded.
    #[test]
    fn implicit_observer_reaches_within_bound_and_stays(
        cantilever in any::<bool>(), q_tip in -1.5f64..1.5, theta_tip in -2.0f64..2.0,
        nu1 in -2.0f64..2.0, nu2 in -2.0f64..2.0,
        m1 in -0.5f64..0.5, m2 in -0.5f64..0.5, f1 in 0.0f64..5.0, f2 in 0.0f64..5.0,
        k3 in 0.5f64..8.0, half_ms in any::<bool>(),
    ) {
        // |mean| + |amp| ≤ 0.9 < κ2 = κ5 = 1.
        let (a1, a2) = (0.9 * m1.signum() - m1, 0.9 * m2.signum() - m2);
        let period = if half_ms { 5e-4 } else { 1e-3 };
        let sets: Vec<String> = vec![
            format!("initial.shape={}", if cantilever { "cantilever" } else { "linear" }),
            format!("initial.q_tip={q_tip}"), format!("initial.theta_tip={theta_tip}"),
            format!("observer.nu1_0={nu1}"), format!("observer.nu2_0={nu2}"),
            format!("observer.kappa3={k3}"), format!("observer.kappa6={k3}"),
            format!("disturbance.tip_bending.mean={m1}"), format!("disturbance.tip_bending.amp={a1}"),
            format!("disturbance.tip_bending.freq={f1}"),
            format!("disturbance.tip_torsion.mean={m2}"), format!("disturbance.tip_torsion.amp={a2}"),
            format!("disturbance.tip_torsion.freq={f2}"),
            format!("observer.sample_period={period}"), format!("discretisation.dt={period}"),
            "horizon.t_end=4".into(),
        ];
        let cfg = apply_overrides(&Config::paper(), &sets).unwrap();
        let run = digital_run(&cfg, None, ObserverRule::Implicit, period, 2.0, 0.5, None).unwrap();
        let o = &cfg.observer;
        let gs = [&cfg.disturbance.tip_bending, &cfg.disturbance.tip_torsion];
        for (i, ch) in run.channels.iter().enumerate() {
            let bound = if i == 0 { bound_38(o.kappa1, o.kappa3, o.a1, o.a2, ch.sigma0) }
                        else { bound_38(o.kappa4, o.kappa6, o.b1, o.b2, ch.sigma0) }.unwrap();
            prop_assume!(bound < 1.4); // leave the 0.5-s window after reaching
            let reach = ch.reach_s.expect("implicit observer reaches the band");
            prop_assert!(reach <= bound + period + 1e-12, "ch {}: reach {} > bound {} + T", i, reach, bound);
            let z = zeta(gs[i]);
            prop_assert!(ch.sigma_after_max <= period * z * (1.0 + 1e-9) + 1e-14,
                "ch {}: |σ| after = {} > T ζ = {}", i, ch.sigma_after_max, period * z);
            let gdot = (gs[i].amp * gs[i].freq).abs();
            prop_assert!(ch.gtilde_max <= period * gdot * 1.01 + 1e-12, "ch {}: g̃ {}", i, ch.gtilde_max);
        }
        // Bounded tip response over 4 s (Theorem 2's UUB, loosely): finite and moderate.
        let out = simulate(&cfg, RunOptions::default()).unwrap();
        let scale = 1.0 + q_tip.abs() + theta_tip.abs();
        let qmax = out.series.q_tip.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let tmax = out.series.theta_tip.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        prop_assert!(qmax.is_finite() && qmax <= 10.0 * scale, "q max {}", qmax);
        prop_assert!(tmax.is_finite() && tmax <= 10.0 * scale, "θ max {}", tmax);
    }
}

/// Filippov reaching time against its closed form: with no fractional term and a constant g,
/// σ̇ = −(κ_lin σ + c) with c = κ_sw − s0·g > 0 reaches 0 at t = ln((κ_lin|σ0| + c)/c)/κ_lin
/// (|σ0|/c for κ_lin = 0; integrate dσ/(κ_lin σ + c)). The computed ± covers the difference
/// and is never below the summation's round-off floor ((2·steps) ε t).
#[test]
fn filippov_reaching_time_matches_its_closed_form_within_its_error() {
    for (lin, sw, g, s0) in
        [(0.5, 1.0, 0.3, 2.0), (3.0, 0.2, -0.1, -0.7), (0.0, 1.5, 0.5, 0.05), (20.0, 0.8, 0.7, 40.0)]
    {
        let gain = ObserverGain { linear: lin, switching: sw, fractional: 0.0, exponent: 0.6 };
        let c: f64 = sw - f64::signum(s0) * g;
        let exact = if lin > 0.0 { ((lin * f64::abs(s0) + c) / c).ln() / lin } else { f64::abs(s0) / c };
        let steps = 2000;
        let f = filippov_reach(&gain, &|_| g, s0, 100.0, steps).unwrap();
        let t = f.reach_s.expect("reaches 0");
        assert!((t - exact).abs() <= f.error_s, "{lin} {sw} {g} {s0}: |{t} − {exact}| > {}", f.error_s);
        assert!(f.error_s >= (2 * steps) as f64 * f64::EPSILON * exact, "{}: below the round-off floor", f.error_s);
    }
}
