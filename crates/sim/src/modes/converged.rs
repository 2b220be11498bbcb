//! Converged natural frequencies with error estimates: the lowest modes on uniform meshes
//! N_0, 2N_0, 4N_0, … (sparse shift-invert on each), Romberg-extrapolated in h² (the
//! eigenvalue error of both discretisations on uniform meshes expands in even powers of h:
//! O(h²) from the linear torsion elements / FD stencils, O(h⁴) from the Hermite bending
//! elements), with the observed order checked before an estimate is trusted. Meshes are added
//! until every estimate is below the requested relative tolerance.

use serde::Serialize;
use wingcheck_model::{Config, Method};

use super::eigen::lowest_eigenvalues;
use crate::estimate::{observed_order, romberg_table, Estimate};
use crate::{Discretisation, NumericalError, SimError};

/// Default relative tolerance on every frequency's error estimate.
pub const DEFAULT_MODE_TOLERANCE: f64 = 1e-9;

/// Coarsest mesh of the extrapolation (the work estimate's, `wingcheck_model::work::modes_meshes`).
const COARSEST: usize = wingcheck_model::work::MODES_COARSEST;
/// Finest mesh allowed (FE: 3·N unknowns, FD: 2·N).
const FINEST: usize = wingcheck_model::work::MODES_FINEST;
/// At most this many meshes enter the Romberg table (the finest ones).
const WINDOW: usize = 4;

/// One converged frequency.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, schemars::JsonSchema)]
pub struct ModeEstimate {
    /// ω (rad/s), extrapolated.
    pub omega: f64,
    /// Estimated bound on |ω − ω_exact| (rad/s): the larger of the last two Romberg
    /// corrections plus the eigen-solver bounds, so it bounds the error of the less accurate
    /// approximations, not only of the reported one.
    pub error: f64,
    /// Observed leading order of the raw values on the three finest meshes (2 for modes with
    /// torsion content, 4 for pure Hermite bending; None if the differences are at round-off).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub observed_order: Option<f64>,
}

impl ModeEstimate {
    /// As an [`Estimate`].
    pub fn estimate(&self) -> Estimate {
        Estimate { value: self.omega, error: self.error }
    }
}

/// Result of [`converged_frequencies`].
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
pub struct ConvergedModes {
    /// Discretisation used (FD or FE, uniform meshes).
    pub method: Method,
    /// Meshes solved (elements / intervals), coarse → fine.
    pub meshes: Vec<usize>,
    /// Requested relative tolerance.
    pub tolerance: f64,
    /// True if every estimate is ≤ tolerance·ω and every observed order is credible.
    pub converged: bool,
    /// The frequencies, ascending.
    pub modes: Vec<ModeEstimate>,
    /// Raw frequencies on each mesh (rad/s), `raw[k][mode]`.
    pub raw: Vec<Vec<f64>>,
}

/// Smallest relative tolerance of [`converged_frequencies`] (double precision resolves no
/// finer extrapolation).
pub const MIN_TOLERANCE: f64 = 1e-13;
/// Most frequencies [`converged_frequencies`] converges at once.
pub const MAX_COUNT: usize = 50;

fn uniform(cfg: &Config) -> Config {
    let mut c = cfg.clone();
    c.discretisation.grading = 0.0;
    c
}

/// The `count` lowest frequencies of the configured wing, converged to relative tolerance
/// `tol` (≥ [`MIN_TOLERANCE`]; 1 ≤ `count` ≤ [`MAX_COUNT`]) by extrapolation over uniform meshes of `method`. Cost at the paper's
/// point and count = 5: meshes 16…256 for the default tolerance, a few ms to tens of ms.
pub fn converged_frequencies(cfg: &Config, method: Method, count: usize, tol: f64) -> Result<ConvergedModes, SimError> {
    if !(tol.is_finite() && tol >= MIN_TOLERANCE) {
        return Err(NumericalError::ModeTolerance { tol, min: MIN_TOLERANCE }.into());
    }
    if count == 0 || count > MAX_COUNT {
        return Err(NumericalError::ModeCount { count, max: MAX_COUNT }.into());
    }
    let cfg = uniform(cfg);
    let mut n = COARSEST.max((2 * count).next_power_of_two());
    let mut meshes = Vec::new();
    let mut raw: Vec<Vec<f64>> = Vec::new();
    let mut solver_err: Vec<Vec<f64>> = Vec::new();
    loop {
        let disc = Discretisation::with(&cfg, method, n);
        let ritz = lowest_eigenvalues(&disc, count)?;
        meshes.push(n);
        raw.push(ritz.iter().map(|r| r.lambda.sqrt()).collect());
        // dω = dλ / (2ω)
        solver_err.push(ritz.iter().map(|r| r.solver_error / (2.0 * r.lambda.sqrt())).collect());
        if raw.len() >= 3 {
            let (modes, ok) = extrapolate(&raw, &solver_err, count, tol);
            if ok || 2 * n > FINEST {
                return Ok(ConvergedModes { method, meshes, tolerance: tol, converged: ok, modes, raw });
            }
        }
        n *= 2;
    }
}

/// Romberg over the finest ≤ [`WINDOW`] meshes; returns the estimates and whether all meet
/// the tolerance with a credible observed order.
fn extrapolate(raw: &[Vec<f64>], solver_err: &[Vec<f64>], count: usize, tol: f64) -> (Vec<ModeEstimate>, bool) {
    let first = raw.len().saturating_sub(WINDOW);
    let mut all_ok = true;
    let modes = (0..count)
        .map(|m| {
            let values: Vec<f64> = raw[first..].iter().map(|r| r[m]).collect();
            let table = romberg_table(&values, &[2.0, 4.0, 6.0]);
            let k = table.len() - 1;
            let best = table[k][k];
            let correction = (best - table[k][k - 1]).abs().max((best - table[k - 1][k - 1]).abs());
            let solver = solver_err[first..].iter().map(|e| e[m]).fold(0.0, f64::max);
            // Romberg weights sum in absolute value to < 2 for these exponents.
            let error = correction + 2.0 * solver + 4.0 * f64::EPSILON * best.abs();
            let l = values.len();
            let order = observed_order(values[l - 3], values[l - 2], values[l - 1]);
            // Credible: leading order ≥ 1.5, or differences already at round-off level.
            let roundoff = (values[l - 2] - values[l - 1]).abs() <= 1e3 * f64::EPSILON * best.abs();
            let credible = roundoff || order.is_some_and(|p| p >= 1.5);
            if !(credible && error <= tol * best.abs()) {
                all_ok = false;
            }
            ModeEstimate { omega: best, error, observed_order: order }
        })
        .collect();
    (modes, all_ok)
}

/// The converged fundamental frequency ω₁ (rad/s) of the configured wing, FE, default
/// tolerance, with its error estimate: the threshold a/b < ω₁ of W ≻ 0.
pub fn fundamental_frequency(cfg: &Config) -> Result<Estimate, SimError> {
    let modes = converged_frequencies(cfg, Method::Fe, 1, DEFAULT_MODE_TOLERANCE)?;
    Ok(modes.modes[0].estimate())
}
