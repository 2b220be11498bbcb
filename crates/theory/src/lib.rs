//! The paper's theory, defined once, apart from the claim rows: W ≻ 0 (Theorem 1), the
//! feasibility of (29)–(32), the best operating point, g_hmax and ε (this file); the bound (37)
//! ([`uub`]); the exact Lyapunov forms W, κ of (22)–(25) ([`lyapunov`]); and the solver front ends
//! that cross-check them — second-order-cone programs ([`socp`], [`convex`]) and SDPs ([`sdp`])
//! over clarabel, every solve's point accepted by the one rule [`status::worth_reverifying`].
//! Typed failures: [`numerics::PencilError`], [`numerics::FormsError`]. The ledger rows
//! (`wingcheck-claims`), `wingcheck search` and the report call these; this crate depends on
//! none of them (only model, sim, cert, lapack and io).
//!
//! **Closed forms of (29)–(32).** For fixed gains the conditions split into three independent
//! blocks (x = |x_ac|, c = 2a|ρx_c|, A3 = bξEI/(2s⁴) − aρ, A4 = bξGJ/(2s²) − aI_p):
//!
//! - μ3, μ4 ≥ t couple η1, η2 through η5: bη1 + cη5 ≤ A3 − t =: R3 and bxη2 + c/η5 ≤ A4 − t =: R4.
//!   Some η1, η2 > 0 exist iff R3, R4 > 0 and R3R4 > c²; minimising b/η1 + bx/η2 (the η-part
//!   of ε) over them gives the tight η1, η2, η5* = (xR3 + c)/(R4 + xc) and the minimum
//!   b²(R4 + 2xc + x²R3)/(R3R4 − c²) (stationarity of a convex function of η5).
//! - μ5 ≥ t: aξEI/η3 + a s⁴ η6 ≤ aEI − t with the silent condition η3 ≤ b/(2a) (the
//!   coefficient bξEI/2 − aξEIη3 of ∫q''² in (31) must be ≥ 0): η3 = b/(2a) is best, so
//!   t < E5 := aEI(1 − 2aξ/b), and min a/η6 = a²s⁴/(E5 − t).
//! - μ6 ≥ t: likewise with E6 := aGJ(1 − 2aξ/b) and min ax/η7 = a²s²x²/(E6 − t).
//!
//! Hence λ3* = sup over the η's of min{μ3..μ6} = min{t34, E5, E6} with t34 the smaller root of
//! (A3 − t)(A4 − t) = c², and (32) (μ1…μ6 > 0) is satisfiable iff k1, k2 > 0 and λ3* > 0.
//! Every constraint is homogeneous of degree one in (a, b) with the η's fixed, so λ3*/a, λ and
//! the η-part of ε divided by a are invariant under (a, b) → (ca, cb); the observer terms
//! η8ζ3² + η9ζ4² = ζ3²/k1 + ζ4²/k2 are not (they do not depend on a, b at all).

#![forbid(unsafe_code)]

pub mod convex;
pub mod lyapunov;
pub mod numerics;
pub mod sdp;
pub mod socp;
pub mod status;
pub mod uub;

use num_rational::BigRational;
use num_traits::{Signed, Zero};
use serde::{Deserialize, Serialize};
use wingcheck_cert::exact::{from_f64_exact, parse_rational};
use wingcheck_model::Config;

pub use wingcheck_model::Estimate;

/// A yes/no fact that may be undecided when an error estimate straddles the threshold.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum Decision {
    /// Decided true.
    Yes,
    /// Decided false.
    No,
    /// The value lies within its stated error of the threshold.
    Undecided,
}

impl Decision {
    /// `Some(true/false)` when decided.
    pub fn as_bool(self) -> Option<bool> {
        match self {
            Decision::Yes => Some(true),
            Decision::No => Some(false),
            Decision::Undecided => None,
        }
    }
}

