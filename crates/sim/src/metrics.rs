//! The run metrics, defined once and used by every crate (the claim ledger, the report's
//! captions and the search): RMS and max |·| over a window of the output samples, the
//! full-rate RMS of τ, settling times, the observer error g̃ = g − ĝ.
//!
//! Rules shared by all of them:
//! - a window is the closed interval [t0, t1] of sample times, with a tolerance of
//!   1e-9 s·(1 + |t1|) at both ends ([`window_indices`]);
//! - an empty window gives `None`, never 0 or NaN;
//! - peaks are taken from the simulator's full-rate [`crate::Peaks`] (every integrator step,
//!   both sides of every jump), never from the output samples, whenever the quantity has one;
//! - the settling time of a signal x is the last exit from the band |x| ≤ [`SETTLE_FRACTION`]
//!   × |x(0)| ([`settle_time`]); the joint settling time of the tip is the later of the
//!   bending and twist channels'.

use crate::{windowed_rms, Series, SimOutput};

/// Settling band of a tip signal as a fraction of its initial magnitude: the signal has
/// settled once |x(t)| ≤ 0.05 |x(0)| for the rest of the run (the usual 5 % settling time).
pub const SETTLE_FRACTION: f64 = 0.05;

/// |g̃| below which the disturbance estimate counts as converged (N or N m).
pub const GTILDE_THRESHOLD: f64 = 1e-4;

/// When |g̃1| and |g̃2| enter the band |g̃| ≤ a threshold for good, and how that was read.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GtildeBand {
    /// Per channel, the time (s) from which |g̃| stays within the band; `None` if it is outside
    /// at the end of the run.
    pub entry: [Option<f64>; 2],
    /// Read at full rate (every integrator step and both sides of every sample's jump: the
    /// simulator tracks the band at [`GTILDE_THRESHOLD`]); false: off the output samples.
    pub full_rate: bool,
}

impl GtildeBand {
    /// The spacing (s) of the instants the entry was read from: the integrator step at full
    /// rate, the output interval otherwise.
    pub fn sampling(&self, cfg: &wingcheck_model::Config) -> f64 {
        if self.full_rate {
            cfg.discretisation.dt
        } else {
            cfg.horizon.sample_every
        }
    }
}

/// The band entry of g̃ at `threshold` (N, N m): at full rate ([`SimOutput::gtilde_band_entry`])
/// where `threshold` is the one the simulator tracks, [`GTILDE_THRESHOLD`]; otherwise the
/// settling time of g̃'s output samples against `threshold` ([`settle_time`]).
pub fn gtilde_band(out: &SimOutput, threshold: f64) -> GtildeBand {
    if threshold == GTILDE_THRESHOLD {
        GtildeBand { entry: out.gtilde_band_entry, full_rate: true }
    } else {
        let entry = [0, 1].map(|c| settle_time(&out.series.t, &observer_error(&out.series, c), threshold));
        GtildeBand { entry, full_rate: false }
    }
}

/// A closed time window [t0, t1] (s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Window {
    /// Start (s).
    pub t0: f64,
    /// End (s).
    pub t1: f64,
}

impl Window {
    /// The whole run of `t`.
    pub fn whole(t: &[f64]) -> Window {
        Window { t0: t.first().copied().unwrap_or(0.0), t1: t.last().copied().unwrap_or(0.0) }
    }

    /// The second half [t_end/2, t_end] of a run ending at t_end.
    pub fn second_half(t_end: f64) -> Window {
        Window { t0: 0.5 * t_end, t1: t_end }
    }
}

/// Indices of the samples with t ∈ [t0, t1] (1e-9 s·(1 + |t1|) tolerance at both ends).
pub fn window_indices(t: &[f64], w: Window) -> std::ops::Range<usize> {
    let tol = 1e-9 * (1.0 + w.t1.abs());
    let lo = t.partition_point(|&x| x < w.t0 - tol);
    let hi = t.partition_point(|&x| x <= w.t1 + tol);
    lo..hi.max(lo)
}

/// Root mean square of the samples (None for none).
pub fn rms(v: &[f64]) -> Option<f64> {
    (!v.is_empty()).then(|| (v.iter().map(|x| x * x).sum::<f64>() / v.len() as f64).sqrt())
}

/// max |v| over the samples (None for none).
pub fn max_abs(v: &[f64]) -> Option<f64> {
    v.iter().map(|x| x.abs()).reduce(f64::max)
}

