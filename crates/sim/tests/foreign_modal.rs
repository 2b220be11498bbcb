//! A controller of any origin in the modal basis ([`wingcheck_sim::modal::ControlledSignal`]):
//! the held inputs sampled from the modal state at every t_k give the built-in controllers'
//! modal runs, which take their held inputs from the precomputed observer signal.

use wingcheck_control::{BoundaryLaw, BuiltIn, ControlError, Controller, Erased, Held, TipMeasurement};
use wingcheck_model::{Config, ControllerKind, ObserverRule, StepBasis, TimeScheme};
use wingcheck_sim::{simulate, BoxedController, RunOptions, SimError, SimOutput};

/// Law (15) without an observer, written outside the built-ins: the continuous part of the
/// configuration and no held input.
struct OwnPd {
    law: BoundaryLaw,
}

impl Controller for OwnPd {
    type Error = ControlError;
    fn continuous(&self) -> BoundaryLaw {
        self.law
    }
    fn reset(&mut self, cfg: &Config) -> Result<(), ControlError> {
        let c = &cfg.control;
        self.law = BoundaryLaw { gains: [c.k1, c.k2], a: c.a, b: c.b };
        Ok(())
    }
    fn sample(&mut self, _tip: &TipMeasurement) -> Result<Held, ControlError> {
        Ok(Held { input: [0.0; 2], sigma: [0.0; 2] })
    }
}

fn run(cfg: &Config, make: Option<&(dyn Fn() -> BoxedController + Sync)>) -> Result<SimOutput, SimError> {
    simulate(cfg, RunOptions { controller: make, ..Default::default() })
}

/// max |a − b| / max |b| over a column.
fn relative(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    a.iter().zip(b).fold(0.0f64, |m, (x, y)| m.max((x - y).abs())) / scale
}

#[test]
fn an_own_pd_in_the_modal_basis_gives_the_builtin_pd_bits() {
    // Reference: the built-in PD's modal run. Its held input is ĝ = 0 from the observer signal;
    // the own PD's is −u = −0 sampled from the state: the same law in the same loop, so every
    // state value is the same bits (a zero may differ in sign only, and == ignores that).
    let mut cfg = Config::paper();
    cfg.control.kind = ControllerKind::Pd;
    for (a, b) in [(cfg.control.a, cfg.control.b), (1.0, 3000.0)] {
        (cfg.control.a, cfg.control.b) = (a, b);
        let reference = run(&cfg, None).unwrap();
        let make = || -> BoxedController { Box::new(OwnPd { law: BoundaryLaw { gains: [0.0; 2], a: 0.0, b: 0.0 } }) };
        let own = run(&cfg, Some(&make)).unwrap();
        assert_eq!(reference.stats.basis, StepBasis::Modal);
        assert_eq!(own.stats.basis, StepBasis::Modal, "auto resolves to modal for a foreign controller too");
        let (r, o) = (&reference.series, &own.series);
        for (name, x, y) in [
            ("q", &o.q_tip, &r.q_tip),
            ("theta", &o.theta_tip, &r.theta_tip),
            ("q rate", &o.q_tip_rate, &r.q_tip_rate),
            ("theta rate", &o.theta_tip_rate, &r.theta_tip_rate),
            ("tau1", &o.tau1, &r.tau1),
            ("tau2", &o.tau2, &r.tau2),
            ("energy", &o.energy, &r.energy),
            ("q'''", &o.q_tip_shear, &r.q_tip_shear),
            ("tau1 rms", &o.tau1_rms, &r.tau1_rms),
        ] {
            assert!(x == y, "{name} at a = {a}, b = {b}");
        }
        // the full-rate peaks of q, θ, q̇, θ̇, τ1, τ2, g̃1, g̃2 (with the initial layer's runs)
        for (o, r) in own.peaks.signals().iter().zip(reference.peaks.signals()) {
            assert_eq!((o.abs_max, o.t), (r.abs_max, r.t));
        }
    }
}

