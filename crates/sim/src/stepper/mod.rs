//! The closed-loop time stepper.
//!
//! Plant: M ẍ + C ẋ + K_c x = f̄ with C = ξK + b·diag(k1, k2)|tip and K_c = K + a·diag(k1, k2)|tip:
//! the analogue part −k(a·tip + b·tip rate) of (15) is inside the step matrix
//! S = M/α + C + αK_c, factorised once per run. Two schemes ([`TimeScheme`]):
//!
//! - TR-BDF2 (default; γ = 2 − √2, α = γh/2): a trapezoidal stage to t + γh, then a BDF2
//!   stage to t + h, both with S (two sparse solves per step). Second order and L-stable: the
//!   stiff Kelvin–Voigt modes are damped (amplification → 0), so the observer's zero-order-hold
//!   jumps do not make the tip rate ring. See [`trbdf2`].
//! - Trapezoidal rule (α = h/2, implicit midpoint form, A-stable): one solve gives
//!   v̄ = (v_n + v_{n+1})/2; then x_{n+1} = x_n + h v̄. The discrete energy balance
//!   E_{n+1} − E_n = h v̄ᵀ f̄_total − h ξ v̄ᵀ K v̄ holds exactly (up to round-off); its stiff modes
//!   ring (amplification → −1) under sampled discontinuous inputs.
//!
//! Inputs: the distributed load and g1, g2 enter as their exact step averages; the digital
//! observer's estimate ĝ_k is held over each sample period T = m·h (zero-order hold).
//!
//! Tip states: q'''(s,t) and θ'(s,t) are integrated from the boundary conditions themselves,
//! ξ S ẇ = s(τ + g) − S w by the same scheme with the same stage values of τ, never read off
//! the field; the observer integrator ν uses the scheme's own quadrature of τ and w, so that
//! σ_{n+1} − σ_n = h(ḡ − ĝ) holds to round-off for either scheme.

mod peaks;
pub mod trbdf2;

pub(crate) use peaks::FullRate;
pub use peaks::{Peak, Peaks, SquareIntegral};

use wingcheck_control::{BoundaryLaw, BuiltIn, Controller, TipChannel, TipMeasurement};
use wingcheck_model::{Config, TimeScheme};

use crate::banded::{BandedCholesky, BandedPair};
use crate::sparse::{SymBuilder, SymMatrix};
use crate::{Discretisation, SimError};

/// The tip boundary states at t = 0 from the initial shape: q'''(s,0) (1/m²) = −3 q_tip/s³ for
/// the cantilever shape and 0 for the linear one; θ'(s,0) = θ_tip/s (1/m).
pub fn initial_tip_states(cfg: &Config) -> [f64; 2] {
    let s = cfg.wing.span;
    let shear = match cfg.initial.shape {
        wingcheck_model::InitialShape::Linear => 0.0,
        wingcheck_model::InitialShape::Cantilever => -3.0 * cfg.initial.q_tip / s.powi(3),
    };
    [shear, cfg.initial.theta_tip / s]
}

/// State of one tip channel (bending or torsion).
#[derive(Debug, Clone)]
pub struct Channel {
    /// Sign s of the tip boundary condition ([`TipChannel::bc_sign`]).
    pub sign: f64,
    /// Stiffness S: EI (bending) or GJ (torsion) (N m²).
    pub stiffness: f64,
    /// Tip boundary state w: q'''(s) (1/m²) for bending, θ'(s) (1/m) for torsion.
    pub w: f64,
    /// Held part of (15) over the current sample with its sign there: ĝ for the built-in
    /// controllers, −u for any [`Controller`] (N, N m).
    pub g_hat: f64,
    /// σ measured at the start of the current sample (the controller's [`wingcheck_control::Held::sigma`]).
    pub sigma: f64,
    /// Feedback gain k (k1 or k2), 0 when the controller is `none`.
    pub k: f64,
    /// Index of the tip unknown.
    pub dof: usize,
}

