//! The theory side of a point: Theorem 1's W ≻ 0 (tight λ2, λ1 on the Galerkin space of
//! `wingcheck_claims::lyapunov`), the μ-conditions (32) (best λ3, λ, ε) and Theorem 2's
//! ultimate bound.
//!
//! Cost: W(a, b) = a·W(1, 0) + b·W(0, 1) exactly (the forms are linear in the weights), and κ
//! does not depend on them. So the exact forms are assembled once per wing
//! ([`wingcheck_claims::lyapunov::assemble`]), κ is factorised once (κ = LLᵀ), and each
//! point only needs the eigenvalues of a·C_a + b·C_b with C = L⁻¹WL⁻ᵀ — the same pencil
//! `tight_constants` solves, to rounding. Verdicts are cached per (wing, a, b), and
//! g_hmax per (distributed load, span, T), so sweeping keys that do not enter the theory
//! costs no theory.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use faer::{Mat, Side};
use serde::{Deserialize, Serialize};
use wingcheck_claims::lyapunov::{assemble, to_dense, Coupling, LyapunovParams};
use wingcheck_claims::mu::MuData;
use wingcheck_model::Config;

use crate::SearchError;

/// Fractions of λ3* tried for the best ε/λ (the same as `wingcheck_claims::mu::best_point`).
const FRACTIONS: [f64; 9] = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9];

/// Verdicts and constants that depend only on the wing and (a, b).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Verdicts {
    /// Tight λ2 = min W/κ on V_N (W ≻ 0 iff > 0).
    pub lambda2: f64,
    /// Tight λ1 = max W/κ on V_N.
    pub lambda1: f64,
    /// Best λ3 = max over the η's of min μ3..μ6 (None if clarabel did not solve).
    pub lambda3_max: Option<f64>,
}

impl Verdicts {
    /// W positive definite on V_N.
    pub fn w_positive_definite(&self) -> bool {
        self.lambda2 > 0.0
    }
    /// (29)–(32) satisfiable: λ3* > 0 (None if the solver failed).
    pub fn feasible_32(&self) -> Option<bool> {
        self.lambda3_max.map(|l| l > 0.0)
    }
}

/// Everything the theory says about a point.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Theory {
    /// Tight λ2 (min W/κ).
    pub lambda2: Option<f64>,
    /// Tight λ1 (max W/κ).
    pub lambda1: Option<f64>,
    /// W ≻ 0.
    pub w_pd: Option<bool>,
    /// max λ3 over the η's.
    pub lambda3_max: Option<f64>,
    /// (32) feasible.
    pub feasible_32: Option<bool>,
    /// Decay rate λ = λ3/λ1 (1/s) at the η's minimising ε/λ.
    pub lambda: Option<f64>,
    /// ε of (32) at those η's.
    pub epsilon: Option<f64>,
    /// Ultimate bound √(s³/λ2 · ε/λ) on |q| (m), when λ2 > 0 and (32) is feasible.
    pub uub_bound_q: Option<f64>,
}

struct Basis {
    ca: Mat<f64>,
    cb: Mat<f64>,
}

/// Caches shared by all points of a search (thread-safe; values are pure functions of their
/// keys, so caching never changes a result).
pub struct TheoryCache {
    elements: usize,
    bases: Mutex<HashMap<String, Arc<Basis>>>,
    verdicts: Mutex<HashMap<(String, u64, u64), Verdicts>>,
    g_hmax: Mutex<HashMap<String, f64>>,
}

fn num(what: &str) -> impl Fn(String) -> SearchError + '_ {
    move |detail| SearchError::Theory { what: what.to_string(), detail }
}

/// L⁻¹ W L⁻ᵀ (symmetrised).
fn congruence(l: faer::MatRef<'_, f64>, w: &Mat<f64>) -> Mat<f64> {
    let mut y = w.clone();
    faer::linalg::triangular_solve::solve_lower_triangular_in_place(l, y.as_mut(), faer::Par::Seq);
    let mut c = y.transpose().to_owned();
    faer::linalg::triangular_solve::solve_lower_triangular_in_place(l, c.as_mut(), faer::Par::Seq);
    let n = c.nrows();
    Mat::from_fn(n, n, |i, j| 0.5 * (c[(i, j)] + c[(j, i)]))
}

impl TheoryCache {
    /// Caches for Galerkin spaces of `elements` elements (the brief's N = 8).
    pub fn new(elements: usize) -> Self {
        TheoryCache {
            elements,
            bases: Mutex::new(HashMap::new()),
            verdicts: Mutex::new(HashMap::new()),
            g_hmax: Mutex::new(HashMap::new()),
        }
    }