/// Sign of an estimate against zero: decided only if |value| exceeds its error.
pub fn positive(e: Estimate) -> Decision {
    if e.value > e.error {
        Decision::Yes
    } else if e.value < -e.error {
        Decision::No
    } else {
        Decision::Undecided
    }
}

/// The threshold of Theorem 1 corrected, ω₁ (rad/s): the fundamental natural frequency of the
/// configured undamped wing, converged by Romberg extrapolation over uniform FE meshes with its
/// error estimate ([`wingcheck_sim::modes::fundamental_frequency`], ~1e-9 relative). Depends on
/// the wing only; cached per wing for the life of the process (a pure function of its key).
pub fn w_threshold(cfg: &Config) -> Result<Estimate, wingcheck_sim::SimError> {
    use std::collections::HashMap;
    use std::sync::{Mutex, OnceLock};
    static CACHE: OnceLock<Mutex<HashMap<String, Estimate>>> = OnceLock::new();
    let key = serde_json::to_string(&cfg.wing).expect("wing serialises");
    let cache = CACHE.get_or_init(|| Mutex::new(HashMap::new()));
    if let Some(e) = cache.lock().expect("ω₁ cache lock").get(&key) {
        return Ok(*e);
    }
    let w = wingcheck_sim::modes::fundamental_frequency(cfg)?;
    let e = Estimate { value: w.value, error: w.error };
    cache.lock().expect("ω₁ cache lock").insert(key, e);
    Ok(e)
}

/// Theorem 1 corrected: W ≻ 0 iff a/b < ω₁ (rad/s), decided against ω₁'s error estimate.
/// `omega1` is the fundamental natural frequency of the undamped wing with its error estimate
/// ([`w_threshold`]); a/b within that error of ω₁ is [`Decision::Undecided`] (at the threshold). b = 0 gives W = a·W_a, indefinite for a > 0.
pub fn w_positive_definite(a: f64, b: f64, omega1: Estimate) -> Decision {
    if b <= 0.0 {
        return if a > 0.0 { Decision::No } else { Decision::Undecided };
    }
    positive(Estimate { value: omega1.value - a / b, error: omega1.error })
}

/// g_hmax = max_t |φ(t)|·|slope|·s (N/m) on a 1e-4 s grid over [0, T]: the bound on the
/// distributed load used in (29)–(32).
pub fn g_hmax(cfg: &Config) -> f64 {
    let d = &cfg.disturbance.distributed;
    let steps = (cfg.horizon.t_end / 1e-4).round() as usize;
    let phi_max = (0..=steps).map(|k| d.phi(k as f64 * 1e-4).abs()).fold(0.0, f64::max);
    phi_max * d.slope.abs() * cfg.wing.span
}

/// The data of (29)–(32) at weights (a, b) (SI units of the config).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct MuData {
    /// Weight a.
    pub a: f64,
    /// Weight b.
    pub b: f64,
    /// ρ (kg/m).
    pub rho: f64,
    /// |ρx_c| (kg).
    pub rho_xc: f64,
    /// EI (N m²).
    pub ei: f64,
    /// GJ (N m²).
    pub gj: f64,
    /// I_p (kg m).
    pub ip: f64,
    /// |x_ac| (m).
    pub x: f64,
    /// ξ (s).
    pub xi: f64,
    /// s (m).
    pub s: f64,
}

/// Which condition of (29)–(32) fails, for the texts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum Obstruction {
    /// k1 = 0: μ2 = k1 − 1/η8 > 0 is impossible.
    K1Zero,
    /// k2 = 0: μ1 = k2 − 1/η9 > 0 is impossible.
    K2Zero,
    /// a = 0: μ5 = −aξEI/η3 − … ≤ 0.
    AZero,
    /// b = 0: η3 ≤ b/(2a) = 0 is impossible.
    BZero,
    /// μ3 < 0 for all η: bξEI/(2s⁴) ≤ aρ.
    Mu3Constant,
    /// μ4 < 0 for all η: bξGJ/(2s²) ≤ aI_p.
    Mu4Constant,
    /// μ3, μ4 cannot both be positive: (A3)(A4) ≤ (2aρx_c)².
    Mu34Coupling,
    /// μ5, μ6 ≤ 0 for all η under η3, η4 ≤ b/(2a): 2aξ ≥ b.
    Mu56Damping,
}