/// Cumulative energy bookkeeping (J), only when requested (costs one extra mat-vec per step).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct EnergyLedger {
    /// ∫ of the power of all external forces (distributed load, tip forces incl. control).
    pub work_in: f64,
    /// ∫ ξ ∫(EI q̇''² + GJ θ̇'²) dz dt: Kelvin–Voigt dissipation.
    pub dissipated: f64,
}

/// One sampled instant of the closed loop.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Time t_k (s).
    pub t: f64,
    /// q(s,t) (m).
    pub q_tip: f64,
    /// θ(s,t) (rad).
    pub theta_tip: f64,
    /// q̇(s,t) (m/s).
    pub q_tip_rate: f64,
    /// θ̇(s,t) (rad/s).
    pub theta_tip_rate: f64,
    /// τ1(t_k) (N): control force, with the estimate held from t_k.
    pub tau1: f64,
    /// τ2(t_k) (N m).
    pub tau2: f64,
    /// g1(t_k) (N).
    pub g1: f64,
    /// g2(t_k) (N m).
    pub g2: f64,
    /// ĝ1 held over [t_k, t_k + T) (N).
    pub g1_hat: f64,
    /// ĝ2 held over [t_k, t_k + T) (N m).
    pub g2_hat: f64,
    /// σ1(t_k) (N).
    pub sigma1: f64,
    /// σ2(t_k) (N m).
    pub sigma2: f64,
    /// Mechanical energy E (J).
    pub energy: f64,
    /// ⟨x, M v⟩ (J s): see [`crate::Series::displacement_momentum`].
    pub displacement_momentum: f64,
    /// Tip shear state q'''(s,t) (1/m²).
    pub q_tip_shear: f64,
    /// Tip slope state θ'(s,t) (1/m).
    pub theta_tip_slope: f64,
}

/// The closed loop, advanced one observer sample at a time, under the controller `C` (by
/// default the paper's, [`BuiltIn`], as `control.kind` names it).
#[derive(Debug)]
pub struct Stepper<C = BuiltIn> {
    cfg: Config,
    /// The control law (15).
    law: BoundaryLaw,
    disc: Discretisation,
    solver: BandedCholesky,
    /// M/α and K_c = K + a·diag(k)|tip, fused for the right-hand side (M/α) v − K_c x.
    rhs_operator: BandedPair,
    h: f64,
    /// The disturbances' means over steps of length `h`.
    means: wingcheck_model::StepMeans,
    /// Scheme and its stage coefficient α (h/2 trapezoid, (1 − 1/√2)h TR-BDF2).
    scheme: TimeScheme,
    alpha: f64,
    /// Stage buffers (TR-BDF2).
    x_stage: Vec<f64>,
    v_stage: Vec<f64>,
    /// Full-rate extremes.
    /// Full-rate extremes and ∫τ² dt over the current output interval.
    full_rate: FullRate,
    steps_per_sample: usize,
    /// Number of the current sample k (t = k T).
    k: usize,
    x: Vec<f64>,
    v: Vec<f64>,
    rhs: Vec<f64>,
    /// Bending and torsion channels.
    pub channels: [Channel; 2],
    track_energy: bool,
    ledger: EnergyLedger,
    /// The controller: its continuous part is `law`, its held part sets the channels' ĝ.
    control: C,
}

impl Stepper<BuiltIn> {
    /// Assemble, factorise and set the initial state. Cost: one sparse Cholesky.
    pub fn new(cfg: &Config) -> Result<Stepper, SimError> {
        Self::with_discretisation(cfg, Discretisation::new(cfg))
    }

    /// As [`Stepper::new`] with a given discretisation.
    pub fn with_discretisation(cfg: &Config, disc: Discretisation) -> Result<Stepper, SimError> {
        Stepper::with_controller(cfg, disc, BuiltIn::of(cfg))
    }

    /// Advance one observer sample period T (see [`Stepper::try_advance_sample`]; the
    /// built-in controllers cannot fail).
    pub fn advance_sample(&mut self) {
        let Ok(()) = self.try_advance_sample();
    }
}

