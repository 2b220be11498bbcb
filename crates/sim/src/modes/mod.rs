//! Natural frequencies of the undamped, uncontrolled wing: the generalised eigenproblem
//! K φ = ω² M φ on one mesh ([`natural_frequencies`], sparse shift-invert), converged
//! frequencies with error estimates by extrapolation over uniform meshes
//! ([`converged_frequencies`], [`fundamental_frequency`]), and the analytic frequencies of the
//! uncoupled problem.

mod converged;
mod eigen;

pub use converged::{
    converged_frequencies, fundamental_frequency, ConvergedModes, ModeEstimate, DEFAULT_MODE_TOLERANCE,
};
pub use eigen::{lowest_eigenvalues, RitzValue};

use crate::{Discretisation, SimError};

/// The `count` lowest natural frequencies ω (rad/s) of K φ = ω² M φ of one discretisation,
/// ascending (sparse shift-invert subspace iteration, [`lowest_eigenvalues`]).
pub fn natural_frequencies(disc: &Discretisation, count: usize) -> Result<Vec<f64>, SimError> {
    let count = count.min(disc.dim());
    Ok(lowest_eigenvalues(disc, count)?.into_iter().map(|r| r.lambda.sqrt()).collect())
}

/// n-th root (n ≥ 1) of the cantilever frequency equation 1 + cos x cosh x = 0, by bisection
/// on cos x + 1/cosh x (same roots, no overflow) in its bracket.
pub fn cantilever_root(n: usize) -> f64 {
    use std::f64::consts::PI;
    let g = |x: f64| x.cos() + 1.0 / x.cosh();
    let c = (n as f64 - 0.5) * PI;
    let (mut lo, mut hi) = if n % 2 == 1 { (c, n as f64 * PI) } else { ((n as f64 - 1.0) * PI, c) };
    let glo = g(lo);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if (g(mid) > 0.0) == (glo > 0.0) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Analytic uncoupled (ρx_c = 0) bending frequencies β_n² √(EI/ρ), β_n s the cantilever roots.
pub fn bending_frequencies(span: f64, ei: f64, rho: f64, count: usize) -> Vec<f64> {
    (1..=count).map(|n| (cantilever_root(n) / span).powi(2) * (ei / rho).sqrt()).collect()
}

/// Analytic uncoupled torsion frequencies (2n − 1)π/(2s)·√(GJ/I_p).
pub fn torsion_frequencies(span: f64, gj: f64, ip: f64, count: usize) -> Vec<f64> {
    (1..=count).map(|n| (2 * n - 1) as f64 * std::f64::consts::PI / (2.0 * span) * (gj / ip).sqrt()).collect()
}

/// The analytic uncoupled frequencies of both families merged and sorted (rad/s).
pub fn uncoupled_frequencies(span: f64, ei: f64, rho: f64, gj: f64, ip: f64, count: usize) -> Vec<f64> {
    let mut all = bending_frequencies(span, ei, rho, count);
    all.extend(torsion_frequencies(span, gj, ip, count));
    all.sort_by(|a, b| a.total_cmp(b));
    all.truncate(count);
    all
}
