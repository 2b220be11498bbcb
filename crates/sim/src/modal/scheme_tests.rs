//! Tests of the modal schemes' steps ([`super`]): the AVX and portable loops, the tip states, the
//! fused tip sums.

use super::*;

/// The AVX loops and the portable ones are the same operations in the same order: after
/// 3000 steps of either implicit scheme (paper wing, an off-default gain pair and dt) the
/// states are equal bit for bit. Where the CPU has no AVX both runs take the portable path
/// (the test then compares a run with itself, and says so).
#[test]
fn avx_and_portable_steps_give_the_same_bits() {
    if !std::arch::is_x86_feature_detected!("avx") {
        println!("skipped: this CPU has no AVX, so there is no second path to compare");
        return;
    }
    for scheme in ["trbdf2", "trapezoid"] {
        let cfg = wingcheck_model::apply_overrides(
            &Config::paper(),
            &[format!("discretisation.stepper={scheme}"), "control.a=3".into(), "discretisation.dt=5e-4".into()],
        )
        .unwrap();
        let basis = ModalBasis::new(&cfg).unwrap();
        let (fast, portable) =
            (ModalLoop::new(&cfg, &basis).unwrap(), ModalLoop::new(&cfg, &basis).unwrap().without_avx());
        let (mut a, mut b) = (fast.initial_state(&cfg, &basis), portable.initial_state(&cfg, &basis));
        for j in 0..3000 {
            let s = j as f64 * 1e-3;
            let input = StepInput { phi: s.cos(), tip_input: [0.1 * s.sin(), -0.2], g_hat: [0.3, (-1f64).powi(j)] };
            fast.step(&mut a, &input);
            portable.step(&mut b, &input);
        }
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&a.eta), bits(&b.eta), "{scheme}");
        assert_eq!(bits(&a.zeta), bits(&b.zeta), "{scheme}");
        assert_eq!((a.x_tip, a.v_tip, a.w), (b.x_tip, b.v_tip, b.w), "{scheme}");
        assert!(a.eta.iter().any(|x| *x != 0.0));
    }
}

/// Without the tip states (the search's steps), TR-BDF2 leaves w at its start and every
/// other value is the same bits as with them (w does not feed back); with them, w moves.
#[test]
fn steps_without_tip_states_change_nothing_else() {
    let cfg = Config::paper();
    let basis = ModalBasis::new(&cfg).unwrap();
    let lp = ModalLoop::new(&cfg, &basis).unwrap();
    let (mut a, mut b) = (lp.initial_state(&cfg, &basis), lp.initial_state(&cfg, &basis));
    let w0 = b.w;
    for j in 0..500 {
        let s = j as f64 * 1e-3;
        let input = StepInput { phi: s.cos(), tip_input: [0.1 * s.sin(), -0.2], g_hat: [0.3, (-1f64).powi(j)] };
        lp.step_with(&mut a, &input, true);
        lp.step_with(&mut b, &input, false);
    }
    assert_eq!(b.w, w0);
    assert_ne!(a.w, w0);
    b.w = a.w;
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&a.eta), bits(&b.eta));
    assert_eq!(bits(&a.zeta), bits(&b.zeta));
    assert_eq!((a.x_tip, a.v_tip), (b.x_tip, b.v_tip));
}

/// The fused tip sums are [`dot`]'s sums bit for bit, with and without a tail beyond the
/// last full pack of [`LANES`].
#[test]
fn tip_dots_are_dots() {
    for n in [3, 8, 16, 21, 72, 75] {
        let v = |k: f64| (0..n).map(|i| ((i as f64 + 1.0) * k).sin() * 10f64.powi(i % 7 - 3)).collect::<Vec<_>>();
        let (u, eta, zeta) = ([v(0.7), v(1.3)], v(2.1), v(0.37));
        let fused = tip_dots(&u, &eta, &zeta);
        let single = [dot(&u[0], &eta), dot(&u[1], &eta), dot(&u[0], &zeta), dot(&u[1], &zeta)];
        assert_eq!(fused.map(f64::to_bits), single.map(f64::to_bits), "n = {n}");
    }
}
