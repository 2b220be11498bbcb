//! The ± of the comparison's simulation values: every run of the row again on the doubled grid
//! and at dt/2 (each stepping the run's own scheme, [`super::same_scheme`]), every metric's
//! error from its changes ([`refinement_error`]), and the errors of the ratios and relative
//! differences formed from them ([`quotient_error`]).
//!
//! The refinements are runs for their series only ([`crate::Study::refinement`]): no initial-layer
//! re-run and no sub-step probe, and the exponential scheme in the loop's eigenbasis where it
//! passes. A peak's change to its refinements therefore also holds what the layer and the
//! probe add to the configured run's peak: a ± at least as wide as the peak's resolution needs.

use std::sync::Arc;

use wingcheck_model::Config;
use wingcheck_sim::SimOutput;

use crate::ClaimsError;

use super::{same_scheme, Metrics, EXPLICIT_RMS_GRID_FACTOR};

/// The refinements of `cfg`: the doubled grid, then dt/2, each stepping `cfg`'s scheme.
pub fn refinements(cfg: &Config) -> [Config; 2] {
    [
        same_scheme(wingcheck_model::work::refined_in_space(cfg), cfg),
        same_scheme(wingcheck_model::work::refined_in_time(cfg), cfg),
    ]
}

/// The refinement runs of `cfg` through `study` ([`refinements`], [`crate::Study::refinement`]):
/// the doubled grid's, dt/2's, and the larger of their eigenbasis round-off estimates
/// (relative; 0 where neither stepped in the eigenbasis).
pub fn refined_runs(study: &crate::Study, cfg: &Config) -> Result<(Arc<SimOutput>, Arc<SimOutput>, f64), ClaimsError> {
    let [fine, half_dt] = refinements(cfg);
    let (fine, half_dt) = (study.refinement(&fine)?, study.refinement(&half_dt)?);
    let roundoff = [&fine, &half_dt].iter().filter_map(|o| o.stats.eigenbasis_roundoff).fold(0.0, f64::max);
    Ok((fine, half_dt, roundoff))
}

/// Error of a metric with value `value` on the configured grid and step, `fine` on the doubled
/// grid and `half_dt` at dt/2: the grid part [`EXPLICIT_RMS_GRID_FACTOR`]·|Δ| (the order-1 tail
/// with a 1.25 margin: RMS values of chattering commands converge in h at orders 1.3–1.8, a
/// settling time or a peak may converge slower still), the time-step part
/// [`wingcheck_sim::RICHARDSON_2`]·|Δ| (order 2 in dt), a round-off floor of
/// [`wingcheck_sim::layer::PEAK_ROUND_OFF`] of the value, and the refinements' eigenbasis
/// round-off (`roundoff`, relative, 0 where they stepped otherwise) through the same factors.
pub fn refinement_error(value: f64, fine: f64, half_dt: f64, roundoff: f64) -> f64 {
    let (grid, time) = (EXPLICIT_RMS_GRID_FACTOR, wingcheck_sim::RICHARDSON_2);
    grid * (value - fine).abs()
        + time * (value - half_dt).abs()
        + wingcheck_sim::layer::PEAK_ROUND_OFF * value.abs()
        + (grid + time) * roundoff * value.abs()
}

/// Error of a time that a run may or may not reach (a settling time, read off samples `sampling`
/// s apart: the crossing lies within one spacing before it): [`refinement_error`] plus the
/// spacing where the run and both refinements reach it; where only some do, the value itself
/// (its ± as large as it: unresolved); `None` where the run does not.
pub fn reached_error(
    value: Option<f64>,
    fine: Option<f64>,
    half_dt: Option<f64>,
    roundoff: f64,
    sampling: f64,
) -> Option<f64> {
    match (value, fine, half_dt) {
        (Some(v), Some(f), Some(h)) => Some(refinement_error(v, f, h, roundoff) + sampling),
        (Some(v), _, _) => Some(v.abs()),
        (None, _, _) => None,
    }
}