impl<C: Controller> Stepper<C>
where
    C::Error: Into<SimError>,
{
    /// Assemble, factorise and set the initial state under `control` (reset first; its
    /// continuous part is read once, after the reset). Cost: one sparse Cholesky.
    pub fn with_controller(cfg: &Config, disc: Discretisation, mut control: C) -> Result<Stepper<C>, SimError> {
        cfg.validate().map_err(SimError::Config)?;
        control.reset(cfg).map_err(Into::into)?;
        let h = cfg.discretisation.dt;
        let n = disc.dim();
        let law = control.continuous();
        law.check()?;
        let [k1, k2] = law.gains;
        let mut tip_damp = SymBuilder::new(n);
        tip_damp.add(disc.tip_q, disc.tip_q, k1);
        tip_damp.add(disc.tip_theta, disc.tip_theta, k2);
        let tip = tip_damp.build();
        let (a, b, xi) = (law.a, law.b, cfg.wing.xi);
        let scheme = cfg.time_scheme(false);
        let alpha = match scheme {
            TimeScheme::Trapezoid => 0.5 * h,
            TimeScheme::Trbdf2 => trbdf2::ALPHA * h,
            TimeScheme::Exponential | TimeScheme::Auto => {
                return Err(SimError::Config(wingcheck_model::ConfigError::Inconsistent {
                    fields: "discretisation.stepper, discretisation.basis".into(),
                    reason: "discretisation.stepper = exponential runs in the modal basis only; this run is \
                             stepped in the nodal basis"
                        .into(),
                }))
            }
        };
        let stiffness_closed = SymMatrix::combine(&[(1.0, &disc.stiffness), (a, &tip)]);
        let step =
            SymMatrix::combine(&[(1.0 / alpha, &disc.mass), (xi + alpha, &disc.stiffness), (b + alpha * a, &tip)]);
        let solver = BandedCholesky::new(&step)?;
        let m_over_alpha = SymMatrix::combine(&[(1.0 / alpha, &disc.mass)]);
        let rhs_operator = BandedPair::new(&m_over_alpha, &stiffness_closed);
        let x = disc.x0.clone();
        let [w1, w2] = initial_tip_states(cfg);
        let mk = |ch: TipChannel, w: f64, k: f64, dof: usize| {
            let stiffness = match ch {
                TipChannel::Bending => cfg.wing.ei,
                TipChannel::Torsion => cfg.wing.gj,
            };
            Channel { sign: ch.bc_sign(), stiffness, w, g_hat: 0.0, sigma: 0.0, k, dof }
        };
        let channels = [mk(TipChannel::Bending, w1, k1, disc.tip_q), mk(TipChannel::Torsion, w2, k2, disc.tip_theta)];
        let mut st = Stepper {
            cfg: cfg.clone(),
            law,
            disc,
            solver,
            rhs_operator,
            h,
            means: cfg.disturbance.step_means(h),
            scheme,
            alpha,
            x_stage: vec![0.0; n],
            v_stage: vec![0.0; n],
            full_rate: FullRate::new(crate::layer::layer_end(cfg)),
            steps_per_sample: cfg.steps_per_sample(),
            k: 0,
            v: vec![0.0; n],
            rhs: vec![0.0; n],
            x,
            channels,
            track_energy: false,
            ledger: EnergyLedger::default(),
            control,
        };
        st.update_estimates().map_err(Into::into)?;
        st.record_peaks(0.0);
        Ok(st)
    }

    /// Keep the energy ledger (work in, dissipation) from now on.
    pub fn track_energy(&mut self, on: bool) {
        self.track_energy = on;
    }

    /// Extremes of the tip values, rates, controls and observer errors over every integrator
    /// step so far (full rate, both sides of each sample's jump), not only at output samples.
    pub fn peaks(&self) -> &Peaks {
        &self.full_rate.peaks
    }

    /// Full-rate extremes after the initial layer ([`crate::layer::layer_end`]).
    pub fn peaks_after_layer(&self) -> &Peaks {
        &self.full_rate.after_layer
    }

    /// The energy ledger so far.
    pub fn ledger(&self) -> EnergyLedger {
        self.ledger
    }

    /// The discretisation in use.
    pub fn discretisation(&self) -> &Discretisation {
        &self.disc
    }

    /// Current time (s).
    pub fn time(&self) -> f64 {
        self.k as f64 * self.cfg.observer.sample_period
    }

    /// Current displacement and velocity vectors.
    pub fn state(&self) -> (&[f64], &[f64]) {
        (&self.x, &self.v)
    }

    /// Number of the current sample.
    pub fn sample_index(&self) -> usize {
        self.k
    }

    /// Solver statistics: (unknowns, stored entries of the step matrix's banded Cholesky factor).
    pub fn solver_size(&self) -> (usize, usize) {
        (self.disc.dim(), self.solver.stored())
    }

    fn tip_disturbance(&self, ch: usize) -> &wingcheck_model::TipDisturbance {
        if ch == 0 {
            &self.cfg.disturbance.tip_bending
        } else {
            &self.cfg.disturbance.tip_torsion
        }
    }

    /// The controller.
    pub fn controller(&self) -> &C {
        &self.control
    }

    /// What the tip sensors read now ([`TipMeasurement`]).
    pub fn measurement(&self) -> TipMeasurement {
        let [b, tr] = &self.channels;
        TipMeasurement {
            t: self.time(),
            x: [self.x[b.dof], self.x[tr.dof]],
            v: [self.v[b.dof], self.v[tr.dof]],
            w: [b.w, tr.w],
        }
    }

    /// Sample the controller at the current instant: σ and the held ĝ = −u of both channels.
    fn update_estimates(&mut self) -> Result<(), C::Error> {
        if self.control.wants_energy() {
            let (t, energy) = (self.time(), self.sample().energy);
            self.control.energy(t, energy);
        }
        let held = self.control.sample(&self.measurement())?;
        for (c, ch) in self.channels.iter_mut().enumerate() {
            ch.sigma = held.sigma[c];
            ch.g_hat = -held.input[c];
        }
        Ok(())
    }

    /// Control force/moment τ at the current instant with the held estimate.
    fn tau(&self, ch: usize) -> f64 {
        let c = &self.channels[ch];
        self.law.tau(ch, self.x[c.dof], self.v[c.dof], c.g_hat)
    }

    /// The current instant as a [`Sample`].
    pub fn sample(&self) -> Sample {
        let t = self.time();
        let [b, tr] = &self.channels;
        Sample {
            t,
            q_tip: self.x[b.dof],
            theta_tip: self.x[tr.dof],
            q_tip_rate: self.v[b.dof],
            theta_tip_rate: self.v[tr.dof],
            tau1: self.tau(0),
            tau2: self.tau(1),
            g1: self.tip_disturbance(0).at(t),
            g2: self.tip_disturbance(1).at(t),
            g1_hat: b.g_hat,
            g2_hat: tr.g_hat,
            sigma1: b.sigma,
            sigma2: tr.sigma,
            energy: self.disc.energy(&self.x, &self.v),
            displacement_momentum: self.disc.mass.form(&self.x, &self.v),
            q_tip_shear: b.w,
            theta_tip_slope: tr.w,
        }
    }

    /// Advance one integrator step of length h starting at time t.
    fn substep(&mut self, t: f64) {
        match self.scheme {
            TimeScheme::Trapezoid => self.substep_trapezoid(t),
            _ => self.substep_trbdf2(t),
        }
        self.record_peaks(t + self.h);
    }

    /// Fold the current state (at time t, with the held estimate) into the peaks.
    fn record_peaks(&mut self, t: f64) {
        let [b, tr] = &self.channels;
        let g = [self.tip_disturbance(0).at(t), self.tip_disturbance(1).at(t)];
        let values = [
            self.x[b.dof],
            self.x[tr.dof],
            self.v[b.dof],
            self.v[tr.dof],
            self.tau(0),
            self.tau(1),
            g[0] - b.g_hat,
            g[1] - tr.g_hat,
        ];
        self.full_rate.update(t, &values);
    }

    /// Full-rate RMS of τ1 (N) and τ2 (N m) since the previous call (see [`SquareIntegral`]);
    /// `simulate` calls it at every output sample.
    pub fn take_tau_rms(&mut self) -> [f64; 2] {
        self.full_rate.take_tau_rms()
    }

    /// From when |g̃1|, |g̃2| stay in the band |g̃| ≤ [`crate::metrics::GTILDE_THRESHOLD`], at
    /// full rate so far (see [`crate::SimOutput::gtilde_band_entry`]).
    pub fn band_entry(&self) -> [Option<f64>; 2] {
        self.full_rate.band_entry()
    }

    /// Full-rate (min, max) of [τ1, τ2, g̃1, g̃2] since the previous call, including `at`, the
    /// values at the output instant ([`crate::run::Envelope`]); `simulate` calls it at every
    /// output sample.
    pub fn take_range(&mut self, at: [f64; 4]) -> [(f64, f64); 4] {
        self.full_rate.take_range(at)
    }

    /// One trapezoidal step of length h starting at time t.
    fn substep_trapezoid(&mut self, t: f64) {
        let h = self.h;
        let (phi_mean, g_mean) = self.means.over_step(t);
        // rhs = (2/h) M v − K_c x + f̄, with f̄ = φ̄ f_h + e(ḡ − ĝ).
        self.rhs_operator.mul_diff_into(&self.v, &self.x, &mut self.rhs);
        for (r, f) in self.rhs.iter_mut().zip(&self.disc.load) {
            *r += phi_mean * f;
        }
        for (c, g) in self.channels.iter().zip(g_mean) {
            self.rhs[c.dof] += g - c.g_hat;
        }
        self.solver.solve_in_place(&mut self.rhs);
        let vbar = &self.rhs;
        let law = self.law;
        let xi = self.cfg.wing.xi;
        let mut tip_power = 0.0;
        let (mut taus, mut ws) = ([0.0; 2], [0.0; 2]);
        for (ci, (c, g)) in self.channels.iter_mut().zip(g_mean).enumerate() {
            let xbar = self.x[c.dof] + 0.5 * h * vbar[c.dof];
            let tau_mean = law.tau(ci, xbar, vbar[c.dof], c.g_hat);
            let s = c.sign;
            let stiff = c.stiffness;
            let force = tau_mean + g;
            let w_new = if xi > 0.0 {
                (xi * stiff * c.w + h * s * force - 0.5 * h * stiff * c.w) / (xi * stiff + 0.5 * h * stiff)
            } else {
                s * force / stiff
            };
            let w_mean = if xi > 0.0 { 0.5 * (c.w + w_new) } else { w_new };
            (taus[ci], ws[ci]) = (tau_mean, w_mean);
            c.w = w_new;
            tip_power += force * vbar[c.dof];
        }
        self.control.integrate(h, taus, ws);
        if self.track_energy {
            let dist_power: f64 = phi_mean * self.disc.load.iter().zip(vbar).map(|(f, v)| f * v).sum::<f64>();
            self.ledger.work_in += h * (dist_power + tip_power);
            self.ledger.dissipated += h * xi * self.disc.stiffness.form(vbar, vbar);
        }
        for i in 0..self.x.len() {
            self.x[i] += h * vbar[i];
            self.v[i] = 2.0 * vbar[i] - self.v[i];
        }
    }

    /// Advance one observer sample period T (m integrator steps with the held inputs), then
    /// sample the controller at the new instant (σ and ĝ of the built-in observers).
    pub fn try_advance_sample(&mut self) -> Result<(), C::Error> {
        let t0 = self.time();
        for j in 0..self.steps_per_sample {
            self.substep(t0 + j as f64 * self.h);
        }
        self.k += 1;
        self.update_estimates()?;
        self.record_peaks(self.time());
        Ok(())
    }
}