impl Obstruction {
    /// The obstruction in words (with the config keys involved).
    pub fn text(self) -> &'static str {
        match self {
            Obstruction::K1Zero => "control.k1 = 0, so μ2 = k1 − 1/η8 > 0 is impossible",
            Obstruction::K2Zero => "control.k2 = 0, so μ1 = k2 − 1/η9 > 0 is impossible",
            Obstruction::AZero => "control.a = 0, so μ5 = aEI − aξEI/η3 − aη6s⁴ = 0",
            Obstruction::BZero => "control.b = 0, so η3 ≤ b/(2a) = 0 is impossible",
            Obstruction::Mu3Constant => "μ3 ≤ bξEI/(2s⁴) − aρ ≤ 0 for every η ≥ 0",
            Obstruction::Mu4Constant => "μ4 ≤ bξGJ/(2s²) − aI_p ≤ 0 for every η ≥ 0",
            Obstruction::Mu34Coupling => {
                "μ3, μ4 > 0 need (bξEI/(2s⁴) − aρ)(bξGJ/(2s²) − aI_p) > (2aρx_c)², which fails"
            }
            Obstruction::Mu56Damping => "μ5, μ6 > 0 under η3, η4 ≤ b/(2a) need 2aξ < b, which fails",
        }
    }
}

/// The η's of a point of (29)–(32) (η8 = 1/k1, η9 = 1/k2 are implied).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Etas(pub [f64; 7]);

impl MuData {
    /// From a configuration at weights (a, b).
    pub fn new(cfg: &Config, a: f64, b: f64) -> Self {
        let w = &cfg.wing;
        MuData {
            a,
            b,
            rho: w.rho,
            rho_xc: w.rho_xc.abs(),
            ei: w.ei,
            gj: w.gj,
            ip: w.ip,
            x: w.x_ac.abs(),
            xi: w.xi,
            s: w.span,
        }
    }

    /// bξEI/(2s⁴) − aρ: the η-free part of μ3.
    pub fn a3(&self) -> f64 {
        self.b * self.xi * self.ei / (2.0 * self.s.powi(4)) - self.a * self.rho
    }
    /// bξGJ/(2s²) − aI_p: the η-free part of μ4.
    pub fn a4(&self) -> f64 {
        self.b * self.xi * self.gj / (2.0 * self.s * self.s) - self.a * self.ip
    }
    /// c = 2a|ρx_c|.
    pub fn c(&self) -> f64 {
        2.0 * self.a * self.rho_xc
    }
    /// E5 = aEI(1 − 2aξ/b): sup of μ5 under η3 ≤ b/(2a).
    pub fn e5(&self) -> f64 {
        self.a * self.ei * (1.0 - 2.0 * self.a * self.xi / self.b)
    }
    /// E6 = aGJ(1 − 2aξ/b).
    pub fn e6(&self) -> f64 {
        self.a * self.gj * (1.0 - 2.0 * self.a * self.xi / self.b)
    }

    /// t34 = sup t with μ3, μ4 ≥ t satisfiable: smaller root of (A3 − t)(A4 − t) = c², in the
    /// cancellation-free form 2(A3A4 − c²)/(A3 + A4 + √((A3 − A4)² + 4c²)).
    fn t34(&self) -> f64 {
        self.roots34().0
    }

