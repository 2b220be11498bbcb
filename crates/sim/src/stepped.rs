//! The closed loop driven one sample period at a time from outside (the step form of
//! `simulate` with a controller; Python's `Wing`, reinforcement-learning and co-simulation
//! codes): [`SteppedRun`].
//!
//! It *is* the callback form's run: [`crate::simulate_base`] with a controller
//! ([`crate::RunOptions::controller`]) on a worker thread, in the basis and scheme the
//! configuration resolves to (modal by default), whose controller hands each sample's
//! measurements out and waits for the held inputs that come back. So the same inputs give the
//! same bits as `simulate(config, controller=f)`, whatever the basis, with no second stepping
//! loop to keep in step with the first. Each sample period costs the run's own steps plus one
//! hand-over between two threads (≈ 30 µs per period measured from Python, docs/python.md; the
//! same-thread nodal stepper it replaced took a few µs, but stepped the nodal basis only and so
//! did not give the default run's bits).
//!
//! The run ends at the configuration's horizon: a step past t_end is
//! [`SimError::HorizonEnded`]; once a run has ended (horizon, divergence, an error) every later
//! step repeats why. Dropping the [`SteppedRun`] ends its worker at its next sample.

use std::sync::mpsc::{sync_channel, Receiver, SyncSender};
use std::sync::Mutex;
use std::thread::JoinHandle;

use wingcheck_control::{BoundaryLaw, ControlError, Controller, Held, PeriodIntegrals, TipMeasurement};
use wingcheck_model::Config;

use crate::run::check_values;
use crate::{simulate_base, BoxedController, RunOptions, SimError};

/// What the loop gives out at a sample t_k.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteppedSample {
    /// The tip measurements at t_k (Remark 2: t, q(s), θ(s), q̇(s), θ̇(s), q'''(s), θ'(s)).
    pub tip: TipMeasurement,
    /// ∫τ dt and ∫w dt over the period that just ended (zero at t = 0).
    pub integrals: PeriodIntegrals,
    /// The loop's mechanical energy E(t_k) (J).
    pub energy: f64,
}

/// The worker's controller: continuous part `law`, held inputs from the driver.
struct Remote {
    law: BoundaryLaw,
    inputs: Receiver<[f64; 2]>,
    samples: SyncSender<SteppedSample>,
    integrals: PeriodIntegrals,
    energy: f64,
}

impl Controller for Remote {
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
    fn wants_energy(&self) -> bool {
        true
    }
    fn energy(&mut self, _t: f64, energy: f64) {
        self.energy = energy;
    }
    fn sample(&mut self, tip: &TipMeasurement) -> Result<Held, ControlError> {
        let out = SteppedSample { tip: *tip, integrals: self.integrals.take(), energy: self.energy };
        let t = tip.t;
        self.samples.send(out).map_err(|_| ControlError::Detached { t })?;
        let input = self.inputs.recv().map_err(|_| ControlError::Detached { t })?;
        Ok(Held { input, sigma: [0.0; 2] })
    }
}

/// A closed-loop run of a configuration stepped from outside (see the module documentation).
#[derive(Debug)]
pub struct SteppedRun {
    inputs: Option<SyncSender<[f64; 2]>>,
    samples: Receiver<SteppedSample>,
    worker: Option<JoinHandle<Result<(), SimError>>>,
    t_end: f64,
    e0: f64,
    /// t_k of the latest sample given out (s).
    t: f64,
    /// Why the run ended, once it has (repeated by every later step).
    ended: Option<Ended>,
}

/// How a [`SteppedRun`] ended, kept to say so again.
#[derive(Debug, Clone)]
enum Ended {
    Horizon,
    Diverged { t: f64, reason: String },
    Failed(String),
}

impl Ended {
    /// The end a run's error makes (a divergence is said again as one; anything else as a failure).
    fn of(e: &SimError) -> Ended {
        match e {
            SimError::Diverged { t, reason } => Ended::Diverged { t: *t, reason: reason.clone() },
            other => Ended::Failed(other.to_string()),
        }
    }

    fn error(&self, t_end: f64) -> SimError {
        match self {
            Ended::Horizon => SimError::HorizonEnded { t_end },
            Ended::Diverged { t, reason } => SimError::Diverged { t: *t, reason: reason.clone() },
            Ended::Failed(why) => SimError::EndedEarlier { why: why.clone() },
        }
    }
}

