//! The ± of the comparison's simulation values: every run of the row again on the doubled grid
//! and at dt/2 ([`crate::study::refine`]), every metric's error from its changes
//! ([`metric_errors`], by [`refinement_error`]), and the errors of the ratios and relative
//! differences formed from them ([`quotient_error`]).

use super::Metrics;
use crate::study::refine::{reached_error, refinement_error};

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
}
