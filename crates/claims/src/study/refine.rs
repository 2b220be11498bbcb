//! The ± of a simulated value from its refinements: the same run on the doubled grid and at
//! dt/2, each stepping the run's own scheme ([`refinements`], [`same_scheme`]), and the error of
//! a value from its changes ([`refinement_error`], [`reached_error`]). The runs themselves come
//! from the study ([`super::Study::refined_runs`]); the comparison's metrics, the finite-time
//! rows and ζ3, ζ4 ([`super::Study::zeta_errors`]) take their ± from here.
//!
//! The refinements are runs for their series only ([`super::Study::refinement`]): no initial-layer
//! re-run and no sub-step probe, and the exponential scheme in the loop's eigenbasis where it
//! passes. A peak's change to its refinements therefore also holds what the layer and the
//! probe add to the configured run's peak: a ± at least as wide as the peak's resolution needs.

use wingcheck_model::Config;

/// Grid-part factor of the explicit FTDO's RMS τ error: F·|RMS(h) − RMS(h/2)| with F = 1.25·2,
/// the Richardson tail for order 1 with a 1.25 margin. The RMS of a chattering command
/// converges in h at an order between 1 and 2 (measured at the paper's point on 24, 48, 96
/// elements: 1.33 for τ1, 1.79 for τ2), so order 2's factor (4/3) would not cover it.
pub const EXPLICIT_RMS_GRID_FACTOR: f64 = 1.25 * 2.0;

/// `refined` stepped with the time scheme `base` is expected to step
/// ([`Config::expected_time_scheme`]), as `simulate --error-estimate` pins its refinements to
/// the base run's: under `stepper = auto` the explicit FTDO's doubled grid could otherwise cross
/// [`wingcheck_model::MODAL_AUTO_UNKNOWNS`] into the nodal basis and TR-BDF2 (from 96 elements
/// on), and the grid part of the error would absorb the two schemes' difference (1–2 % of RMS τ).
pub fn same_scheme(mut refined: Config, base: &Config) -> Config {
    refined.discretisation.stepper = base.expected_time_scheme();
    refined
}

/// The refinements of `cfg`: the doubled grid, then dt/2, each stepping `cfg`'s scheme.
pub fn refinements(cfg: &Config) -> [Config; 2] {
    [
        same_scheme(wingcheck_model::work::refined_in_space(cfg), cfg),
        same_scheme(wingcheck_model::work::refined_in_time(cfg), cfg),
    ]
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

#[cfg(test)]
mod tests {
    use super::*;

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
