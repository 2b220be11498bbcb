//! The observer signal replaced by a controller of any origin ([`ControlledSignal`]): the held
//! inputs of a [`Controller`] that reads the plant (a user's), sampled from the modal state at
//! every t_k, for the one driver [`super::drive`].
//!
//! The built-in controllers keep their precomputed signal ([`super::ObserverSignal`]): their
//! held inputs do not depend on the plant (σ_{n+1} − σ_n = h(ḡ − ĝ_k) whatever it does), which
//! a foreign controller's do. Here the driver hands the controller, at the end of each sample
//! period, every step's quadrature of τ and w in order ([`Controller::integrate`]) and then the
//! measurements at t_{k+1} ([`Controller::sample`]): the order and the values a controller sees in
//! the nodal stepper, the held inputs being constant over the period.

use wingcheck_control::{Controller, TipMeasurement};
use wingcheck_model::{Config, MeanSteps, TipValues};

use super::{ModalBasis, ModalLoop, ModalState, SampleInput, Signal, StepInput};
use crate::{BoxedController, ControllerFactory, SimError};

/// A step's quadrature of τ and of the tip boundary states w: their means over the step
/// (N, N m; 1/m², 1/m), what [`wingcheck_control::Controller::integrate`] receives. TR-BDF2 and
/// the trapezoidal rule: the scheme's own quadrature (the nodal stepper's), under which the
/// tip boundary condition holds exactly, so an observer integrating ν from it keeps
/// σ_{n+1} − σ_n = h(ḡ − ĝ) to round-off. The exponential scheme: the trapezoid of the step's
/// two ends (second order; its steps carry no exact ∫τ, ∫w).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StepQuadrature {
    /// Mean of τ_c over the step (N, N m).
    pub tau: [f64; 2],
    /// Mean of w_c over the step (1/m², 1/m).
    pub w: [f64; 2],
}

impl StepQuadrature {
    /// The trapezoid of two ends.
    pub(crate) fn mean_with(self, end: StepQuadrature) -> StepQuadrature {
        let mean = |a: [f64; 2], b: [f64; 2]| [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
        StepQuadrature { tau: mean(self.tau, end.tau), w: mean(self.w, end.w) }
    }
}

/// What a controller measures at the tip of the modal state at time t (the tip values the
/// steps carry, the ones τ is formed from; w as the scheme advances it).
pub fn measurement(st: &ModalState, t: f64) -> TipMeasurement {
    TipMeasurement { t, x: st.x_tip, v: st.v_tip, w: st.w }
}

/// The loop of a controller of any origin on `basis` (built from `cfg`'s wing and grid): the
/// controller `make` makes, reset for `cfg`, its continuous part checked and put in the loop,
/// the initial state, and the signal sampled there at t = 0 — the one set-up of `simulate`
/// and the search.
pub fn controlled_loop<'b>(
    cfg: &Config,
    basis: &'b ModalBasis,
    make: ControllerFactory<'_>,
) -> Result<(ModalLoop<'b>, ModalState, ControlledSignal), SimError> {
    let mut control = make();
    control.reset(cfg)?;
    let law = control.continuous();
    law.check()?;
    let lp = ModalLoop::with_law(cfg, basis, law)?;
    let st = lp.initial_state(cfg, basis);
    let energy = basis.energy(&st.eta, &st.zeta);
    let signal = ControlledSignal::new(cfg, control, &measurement(&st, 0.0), energy)?;
    Ok((lp, st, signal))
}

/// The held inputs of a controller of any origin, one sample period at a time ([`Signal`]).
pub struct ControlledSignal {
    control: BoxedController,
    /// The disturbances' means over steps of length `h`, step after step.
    means: MeanSteps,
    /// g(t) at the samples, sample after sample.
    tip_values: TipValues,
    h: f64,
    period: f64,
    steps_per_sample: usize,
    k: usize,
    /// The output at the current sample (ĝ = −u, the controller's σ, g(t_k)).
    now: SampleInput,
}

impl ControlledSignal {
    /// The signal of `control` (already reset, its continuous part read) on `cfg`, sampled at
    /// t = 0 from `tip` with the loop's energy `energy` (J) there ([`Controller::energy`]).
    pub fn new(
        cfg: &Config,
        control: BoxedController,
        tip: &TipMeasurement,
        energy: f64,
    ) -> Result<ControlledSignal, SimError> {
        let mut tip_values = cfg.disturbance.tip_values(cfg.observer.sample_period);
        let g = tip_values.at(0.0);
        let mut signal = ControlledSignal {
            control,
            means: cfg.disturbance.step_means(cfg.discretisation.dt).steps(),
            tip_values,
            h: cfg.discretisation.dt,
            period: cfg.observer.sample_period,
            steps_per_sample: cfg.steps_per_sample(),
            k: 0,
            now: SampleInput { g_hat: [0.0; 2], sigma: [0.0; 2], g },
        };
        signal.sample(tip, energy)?;
        Ok(signal)
    }

    /// Ask the controller for the held inputs at the current sample (ĝ = −u, as the nodal
    /// stepper holds them), telling it the energy first where it wants it.
    fn sample(&mut self, tip: &TipMeasurement, energy: f64) -> Result<(), SimError> {
        if self.control.wants_energy() {
            self.control.energy(tip.t, energy);
        }
        let held = self.control.sample(tip)?;
        self.now.g_hat = [-held.input[0], -held.input[1]];
        self.now.sigma = held.sigma;
        Ok(())
    }
}

impl Signal for ControlledSignal {
    const READS_PLANT: bool = true;

    fn current(&self) -> SampleInput {
        self.now
    }

    fn advance(&mut self, mut step: impl FnMut(f64, &StepInput)) {
        let t0 = self.k as f64 * self.period;
        let (h, g_hat) = (self.h, self.now.g_hat);
        for j in 0..self.steps_per_sample {
            // the times and inputs as `ObserverSignal::advance` forms them
            let t = t0 + j as f64 * h;
            step(t, &super::signal::step_input(&mut self.means, t, g_hat));
        }
        self.k += 1;
        self.now.g = self.tip_values.at(self.k as f64 * self.period);
    }

    fn observe(&mut self, steps: &[StepQuadrature], tip: &TipMeasurement, energy: f64) -> Result<(), SimError> {
        for q in steps {
            self.control.integrate(self.h, q.tau, q.w);
        }
        self.sample(tip, energy)
    }
}
