//! The observer signal of a run, generated sample by sample: ĝ_k, σ_k and g(t_k) at each
//! observer sample, and the step inputs (φ̄, ḡ − ĝ_k) of its integrator steps.
//!
//! σ_{n+1} − σ_n = h(ḡ − ĝ_k) holds for the plant of either scheme (see the module docs), so
//! this is the observer of [`crate::Stepper`] without the plant: σ_0 = s ξ S w(0) − ν(0) as
//! `ChannelObserver::sigma` measures it, then accumulated step by step.

use wingcheck_control::{ChannelObserver, TipChannel};
use wingcheck_model::{Config, TipDisturbance};

use super::StepInput;

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
    tips: [TipDisturbance; 2],
    distributed: wingcheck_model::Distributed,
    h: f64,
    period: f64,
    steps_per_sample: usize,
    k: usize,
    sigma: [f64; 2],
    g_hat: [f64; 2],
}

impl ObserverSignal {
    /// The signal of `cfg` (its observer, disturbances, initial tip states and step).
    pub fn new(cfg: &Config) -> ObserverSignal {
        let w0 = crate::stepper::initial_tip_states(cfg);
        let observers =
            [ChannelObserver::new(cfg, TipChannel::Bending), ChannelObserver::new(cfg, TipChannel::Torsion)];
        let sigma = [observers[0].sigma(w0[0]), observers[1].sigma(w0[1])];
        let mut signal = ObserverSignal {
            tips: [cfg.disturbance.tip_bending.clone(), cfg.disturbance.tip_torsion.clone()],
            distributed: cfg.disturbance.distributed.clone(),
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
        let t = self.k as f64 * self.period;
        SampleInput { g_hat: self.g_hat, sigma: self.sigma, g: [self.tips[0].at(t), self.tips[1].at(t)] }
    }

    /// Advance one sample period: call `step(t_j, input)` for each integrator step
    /// [t_j, t_j + h) with its inputs, then take the next sample of σ and update ĝ.
    pub fn advance(&mut self, mut step: impl FnMut(f64, &StepInput)) {
        let t0 = self.k as f64 * self.period;
        let h = self.h;
        for j in 0..self.steps_per_sample {
            let t = t0 + j as f64 * h;
            let g_mean = [self.tips[0].mean_over(t, t + h), self.tips[1].mean_over(t, t + h)];
            let input = StepInput {
                phi: self.distributed.phi_integral(t, t + h) / h,
                tip_input: [g_mean[0] - self.g_hat[0], g_mean[1] - self.g_hat[1]],
                g_hat: self.g_hat,
            };
            step(t, &input);
            for c in 0..2 {
                self.sigma[c] += h * input.tip_input[c];
            }
        }
        self.k += 1;
        self.update_estimates();
    }
}