impl SteppedRun {
    /// Start the run of `cfg` under the continuous part `law` (k1, k2, a, b of law (15)); the
    /// measurements at t = 0. Errors: an invalid configuration or continuous part, a failed
    /// set-up (as `simulate` reports them).
    pub fn start(cfg: &Config, law: BoundaryLaw) -> Result<(SteppedRun, SteppedSample), SimError> {
        cfg.validate()?;
        law.check()?;
        let (input_tx, input_rx) = sync_channel(1);
        let (sample_tx, sample_rx) = sync_channel(1);
        let remote = Remote { law, inputs: input_rx, samples: sample_tx, integrals: Default::default(), energy: 0.0 };
        let cfg = cfg.clone();
        let t_end = cfg.horizon.t_end;
        let worker = std::thread::Builder::new()
            .name("wingcheck-stepped".into())
            .spawn(move || {
                // the run makes its controller once (simulate_base has no refinement runs)
                let slot = Mutex::new(Some(remote));
                let make = || -> BoxedController {
                    match slot.lock().ok().and_then(|mut s| s.take()) {
                        Some(remote) => Box::new(remote),
                        None => Box::new(Remote::detached(law)),
                    }
                };
                simulate_base(&cfg, RunOptions { controller: Some(&make), ..Default::default() }).map(drop)
            })
            .map_err(SimError::Thread)?;
        let mut run = SteppedRun {
            inputs: Some(input_tx),
            samples: sample_rx,
            worker: Some(worker),
            t_end,
            e0: 0.0,
            t: 0.0,
            ended: None,
        };
        let first = match run.samples.recv() {
            Ok(first) => first,
            Err(_) => return Err(run.finish()),
        };
        run.e0 = first.energy;
        Ok((run, first))
    }

    /// Hold `input` = (τ1 (N), τ2 (N m)) over the next sample period and advance; the
    /// measurements at its end. Errors: a non-finite input, a diverged loop (non-finite
    /// measurements or the energy above the divergence limit), the horizon's end.
    pub fn step(&mut self, input: [f64; 2]) -> Result<SteppedSample, SimError> {
        if let Some(ended) = &self.ended {
            return Err(ended.error(self.t_end));
        }
        for (name, value) in [("tau1", input[0]), ("tau2", input[1])] {
            if !value.is_finite() {
                return Err(ControlError::NonFinite { t: self.t, name, value }.into());
            }
        }
        let sent = self.inputs.as_ref().is_some_and(|inputs| inputs.send(input).is_ok());
        let received = if sent { self.samples.recv().ok() } else { None };
        let Some(sample) = received else {
            return Err(self.finish());
        };
        let tip = &sample.tip;
        self.t = tip.t;
        let values = [
            ("q(s,t)", tip.x[0]),
            ("θ(s,t)", tip.x[1]),
            ("q̇(s,t)", tip.v[0]),
            ("θ̇(s,t)", tip.v[1]),
            ("q'''(s,t)", tip.w[0]),
            ("θ'(s,t)", tip.w[1]),
        ];
        if let Err(e) = check_values(tip.t, &values, sample.energy, self.e0) {
            self.ended = Some(Ended::of(&e));
            self.stop();
            return Err(e);
        }
        Ok(sample)
    }

    /// End the worker and say why no sample came: its error, or the horizon's end (kept for
    /// later steps).
    fn finish(&mut self) -> SimError {
        self.inputs = None;
        let ended = match self.worker.take().map(JoinHandle::join) {
            Some(Ok(Err(e))) => {
                self.ended = Some(Ended::of(&e));
                return e;
            }
            Some(Err(_)) => Ended::Failed("the stepping thread panicked".into()),
            _ => Ended::Horizon,
        };
        let error = ended.error(self.t_end);
        self.ended = Some(ended);
        error
    }

    /// End the worker now (its controller fails at its next hand-over) and wait for it.
    fn stop(&mut self) {
        self.inputs = None;
        let (_, closed) = sync_channel::<SteppedSample>(0);
        drop(std::mem::replace(&mut self.samples, closed));
        if let Some(worker) = self.worker.take() {
            let _ = worker.join();
        }
    }
}

impl Drop for SteppedRun {
    fn drop(&mut self) {
        // the worker waits for an input or for room to hand out a sample: closing both ends
        // makes its controller fail at once, and the run returns
        self.stop();
    }
}

impl Remote {
    /// A controller with no driver: its first sample fails ([`ControlError::Detached`]).
    fn detached(law: BoundaryLaw) -> Remote {
        let (_, inputs) = sync_channel(0);
        let (samples, _) = sync_channel(0);
        Remote { law, inputs, samples, integrals: Default::default(), energy: 0.0 }
    }
}