    fn basis(&self, cfg: &Config) -> Result<Arc<Basis>, SearchError> {
        let key = serde_json::to_string(&cfg.wing).expect("wing serialises");
        if let Some(b) = self.bases.lock().expect("cache lock").get(&key) {
            return Ok(b.clone());
        }
        let p = LyapunovParams::from_config(cfg, Coupling::Corrected, self.elements);
        let fa = assemble(&p.with_weights("1", "0")).map_err(num("assembly of W"))?;
        let fb = assemble(&p.with_weights("0", "1")).map_err(num("assembly of W"))?;
        let kappa = to_dense(&fa.kappa);
        let llt = kappa.llt(Side::Lower).map_err(|e| num("κ")(format!("not positive definite: {e:?}")))?;
        let l = llt.L();
        let basis = Arc::new(Basis { ca: congruence(l, &to_dense(&fa.w)), cb: congruence(l, &to_dense(&fb.w)) });
        self.bases.lock().expect("cache lock").insert(key, basis.clone());
        Ok(basis)
    }

    /// λ2, λ1 (eigenvalues of a·C_a + b·C_b) and λ3* for the configuration's wing and (a, b).
    pub fn verdicts(&self, cfg: &Config) -> Result<Verdicts, SearchError> {
        let (a, b) = (cfg.control.a, cfg.control.b);
        let key = (serde_json::to_string(&cfg.wing).expect("wing serialises"), a.to_bits(), b.to_bits());
        if let Some(v) = self.verdicts.lock().expect("cache lock").get(&key) {
            return Ok(*v);
        }
        let basis = self.basis(cfg)?;
        let n = basis.ca.nrows();
        let c = Mat::from_fn(n, n, |i, j| a * basis.ca[(i, j)] + b * basis.cb[(i, j)]);
        let mut vals = c.self_adjoint_eigenvalues(Side::Lower).map_err(|e| num("eigenvalues")(format!("{e:?}")))?;
        vals.sort_by(f64::total_cmp);
        let top = MuData::new(cfg, a, b).max_lambda3().map_err(|e| num("μ SOCP")(e.to_string()))?;
        let v = Verdicts { lambda2: vals[0], lambda1: vals[n - 1], lambda3_max: top.solved().then(|| top.x[0]) };
        self.verdicts.lock().expect("cache lock").insert(key, v);
        Ok(v)
    }

    /// g_hmax = max_t |φ(t)|·|slope|·s on a 1e-4 s grid over [0, T] (N/m), as
    /// `wingcheck_claims::mu::disturbance_bounds` computes it.
    pub fn g_hmax(&self, cfg: &Config) -> f64 {
        let d = &cfg.disturbance.distributed;
        let key = format!("{}|{}|{}", serde_json::to_string(d).expect("serialises"), cfg.wing.span, cfg.horizon.t_end);
        if let Some(g) = self.g_hmax.lock().expect("cache lock").get(&key) {
            return *g;
        }
        let steps = (cfg.horizon.t_end / 1e-4).round() as usize;
        let phi_max = (0..=steps).map(|k| d.phi(k as f64 * 1e-4).abs()).fold(0.0, f64::max);
        let g = phi_max * d.slope.abs() * cfg.wing.span;
        self.g_hmax.lock().expect("cache lock").insert(key, g);
        g
    }

    /// The full theory of a point. `bounds` = (g_hmax, ζ3, ζ4) from the point's FTDO run
    /// (None if that run failed: then λ, ε and the ultimate bound are not available).
    pub fn evaluate(&self, cfg: &Config, bounds: Option<(f64, f64, f64)>) -> Result<Theory, SearchError> {
        let v = self.verdicts(cfg)?;
        let mut t = Theory {
            lambda2: Some(v.lambda2),
            lambda1: Some(v.lambda1),
            w_pd: Some(v.w_positive_definite()),
            lambda3_max: v.lambda3_max,
            feasible_32: v.feasible_32(),
            ..Default::default()
        };
        if let (Some(true), Some(bounds), Some(top)) = (t.feasible_32, bounds, v.lambda3_max) {
            let (a, b) = (cfg.control.a, cfg.control.b);
            let d = MuData::new(cfg, a, b);
            let sg2 = cfg.wing.span * bounds.0 * bounds.0;
            let (k1, k2) = (cfg.control.k1.max(1e-300), cfg.control.k2.max(1e-300));
            let mut best: Option<(f64, f64)> = None;
            for frac in FRACTIONS {
                let l3 = frac * top;
                let (eps, _) =
                    d.min_epsilon(l3, sg2, bounds.1, bounds.2, k1, k2).map_err(|e| num("ε SOCP")(e.to_string()))?;
                let lam = l3 / v.lambda1;
                if best.is_none_or(|(bl, be)| eps / lam < be / bl) {
                    best = Some((lam, eps));
                }
            }
            if let Some((lam, eps)) = best {
                t.lambda = Some(lam);
                t.epsilon = Some(eps);
                if v.lambda2 > 0.0 {
                    t.uub_bound_q = Some((cfg.wing.span.powi(3) / v.lambda2 * eps / lam).sqrt());
                }
            }
        }
        Ok(t)
    }
}