    /// Both roots t34 ≤ t34' of (A3 − t)(A4 − t) = c², the smaller one cancellation-free.
    fn roots34(&self) -> (f64, f64) {
        let (a3, a4, c) = (self.a3(), self.a4(), self.c());
        let root = ((a3 - a4).powi(2) + 4.0 * c * c).sqrt();
        let sum = a3 + a4;
        if sum > 0.0 {
            let big = 0.5 * (sum + root);
            ((a3 * a4 - c * c) / big, big)
        } else {
            let small = 0.5 * (sum - root);
            (small, if small != 0.0 { (a3 * a4 - c * c) / small } else { 0.0 })
        }
    }

    /// D(t) = (A3 − t)(A4 − t) − c² = (t34 − t)(t34' − t), without cancellation near t34.
    fn d34(&self, t: f64) -> f64 {
        let (lo, hi) = self.roots34();
        (lo - t) * (hi - t)
    }

    /// λ3* = sup over the η's of min{μ3, μ4, μ5, μ6} (closed form, module docs); not attained.
    /// Defined for a, b > 0.
    pub fn lambda3_sup(&self) -> f64 {
        self.t34().min(self.e5()).min(self.e6())
    }

    /// The first obstruction to (32) evaluated in exact rational arithmetic from the
    /// configuration's decimals (`None`: satisfiable). This is the closed-form criterion,
    /// decided exactly.
    pub fn obstruction_exact(&self, k1: f64, k2: f64) -> Option<Obstruction> {
        if k1 <= 0.0 {
            return Some(Obstruction::K1Zero);
        }
        if k2 <= 0.0 {
            return Some(Obstruction::K2Zero);
        }
        if self.a <= 0.0 {
            return Some(Obstruction::AZero);
        }
        if self.b <= 0.0 {
            return Some(Obstruction::BZero);
        }
        let ExactData { a, b, rho, rxc, ei, gj, ip, xi, s, .. } = self.exact_data();
        let two = BigRational::from_integer(2.into());
        let s2 = &s * &s;
        let a3 = &b * &xi * &ei / (&two * &s2 * &s2) - &a * &rho;
        let a4 = &b * &xi * &gj / (&two * &s2) - &a * &ip;
        let c = &two * &a * &rxc;
        if !a3.is_positive() {
            return Some(Obstruction::Mu3Constant);
        }
        if !a4.is_positive() {
            return Some(Obstruction::Mu4Constant);
        }
        if &a3 * &a4 <= &c * &c {
            return Some(Obstruction::Mu34Coupling);
        }
        if &two * &a * &xi >= b {
            return Some(Obstruction::Mu56Damping);
        }
        None
    }

    /// The η's minimising the η-part of ε subject to μ3..μ6 ≥ t (0 ≤ t < λ3*), closed form.
    /// Where a variable does not enter (x = 0: η2, η7; c = 0: η5) a feasible value is chosen.
    pub fn etas_at(&self, t: f64) -> Etas {
        let (b, c, x) = (self.b, self.c(), self.x);
        let (r3, r4) = (self.a3() - t, self.a4() - t);
        // η1 = (R3 − cη5)/b and η2 = (R4 − c/η5)/(bx) at η5*, written through D = R3R4 − c²
        let dd = self.d34(t);
        let eta5 = if c > 0.0 { (x * r3 + c) / (r4 + x * c) } else { 1.0 };
        let eta1 = dd / (b * (r4 + x * c));
        let eta2 = if x > 0.0 { dd / (b * (x * r3 + c)) } else { 1.0 };
        // the cap b/(2a) rounded down, so that η3 ≤ b/(2a) holds exactly
        let eta3 = b / (2.0 * self.a) * (1.0 - 4.0 * f64::EPSILON);
        let eta6 = (self.e5() - t) / (self.a * self.s.powi(4));
        let eta7 = if x > 0.0 { (self.e6() - t) / (self.a * self.s * self.s * x) } else { 1.0 };
        Etas([eta1, eta2, eta3, eta3, eta5, eta6, eta7])
    }

