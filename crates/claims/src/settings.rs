//! The checker's numerical settings: every grid, tolerance and threshold a row uses, in one
//! struct with the documented defaults, recorded in the ledger so a reader sees what was used.

use serde::Serialize;

/// Numerical settings of the claim checker (not part of the configuration: they choose how
/// hard the checker looks, not what is checked).
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
pub struct CheckSettings {
    /// Uniform Galerkin element counts of the W/κ refinement study (W-bounds); the last two
    /// are Richardson-extrapolated.
    pub w_grids: [usize; 4],
    /// Element counts of the SDP cross-check of W/κ (W-bounds).
    pub sdp_grids: [usize; 5],
    /// Re-verification tolerance of the SDP cross-check, relative to each pencil's scale.
    pub sdp_tolerance: f64,
    /// Galerkin elements of the tight λ1 = sup W/κ used in λ = λ3/λ1 (mu-conditions).
    pub mu_lambda1_elements: usize,
    /// Relative agreement required between a clarabel value and its closed form.
    pub mu_cross_check_tolerance: f64,
    /// Galerkin elements of the tight λ2 = inf W/κ used in the bound (37) (UUB).
    pub uub_lambda2_elements: usize,
    /// Uniform FE meshes on which W(0) is computed (UUB).
    pub uub_w0_elements: [usize; 3],
    /// W(0) is called divergent when W(0) on the finest mesh exceeds this × the next (UUB).
    pub uub_w0_divergence_ratio: f64,
    /// Bound / simulated envelope above which a bound that holds is called vacuous (UUB).
    pub vacuity_ratio: f64,
    /// Hold periods T_s of the digital-observer study (s) (finite-time rows).
    pub hold_periods: [f64; 3],
    /// Length of the chatter window at the end of each digital run (s) (finite-time rows).
    pub chatter_window_s: f64,
    /// RK4 steps of the σ-domain Filippov integrator (doubled for its error estimate).
    pub filippov_steps: usize,
    /// Largest polynomial degree of the Lemma 2 search.
    pub lemma2_max_degree: usize,
    /// Settling band as a fraction of the initial tip value ([`wingcheck_sim::metrics`]).
    pub settle_fraction: f64,
    /// |g̃| below which the disturbance estimate counts as converged (N or N m).
    pub gtilde_threshold: f64,
    /// Relative difference of tip metrics below which two controllers are indistinguishable
    /// (ftdo-vs-dobc).
    pub indistinguishable: f64,
    /// Factor by which each weight is multiplied and divided in the (a, b) sweep (ftdo-vs-dobc).
    pub sweep_factor: f64,
}

impl Default for CheckSettings {
    fn default() -> Self {
        CheckSettings {
            w_grids: [2, 4, 8, 16],
            sdp_grids: wingcheck_theory::sdp::SDP_GRIDS,
            sdp_tolerance: wingcheck_theory::sdp::SDP_TOLERANCE,
            mu_lambda1_elements: 8,
            mu_cross_check_tolerance: 1e-6,
            uub_lambda2_elements: 16,
            uub_w0_elements: [16, 32, 64],
            uub_w0_divergence_ratio: 1.5,
            vacuity_ratio: 100.0,
            hold_periods: wingcheck_model::work::FINITE_TIME_PERIODS,
            chatter_window_s: wingcheck_model::work::FINITE_TIME_WINDOW_S,
            filippov_steps: 2000,
            lemma2_max_degree: 8,
            settle_fraction: wingcheck_sim::metrics::SETTLE_FRACTION,
            gtilde_threshold: wingcheck_sim::metrics::GTILDE_THRESHOLD,
            indistinguishable: 0.05,
            sweep_factor: 2.0,
        }
    }
}
