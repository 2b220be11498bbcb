//! The step form ([`wingcheck_sim::SteppedRun`]) against the callback form (`simulate` with a
//! controller): a controller that computes its held inputs from the tip measurements, once
//! as a callback and once by a driver stepping the loop, must see the same measurements at
//! every sample, bit for bit, in the modal basis (the default) and the nodal one, under each
//! time scheme; the energies the step form gives out equal the callback run's series at its
//! output samples. Independent truth: the callback run (`simulate_base`), whose controller
//! records what it was given.

use std::sync::{Arc, Mutex};

use wingcheck_control::{BoundaryLaw, ControlError, Controller, Held, PeriodIntegrals, TipMeasurement};
use wingcheck_model::{apply_overrides, Config, StepBasis};
use wingcheck_sim::{simulate_base, BoxedController, RunOptions, SimError, SteppedRun};

/// A saturated tip feedback of the measurements (not law (15)'s held input): the rule both
/// forms apply.
fn rule(tip: &TipMeasurement, integrals: &PeriodIntegrals) -> [f64; 2] {
    let sat = |u: f64| u.clamp(-0.5, 0.5);
    [sat(-3.0 * tip.v[0] - 0.1 * integrals.tau[0]), sat(-0.7 * tip.v[1] + 0.01 * tip.w[1])]
}

fn law_of(cfg: &Config) -> BoundaryLaw {
    let c = &cfg.control;
    BoundaryLaw { gains: [c.k1, c.k2], a: c.a, b: c.b }
}

/// The callback form's controller: applies [`rule`] and records what it saw.
struct Recording {
    law: BoundaryLaw,
    integrals: PeriodIntegrals,
    seen: Arc<Mutex<Vec<(TipMeasurement, PeriodIntegrals)>>>,
}

impl Controller for Recording {
    type Error = ControlError;
    fn continuous(&self) -> BoundaryLaw {
        self.law
    }
    fn reset(&mut self, _cfg: &Config) -> Result<(), ControlError> {
        self.integrals = PeriodIntegrals::default();
        Ok(())
    }
    fn integrate(&mut self, h: f64, tau_mean: [f64; 2], w_mean: [f64; 2]) {
        self.integrals.add(h, tau_mean, w_mean);
    }
    fn sample(&mut self, tip: &TipMeasurement) -> Result<Held, ControlError> {
        let integrals = self.integrals.take();
        self.seen.lock().unwrap().push((*tip, integrals));
        Ok(Held { input: rule(tip, &integrals), sigma: [0.0; 2] })
    }
}

#[test]
fn the_step_form_gives_the_callback_forms_bits_in_every_basis_and_scheme() {
    let cases: [&[&str]; 4] = [
        &[],
        &["discretisation.basis=nodal"],
        &["discretisation.stepper=exponential", "control.a=1", "control.b=3000"],
        &["discretisation.stepper=trapezoid", "discretisation.method=fd", "discretisation.grading=0", "wing.xi=0.3"],
    ];
    for sets in cases {
        let mut over: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        over.push("horizon.t_end=0.5".into());
        let cfg = apply_overrides(&Config::paper(), &over).unwrap();
        let seen = Arc::new(Mutex::new(Vec::new()));
        let make = || -> BoxedController {
            Box::new(Recording { law: law_of(&cfg), integrals: PeriodIntegrals::default(), seen: seen.clone() })
        };
        let callback = simulate_base(&cfg, RunOptions { controller: Some(&make), ..Default::default() }).unwrap();
        let expected_basis =
            if sets.contains(&"discretisation.basis=nodal") { StepBasis::Nodal } else { StepBasis::Modal };
        assert_eq!(callback.stats.basis, expected_basis, "{sets:?}");
        let seen = seen.lock().unwrap().clone();

        let (mut run, mut sample) = SteppedRun::start(&cfg, law_of(&cfg)).unwrap();
        let mut energies = vec![sample.energy];
        for (k, (tip, integrals)) in seen.iter().enumerate() {
            assert_eq!((&sample.tip, &sample.integrals), (tip, integrals), "{sets:?}: sample {k}");
            if k + 1 == seen.len() {
                break;
            }
            sample = run.step(rule(&sample.tip, &sample.integrals)).unwrap();
            energies.push(sample.energy);
        }
        // the callback form's series at its outputs (every sample_every) carries the same energies
        let every = cfg.samples_per_output();
        for (i, e) in callback.series.energy.iter().enumerate() {
            assert_eq!(*e, energies[(i * every).min(energies.len() - 1)], "{sets:?}: output {i}");
        }
        // one more period ends the run: the horizon is reached
        let last = rule(&sample.tip, &sample.integrals);
        assert!(matches!(run.step(last), Err(SimError::HorizonEnded { .. })), "{sets:?}");
        assert!(matches!(run.step(last), Err(SimError::HorizonEnded { .. })), "{sets:?}: and stays ended");
    }
}

#[test]
fn bad_inputs_divergence_and_early_drop_end_the_run_cleanly() {
    let cfg = apply_overrides(&Config::paper(), &["horizon.t_end=0.05".to_string()]).unwrap();
    let (mut run, _) = SteppedRun::start(&cfg, law_of(&cfg)).unwrap();
    run.step([0.1, 0.0]).unwrap();
    let err = run.step([f64::NAN, 0.0]).unwrap_err();
    assert!(matches!(err, SimError::Control(ControlError::NonFinite { name: "tau1", .. })), "{err}");
    // a rejected input leaves the run where it was
    let next = run.step([0.0, 0.0]).unwrap();
    assert!((next.tip.t - 2.0 * cfg.observer.sample_period).abs() < 1e-12, "{}", next.tip.t);
    // a huge held force drives the energy past the divergence limit
    let (mut wild, _) = SteppedRun::start(&cfg, law_of(&cfg)).unwrap();
    let err = (0..40).find_map(|_| wild.step([1e150, -1e150]).err()).expect("diverges");
    let SimError::Diverged { t, .. } = err else { panic!("{err}") };
    // and says so again, not that the horizon was reached
    assert!(matches!(wild.step([0.0, 0.0]), Err(SimError::Diverged { t: again, .. }) if again == t));
    // dropped mid-run: the worker ends (the test would hang otherwise)
    let (early, _) = SteppedRun::start(&cfg, law_of(&cfg)).unwrap();
    drop(early);
    // an invalid continuous part is refused before any thread starts
    let bad = BoundaryLaw { gains: [-1.0, 0.0], a: 1.0, b: 1.0 };
    assert!(SteppedRun::start(&cfg, bad).is_err());
}
