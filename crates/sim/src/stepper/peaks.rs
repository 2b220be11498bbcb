//! Full-rate extremes of the closed loop: updated after every integrator step and on both
//! sides of every sample's jump of the held estimate, so a peak is never missed between
//! output samples (a peak read off 0.01-s output samples can be 20 % low).

use serde::Serialize;

/// The largest |value| of one signal and when it occurred.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct Peak {
    /// max |value| (units of the signal).
    pub abs_max: f64,
    /// The signed value at that instant.
    pub value: f64,
    /// Its time (s).
    pub t: f64,
}

impl Peak {
    fn update(&mut self, t: f64, v: f64) {
        if v.abs() > self.abs_max {
            *self = Peak { abs_max: v.abs(), value: v, t };
        }
    }
}

/// Full-rate extremes over the run so far.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct Peaks {
    /// q(s,t) (m).
    pub q_tip: Peak,
    /// θ(s,t) (rad).
    pub theta_tip: Peak,
    /// q̇(s,t) (m/s).
    pub q_tip_rate: Peak,
    /// θ̇(s,t) (rad/s).
    pub theta_tip_rate: Peak,
    /// τ1 (N).
    pub tau1: Peak,
    /// τ2 (N m).
    pub tau2: Peak,
    /// Observer error g̃1 = g1 − ĝ1 (N).
    pub g1_error: Peak,
    /// Observer error g̃2 = g2 − ĝ2 (N m).
    pub g2_error: Peak,
}

impl Peaks {
    /// Fold in the values [q, θ, q̇, θ̇, τ1, τ2, g̃1, g̃2] at time t.
    pub(crate) fn update(&mut self, t: f64, v: &[f64; 8]) {
        self.q_tip.update(t, v[0]);
        self.theta_tip.update(t, v[1]);
        self.q_tip_rate.update(t, v[2]);
        self.theta_tip_rate.update(t, v[3]);
        self.tau1.update(t, v[4]);
        self.tau2.update(t, v[5]);
        self.g1_error.update(t, v[6]);
        self.g2_error.update(t, v[7]);
    }
}
