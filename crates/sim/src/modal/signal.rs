//! The observer signal of a run, generated sample by sample: ĝ_k, σ_k and g(t_k) at each
//! observer sample, and the step inputs (φ̄, ḡ − ĝ_k) of its integrator steps.
//!
//! σ_{n+1} − σ_n = h(ḡ − ĝ_k) holds for the plant of either scheme (see the module docs), so
//! this is the observer of [`crate::Stepper`] without the plant: σ_0 = s ξ S w(0) − ν(0) as
//! `ChannelObserver::sigma` measures it, then accumulated step by step.

use wingcheck_control::{ChannelObserver, TipChannel};
use wingcheck_model::{Config, MeanSteps, TipValues};

use super::{Signal, StepInput};

/// The observer's output at one sample t_k.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SampleInput {
    /// ĝ_k, held over [t_k, t_k + T): N (bending), N m (torsion).
    pub g_hat: [f64; 2],
    /// σ(t_k): N, N m.
    pub sigma: [f64; 2],
    /// g(t_k): N, N m.
    pub g: [f64; 2],
}

/// The observer and disturbances of a configuration, advanced one sample period at a time.
#[derive(Debug, Clone)]
pub struct ObserverSignal {
    observers: [ChannelObserver; 2],
    /// The disturbances' means over steps of length `h`, step after step.
    means: MeanSteps,
    /// g(t) at the samples, sample after sample.
    tip_values: TipValues,
    /// g(t_k) at the current sample.
    g: [f64; 2],
    h: f64,
    period: f64,
    steps_per_sample: usize,
    k: usize,
    sigma: [f64; 2],
    g_hat: [f64; 2],
}

impl ObserverSignal {
    /// A text that is equal for two configurations exactly when their signals are: everything
    /// [`ObserverSignal::new`] and a run's length read (observer, disturbances, controller
    /// kind, initial shape, the wing's span, EI, GJ and ξ, dt, horizon). The search's cache key.
    pub fn key(cfg: &Config) -> String {
        serde_json::to_string(&(
            &cfg.observer,
            &cfg.disturbance,
            &cfg.control.kind,
            &cfg.initial,
            (cfg.wing.span, cfg.wing.ei, cfg.wing.gj, cfg.wing.xi),
            cfg.discretisation.dt,
            &cfg.horizon,
        ))
        .expect("a config serialises")
    }

    /// The signal of `cfg` (its observer, disturbances, initial tip states and step).
    pub fn new(cfg: &Config) -> ObserverSignal {
        let w0 = crate::stepper::initial_tip_states(cfg);
        let observers =
            [ChannelObserver::new(cfg, TipChannel::Bending), ChannelObserver::new(cfg, TipChannel::Torsion)];
        let sigma = [observers[0].sigma(w0[0]), observers[1].sigma(w0[1])];
        let mut tip_values = cfg.disturbance.tip_values(cfg.observer.sample_period);
        let mut signal = ObserverSignal {
            means: cfg.disturbance.step_means(cfg.discretisation.dt).steps(),
            g: tip_values.at(0.0),
            tip_values,
            h: cfg.discretisation.dt,
            period: cfg.observer.sample_period,
            steps_per_sample: cfg.steps_per_sample(),
            k: 0,
            sigma,
            g_hat: [0.0; 2],
            observers,
        };
        signal.update_estimates();
        signal
    }

    fn update_estimates(&mut self) {
        for (c, obs) in self.observers.iter().enumerate() {
            self.g_hat[c] = if obs.active { obs.gain.sample(obs.rule, self.sigma[c], obs.period) } else { 0.0 };
        }
    }

    /// Number k of the current sample (t_k = k T).
    pub fn sample_index(&self) -> usize {
        self.k
    }

    /// Integrator steps per sample period.
    pub fn steps_per_sample(&self) -> usize {
        self.steps_per_sample
    }

    /// The observer's output at the current sample t_k.
    pub fn current(&self) -> SampleInput {
        SampleInput { g_hat: self.g_hat, sigma: self.sigma, g: self.g }
    }

    /// Advance one sample period: call `step(t_j, input)` for each integrator step
    /// [t_j, t_j + h) with its inputs, then take the next sample of σ and update ĝ.
    pub fn advance(&mut self, mut step: impl FnMut(f64, &StepInput)) {
        let t0 = self.k as f64 * self.period;
        let h = self.h;
        for j in 0..self.steps_per_sample {
            let t = t0 + j as f64 * h;
            let input = step_input(&mut self.means, t, self.g_hat);
            step(t, &input);
            for c in 0..2 {
                self.sigma[c] += h * input.tip_input[c];
            }
        }
        self.k += 1;
        self.g = self.tip_values.at(self.k as f64 * self.period);
        self.update_estimates();
    }
}