    /// μ3..μ6 at the η's, from the printed formulas (float).
    pub fn mus(&self, e: &Etas) -> [f64; 4] {
        let [e1, e2, e3, e4, e5, e6, e7] = e.0;
        let (a, b, s) = (self.a, self.b, self.s);
        [
            self.b * self.xi * self.ei / (2.0 * s.powi(4)) - e1 * b - a * self.rho - self.c() * e5,
            self.b * self.xi * self.gj / (2.0 * s * s) - e2 * b * self.x - a * self.ip - self.c() / e5,
            a * self.ei - a * self.xi * self.ei / e3 - e6 * a * s.powi(4),
            a * self.gj - a * self.xi * self.gj / e4 - e7 * a * s * s * self.x,
        ]
    }

    /// The η-part (b/η1 + bx/η2 + a/η6 + ax/η7)·s·g² of ε at given η's (printed formula).
    pub fn epsilon_eta_part(&self, e: &Etas, g_hmax: f64) -> f64 {
        let [e1, e2, _, _, _, e6, e7] = e.0;
        let x = self.x;
        let sum = self.b / e1
            + if x > 0.0 { self.b * x / e2 } else { 0.0 }
            + self.a / e6
            + if x > 0.0 { self.a * x / e7 } else { 0.0 };
        if g_hmax == 0.0 {
            0.0
        } else {
            sum * self.s * g_hmax * g_hmax
        }
    }

    /// min over the η's of the η-part of ε subject to μ3..μ6 ≥ t, closed form (module docs).
    pub fn epsilon_eta_min(&self, t: f64, g_hmax: f64) -> f64 {
        if g_hmax == 0.0 {
            return 0.0;
        }
        let (b, c, x, a, s) = (self.b, self.c(), self.x, self.a, self.s);
        let (r3, r4) = (self.a3() - t, self.a4() - t);
        let block34 = b * b * (r4 + 2.0 * x * c + x * x * r3) / self.d34(t);
        let block5 = a * a * s.powi(4) / (self.e5() - t);
        let block6 = a * a * s * s * x * x / (self.e6() - t);
        (block34 + block5 + block6) * s * g_hmax * g_hmax
    }

    /// Check μ3..μ6 > 0 at the η's in exact rational arithmetic (the η's as the exact binary
    /// fractions they are, the data as the config's decimals). True: a proof that (32) holds.
    pub fn verify_exact(&self, e: &Etas) -> bool {
        let Ok(eta) = e.0.iter().map(|&v| from_f64_exact(v)).collect::<Result<Vec<_>, _>>() else {
            return false;
        };
        if eta.iter().any(|v| !v.is_positive()) {
            return false;
        }
        let ExactData { a, b, rho, rxc, ei, gj, ip, x, xi, s } = self.exact_data();
        let two = BigRational::from_integer(2.into());
        let s2 = &s * &s;
        let s4 = &s2 * &s2;
        let c = &two * &a * &rxc;
        let m3 = &b * &xi * &ei / (&two * &s4) - &eta[0] * &b - &a * &rho - &c * &eta[4];
        let m4 = &b * &xi * &gj / (&two * &s2) - &eta[1] * &b * &x - &a * &ip - &c / &eta[4];
        let m5 = &a * &ei - &a * &xi * &ei / &eta[2] - &eta[5] * &a * &s4;
        let m6 = &a * &gj - &a * &xi * &gj / &eta[3] - &eta[6] * &a * &s2 * &x;
        let cap = &b / (&two * &a);
        let silent = eta[2] <= cap && eta[3] <= cap;
        silent && [m3, m4, m5, m6].iter().all(|m| m.is_positive() && !m.is_zero())
    }
}

/// The data of (29)–(32) as exact rationals (the configuration's decimals).
struct ExactData {
    a: BigRational,
    b: BigRational,
    rho: BigRational,
    rxc: BigRational,
    ei: BigRational,
    gj: BigRational,
    ip: BigRational,
    x: BigRational,
    xi: BigRational,
    s: BigRational,
}