/// The errors of every metric of a run (a [`Metrics`] holding, per field, the error of that
/// field of `base`) from its values on the doubled grid (`fine`) and at dt/2 (`half_dt`);
/// `sampling`: the spacing (s) of the samples the settling times are read from (the output
/// samples for q and θ, the steps for g̃'s band entry), `[tip, g̃]`.
pub fn metric_errors(base: &Metrics, fine: &Metrics, half_dt: &Metrics, roundoff: f64, sampling: [f64; 2]) -> Metrics {
    let e = |v: fn(&Metrics) -> f64| refinement_error(v(base), v(fine), v(half_dt), roundoff);
    let t =
        |v: fn(&Metrics) -> Option<f64>, spacing: f64| reached_error(v(base), v(fine), v(half_dt), roundoff, spacing);
    Metrics {
        rms_q_full: e(|m| m.rms_q_full),
        rms_q_late: e(|m| m.rms_q_late),
        peak_q: e(|m| m.peak_q),
        rms_theta_full: e(|m| m.rms_theta_full),
        rms_theta_late: e(|m| m.rms_theta_late),
        peak_theta: e(|m| m.peak_theta),
        settle_q: t(|m| m.settle_q, sampling[0]),
        settle_theta: t(|m| m.settle_theta, sampling[0]),
        rms_tau1: e(|m| m.rms_tau1),
        peak_tau1: e(|m| m.peak_tau1),
        rms_tau2: e(|m| m.rms_tau2),
        peak_tau2: e(|m| m.peak_tau2),
        rms_gtilde_full: [e(|m| m.rms_gtilde_full[0]), e(|m| m.rms_gtilde_full[1])],
        rms_gtilde_late: [e(|m| m.rms_gtilde_late[0]), e(|m| m.rms_gtilde_late[1])],
        gtilde_settle: [t(|m| m.gtilde_settle[0], sampling[1]), t(|m| m.gtilde_settle[1], sampling[1])],
    }
}

/// Error of y/x (and of (y − x)/|x|, which differs from it by a constant and a sign) from the
/// errors `dx`, `dy` of x and y, to first order: (dy + |y/x|·dx)/|x|. Where x's interval
/// reaches 0 the quotient is unresolved: its error is then max(1, |y/x|), a ± as large as it.
pub fn quotient_error(x: f64, dx: f64, y: f64, dy: f64) -> f64 {
    if x.abs() <= dx {
        return if x == 0.0 { 1.0 } else { (y / x).abs().max(1.0) };
    }
    (dy + (y / x).abs() * dx) / x.abs()
}

/// Error of the late RMS g̃ of both channels combined (hypot): the hypot of the channels' errors
/// (the triangle inequality in the plane).
pub fn gtilde_late_error(errors: &Metrics) -> f64 {
    errors.rms_gtilde_late[0].hypot(errors.rms_gtilde_late[1])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The quotient's first-order error against the exact extremes of y/x over the boxes
    /// [x ± dx] × [y ± dy] (x > dx): the bound covers them to first order in the relative errors.
    #[test]
    fn quotient_error_covers_the_box() {
        for (x, dx, y, dy) in [(2.0, 0.01, 3.0, 0.02), (0.5, 1e-4, -0.2, 1e-3), (1e-3, 1e-6, 5e-3, 1e-7)] {
            let e = quotient_error(x, dx, y, dy);
            let corners = [(x - dx, y - dy), (x - dx, y + dy), (x + dx, y - dy), (x + dx, y + dy)];
            let worst = corners.iter().map(|(a, b)| (b / a - y / x).abs()).fold(0.0, f64::max);
            // second-order terms: (dx/x)·(the bound)
            assert!(worst <= e * (1.0 + 2.0 * dx / x), "{x} {dx} {y} {dy}: {worst:e} > {e:e}");
            assert!(worst >= 0.5 * e, "not needlessly wide: {worst:e} vs {e:e}");
        }
        // a denominator whose interval reaches 0: unresolved (the ± as large as the value)
        assert!(quotient_error(1e-3, 2e-3, 5.0, 0.0) >= 5.0 / 1e-3);
    }

    /// A metric that converges at order 2 in h and in dt: the bar from N, 2N and dt/2 covers the
    /// exact error of the configured value (a synthetic value v(h, dt) = v* + c h² + d dt²).
    #[test]
    fn refinement_error_covers_a_second_order_value() {
        let exact = 1.0;
        let v = |h: f64, dt: f64| exact + 0.3 * h * h - 0.7 * dt * dt;
        let (h, dt) = (0.1, 0.05);
        let e = refinement_error(v(h, dt), v(h / 2.0, dt), v(h, dt / 2.0), 0.0);
        assert!((v(h, dt) - exact).abs() <= e, "{} > {e}", (v(h, dt) - exact).abs());
    }
}