/// RMS of the samples of `v` in the window.
pub fn rms_in(t: &[f64], v: &[f64], w: Window) -> Option<f64> {
    rms(&v[window_indices(t, w)])
}

/// max |v| over the samples of `v` in the window.
pub fn max_abs_in(t: &[f64], v: &[f64], w: Window) -> Option<f64> {
    max_abs(&v[window_indices(t, w)])
}

/// Time after which |x| ≤ `threshold` for the rest of the series: the sample after the last
/// one outside the band (the first sample if none is); None if the last sample is outside.
pub fn settle_time(t: &[f64], x: &[f64], threshold: f64) -> Option<f64> {
    match x.iter().rposition(|v| v.abs() > threshold) {
        None => t.first().copied(),
        Some(i) if i + 1 < t.len() => Some(t[i + 1]),
        Some(_) => None,
    }
}

/// Settling time of a tip signal: [`settle_time`] with the band `fraction`·|x(0)| (the ledger's
/// `settle_fraction`, default [`SETTLE_FRACTION`]). A signal that starts at 0 is settled from
/// the start only if it stays at 0.
pub fn tip_settle_time(t: &[f64], x: &[f64], fraction: f64) -> Option<f64> {
    settle_time(t, x, fraction * x.first().map_or(0.0, |v| v.abs()))
}

/// Joint settling time of the tip: the first sample time after which |q(s,t)| ≤
/// `fraction`·|q(s,0)| and |θ(s,t)| ≤ `fraction`·|θ(s,0)| for the rest of the run, i.e. the
/// later of the two channels' [`tip_settle_time`]. A channel that starts at 0 has no band and is
/// left out; None if both start at 0, or a channel has not settled by the end.
pub fn joint_tip_settle_time(t: &[f64], q_tip: &[f64], theta_tip: &[f64], fraction: f64) -> Option<f64> {
    let starts_nonzero = |x: &[f64]| x.first().is_some_and(|v| *v != 0.0);
    let channels: Vec<&[f64]> = [q_tip, theta_tip].into_iter().filter(|x| starts_nonzero(x)).collect();
    if channels.is_empty() {
        return None;
    }
    channels.into_iter().try_fold(f64::NEG_INFINITY, |later, x| Some(later.max(tip_settle_time(t, x, fraction)?)))
}

/// Full-rate RMS of τ over the window ([`windowed_rms`]: ∫τ² dt over every integrator step);
/// `channel` 0 is τ1, 1 is τ2.
pub fn tau_rms_in(s: &Series, channel: usize, w: Window) -> Option<f64> {
    let interval = if channel == 0 { &s.tau1_rms } else { &s.tau2_rms };
    windowed_rms(&s.t, interval, w.t0, w.t1)
}

/// g̃ = g − ĝ of one channel at the output samples (N or N m).
pub fn observer_error(s: &Series, channel: usize) -> Vec<f64> {
    let (g, g_hat) = if channel == 0 { (&s.g1, &s.g1_hat) } else { (&s.g2, &s.g2_hat) };
    g.iter().zip(g_hat).map(|(a, b)| a - b).collect()
}

/// sup_t |g̃| of one channel over the whole run at full rate ([`crate::Peaks`]).
pub fn observer_error_sup(out: &SimOutput, channel: usize) -> f64 {
    if channel == 0 {
        out.peaks.g1_error.abs_max
    } else {
        out.peaks.g2_error.abs_max
    }
}

/// The full-rate envelope of one chattering signal ([`crate::Envelope`]): 0 is τ1, 1 is τ2,
/// 2 is g̃1, 3 is g̃2; (min, max) per output interval.
pub fn envelope_of(out: &SimOutput, signal: usize) -> &[(f64, f64)] {
    let e = &out.envelope;
    match signal {
        0 => &e.tau1,
        1 => &e.tau2,
        2 => &e.g1_error,
        _ => &e.g2_error,
    }
}

/// max |v| per output interval of a full-rate envelope: max(|min|, |max|).
pub fn envelope_abs_max(env: &[(f64, f64)]) -> Vec<f64> {
    env.iter().map(|(lo, hi)| lo.abs().max(hi.abs())).collect()
}

