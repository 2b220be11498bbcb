//! Full-rate extremes of the closed loop: updated after every integrator step and on both
//! sides of every sample's jump of the held estimate, so a peak is never missed between
//! output samples (a peak read off 0.01-s output samples can be 20 % low).

use serde::Serialize;

/// The largest |value| of one signal and when it occurred.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, schemars::JsonSchema)]
pub struct Peak {
    /// max |value| (units of the signal).
    pub abs_max: f64,
    /// The signed value at that instant.
    pub value: f64,
    /// Its time (s).
    pub t: f64,
    /// How far the true maximum may lie above `abs_max` where the peak was found inside an
    /// integrator step by the exponential scheme's sub-step probe (`crate::modal`'s probe: the
    /// fine grid's resolution, one-sided); 0 for a value at a recorded instant.
    pub sub_step_error: f64,
}

impl Peak {
    fn update(&mut self, t: f64, v: f64) {
        self.update_sub_step(t, v, 0.0);
    }

    fn update_sub_step(&mut self, t: f64, v: f64, sub_step_error: f64) {
        if v.abs() > self.abs_max {
            *self = Peak { abs_max: v.abs(), value: v, t, sub_step_error };
        }
    }
}

/// Full-rate extremes over the run so far.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, schemars::JsonSchema)]
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
        for (i, v) in v.iter().enumerate() {
            self.signal_mut(i).update(t, *v);
        }
    }

    /// Signal `index` in [`Peaks::signals`]'s order.
    fn signal_mut(&mut self, index: usize) -> &mut Peak {
        match index {
            0 => &mut self.q_tip,
            1 => &mut self.theta_tip,
            2 => &mut self.q_tip_rate,
            3 => &mut self.theta_tip_rate,
            4 => &mut self.tau1,
            5 => &mut self.tau2,
            6 => &mut self.g1_error,
            _ => &mut self.g2_error,
        }
    }

    /// Fold in the value v of signal `index` ([`Peaks::signals`]'s order) found inside a step
    /// at time t, with its one-sided `sub_step_error`.
    pub(crate) fn update_sub_step(&mut self, index: usize, t: f64, v: f64, sub_step_error: f64) {
        self.signal_mut(index).update_sub_step(t, v, sub_step_error);
    }
}

/// Full-rate ∫τ² dt of both control channels (N² s, N² m² s) over the current output interval:
/// the trapezoidal rule between consecutive recorded instants — every integrator step's end and
/// both sides of every sample's jump of the held estimate (a jump adds no time). This is the
/// RMS of τ(t) itself; an RMS of the output samples alone is phase-locked for a controller that
/// chatters at the sample rate (every output instant sees the same phase of the chatter: for
/// the explicit FTDO at the paper point 3.51 N from 10-ms samples against 3.45 N full rate).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SquareIntegral {
    start: f64,
    last_t: f64,
    last: [f64; 2],
    integral: [f64; 2],
    started: bool,
}

impl SquareIntegral {
    /// Record the values [τ1, τ2] at time t (t never decreases).
    pub fn update(&mut self, t: f64, v: [f64; 2]) {
        self.update_step(t, v, None);
    }

    /// Record the values [τ1, τ2] at time t, with the exact ∫τ² dt since the previous instant
    /// if the scheme provides it (the exponential scheme), the trapezoidal rule otherwise.
    pub fn update_step(&mut self, t: f64, v: [f64; 2], exact: Option<[f64; 2]>) {
        if !self.started {
            (self.start, self.started) = (t, true);
        }
        let h = t - self.last_t;
        if h > 0.0 {
            for c in 0..2 {
                self.integral[c] += match exact {
                    Some(square) => square[c],
                    None => 0.5 * h * (self.last[c] * self.last[c] + v[c] * v[c]),
                };
            }
        }
        (self.last_t, self.last) = (t, v);
    }

    /// Add `squares` (N² s, N² m² s) to the current interval's ∫τ² dt: the part a scheme
    /// defers from its steps to the interval's end ([`crate::modal::Recorder::deferred_squares`]).
    pub fn add_squares(&mut self, squares: [f64; 2]) {
        for (i, s) in self.integral.iter_mut().zip(squares) {
            *i += s;
        }
    }

    /// RMS √(∫τ² dt / Δt) of each channel over the interval since the previous call (|τ| at
    /// the latest instant for an interval of zero length), and start the next interval there.
    pub fn take_rms(&mut self) -> [f64; 2] {
        let span = self.last_t - self.start;
        let rms = [0, 1].map(|c| if span > 0.0 { (self.integral[c] / span).sqrt() } else { self.last[c].abs() });
        (self.start, self.integral) = (self.last_t, [0.0; 2]);
        rms
    }
}

