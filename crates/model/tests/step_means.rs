//! The disturbances' exact step means (what every integrator step's held inputs are) against
//! an independent quadrature, and the per-step forms with the factors computed once against
//! the forms from the step's ends; `Disturbance::step_means`, which every time scheme holds, is
//! these per-step forms.

use proptest::prelude::*;
use wingcheck_model::{Distributed, Disturbance, TipDisturbance};

/// (1/(b − a))∫_a^b f by 5-point Gauss–Legendre on 64 panels: the error is of order
/// (ω(b − a)/64)^10 / 10! relative, below 1e-16 for ω(b − a) ≤ 20.
fn quadrature_mean(f: impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    const NODES: [f64; 5] =
        [-0.906_179_845_938_664, -0.538_469_310_105_683, 0.0, 0.538_469_310_105_683, 0.906_179_845_938_664];
    const WEIGHTS: [f64; 5] = [
        0.236_926_885_056_189,
        0.478_628_670_499_366,
        0.568_888_888_888_889,
        0.478_628_670_499_366,
        0.236_926_885_056_189,
    ];
    let panels = 64;
    let w = (b - a) / panels as f64;
    let mut sum = 0.0;
    for p in 0..panels {
        let mid = a + (p as f64 + 0.5) * w;
        for (x, c) in NODES.iter().zip(WEIGHTS) {
            sum += c * 0.5 * f(mid + 0.5 * w * x);
        }
    }
    sum / panels as f64
}

proptest! {
    #[test]
    fn step_means_are_the_exact_means_over_the_step(
        t0 in 0.0f64..100.0,
        h in prop_oneof![1e-6f64..1e-4, 1e-4f64..1e-2, 1e-2f64..0.5],
        freq in 0.1f64..40.0,
        amp in -5.0f64..5.0,
        mean in -2.0f64..2.0,
    ) {
        let load = Distributed { mean, cos_amp: amp, cos_freq: 3.0 * freq, sin_amp: 0.5 - amp, sin_freq: freq, slope: 1.0 / 30.0 };
        let tip = TipDisturbance { mean, amp, freq };
        let scale = mean.abs() + 2.0 * amp.abs() + 0.5;
        // the quadrature is independent of both closed forms; its own error and the round-off
        // of φ's values at t0 ≤ 100 s (ω t up to 1.2e4 rad: ε·ωt ≈ 3e-12) bound the difference
        let tol = 1e-11 * scale;
        let phi = load.step_mean(t0, h, load.step_factors(h));
        let reference = quadrature_mean(|t| load.phi(t), t0, t0 + h);
        prop_assert!((phi - reference).abs() <= tol, "φ mean {phi} against quadrature {reference}");
        let g = tip.step_mean(t0, h, tip.step_factor(h));
        let reference = quadrature_mean(|t| tip.at(t), t0, t0 + h);
        prop_assert!((g - reference).abs() <= tol, "g mean {g} against quadrature {reference}");
        // and the general-interval forms from the step's ends: the same to
        // round-off, which there includes the rounding of t0 + h (their interval
        // fl(t0 + h) − t0 differs from h by up to ε(t0 + h), relative ε(t0 + h)/h)
        let ends = tol + 2.0 * f64::EPSILON * (t0 + h) / h * scale;
        prop_assert!((phi - load.phi_integral(t0, t0 + h) / h).abs() <= ends);
        prop_assert!((g - tip.mean_over(t0, t0 + h)).abs() <= ends);
        // what the time schemes hold: the same per-step forms, bit for bit
        let d = Disturbance { distributed: load.clone(), tip_bending: tip.clone(), tip_torsion: tip.clone() };
        let (phi_held, g_held) = d.step_means(h).over_step(t0);
        prop_assert_eq!(phi_held.to_bits(), phi.to_bits());
        prop_assert_eq!(g_held.map(f64::to_bits), [g.to_bits(); 2]);
    }
}

proptest! {
    /// The step-after-step means ([`wingcheck_model::MeanSteps`], the modal observer signal's)
    /// and tip values ([`wingcheck_model::TipValues`]) against the exact per-step forms over a
    /// run of consecutive steps t_n = k·T + j·h as the runs form them: within their stated
    /// bounds everywhere, and the same bits at the anchors (every 16th step).
    #[test]
    fn step_after_step_values_are_the_exact_ones_within_their_bound(
        h in prop_oneof![1e-5f64..1e-3, 1e-3f64..2e-2],
        freq in 0.1f64..40.0,
        amp in -5.0f64..5.0,
        mean in -2.0f64..2.0,
    ) {
        let load = Distributed { mean, cos_amp: amp, cos_freq: 3.0 * freq, sin_amp: 0.5 - amp, sin_freq: freq, slope: 1.0 / 30.0 };
        let tip = TipDisturbance { mean, amp, freq };
        let d = Disturbance { distributed: load, tip_bending: tip.clone(), tip_torsion: TipDisturbance { freq: 0.7 * freq, ..tip } };
        let exact = d.step_means(h);
        let mut steps = exact.steps();
        let mut values = d.tip_values(h);
        let steps_total = 4000;
        let t_max = steps_total as f64 * h;
        let (phi_bound, g_bound) = steps.error_bound(t_max);
        let value_bound = values.error_bound(t_max);
        for n in 0..steps_total {
            // 5 steps per sample period, as ObserverSignal::advance forms the times
            let t = (n / 5) as f64 * (5.0 * h) + (n % 5) as f64 * h;
            let (phi, g) = steps.over_step(t);
            let (phi_exact, g_exact) = exact.over_step(t);
            prop_assert!((phi - phi_exact).abs() <= phi_bound, "φ̄ at step {n}: {phi} against {phi_exact}");
            for c in 0..2 {
                prop_assert!((g[c] - g_exact[c]).abs() <= g_bound[c], "ḡ{c} at step {n}");
            }
            if n % 16 == 0 {
                prop_assert_eq!((phi.to_bits(), g.map(f64::to_bits)), (phi_exact.to_bits(), g_exact.map(f64::to_bits)));
            }
            let v = values.at(t + h);
            let v_exact = [d.tip_bending.at(t + h), d.tip_torsion.at(t + h)];
            for c in 0..2 {
                prop_assert!((v[c] - v_exact[c]).abs() <= value_bound[c], "g{c}({}) at step {n}", t + h);
            }
        }
        // the bounds are small against the disturbances
        prop_assert!(phi_bound <= 1e-9 * (amp.abs() + 1.0) && g_bound[0] <= 1e-9 * (amp.abs() + 1.0));
    }
}