/// min |v| per output interval of a full-rate envelope (0 when the interval's range holds 0;
/// the values between the recorded instants are taken as continuous).
pub fn envelope_abs_min(env: &[(f64, f64)]) -> Vec<f64> {
    env.iter().map(|&(lo, hi)| if lo <= 0.0 && hi >= 0.0 { 0.0 } else { lo.abs().min(hi.abs()) }).collect()
}

/// Full-rate peak |τ| of one channel over the whole run.
pub fn tau_peak(out: &SimOutput, channel: usize) -> f64 {
    if channel == 0 {
        out.peaks.tau1.abs_max
    } else {
        out.peaks.tau2.abs_max
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn windows_are_closed_and_empty_windows_give_none() {
        let t = [0.0, 0.5, 1.0, 1.5, 2.0];
        let v = [4.0, -3.0, 0.0, 1.0, -1.0];
        assert_eq!(window_indices(&t, Window { t0: 1.0, t1: 2.0 }), 2..5);
        assert_eq!(max_abs_in(&t, &v, Window { t0: 0.5, t1: 1.0 }), Some(3.0));
        // RMS of (0, 1, −1) = √(2/3)
        assert_eq!(rms_in(&t, &v, Window::second_half(2.0)), Some((2.0f64 / 3.0).sqrt()));
        assert_eq!(rms_in(&t, &v, Window { t0: 3.0, t1: 4.0 }), None);
        assert_eq!(max_abs(&[]), None);
    }

    #[test]
    fn settling_is_the_last_exit_from_the_band() {
        let t = [0.0, 1.0, 2.0, 3.0, 4.0];
        // band 0.05 × 1: last sample outside is t = 2, so settled from t = 3
        assert_eq!(tip_settle_time(&t, &[1.0, 0.5, -0.2, 0.01, 0.0], SETTLE_FRACTION), Some(3.0));
        // outside at the end: never
        assert_eq!(tip_settle_time(&t, &[1.0, 0.5, 0.2, 0.1, 0.06], SETTLE_FRACTION), None);
        // never outside: settled at the first sample
        assert_eq!(settle_time(&t, &[0.0; 5], 0.1), Some(0.0));
    }
}

/// The median of `v` (the mean of the two middle values for an even count; NaNs sort last by
/// `total_cmp`), or `None` for no values: the one median of wingcheck (the report's region-map
/// statistics, every benchmark's timings).
pub fn median(mut v: Vec<f64>) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    Some(if n % 2 == 1 { v[n / 2] } else { 0.5 * (v[n / 2 - 1] + v[n / 2]) })
}

/// Least-squares slope of log(y) against log(x) (pairs with x, y > 0 only; NaN for fewer than
/// two such pairs): the one fitted exponent of wingcheck (the benchmarks' scaling exponents, the
/// report's convergence orders).
pub fn loglog_slope(x: &[f64], y: &[f64]) -> f64 {
    let pts: Vec<(f64, f64)> =
        x.iter().zip(y).filter(|(a, b)| **a > 0.0 && **b > 0.0).map(|(a, b)| (a.ln(), b.ln())).collect();
    let n = pts.len() as f64;
    if pts.len() < 2 {
        return f64::NAN;
    }
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    sxy / sxx
}

#[cfg(test)]
mod median_tests {
    #[test]
    fn median_of_odd_even_and_empty() {
        // by hand: sorted [1, 2, 9] → 2; [1, 2, 3, 10] → (2 + 3)/2
        assert_eq!(super::median(vec![9.0, 1.0, 2.0]), Some(2.0));
        assert_eq!(super::median(vec![10.0, 3.0, 1.0, 2.0]), Some(2.5));
        assert_eq!(super::median(vec![]), None);
    }

    #[test]
    fn loglog_slope_of_a_power_law_and_of_bad_pairs() {
        use super::loglog_slope;
        // y = x^-2 exactly: slope −2 (by hand)
        assert!((loglog_slope(&[1.0, 2.0, 4.0], &[1.0, 0.25, 0.0625]) + 2.0).abs() < 1e-12);
        // non-positive pairs are left out (ln undefined), not turned into NaN or −∞: y = x³
        assert!((loglog_slope(&[1.0, 0.0, 2.0, 3.0], &[1.0, 5.0, 8.0, -1.0]) - 3.0).abs() < 1e-12);
        // fewer than two usable pairs: no slope
        assert!(loglog_slope(&[1.0, 2.0], &[1.0, 0.0]).is_nan());
    }
}
