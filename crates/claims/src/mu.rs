//! The `mu-conditions` row, (29)–(32): conditions μ1…μ6 > 0 on the gains and the η's,
//! λ3 = min μ3..μ6, λ = λ3/λ1, ε.
//!
//! Evidence → verdict → text: [`evidence`] computes [`MuEvidence`] from the closed forms of
//! [`wingcheck_theory`] (satisfiability decided in exact rational arithmetic; the best point's
//! μ's re-checked exactly) and the clarabel cross-checks of [`wingcheck_theory::convex`]; its
//! [`crate::explain::Explain`] reads only that evidence ([`explain`]).

mod explain;

use wingcheck_model::Config;

use crate::settings::CheckSettings;
use crate::study::Study;
use crate::ClaimsError;
use wingcheck_theory::convex::{check_epsilon, check_lambda3, CrossCheck};
use wingcheck_theory::{self as theory, ratio_boundary, BestPoint, DisturbanceBounds, MuData, Obstruction};

pub use explain::{check, MuEvidence, MuResult};

/// Tight λ1 (sup W/κ) at weights (a, b) on `elements` Galerkin elements (a lower bound of
/// sup W/κ: the maximum over a subspace).
pub fn lambda1_on(cfg: &Config, a: f64, b: f64, elements: usize) -> Result<f64, ClaimsError> {
    use wingcheck_theory::lyapunov::{assemble, decimal, tight_constants, Coupling, LyapunovParams};
    let p = LyapunovParams::from_config(cfg, Coupling::Corrected, elements).with_weights(&decimal(a), &decimal(b));
    let f = assemble(&p).map_err(crate::wbounds::num("assembly"))?;
    Ok(tight_constants(&f).map_err(crate::wbounds::num("eigen"))?.lambda1)
}

/// The ε/λ-optimal point at weights (a, b) with bounds (g_hmax, ζ3, ζ4) ([`theory::best_point`]
/// with the tight λ1 on `elements` Galerkin elements; the row uses
/// [`CheckSettings::mu_lambda1_elements`]).
pub fn best_point(
    cfg: &Config,
    a: f64,
    b: f64,
    bounds: (f64, f64, f64),
    elements: usize,
) -> Result<Option<BestPoint>, ClaimsError> {
    let d = MuData::new(cfg, a, b);
    if d.obstruction_exact(cfg.control.k1, cfg.control.k2).is_some() {
        return Ok(None);
    }
    let l1 = lambda1_on(cfg, a, b, elements)?;
    let bounds = DisturbanceBounds { g_hmax: bounds.0, zeta3: bounds.1, zeta4: bounds.2 };
    Ok(theory::best_point(&d, l1, &bounds, cfg.control.k1, cfg.control.k2))
}

/// Everything the mu-conditions row computes, before it is put into words.
#[derive(Debug, Clone)]
pub struct Computed {
    /// (32) satisfiable at the configured gains (closed-form criterion, exact arithmetic), else
    /// the first condition that fails.
    pub obstruction: Option<Obstruction>,
    /// λ3* = sup min{μ3..μ6} at the configured (a, b) (a, b > 0 only).
    pub lambda3_sup: Option<f64>,
    /// clarabel's max λ3, re-verified (a, b > 0 only).
    pub lambda3_socp: Option<CrossCheck>,
    /// Closed-form largest a/b (0: none).
    pub r_star: f64,
    /// Sign agreement of clarabel with the closed form on a grid around r*: (agree, accepted, tried).
    pub grid: (usize, usize, usize),
    /// g_hmax, ζ3, ζ4.
    pub bounds: DisturbanceBounds,
    /// The errors of ζ3, ζ4 ([`Study::zeta_errors`]).
    pub zeta_errors: [f64; 2],
    /// The ε/λ-optimal point (configured gains if satisfiable, else a/b = r*/2, same b).
    pub best: Option<BestPoint>,
    /// clarabel's min ε at the best point's λ3, re-verified.
    pub epsilon_socp: Option<CrossCheck>,
}

/// The weights (a, b) where the row evaluates the ε/λ-optimal point (and the UUB row its bound):
/// the configured ones when (32) holds there, else a/b = r*/2 with the configured b; None when
/// no a/b satisfies (32).
pub fn operating_point(cfg: &Config) -> Option<(f64, f64)> {
    let (a, b, k1, k2) = (cfg.control.a, cfg.control.b, cfg.control.k1, cfg.control.k2);
    let r_star = ratio_boundary(cfg);
    if MuData::new(cfg, a, b).obstruction_exact(k1, k2).is_none() {
        Some((a, b))
    } else if r_star > 0.0 && b > 0.0 && k1 > 0.0 && k2 > 0.0 {
        Some((0.5 * r_star * b, b))
    } else {
        None
    }
}

/// Compute the row's facts.
pub fn compute(cfg: &Config, study: &Study, settings: &CheckSettings) -> Result<Computed, ClaimsError> {
    let (a, b, k1, k2) = (cfg.control.a, cfg.control.b, cfg.control.k1, cfg.control.k2);
    let d = MuData::new(cfg, a, b);
    let obstruction = d.obstruction_exact(k1, k2);
    let weights_positive = a > 0.0 && b > 0.0;
    let r_star = ratio_boundary(cfg);
    let bounds = study.disturbance_bounds(cfg)?;
    let zeta_errors = study.zeta_errors(cfg)?;
    let (mut agree, mut accepted, mut tried) = (0, 0, 0);
    if r_star > 0.0 && b > 0.0 {
        for i in 0..24 {
            let r = r_star * 10f64.powf(-1.5 + 3.0 * i as f64 / 23.0);
            let cc = check_lambda3(&MuData::new(cfg, r * b, b));
            tried += 1;
            if cc.accepted && (r / r_star).ln().abs() > 0.05 {
                accepted += 1;
                agree += usize::from((cc.solver_value > 0.0) == (r < r_star));
            }
        }
    }
    let best = match operating_point(cfg) {
        Some((aa, bb)) => {
            let l1 = lambda1_on(cfg, aa, bb, settings.mu_lambda1_elements)?;
            theory::best_point(&MuData::new(cfg, aa, bb), l1, &bounds, k1, k2)
        }
        None => None,
    };
    let epsilon_socp = best.as_ref().map(|p| check_epsilon(&MuData::new(cfg, p.a, p.b), p.lambda3));
    Ok(Computed {
        obstruction,
        lambda3_sup: weights_positive.then(|| d.lambda3_sup()),
        lambda3_socp: weights_positive.then(|| check_lambda3(&d)),
        r_star,
        grid: (agree, accepted, tried),
        bounds,
        zeta_errors,
        best,
        epsilon_socp,
    })
}