impl MuData {
    /// [`ExactData`] of this point.
    fn exact_data(&self) -> ExactData {
        ExactData {
            a: exact(self.a),
            b: exact(self.b),
            rho: exact(self.rho),
            rxc: exact(self.rho_xc),
            ei: exact(self.ei),
            gj: exact(self.gj),
            ip: exact(self.ip),
            x: exact(self.x),
            xi: exact(self.xi),
            s: exact(self.s),
        }
    }
}

/// The config value as the exact rational its shortest decimal denotes.
fn exact(v: f64) -> BigRational {
    parse_rational(&format!("{v}")).unwrap_or_else(|_| from_f64_exact(v).unwrap_or_else(|_| BigRational::zero()))
}

/// ε of (32) at λ3 = t: the η-part minimum plus the observer terms ζ3²/k1 + ζ4²/k2
/// (η8 = 1/k1, η9 = 1/k2, their infima).
pub fn epsilon(d: &MuData, t: f64, bounds: &DisturbanceBounds, k1: f64, k2: f64) -> f64 {
    d.epsilon_eta_min(t, bounds.g_hmax) + bounds.zeta3 * bounds.zeta3 / k1 + bounds.zeta4 * bounds.zeta4 / k2
}

/// Closed-form largest a/b for which (32) can hold (0 if none): the smallest positive root
/// of (α − rρ)(β − rI_p) = (2ρx_c r)², α = ξEI/(2s⁴), β = ξGJ/(2s²), capped at 1/(2ξ).
pub fn ratio_boundary(cfg: &Config) -> f64 {
    let w = &cfg.wing;
    if w.xi <= 0.0 {
        return 0.0;
    }
    let alpha = w.xi * w.ei / (2.0 * w.span.powi(4));
    let beta = w.xi * w.gj / (2.0 * w.span * w.span);
    let c = 2.0 * w.rho_xc.abs();
    let lin = alpha * w.ip + beta * w.rho;
    let disc = (alpha * w.ip - beta * w.rho).powi(2) + 4.0 * c * c * alpha * beta;
    let r34 = 2.0 * alpha * beta / (lin + disc.sqrt());
    r34.min(1.0 / (2.0 * w.xi))
}

impl MuData {
    /// Closed-form boundary of a/b ([`ratio_boundary`]).
    pub fn closed_form_ratio(cfg: &Config) -> f64 {
        ratio_boundary(cfg)
    }
}

/// The bounds on the disturbances assumed in (29)–(32).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct DisturbanceBounds {
    /// g_hmax (N/m), see [`g_hmax`].
    pub g_hmax: f64,
    /// ζ3 = sup_t |g̃1| (N) of the FTDO run.
    pub zeta3: f64,
    /// ζ4 = sup_t |g̃2| (N m) of the FTDO run.
    pub zeta4: f64,
}

/// The operating point of (32) that minimises ε/λ (hence Theorem 2's ultimate bound).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct BestPoint {
    /// a.
    pub a: f64,
    /// b.
    pub b: f64,
    /// λ3* = sup min{μ3..μ6} (closed form).
    pub lambda3_sup: f64,
    /// sup λ = λ3*/λ1 (1/s): the supremum of the decay rate, not attained.
    pub lambda_sup: f64,
    /// λ3 at the ε/λ-optimal point.
    pub lambda3: f64,
    /// λ = λ3/λ1 (1/s) at the ε/λ-optimal point.
    pub lambda: f64,
    /// ε of (32) there.
    pub epsilon: f64,
    /// The η-part of ε there (homogeneous of degree one in (a, b)).
    pub epsilon_eta_part: f64,
    /// η1..η7 there.
    pub etas: Etas,
    /// μ3..μ6 > 0 at those η's re-checked in exact rational arithmetic.
    pub verified_exact: bool,
}