/// Full-rate extremes of the chattering signals [τ1, τ2, g̃1, g̃2] over the current output
/// interval: the smallest and largest value at every recorded instant since the previous output
/// (every integrator step's end and both sides of every sample's jump). An output sample alone
/// aliases a signal that chatters at the sample rate (the explicit FTDO's τ1 jumps between about
/// +3.35 and −3.8 N every millisecond; its 10-ms samples read a steady +3.4 N): these bound it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IntervalRange {
    lo: [f64; 4],
    hi: [f64; 4],
    seen: bool,
}

impl Default for IntervalRange {
    fn default() -> Self {
        IntervalRange { lo: [f64::INFINITY; 4], hi: [f64::NEG_INFINITY; 4], seen: false }
    }
}

impl IntervalRange {
    /// Fold in the values [τ1, τ2, g̃1, g̃2] of one instant.
    pub fn update(&mut self, v: [f64; 4]) {
        for (c, v) in v.into_iter().enumerate() {
            self.include(c, v);
        }
        self.seen = true;
    }

    /// Fold in one value of signal `c` (τ1, τ2, g̃1, g̃2) without the others (a sub-step value).
    pub fn include(&mut self, c: usize, v: f64) {
        self.lo[c] = self.lo[c].min(v);
        self.hi[c] = self.hi[c].max(v);
    }

    /// The (min, max) of each signal since the previous call — `at` (the values at the output
    /// instant) when no instant was recorded, and always including `at` — and start the next
    /// interval.
    pub fn take(&mut self, at: [f64; 4]) -> [(f64, f64); 4] {
        self.update(at);
        let r = [0, 1, 2, 3].map(|c| (self.lo[c], self.hi[c]));
        *self = IntervalRange::default();
        r
    }
}

/// When |g̃| enters the band |g̃| ≤ [`crate::metrics::GTILDE_THRESHOLD`] for good, at full rate:
/// the first recorded instant after the last one outside the band.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct BandEntry {
    /// Whether an instant has been recorded.
    seen: bool,
    /// Whether some instant so far was outside the band.
    left: bool,
    /// The first instant inside the band since the last one outside (None while outside).
    entry: Option<f64>,
    /// The first recorded instant.
    first: f64,
}

impl BandEntry {
    fn update(&mut self, t: f64, g_error: f64) {
        if !self.seen {
            self.seen = true;
            self.first = t;
        }
        if g_error.abs() > crate::metrics::GTILDE_THRESHOLD {
            self.left = true;
            self.entry = None;
        } else if self.entry.is_none() {
            self.entry = Some(t);
        }
    }

    /// The entry time (s): the first instant if the signal never left the band; None if it is
    /// outside at the last instant (or nothing was recorded).
    pub(crate) fn time(&self) -> Option<f64> {
        match (self.seen, self.left) {
            (false, _) => None,
            (true, false) => Some(self.first),
            (true, true) => self.entry,
        }
    }
}

/// What is tracked at every recorded instant of a run (every integrator step's end and both
/// sides of every jump): the extremes and the τ square integrals, fed the same values
/// [q, θ, q̇, θ̇, τ1, τ2, g̃1, g̃2].
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct FullRate {
    /// The extremes.
    pub(crate) peaks: Peaks,
    /// The extremes after the initial layer (t > `layer_end`, [`crate::layer`]).
    pub(crate) after_layer: Peaks,
    layer_end: f64,
    squares: SquareIntegral,
    range: IntervalRange,
    band: [BandEntry; 2],
}

impl FullRate {
    /// Tracking from t = 0, with the peaks after `layer_end` (s) kept apart.
    pub(crate) fn new(layer_end: f64) -> FullRate {
        FullRate { layer_end, ..Default::default() }
    }

    /// Fold in the values at time t.
    pub(crate) fn update(&mut self, t: f64, v: &[f64; 8]) {
        self.update_step(t, v, None);
    }

    /// Fold in the values at time t, the end of a step whose exact ∫τ² the scheme may give
    /// ([`SquareIntegral::update_step`]).
    pub(crate) fn update_step(&mut self, t: f64, v: &[f64; 8], exact: Option<[f64; 2]>) {
        self.peaks.update(t, v);
        if t > self.layer_end {
            self.after_layer.update(t, v);
        }
        self.squares.update_step(t, [v[4], v[5]], exact);
        self.range.update([v[4], v[5], v[6], v[7]]);
        self.band[0].update(t, v[6]);
        self.band[1].update(t, v[7]);
    }

    /// Fold in the value v of signal `index` ([`Peaks::signals`]'s order) found inside a step at
    /// time t by the sub-step probe, with its one-sided error: the peaks (after the layer too,
    /// for t past it) and, for τ, the interval's range; not the ∫τ² (the scheme's is exact).
    pub(crate) fn update_sub_step(&mut self, index: usize, t: f64, v: f64, sub_step_error: f64) {
        self.peaks.update_sub_step(index, t, v, sub_step_error);
        if t > self.layer_end {
            self.after_layer.update_sub_step(index, t, v, sub_step_error);
        }
        if (4..6).contains(&index) {
            self.range.include(index - 4, v);
        }
    }

