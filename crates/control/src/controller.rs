//! The controller interface: what any boundary controller supplies to the simulator.
//!
//! A boundary controller of the wing has two parts (the split law (15) already has):
//!
//! - a **continuous linear part** per channel, τ_c ⊇ −k_c (a x_c + b ẋ_c): a tip stiffness
//!   k_c·a (N/m, N m/rad) and damper k_c·b (N s/m, N m s/rad) that the simulator integrates
//!   implicitly inside its step matrix ([`Controller::continuous`], a [`BoundaryLaw`]; zero gains
//!   for a purely sampled controller);
//! - a **held part** u_c, computed once per sample period T_s = `observer.sample_period` at
//!   t_k = k T_s from the tip measurements of Remark 2 ([`TipMeasurement`], taken at t_k with no
//!   delay) and held constant (zero-order hold) over [t_k, t_k + T_s)
//!   ([`Controller::sample`]).
//!
//! The input applied is τ_c(t) = −k_c (a x_c(t) + b ẋ_c(t)) + u_c(t_k) for t ∈ [t_k, t_k + T_s)
//! (channel 0: bending, τ1 in N; channel 1: torsion, τ2 in N m). The paper's controllers are
//! implementations ([`BuiltIn`]): u = −ĝ, with ĝ from the observer of (16)–(21) (FTDO, either
//! sampling rule), of (57) (DOBC), or 0 (PD, none). An observer that integrates what happens
//! between samples gets every integrator step's quadrature of τ and of the tip state w through
//! [`Controller::integrate`] (the simulator's own quadrature, the one the built-in observer's ν
//! uses).

use std::convert::Infallible;

use wingcheck_model::Config;

use crate::{BoundaryLaw, ChannelObserver, TipChannel};

/// What a digital implementation measures at the tip at a sample instant t_k (Remark 2), in SI
/// units. Channel 0 is bending, channel 1 torsion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TipMeasurement {
    /// t_k = k T_s (s).
    pub t: f64,
    /// q(s, t_k) (m), θ(s, t_k) (rad).
    pub x: [f64; 2],
    /// q̇(s, t_k) (m/s), θ̇(s, t_k) (rad/s).
    pub v: [f64; 2],
    /// The tip boundary states w: q'''(s, t_k) (1/m²), θ'(s, t_k) (1/m).
    pub w: [f64; 2],
}

/// A controller's output at a sample t_k: the held inputs u and, for an observer-based
/// controller, its σ (for the record; 0 where the controller has none).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Held {
    /// u_c held over [t_k, t_k + T_s): N (bending), N m (torsion), added to the continuous part.
    pub input: [f64; 2],
    /// The observer's σ(t_k) (N, N m); 0 without an observer.
    pub sigma: [f64; 2],
}

/// Why a controller could not supply its held inputs.
#[derive(Debug, thiserror::Error)]
pub enum ControlError {
    /// A held input is NaN or infinite.
    #[error("the controller returned {name} = {value} at t = {t} s (held inputs must be finite)")]
    NonFinite {
        /// t_k (s).
        t: f64,
        /// Which input ("tau1" or "tau2").
        name: &'static str,
        /// The value returned.
        value: f64,
    },
    /// The controller's output does not have the expected shape.
    #[error("the controller's output at t = {t} s is not a pair (tau1, tau2) of numbers: {found}")]
    Shape {
        /// t_k (s).
        t: f64,
        /// What was returned, as the front end describes it.
        found: String,
    },
    /// The controller itself failed (e.g. a Python exception; the front end keeps the original).
    #[error("the controller failed at t = {t} s: {message}")]
    Failed {
        /// t_k (s).
        t: f64,
        /// The failure, in words.
        message: String,
    },
    /// The continuous part is not usable.
    #[error("controller.continuous: {reason}")]
    Continuous {
        /// What is wrong, naming the field and its range.
        reason: String,
    },
    /// A controller driven from outside lost its driver (the step form was reset or dropped).
    #[error("the step-by-step driver went away at t = {t} s")]
    Detached {
        /// t_k (s).
        t: f64,
    },
}