/// The ε/λ-optimal point: minimise ε(t)/t over t ∈ (0, λ3*) (ε convex in t, so ε/t is
/// quasi-convex: golden-section search on σ = t/λ3*, 200 iterations). `lambda1` is the tight
/// sup W/κ at (a, b). `None` if (32) is not satisfiable ([`MuData::obstruction_exact`]).
pub fn best_point(d: &MuData, lambda1: f64, bounds: &DisturbanceBounds, k1: f64, k2: f64) -> Option<BestPoint> {
    if d.obstruction_exact(k1, k2).is_some() {
        return None;
    }
    let top = d.lambda3_sup();
    if top <= 0.0 || lambda1 <= 0.0 {
        return None;
    }
    let f = |sig: f64| epsilon(d, sig * top, bounds, k1, k2) / (sig * top);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    let (mut x1, mut x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
    let (mut f1, mut f2) = (f(x1), f(x2));
    for _ in 0..200 {
        if f1 <= f2 {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - g * (hi - lo);
            f1 = f(x1);
        } else {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + g * (hi - lo);
            f2 = f(x2);
        }
    }
    let mut sig = if f1 <= f2 { x1 } else { x2 };
    // stay strictly inside (0, 1) so that every μ is positive at the returned η's
    sig = sig.clamp(1e-9, 1.0 - 1e-9);
    let t = sig * top;
    let etas = d.etas_at(t);
    Some(BestPoint {
        a: d.a,
        b: d.b,
        lambda3_sup: top,
        lambda_sup: top / lambda1,
        lambda3: t,
        lambda: t / lambda1,
        epsilon: epsilon(d, t, bounds, k1, k2),
        epsilon_eta_part: d.epsilon_eta_min(t, bounds.g_hmax),
        etas,
        verified_exact: d.verify_exact(&etas),
    })
}

/// W(a, b) = a·W(1, 0) + b·W(0, 1) on the Galerkin space of [`crate::lyapunov`] with κ = LLᵀ
/// factorised once: the tight λ2 = min W/κ, λ1 = max W/κ at any (a, b) are the extreme
/// eigenvalues of a·C_a + b·C_b, C = L⁻¹WL⁻ᵀ (symmetrised) — the pencil `tight_constants`
/// solves, to rounding, and exactly linear in (a, b).
#[derive(Debug, Clone)]
pub struct WPencil {
    ca: faer::Mat<f64>,
    cb: faer::Mat<f64>,
}

impl WPencil {
    /// The pencil of the configuration's wing on `elements` uniform elements (corrected cross term).
    pub fn new(cfg: &Config, elements: usize) -> Result<Self, numerics::PencilError> {
        use crate::lyapunov::{assemble, to_dense, Coupling, LyapunovParams};
        let p = LyapunovParams::from_config(cfg, Coupling::Corrected, elements);
        let fa = assemble(&p.with_weights("1", "0"))?;
        let fb = assemble(&p.with_weights("0", "1"))?;
        let kappa = to_dense(&fa.kappa);
        let llt = kappa
            .llt(faer::Side::Lower)
            .map_err(|cause| numerics::PencilError::NotPositiveDefinite { what: "κ", cause })?;
        let l = llt.L();
        use wingcheck_sim::dense::congruence;
        Ok(WPencil { ca: congruence(l, &to_dense(&fa.w)), cb: congruence(l, &to_dense(&fb.w)) })
    }

    /// (λ2, λ1) = (min, max) of W/κ at weights (a, b).
    pub fn constants(&self, a: f64, b: f64) -> Result<(f64, f64), numerics::PencilError> {
        let n = self.ca.nrows();
        let c = faer::Mat::from_fn(n, n, |i, j| a * self.ca[(i, j)] + b * self.cb[(i, j)]);
        let mut vals = c
            .self_adjoint_eigenvalues(faer::Side::Lower)
            .map_err(|cause| numerics::PencilError::Eigen { what: "eigenvalues", cause })?;
        vals.sort_by(f64::total_cmp);
        Ok((vals[0], vals[n - 1]))
    }
}