#[test]
fn builtin_observers_handed_over_as_foreign_controllers_reproduce_their_modal_runs() {
    // Reference: the built-in FTDO (both rules) and DOBC modal runs, whose observer advances σ
    // by σ_{n+1} − σ_n = h(ḡ − ĝ_k). Handed over as Box<dyn Controller>, the same observer
    // integrates ν from the period's quadratures of τ and w the modal runner hands it and
    // measures σ = sξSw − ν: equal to the reference up to the rounding of that identity, which
    // holds to round-off in TR-BDF2's own quadrature (the nodal stepper's). Measured at the
    // paper point: implicit FTDO 7e-15 (q), 1.2e-14 (θ); DOBC 5e-15, 9e-15 relative; bound 1e-9,
    // the one the Python explicit FTDO meets against the nodal run. The explicit rule's
    // sign(σ) turns round-off in σ ≈ 0 into a full switching term for a period: there the
    // reference's own nodal and modal runs (the same equations) differ by 2.1e-6 (q) and
    // 7.2e-6 (θ), the handed-over one from the modal run by 8.4e-6 and 1.4e-5; both must stay
    // within 10 × that nodal–modal difference.
    let mut cfg = Config::paper();
    let cases = [
        (ControllerKind::Ftdo, ObserverRule::Implicit),
        (ControllerKind::Ftdo, ObserverRule::Explicit),
        (ControllerKind::Dobc, ObserverRule::Implicit),
    ];
    for (kind, rule) in cases {
        (cfg.control.kind, cfg.observer.rule) = (kind, rule);
        let reference = run(&cfg, None).unwrap();
        let c = cfg.clone();
        let make = move || -> BoxedController { Box::new(Erased(BuiltIn::of(&c))) };
        let own = run(&cfg, Some(&make)).unwrap();
        assert_eq!(own.stats.basis, StepBasis::Modal);
        let diff = |o: &SimOutput| {
            [
                relative(&o.series.q_tip, &reference.series.q_tip),
                relative(&o.series.theta_tip, &reference.series.theta_tip),
            ]
        };
        let [eq, et] = diff(&own);
        println!("{kind:?} {rule:?}: q {eq:.2e}, theta {et:.2e} relative");
        if rule == ObserverRule::Implicit {
            assert!(eq <= 1e-9 && et <= 1e-9, "{kind:?} {rule:?}: {eq:e} {et:e}");
        } else {
            let mut nodal_cfg = cfg.clone();
            nodal_cfg.discretisation.basis = StepBasis::Nodal;
            let [nq, nt] = diff(&run(&nodal_cfg, None).unwrap());
            println!("  the built-in's nodal run: q {nq:.2e}, theta {nt:.2e} relative");
            assert!(eq <= 10.0 * nq && et <= 10.0 * nt && nq <= 1e-4, "{eq:e} {et:e} against {nq:e} {nt:e}");
        }
    }
}

#[test]
fn the_exponential_scheme_runs_a_foreign_controller() {
    // Reference: the built-in implicit FTDO under the exponential scheme. A foreign observer gets
    // the trapezoid of each exact step's ends as its quadrature (the exact steps carry no ∫τ, ∫w),
    // a second-order rule: its ν drifts from the exact one by O(h²), so halving dt (at the same
    // T_s) must shrink the difference about 4-fold (≥ 3-fold asserted at each halving). Measured
    // at the paper point over 5 s: 6.9e-6, 2.0e-6, 5.9e-7 relative at dt = 1, 0.5, 0.25 ms
    // (ratios 3.4, 3.4); bound 1e-4 at dt = 1 ms.
    let mut cfg = Config::paper();
    cfg.discretisation.stepper = TimeScheme::Exponential;
    cfg.horizon.t_end = 5.0;
    let mut errors = Vec::new();
    for dt in [cfg.discretisation.dt, 0.5 * cfg.discretisation.dt, 0.25 * cfg.discretisation.dt] {
        cfg.discretisation.dt = dt;
        let reference = run(&cfg, None).unwrap();
        let c = cfg.clone();
        let make = move || -> BoxedController { Box::new(Erased(BuiltIn::of(&c))) };
        let own = run(&cfg, Some(&make)).unwrap();
        assert_eq!(own.stats.stepper, TimeScheme::Exponential);
        let e = relative(&own.series.q_tip, &reference.series.q_tip);
        println!("exponential FTDO, dt = {dt} s: q {e:.2e} relative");
        errors.push(e);
    }
    assert!(errors[0] <= 1e-4, "{errors:?}");
    assert!(errors.windows(2).all(|w| w[1] * 3.0 <= w[0]), "not second order: {errors:?}");
}

#[test]
fn a_failing_controller_stops_the_modal_run_at_its_time() {
    struct Fails;
    impl Controller for Fails {
        type Error = ControlError;
        fn continuous(&self) -> BoundaryLaw {
            BoundaryLaw { gains: [0.0; 2], a: 0.0, b: 0.0 }
        }
        fn reset(&mut self, _cfg: &Config) -> Result<(), ControlError> {
            Ok(())
        }
        fn sample(&mut self, tip: &TipMeasurement) -> Result<Held, ControlError> {
            if tip.t >= 0.5 {
                return Err(ControlError::Failed { t: tip.t, message: "gave up".into() });
            }
            Ok(Held { input: [0.0; 2], sigma: [0.0; 2] })
        }
    }
    let make = || -> BoxedController { Box::new(Fails) };
    let cfg = Config::paper();
    match run(&cfg, Some(&make)) {
        // t_k = k T_s: the first sample at or after 0.5 s (T_s = 1 ms: k = 500)
        Err(SimError::Control(ControlError::Failed { t, .. })) => assert_eq!(t, 500.0 * cfg.observer.sample_period),
        other => panic!("expected the controller's failure, got {:?}", other.map(|o| o.stats)),
    }
}