    /// The running peaks |max| of the signals `indices` ([`Peaks::signals`]'s order) that a
    /// value at time t competes with: after the initial layer, those after it.
    pub(crate) fn running<const K: usize>(&self, t: f64, indices: [usize; K]) -> [f64; K] {
        let peaks = if t > self.layer_end { &self.after_layer } else { &self.peaks };
        let s = peaks.signals();
        indices.map(|i| s[i].abs_max)
    }

    /// Full-rate (min, max) of τ1, τ2, g̃1, g̃2 since the previous call, including the values
    /// `at` of the output instant ([`IntervalRange::take`]).
    pub(crate) fn take_range(&mut self, at: [f64; 4]) -> [(f64, f64); 4] {
        self.range.take(at)
    }

    /// From when |g̃1|, |g̃2| stay in the band |g̃| ≤ [`crate::metrics::GTILDE_THRESHOLD`], at full
    /// rate ([`BandEntry::time`]).
    pub(crate) fn band_entry(&self) -> [Option<f64>; 2] {
        [self.band[0].time(), self.band[1].time()]
    }

    /// See [`SquareIntegral::add_squares`].
    pub(crate) fn add_squares(&mut self, squares: [f64; 2]) {
        self.squares.add_squares(squares);
    }

    /// Full-rate RMS of τ1, τ2 since the previous call ([`SquareIntegral::take_rms`]).
    pub(crate) fn take_tau_rms(&mut self) -> [f64; 2] {
        self.squares.take_rms()
    }
}

#[cfg(test)]
mod tests {
    use super::{BandEntry, IntervalRange, SquareIntegral};

    #[test]
    fn band_entry_is_the_first_instant_after_the_last_one_outside() {
        // Reference: the instants fed in, by inspection (threshold 1e-4).
        let mut b = BandEntry::default();
        assert_eq!(b.time(), None);
        for (t, g) in [(0.0, 1.0), (0.001, 5e-5), (0.002, 2e-4), (0.003, 2e-4), (0.003, 3e-5), (0.004, 1e-6)] {
            b.update(t, g);
        }
        // both sides of a jump at 0.003: outside before it, inside after it
        assert_eq!(b.time(), Some(0.003));
        b.update(0.005, -2e-4);
        assert_eq!(b.time(), None, "outside at the last instant");
        let mut inside = BandEntry::default();
        inside.update(0.5, 0.0);
        inside.update(0.6, -1e-5);
        assert_eq!(inside.time(), Some(0.5), "never outside: from the first instant");
    }

    #[test]
    fn interval_range_holds_every_instant_and_restarts() {
        // Reference: the extremes of the values fed in, by inspection.
        let mut r = IntervalRange::default();
        r.update([3.35, 1.0, -0.5, 0.0]);
        r.update([-3.8, 2.0, 0.5, 0.0]);
        let got = r.take([3.4, 1.5, 0.0, 0.0]);
        assert_eq!(got[0], (-3.8, 3.4));
        assert_eq!(got[1], (1.0, 2.0));
        assert_eq!(got[2], (-0.5, 0.5));
        // nothing recorded since: the output instant's own values
        assert_eq!(r.take([1.0, 2.0, 3.0, 4.0])[3], (4.0, 4.0));
    }

    #[test]
    fn full_rate_rms_of_a_sine_and_of_a_jump() {
        // Reference: RMS of sin over whole periods is 1/√2 (analytic); the trapezoidal rule on
        // 20 000 points per period is exact to ~1e-9 for this periodic integrand.
        let mut sq = SquareIntegral::default();
        let n = 20_000;
        for i in 0..=n {
            let t = i as f64 / n as f64;
            let v = (2.0 * std::f64::consts::PI * t).sin();
            sq.update(t, [v, 2.0]);
        }
        let [rms, constant] = sq.take_rms();
        assert!((rms - std::f64::consts::FRAC_1_SQRT_2).abs() < 1e-9, "{rms}");
        assert!((constant - 2.0).abs() < 1e-15);
        // A jump adds no time: 1 over [1, 2] then 3 over [2, 3] (jump at t = 2) → √5.
        sq.update(2.0, [1.0, 1.0]);
        sq.update(2.0, [3.0, 3.0]);
        sq.update(3.0, [3.0, 3.0]);
        let [after, _] = sq.take_rms();
        // the first interval after the reset runs from t = 1 (last take) with values 0→1 at
        // t = 1 → 2: ∫ = ½(0² + 1²)·1 = 0.5; then 3² over [2, 3] = 9; RMS √(9.5/2)
        assert!((after - (9.5f64 / 2.0).sqrt()).abs() < 1e-12, "{after}");
    }
}