/// A boundary controller of the wing (see the module documentation for the semantics).
pub trait Controller {
    /// Why [`Controller::sample`] may fail ([`Infallible`] for the built-in controllers).
    type Error;

    /// The continuous linear part (gains k_c in N/m and N m/rad, weights a (–) and b (s)),
    /// constant over a run; read once when a run starts, after [`Controller::reset`].
    fn continuous(&self) -> BoundaryLaw;

    /// Return to the state at t = 0 before a run (a run may be one of several: an error
    /// estimate's refinements, the initial layer's runs).
    fn reset(&mut self, cfg: &Config) -> Result<(), Self::Error>;

    /// One integrator step [t, t + h) just made with the held inputs: `tau_mean` the
    /// scheme's quadrature of τ over the step (N, N m), `w_mean` that of the tip states w
    /// (1/m², 1/m). The default ignores it.
    fn integrate(&mut self, _h: f64, _tau_mean: [f64; 2], _w_mean: [f64; 2]) {}

    /// The held inputs over [t_k, t_k + T_s) from the measurements at t_k.
    fn sample(&mut self, tip: &TipMeasurement) -> Result<Held, Self::Error>;

    /// Whether the run should tell this controller the loop's energy before each sample
    /// ([`Controller::energy`]); false by default, so other runs skip computing it.
    fn wants_energy(&self) -> bool {
        false
    }

    /// The loop's mechanical energy E(t_k) (J) just before [`Controller::sample`] at t_k, for a
    /// controller that [`Controller::wants_energy`]. Not a tip measurement (a real loop has no
    /// such sensor): the step form reports it beside the measurements. The default ignores it.
    fn energy(&mut self, _t: f64, _energy: f64) {}
}

impl<C: Controller + ?Sized> Controller for Box<C> {
    type Error = C::Error;
    fn continuous(&self) -> BoundaryLaw {
        (**self).continuous()
    }
    fn reset(&mut self, cfg: &Config) -> Result<(), Self::Error> {
        (**self).reset(cfg)
    }
    fn integrate(&mut self, h: f64, tau_mean: [f64; 2], w_mean: [f64; 2]) {
        (**self).integrate(h, tau_mean, w_mean)
    }
    fn sample(&mut self, tip: &TipMeasurement) -> Result<Held, Self::Error> {
        (**self).sample(tip)
    }
    fn wants_energy(&self) -> bool {
        (**self).wants_energy()
    }
    fn energy(&mut self, t: f64, energy: f64) {
        (**self).energy(t, energy)
    }
}

/// The paper's controllers (`control.kind`): law (15) with k = (k1, k2) (0 for `none`) and the
/// held input u = −ĝ, ĝ from the digital observers (FTDO (16)–(21) with `observer.rule`, DOBC
/// (57)), or u = 0 (`pd`, `none`).
#[derive(Debug, Clone, PartialEq)]
pub struct BuiltIn {
    /// Law (15) of the configuration.
    pub law: BoundaryLaw,
    /// The bending and torsion observers (inactive for `pd` and `none`).
    pub observers: [ChannelObserver; 2],
}

impl BuiltIn {
    /// The controller `cfg.control.kind` names, at t = 0.
    pub fn of(cfg: &Config) -> BuiltIn {
        BuiltIn {
            law: BoundaryLaw::of(cfg),
            observers: [ChannelObserver::new(cfg, TipChannel::Bending), ChannelObserver::new(cfg, TipChannel::Torsion)],
        }
    }
}

impl Controller for BuiltIn {
    type Error = Infallible;

    fn continuous(&self) -> BoundaryLaw {
        self.law
    }

    fn reset(&mut self, cfg: &Config) -> Result<(), Infallible> {
        *self = BuiltIn::of(cfg);
        Ok(())
    }