/// The inputs of the integrator step [t, t + h) under the held estimate ĝ: the disturbances'
/// exact means over the step and ḡ − ĝ at the tip. The one definition for every signal (the
/// observers' and a controller's, [`super::ControlledSignal`]), whose bit-for-bit agreement
/// rests on it.
pub(crate) fn step_input(means: &mut MeanSteps, t: f64, g_hat: [f64; 2]) -> StepInput {
    let (phi, g_mean) = means.over_step(t);
    StepInput { phi, tip_input: [g_mean[0] - g_hat[0], g_mean[1] - g_hat[1]], g_hat }
}

impl Signal for ObserverSignal {
    fn current(&self) -> SampleInput {
        ObserverSignal::current(self)
    }

    fn advance(&mut self, step: impl FnMut(f64, &StepInput)) {
        ObserverSignal::advance(self, step)
    }
}

/// The whole observer signal of a run, generated once by [`ObserverSignal`] and replayed by
/// [`RecordedSignal::replay`] for any number of runs that share it (the search's points): the
/// same numbers as generating it while stepping. Memory: [`RecordedSignal::bytes`], 24 bytes
/// per integrator step and 48 per observer sample, allocated once at their exact size.
#[derive(Debug)]
pub struct RecordedSignal {
    /// Per integrator step: φ̄ and ḡ − ĝ of both channels.
    steps: Vec<[f64; 3]>,
    /// Per observer sample k = 0..=K.
    samples: Vec<SampleInput>,
    h: f64,
    period: f64,
    steps_per_sample: usize,
}

/// Bytes of one integrator step's inputs in a [`RecordedSignal`] (φ̄ and ḡ − ĝ of both channels).
const STEP_BYTES: usize = std::mem::size_of::<[f64; 3]>();

impl RecordedSignal {
    /// Bytes the signal of `cfg` holds: [`STEP_BYTES`] per integrator step, one
    /// [`SampleInput`] per observer sample k = 0..=K (the vectors are allocated at exactly
    /// these lengths). The search's memory estimate counts signals with this.
    pub fn bytes(cfg: &Config) -> f64 {
        let (m, total) = (cfg.steps_per_sample() as f64, cfg.total_samples() as f64);
        STEP_BYTES as f64 * total * m + std::mem::size_of::<SampleInput>() as f64 * (total + 1.0)
    }

    /// The signal of `cfg` over its horizon (K = `cfg.total_samples()` sample periods).
    pub fn new(cfg: &Config) -> RecordedSignal {
        let (m, total) = (cfg.steps_per_sample(), cfg.total_samples());
        let mut signal = ObserverSignal::new(cfg);
        let mut steps = Vec::with_capacity(total * m);
        let mut samples = Vec::with_capacity(total + 1);
        for k in 0..=total {
            samples.push(signal.current());
            if k < total {
                signal.advance(|_, input| steps.push([input.phi, input.tip_input[0], input.tip_input[1]]));
            }
        }
        RecordedSignal { steps, samples, h: signal.h, period: signal.period, steps_per_sample: m }
    }

    /// The observer's output at every sample t_k, k = 0..=K.
    pub fn samples(&self) -> &[SampleInput] {
        &self.samples
    }

    /// A cursor at t = 0 that replays the signal ([`Signal`]).
    pub fn replay(&self) -> Replay<'_> {
        Replay { signal: self, k: 0 }
    }
}

/// A [`RecordedSignal`] being replayed.
#[derive(Debug)]
pub struct Replay<'a> {
    signal: &'a RecordedSignal,
    k: usize,
}

impl Signal for Replay<'_> {
    fn current(&self) -> SampleInput {
        self.signal.samples[self.k]
    }

    fn advance(&mut self, mut step: impl FnMut(f64, &StepInput)) {
        let s = self.signal;
        let (t0, h, m) = (self.k as f64 * s.period, s.h, s.steps_per_sample);
        let g_hat = s.samples[self.k].g_hat;
        for (j, &[phi, u0, u1]) in s.steps[self.k * m..(self.k + 1) * m].iter().enumerate() {
            // the times as `ObserverSignal::advance` computes them
            step(t0 + j as f64 * h, &StepInput { phi, tip_input: [u0, u1], g_hat });
        }
        self.k += 1;
    }
}
