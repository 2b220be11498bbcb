//! The disturbances (56) and their exact means over an integrator step, which every time
//! scheme holds ([`StepMeans`]). Units are SI (N/m, N, N m, s, rad/s).

use serde::{Deserialize, Serialize};

use crate::oscillator::Oscillator;

/// Disturbances (56), generalised only in their coefficients.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Disturbance {
    /// Distributed load g_h(z,t) = (mean + cos_amp cos(cos_freq t) + sin_amp sin(sin_freq t)) · slope · z.
    pub distributed: Distributed,
    /// Tip bending force g1(t) = mean + amp sin(freq t).
    pub tip_bending: TipDisturbance,
    /// Tip torsion moment g2(t) = mean + amp sin(freq t).
    pub tip_torsion: TipDisturbance,
}

impl Disturbance {
    /// The tip force and moment at times a step h (s) apart ([`TipValues`]).
    pub fn tip_values(&self, h: f64) -> TipValues {
        TipValues {
            oscillators: [Oscillator::new(self.tip_bending.freq, h), Oscillator::new(self.tip_torsion.freq, h)],
            tips: [self.tip_bending.clone(), self.tip_torsion.clone()],
        }
    }

    /// The exact means of the disturbances over integrator steps of length h (s): what every
    /// step of every time scheme holds ([`StepMeans::over_step`]).
    pub fn step_means(&self, h: f64) -> StepMeans {
        StepMeans {
            load_factors: self.distributed.step_factors(h),
            tip_factors: [&self.tip_bending, &self.tip_torsion].map(|d| d.step_factor(h)),
            disturbance: self.clone(),
            h,
        }
    }
}

/// The disturbances' exact means over steps of one length h, their sinc factors computed once
/// ([`Disturbance::step_means`]).
#[derive(Debug, Clone)]
pub struct StepMeans {
    disturbance: Disturbance,
    h: f64,
    load_factors: [f64; 2],
    tip_factors: [f64; 2],
}

impl StepMeans {
    /// (φ̄, [ḡ1, ḡ2]): the means of φ (1) and of the tip force (N) and moment (N m) over
    /// [t0, t0 + h] (t0 in s), exact ([`Distributed::step_mean`], [`TipDisturbance::step_mean`]).
    pub fn over_step(&self, t0: f64) -> (f64, [f64; 2]) {
        let d = &self.disturbance;
        let tips = [&d.tip_bending, &d.tip_torsion];
        (
            d.distributed.step_mean(t0, self.h, self.load_factors),
            [0, 1].map(|c| tips[c].step_mean(t0, self.h, self.tip_factors[c])),
        )
    }

    /// The disturbances these means are of.
    pub fn disturbance(&self) -> &Disturbance {
        &self.disturbance
    }

    /// A cursor for consecutive steps ([`MeanSteps`]): these means with the sinusoids by
    /// rotation from one step to the next.
    pub fn steps(&self) -> MeanSteps {
        let (d, h) = (&self.disturbance, self.h);
        MeanSteps {
            load: [Oscillator::new(d.distributed.cos_freq, h), Oscillator::new(d.distributed.sin_freq, h)],
            tips: [Oscillator::new(d.tip_bending.freq, h), Oscillator::new(d.tip_torsion.freq, h)],
            means: self.clone(),
        }
    }
}

/// [`StepMeans::over_step`] for steps that follow one another: the same expressions with the
/// sines and cosines at the steps' midpoints from [`Oscillator`]s (exact at every
/// [`crate::oscillator::ANCHOR_EVERY`]-th step and wherever a step does not follow the
/// previous one, where the values are `over_step`'s bits; within
/// [`MeanSteps::error_bound`] of them in between).
#[derive(Debug, Clone)]
pub struct MeanSteps {
    means: StepMeans,
    /// cos(cos_freq t), sin(sin_freq t) of the distributed load.
    load: [Oscillator; 2],
    /// sin(freq t) of the tip force and moment.
    tips: [Oscillator; 2],
}

impl MeanSteps {
    /// (φ̄, [ḡ1, ḡ2]) over [t0, t0 + h] as [`StepMeans::over_step`].
    #[inline]
    pub fn over_step(&mut self, t0: f64) -> (f64, [f64; 2]) {
        let m = &self.means;
        let (d, mid) = (&m.disturbance, t0 + 0.5 * m.h);
        let l = &d.distributed;
        let phi = l.mean
            + l.cos_amp * self.load[0].at(mid).0 * m.load_factors[0]
            + l.sin_amp * self.load[1].at(mid).1 * m.load_factors[1];
        let tips = [&d.tip_bending, &d.tip_torsion];
        let mut g = [0.0; 2];
        for c in 0..2 {
            g[c] = tips[c].mean + tips[c].amp * self.tips[c].at(mid).1 * m.tip_factors[c];
        }
        (phi, g)
    }

    /// A bound on |φ̄ − φ̄_exact| (1) and on the tip means' errors (N, N m) against
    /// [`StepMeans::over_step`] for steps up to `t_max` (s): the amplitudes times
    /// [`Oscillator::error_bound`].
    pub fn error_bound(&self, t_max: f64) -> (f64, [f64; 2]) {
        let d = &self.means.disturbance;
        let l = &d.distributed;
        let phi = l.cos_amp.abs() * self.load[0].error_bound(t_max) + l.sin_amp.abs() * self.load[1].error_bound(t_max);
        let tips = [&d.tip_bending, &d.tip_torsion];
        (phi, [0, 1].map(|c| tips[c].amp.abs() * self.tips[c].error_bound(t_max)))
    }
}