    /// ν += h(ĝ + τ̄ − s S w̄) per channel (17)/(19), with the held ĝ = −u.
    fn integrate(&mut self, h: f64, tau_mean: [f64; 2], w_mean: [f64; 2]) {
        for (c, obs) in self.observers.iter_mut().enumerate() {
            obs.integrate(h, obs.held, tau_mean[c], w_mean[c]);
        }
    }

    /// σ_k from the tip state w(t_k) and ν, ĝ_k = φ(σ_k) by the sampling rule, u = −ĝ_k.
    fn sample(&mut self, tip: &TipMeasurement) -> Result<Held, Infallible> {
        let mut held = Held { input: [0.0; 2], sigma: [0.0; 2] };
        for (c, obs) in self.observers.iter_mut().enumerate() {
            held.sigma[c] = obs.sigma(tip.w[c]);
            let g_hat = obs.estimate(tip.w[c]);
            obs.held = g_hat;
            held.input[c] = -g_hat;
        }
        Ok(held)
    }
}

impl From<Infallible> for ControlError {
    fn from(never: Infallible) -> ControlError {
        match never {}
    }
}

/// Any controller with its error as a [`ControlError`]: how a built-in controller is handed to
/// code that takes controllers of any origin (`Box<dyn Controller<Error = ControlError>>`).
#[derive(Debug, Clone, PartialEq)]
pub struct Erased<C>(pub C);

impl<C: Controller> Controller for Erased<C>
where
    C::Error: Into<ControlError>,
{
    type Error = ControlError;
    fn continuous(&self) -> BoundaryLaw {
        self.0.continuous()
    }
    fn reset(&mut self, cfg: &Config) -> Result<(), ControlError> {
        self.0.reset(cfg).map_err(Into::into)
    }
    fn integrate(&mut self, h: f64, tau_mean: [f64; 2], w_mean: [f64; 2]) {
        self.0.integrate(h, tau_mean, w_mean)
    }
    fn sample(&mut self, tip: &TipMeasurement) -> Result<Held, ControlError> {
        self.0.sample(tip).map_err(Into::into)
    }
    fn wants_energy(&self) -> bool {
        self.0.wants_energy()
    }
    fn energy(&mut self, t: f64, energy: f64) {
        self.0.energy(t, energy)
    }
}

/// ∫τ dt and ∫w dt over the current sample period, accumulated from
/// [`Controller::integrate`]'s step quadratures (N s, N m s; 1/m² s, 1/m s): what an observer
/// outside the simulator needs to integrate (17)/(19) as the built-in one does.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PeriodIntegrals {
    /// ∫τ_c dt over the period so far.
    pub tau: [f64; 2],
    /// ∫w_c dt over the period so far.
    pub w: [f64; 2],
}

impl PeriodIntegrals {
    /// Add one step of length h with the quadrature means.
    pub fn add(&mut self, h: f64, tau_mean: [f64; 2], w_mean: [f64; 2]) {
        for c in 0..2 {
            self.tau[c] += h * tau_mean[c];
            self.w[c] += h * w_mean[c];
        }
    }

    /// The integrals so far, and start a new period.
    pub fn take(&mut self) -> PeriodIntegrals {
        std::mem::take(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use wingcheck_model::ControllerKind;

    #[test]
    fn built_in_holds_minus_the_estimate() {
        // Reference: the observer's own estimate (ChannelObserver::estimate) with u = −ĝ of (15).
        let mut cfg = Config::paper();
        cfg.observer.nu1_0 = 0.3;
        let mut c = BuiltIn::of(&cfg);
        let tip = TipMeasurement { t: 0.0, x: [0.1, 0.2], v: [0.0; 2], w: [0.5, -0.25] };
        let held = c.sample(&tip).unwrap();
        let obs = ChannelObserver::new(&cfg, TipChannel::Bending);
        assert_eq!(held.input[0], -obs.estimate(0.5));
        assert_eq!(held.sigma[0], obs.sigma(0.5));
        cfg.control.kind = ControllerKind::Pd;
        let mut pd = BuiltIn::of(&cfg);
        assert_eq!(pd.sample(&tip).unwrap().input, [0.0, 0.0]);
    }
}
