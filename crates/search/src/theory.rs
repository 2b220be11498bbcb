//! The theory side of a point: Theorem 1's W ≻ 0 (decided as a/b < ω₁ against the converged
//! fundamental frequency and its error, [`wingcheck_theory::w_threshold`], as in the
//! ledger's W-bounds row; tight λ2, λ1 on the Galerkin space of `wingcheck_theory::lyapunov`), the μ-conditions (32) (λ3*, λ, ε) and Theorem 2's
//! ultimate bound — all computed by `wingcheck_theory` (one definition, shared with the
//! ledger); this module only caches.
//!
//! Cost: W(a, b) = a·W(1, 0) + b·W(0, 1) exactly, so the pencil
//! ([`wingcheck_theory::WPencil`]) is built once per wing and each point needs only
//! one symmetric eigenvalue problem. (32) is decided by its closed form in exact arithmetic and
//! λ3*, ε are closed forms (no solver per point). Verdicts are cached per (wing, a, b), and
//! g_hmax per (distributed load, span, T), so sweeping keys that do not enter the theory
//! costs no theory.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use serde::{Deserialize, Serialize};
use wingcheck_model::Config;
use wingcheck_theory::{self as theory, Decision, DisturbanceBounds, MuData, WPencil};

use crate::SearchError;

/// Verdicts and constants that depend only on the wing and (a, b).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Verdicts {
    /// Tight λ2 = min W/κ on V_N (> 0 up to a/b = ω₁(V_N), slightly above the converged ω₁).
    pub lambda2: f64,
    /// Tight λ1 = max W/κ on V_N.
    pub lambda1: f64,
    /// λ3* = sup over the η's of min μ3..μ6 (closed form; None for a = 0 or b = 0).
    pub lambda3_max: Option<f64>,
    /// (32) satisfiable: closed-form criterion in exact arithmetic (gains k1, k2 included).
    pub satisfiable: bool,
    /// W ≻ 0: a/b < ω₁ decided against ω₁'s error ([`theory::w_positive_definite`]).
    pub w_pd: Decision,
}

impl Verdicts {
    /// W decided positive definite (a/b below the converged ω₁ by more than its error); false
    /// also at the threshold (a/b within ω₁'s error, ~1e-12 relative: see [`Verdicts::w_pd`]).
    pub fn w_positive_definite(&self) -> bool {
        self.w_pd == Decision::Yes
    }
    /// (29)–(32) satisfiable ([`wingcheck_theory::MuData::obstruction_exact`]).
    pub fn feasible_32(&self) -> Option<bool> {
        Some(self.satisfiable)
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
    /// λ3* over the η's.
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

impl Theory {
    /// What the verdicts alone decide (λ2, λ1, W ≻ 0, max min μ, (32)); λ, ε and the bound unset.
    pub fn decided(v: &Verdicts) -> Theory {
        Theory {
            lambda2: Some(v.lambda2),
            lambda1: Some(v.lambda1),
            w_pd: v.w_pd.as_bool(),
            lambda3_max: v.lambda3_max,
            feasible_32: v.feasible_32(),
            ..Default::default()
        }
    }
}

/// (wing JSON, a, b, k1, k2 bits): everything the theory verdicts depend on.
type VerdictKey = (String, u64, u64, u64, u64);

/// Caches shared by all points of a search (thread-safe; values are pure functions of their
/// keys, so caching never changes a result).
pub struct TheoryCache {
    elements: usize,
    pencils: Mutex<HashMap<String, Arc<WPencil>>>,
    verdicts: Mutex<HashMap<VerdictKey, Verdicts>>,
    g_hmax: Mutex<HashMap<String, f64>>,
}

fn num(what: &'static str) -> impl Fn(wingcheck_theory::numerics::PencilError) -> SearchError {
    move |cause| SearchError::Theory { what, cause }
}

impl TheoryCache {
    /// Caches for Galerkin spaces of `elements` elements (the brief's N = 8).
    pub fn new(elements: usize) -> Self {
        TheoryCache {
            elements,
            pencils: Mutex::new(HashMap::new()),
            verdicts: Mutex::new(HashMap::new()),
            g_hmax: Mutex::new(HashMap::new()),
        }
    }

    fn pencil(&self, cfg: &Config) -> Result<Arc<WPencil>, SearchError> {
        let key = serde_json::to_string(&cfg.wing).expect("wing serialises");
        if let Some(b) = self.pencils.lock().expect("cache lock").get(&key) {
            return Ok(b.clone());
        }
        let p = Arc::new(WPencil::new(cfg, self.elements).map_err(num("W pencil"))?);
        self.pencils.lock().expect("cache lock").insert(key, p.clone());
        Ok(p)
    }

    /// λ2, λ1 and λ3* for the configuration's wing and (a, b).
    pub fn verdicts(&self, cfg: &Config) -> Result<Verdicts, SearchError> {
        let c = &cfg.control;
        let key = (
            serde_json::to_string(&cfg.wing).expect("wing serialises"),
            c.a.to_bits(),
            c.b.to_bits(),
            c.k1.to_bits(),
            c.k2.to_bits(),
        );
        if let Some(v) = self.verdicts.lock().expect("cache lock").get(&key) {
            return Ok(*v);
        }
        let (lambda2, lambda1) = self.pencil(cfg)?.constants(c.a, c.b).map_err(num("eigenvalues"))?;
        let d = MuData::new(cfg, c.a, c.b);
        let omega1 = theory::w_threshold(cfg).map_err(SearchError::Omega1)?;
        let v = Verdicts {
            w_pd: theory::w_positive_definite(c.a, c.b, omega1),
            lambda2,
            lambda1,
            lambda3_max: (c.a > 0.0 && c.b > 0.0).then(|| d.lambda3_sup()),
            satisfiable: d.obstruction_exact(c.k1, c.k2).is_none(),
        };
        self.verdicts.lock().expect("cache lock").insert(key, v);
        Ok(v)
    }

    /// g_hmax ([`wingcheck_theory::g_hmax`]), cached.
    pub fn g_hmax(&self, cfg: &Config) -> f64 {
        let d = &cfg.disturbance.distributed;
        let key = format!("{}|{}|{}", serde_json::to_string(d).expect("serialises"), cfg.wing.span, cfg.horizon.t_end);
        if let Some(g) = self.g_hmax.lock().expect("cache lock").get(&key) {
            return *g;
        }
        let g = theory::g_hmax(cfg);
        self.g_hmax.lock().expect("cache lock").insert(key, g);
        g
    }

    /// The full theory of a point. `bounds` = (g_hmax, ζ3, ζ4) from the point's FTDO run
    /// (None if that run failed: then λ, ε and the ultimate bound are not available).
    pub fn evaluate(&self, cfg: &Config, bounds: Option<(f64, f64, f64)>) -> Result<Theory, SearchError> {
        let v = self.verdicts(cfg)?;
        let mut t = Theory::decided(&v);
        if let (true, Some(bounds)) = (v.satisfiable, bounds) {
            let c = &cfg.control;
            let d = MuData::new(cfg, c.a, c.b);
            let db = DisturbanceBounds { g_hmax: bounds.0, zeta3: bounds.1, zeta4: bounds.2 };
            if let Some(p) = theory::best_point(&d, v.lambda1, &db, c.k1, c.k2) {
                t.lambda = Some(p.lambda);
                t.epsilon = Some(p.epsilon);
                t.uub_bound_q = theory::uub::ultimate_bound_q(cfg.wing.span, v.lambda2, &p);
            }
        }
        Ok(t)
    }
}