/// The tip force and moment g1(t), g2(t) (N, N m) at times that advance one step h at a time
/// ([`Disturbance::tip_values`]): [`TipDisturbance::at`] with the sines from [`Oscillator`]s.
#[derive(Debug, Clone)]
pub struct TipValues {
    tips: [TipDisturbance; 2],
    oscillators: [Oscillator; 2],
}

impl TipValues {
    /// [g1(t), g2(t)] (exact where the [`Oscillator`]s evaluate exactly).
    #[inline]
    pub fn at(&mut self, t: f64) -> [f64; 2] {
        let mut g = [0.0; 2];
        for c in 0..2 {
            g[c] = self.tips[c].mean + self.tips[c].amp * self.oscillators[c].at(t).1;
        }
        g
    }

    /// A bound on each channel's error against [`TipDisturbance::at`] at times up to `t_max`.
    pub fn error_bound(&self, t_max: f64) -> [f64; 2] {
        [0, 1].map(|c| self.tips[c].amp.abs() * self.oscillators[c].error_bound(t_max))
    }
}

/// Distributed disturbance g_h(z,t) = φ(t)·slope·z with φ(t) = mean + cos_amp cos(cos_freq t) + sin_amp sin(sin_freq t) (N/m).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Distributed {
    /// Constant part of φ (paper: 1).
    pub mean: f64,
    /// Cosine amplitude (paper: 3).
    pub cos_amp: f64,
    /// Cosine angular frequency (rad/s) (paper: 3π).
    pub cos_freq: f64,
    /// Sine amplitude (paper: 1).
    pub sin_amp: f64,
    /// Sine angular frequency (rad/s) (paper: π).
    pub sin_freq: f64,
    /// Spatial slope (1/m) (paper: 1/30).
    pub slope: f64,
}

impl Distributed {
    /// Time factor φ(t) of g_h(z,t) = φ(t)·slope·z.
    pub fn phi(&self, t: f64) -> f64 {
        self.mean + self.cos_amp * (self.cos_freq * t).cos() + self.sin_amp * (self.sin_freq * t).sin()
    }
    /// Exact integral ∫_{t0}^{t1} φ(t) dt (product forms, no cancellation for short steps).
    pub fn phi_integral(&self, t0: f64, t1: f64) -> f64 {
        let dt = t1 - t0;
        let mid = 0.5 * (t0 + t1);
        self.mean * dt
            + self.cos_amp * (self.cos_freq * mid).cos() * dt * sinc(0.5 * self.cos_freq * dt)
            + self.sin_amp * (self.sin_freq * mid).sin() * dt * sinc(0.5 * self.sin_freq * dt)
    }
    /// The factors sinc(ω h/2) of the cosine and the sine term by which a step of length h (s)
    /// averages them, for [`Distributed::step_mean`] (once per run instead of at every step).
    pub fn step_factors(&self, h: f64) -> [f64; 2] {
        [sinc(0.5 * self.cos_freq * h), sinc(0.5 * self.sin_freq * h)]
    }
    /// Exact mean (1/h)∫_{t0}^{t0+h} φ(t) dt with `factors` = [`Distributed::step_factors`]`(h)`:
    /// the value of [`Distributed::phi_integral`]`(t0, t0 + h)/h` up to round-off, with two
    /// trigonometric calls instead of four.
    pub fn step_mean(&self, t0: f64, h: f64, factors: [f64; 2]) -> f64 {
        let mid = t0 + 0.5 * h;
        self.mean
            + self.cos_amp * (self.cos_freq * mid).cos() * factors[0]
            + self.sin_amp * (self.sin_freq * mid).sin() * factors[1]
    }
}

/// sin(x)/x with sinc(0) = 1: ∫ of sin/cos over [m − δ, m + δ] is 2δ·sinc(ωδ)·(value at m).
fn sinc(x: f64) -> f64 {
    if x.abs() < 1e-4 {
        1.0 - x * x / 6.0
    } else {
        x.sin() / x
    }
}

/// Tip disturbance mean + amp·sin(freq·t).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TipDisturbance {
    /// Constant part.
    pub mean: f64,
    /// Amplitude of the sine.
    pub amp: f64,
    /// Angular frequency (rad/s).
    pub freq: f64,
}

impl TipDisturbance {
    /// Value at time t.
    pub fn at(&self, t: f64) -> f64 {
        self.mean + self.amp * (self.freq * t).sin()
    }
    /// Exact mean (1/(t1 − t0))∫_{t0}^{t1} g dt over a step (t1 = t0 gives g(t0)).
    pub fn mean_over(&self, t0: f64, t1: f64) -> f64 {
        let mid = 0.5 * (t0 + t1);
        self.mean + self.amp * (self.freq * mid).sin() * sinc(0.5 * self.freq * (t1 - t0))
    }
    /// The factor sinc(ω h/2) by which a step of length h (s) averages the sine, for
    /// [`TipDisturbance::step_mean`] (once per run instead of at every step).
    pub fn step_factor(&self, h: f64) -> f64 {
        sinc(0.5 * self.freq * h)
    }
    /// Exact mean of g over [t0, t0 + h] with `factor` = [`TipDisturbance::step_factor`]`(h)`:
    /// [`TipDisturbance::mean_over`]`(t0, t0 + h)` up to round-off, with one trigonometric call
    /// instead of two.
    pub fn step_mean(&self, t0: f64, h: f64, factor: f64) -> f64 {
        self.mean + self.amp * (self.freq * (t0 + 0.5 * h)).sin() * factor
    }
}
