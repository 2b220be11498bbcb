//! The certificate `omega1-enclosure.json`: ω̲₁ ≤ ω₁ ≤ ω̄₁ for the continuous wing.
//!
//! The file holds only data — the wing's decimals, the number of modes k, the inertia mesh and
//! the shifts Λ₂ … Λ_k, the Rayleigh mesh and the test vector — and the verifier re-derives the
//! enclosure from them in exact rational arithmetic ([`wingcheck_cert::enclosure::check`]: the
//! trace tr(G²) of the compliance operator by exact integration of the cantilever Green's
//! functions, an exact inertia count of K_N − Λᵢ M_N per shift, the Rayleigh quotient of the
//! test vector) and writes the statement itself.
//!
//! [`compute`] is the one function that makes the data for a configuration (floating-point
//! eigenpairs of the Galerkin pencils, rounded to decimals) and checks them exactly; `certify`
//! writes its certificate, the W-bounds row and the search use its enclosure.
//!
//! Choices (work ≈ k − 1 exact LDLᵀ of dimension 4·N_I + 1): k, N_I and N_R of [`PLAN`]; shifts
//! are decimals with [`SHIFT_DIGITS`] significant digits rounded up from μᵢ(1 + [`SHIFT_MARGIN`])
//! (each costs ≤ 1e-9 relative in its Λᵢ, weighted by (ω₁/ωᵢ)⁴ in the bound), the test
//! vector's entries decimals with [`VECTOR_DIGITS`] significant digits (R(v) is stationary at
//! the eigenvector, so their rounding moves the upper bound by ~1e-20 relative).

use crate::numerics::NumericsError;
use std::collections::HashMap;
use std::fmt::Write as _;
use std::sync::{Arc, Mutex, OnceLock};

use num_rational::BigRational;
use num_traits::Signed;
use serde::{Deserialize, Serialize};
use wingcheck_cert::enclosure::{
    self, pencil, unknown_index, unknowns, CheckedEnclosure, EnclosureData, EnclosureError, Limits, WingConstants,
};
use wingcheck_cert::exact::{parse_rational_bounded, to_f64, NumberLimits};
use wingcheck_model::Config;

use super::facts::{CheckedFact, ExactParams, FactKind, WingText, FORMAT, MAX_FILE_BYTES, VERSION, WING_FIELDS};
use super::{format_decimal, CertifyError};
use float::Band;

mod float;
mod summary;

pub use summary::EnclosureSummary;

/// Certificate id (the file is `omega1-enclosure.json`).
pub const ID: &str = "omega1-enclosure";
/// The sizes of an enclosure: k and the two meshes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Plan {
    /// Modes k of the trace bound (shifts Λ₂ … Λ_k).
    pub modes: usize,
    /// Elements of the mesh on which the shifts are certified.
    pub inertia_elements: usize,
    /// Elements of the test vector's mesh.
    pub rayleigh_elements: usize,
}

/// What `certify` writes (and the search's refined boundary uses): the tightest enclosure.
pub const PLAN: Plan = Plan { modes: 36, inertia_elements: 24, rayleigh_elements: 64 };
/// The plans the ledger tries, coarse to fine, using the first whose enclosure decides where
/// the configured a/b lies ([`EnclosureSummary::deciding`]). Measured on the paper's wing
/// (2026-12-02, 2-core VM): relative widths 5.3e-6, 3.8e-7, 4.1e-8, 2.7e-9 in 0.011, 0.021,
/// 0.076, 0.77 s; on a wing with a 16-digit span 3.1e-6 … 1.3e-9 in 0.016 … 5.1 s. A coarser
/// plan's bounds are never tighter (more modes subtracted in the trace bound and a finer
/// inertia mesh raise the lower bound; a finer test mesh lowers the Rayleigh quotient), so a
/// position it decides is the one [`PLAN`]'s certificate decides too.
pub const LADDER: [Plan; 4] = [
    Plan { modes: 4, inertia_elements: 4, rayleigh_elements: 8 },
    Plan { modes: 8, inertia_elements: 8, rayleigh_elements: 16 },
    Plan { modes: 16, inertia_elements: 12, rayleigh_elements: 32 },
    PLAN,
];
/// Relative margin of each shift above its float Galerkin eigenvalue.
pub const SHIFT_MARGIN: f64 = 1e-9;
/// Significant digits of the shifts (rounded up).
pub const SHIFT_DIGITS: usize = 10;
/// Significant digits of the test vector's entries.
pub const VECTOR_DIGITS: usize = 10;
/// What the verifier accepts (checked before any arithmetic).
pub const LIMITS: Limits = Limits { max_modes: 40, max_inertia_elements: 28, max_rayleigh_elements: 128 };

/// The certificate file, field for field.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Omega1Certificate {
    /// Always [`FORMAT`].
    pub format: String,
    /// Always [`VERSION`].
    pub version: u64,
    /// Always [`ID`].
    pub id: String,
    /// Always [`FactKind::Omega1Enclosure`].
    pub fact: FactKind,
    /// Wing parameters (ξ is carried for the set's consistency check; it does not enter).
    pub wing: WingText,
    /// k: the trace bound subtracts Λ₂⁻² … Λ_k⁻².
    pub modes: usize,
    /// Elements N_I of the mesh of the inertia counts.
    pub inertia_elements: usize,
    /// Λ₂ … Λ_k (rad²/s²), k − 1 exact numbers.
    pub shifts: Vec<String>,
    /// Elements N_R of the test vector's mesh.
    pub rayleigh_elements: usize,
    /// Test vector: (q, q', θ, θ') at nodes 0 … N_R (m, 1, rad, rad/m), 4(N_R + 1) numbers.
    pub vector: Vec<String>,
}

/// The checked enclosure, as the ledger and the search use it.
#[derive(Debug, Clone, PartialEq)]
pub struct Omega1Enclosure {
    /// ω̲₁ (rad/s), exact.
    pub lower: BigRational,
    /// ω̄₁ (rad/s), exact.
    pub upper: BigRational,
    /// k.
    pub modes: usize,
    /// N_I.
    pub inertia_elements: usize,
    /// N_R.
    pub rayleigh_elements: usize,
    /// Everything the exact check established.
    pub checked: CheckedEnclosure,
}

/// Where a ratio a/b lies relative to the enclosure.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum Position {
    /// a/b < ω̲₁ ≤ ω₁.
    Below,
    /// ω̲₁ ≤ a/b ≤ ω̄₁: not decided by the certificate.
    Inside,
    /// a/b > ω̄₁ ≥ ω₁.
    Above,
}

/// Exact decimal text of a rational whose denominator divides a power of ten below 10⁴⁰
/// (the enclosure's bounds), else its fraction.
pub fn exact_decimal(r: &BigRational) -> String {
    let mut scaled = r.clone();
    for digits in 0..40usize {
        if scaled.is_integer() {
            let n = scaled.to_integer();
            let (sign, mag) = if n.is_negative() { ("-", -n) } else { ("", n) };
            let text = format!("{:0>width$}", mag.to_string(), width = digits + 1);
            let (int, frac) = text.split_at(text.len() - digits);
            return if digits == 0 { format!("{sign}{int}") } else { format!("{sign}{int}.{frac}") };
        }
        scaled *= BigRational::from_integer(10.into());
    }
    wingcheck_cert::exact::to_fraction_string(r)
}

impl Omega1Enclosure {
    /// ω̲₁ as f64 (display).
    pub fn lower_f64(&self) -> f64 {
        to_f64(&self.lower)
    }
    /// ω̄₁ as f64 (display).
    pub fn upper_f64(&self) -> f64 {
        to_f64(&self.upper)
    }
    /// (ω̄₁ − ω̲₁)/ω̲₁.
    pub fn relative_width(&self) -> f64 {
        to_f64(&((&self.upper - &self.lower) / &self.lower))
    }
    /// Position of the exact ratio `ratio` (= a/b).
    pub fn position(&self, ratio: &BigRational) -> Position {
        if ratio < &self.lower {
            Position::Below
        } else if ratio > &self.upper {
            Position::Above
        } else {
            Position::Inside
        }
    }
}

fn invalid(field: &str, message: impl Into<String>) -> CertifyError {
    CertifyError::Invalid { field: field.into(), message: message.into() }
}

fn number(field: &str, text: &str) -> Result<BigRational, CertifyError> {
    parse_rational_bounded(text, &NumberLimits::CERTIFICATE).map_err(|e| invalid(field, e.to_string()))
}

fn from_enclosure_error(e: EnclosureError) -> CertifyError {
    match e {
        EnclosureError::Invalid { field, message } => CertifyError::Invalid { field, message },
        other => CertifyError::Refuted(other.to_string().trim_start_matches("refuted: ").to_string()),
    }
}

impl Omega1Certificate {
    /// The sizes it was made with.
    pub fn plan(&self) -> Plan {
        Plan { modes: self.modes, inertia_elements: self.inertia_elements, rayleigh_elements: self.rayleigh_elements }
    }

    /// Parses certificate text (at most [`MAX_FILE_BYTES`]): syntax, format, version, id, fact.
    /// No arithmetic happens here.
    pub fn parse(text: &str) -> Result<Self, CertifyError> {
        if text.len() as u64 > MAX_FILE_BYTES {
            return Err(invalid("file", format!("{} bytes, at most {MAX_FILE_BYTES} allowed", text.len())));
        }
        let f: Omega1Certificate = serde_json::from_str(text)
            .map_err(|e| invalid("file", format!("not a version-{VERSION} ω₁-enclosure certificate: {e}")))?;
        if f.format != FORMAT {
            return Err(invalid("format", format!("{:?}, expected {FORMAT:?}", f.format)));
        }
        if f.version != VERSION {
            return Err(invalid("version", format!("{}, this verifier reads version {VERSION}", f.version)));
        }
        if f.fact != FactKind::Omega1Enclosure {
            return Err(invalid(
                "fact",
                format!("{}, expected {}", f.fact.as_str(), FactKind::Omega1Enclosure.as_str()),
            ));
        }
        Ok(f)
    }

    /// Pretty JSON text with a trailing newline (what `certify` writes).
    pub fn to_text(&self) -> String {
        let mut s = serde_json::to_string_pretty(self).expect("certificate serialises");
        s.push('\n');
        s
    }

    /// The wing's exact decimals (span, ρ, ρx_c, EI, GJ, I_p, ξ), bounded parsing.
    pub fn exact_wing(&self) -> Result<[BigRational; 7], CertifyError> {
        let w = &self.wing;
        let texts = [&w.span, &w.rho, &w.rho_xc, &w.ei, &w.gj, &w.ip, &w.xi];
        let mut out: [BigRational; 7] = Default::default();
        for (k, t) in texts.iter().enumerate() {
            out[k] = number(&format!("wing.{}", WING_FIELDS[k]), t)?;
        }
        Ok(out)
    }

    /// The data, with every size checked against [`LIMITS`] before any number is parsed.
    pub fn data(&self) -> Result<EnclosureData, CertifyError> {
        if !(1..=LIMITS.max_modes).contains(&self.modes) {
            return Err(invalid("modes", format!("k = {} outside [1, {}]", self.modes, LIMITS.max_modes)));
        }
        if self.shifts.len() + 1 != self.modes {
            return Err(invalid(
                "shifts",
                format!("{} shifts, k − 1 = {} required (Λ₂ … Λ_k)", self.shifts.len(), self.modes - 1),
            ));
        }
        if !(1..=LIMITS.max_inertia_elements).contains(&self.inertia_elements) {
            return Err(invalid(
                "inertia_elements",
                format!("{} outside [1, {}]", self.inertia_elements, LIMITS.max_inertia_elements),
            ));
        }
        if !(1..=LIMITS.max_rayleigh_elements).contains(&self.rayleigh_elements) {
            return Err(invalid(
                "rayleigh_elements",
                format!("{} outside [1, {}]", self.rayleigh_elements, LIMITS.max_rayleigh_elements),
            ));
        }
        let len = 4 * (self.rayleigh_elements + 1);
        if self.vector.len() != len {
            return Err(invalid(
                "vector",
                format!(
                    "{} entries, {len} required (q, q', θ, θ' at {} nodes)",
                    self.vector.len(),
                    self.rayleigh_elements + 1
                ),
            ));
        }
        let [span, rho, rho_xc, ei, gj, ip, _xi] = self.exact_wing()?;
        let shifts = self
            .shifts
            .iter()
            .enumerate()
            .map(|(i, t)| number(&format!("shifts[{i}]"), t))
            .collect::<Result<_, _>>()?;
        let vector = self
            .vector
            .iter()
            .enumerate()
            .map(|(i, t)| number(&format!("vector[{i}]"), t))
            .collect::<Result<_, _>>()?;
        Ok(EnclosureData {
            wing: WingConstants { span, rho, rho_xc, ei, gj, ip },
            inertia_elements: self.inertia_elements,
            shifts,
            rayleigh_elements: self.rayleigh_elements,
            vector,
        })
    }

    /// Re-derives the enclosure exactly (sizes and numbers bounded first).
    pub fn check_exact(&self) -> Result<Omega1Enclosure, CertifyError> {
        let c = enclosure::check(&self.data()?, &LIMITS).map_err(from_enclosure_error)?;
        Ok(self.enclosure_from(c))
    }

    fn enclosure_from(&self, c: CheckedEnclosure) -> Omega1Enclosure {
        Omega1Enclosure {
            lower: c.lower.clone(),
            upper: c.upper.clone(),
            modes: self.modes,
            inertia_elements: self.inertia_elements,
            rayleigh_elements: self.rayleigh_elements,
            checked: c,
        }
    }

    /// Re-derives the enclosure exactly and writes the statement. `weights` are the set's a, b
    /// (they do not enter this fact; [`CheckedFact::params`] carries them for uniformity).
    pub fn check(&self, weights: &[BigRational; 2]) -> Result<(CheckedFact, Omega1Enclosure), CertifyError> {
        let e = self.check_exact()?;
        let fact = CheckedFact {
            kind: FactKind::Omega1Enclosure,
            params: ExactParams { wing: self.exact_wing()?, weights: weights.clone() },
            lambda: None,
            elements: Some(self.inertia_elements),
            statement: statement(&e),
        };
        Ok((fact, e))
    }
}

/// The verifier's sentence for a checked enclosure.
pub fn statement(e: &Omega1Enclosure) -> String {
    let c = &e.checked;
    let counts = c.counts.iter().map(|n| n.to_string()).collect::<Vec<_>>().join(", ");
    let mut s = format!(
        "ω̲₁ = {} ≤ ω₁ ≤ ω̄₁ = {} rad/s for the continuous wing (undamped, free tip; ξ, a, b do not enter; relative width {:.1e}): ",
        exact_decimal(&e.lower),
        exact_decimal(&e.upper),
        e.relative_width()
    );
    let _ = write!(
        s,
        "ω₁² ≤ R(v) ≈ {:.12e} for the admissible test state v on {} elements; ω₁⁻⁴ ≤ tr(G²) − Σ_{{i=2}}^{{{}}} Λᵢ⁻² ≈ {:.12e} s⁴ \
         with tr(G²) ≈ {:.12e} s⁴ (exact integral of the cantilever Green's functions) and Λᵢ > ωᵢ² because K_N − Λᵢ M_N on \
         {} conforming C¹-cubic elements has ≥ i negative pivots (exact LDLᵀ; counts {counts})",
        to_f64(&c.rayleigh),
        e.rayleigh_elements,
        e.modes,
        to_f64(&c.inverse_fourth_bound),
        to_f64(&c.trace),
        e.inertia_elements,
    );
    s
}

/// Decimal text with `digits` significant digits of x > 0, rounded up.
fn decimal_up(x: f64, digits: usize) -> String {
    let t = format!("{:.*e}", digits - 1, x);
    let v: f64 = t.parse().expect("formatted float");
    if v >= x {
        return t;
    }
    // one unit in the last digit up
    let (m, e) = t.split_once('e').expect("exponent");
    let unit = 10f64.powi(-(digits as i32 - 1));
    format!("{:.*}e{e}", digits - 1, m.parse::<f64>().expect("mantissa") + unit)
}

/// The wing of a configuration as exact constants and its decimals.
fn wing_of(cfg: &Config) -> Result<(WingText, WingConstants), CertifyError> {
    let w = &cfg.wing;
    let d = format_decimal;
    let text = WingText {
        span: d(w.span),
        rho: d(w.rho),
        rho_xc: d(w.rho_xc),
        ei: d(w.ei),
        gj: d(w.gj),
        ip: d(w.ip),
        xi: d(w.xi),
    };
    let q = |field: &str, t: &str| {
        parse_rational_bounded(t, &NumberLimits::CERTIFICATE)
            .map_err(|e| invalid(&format!("wing.{field}"), format!("cannot be certified: {e}")))
    };
    let (span, rho, rho_xc) = (q("span", &text.span)?, q("rho", &text.rho)?, q("rho_xc", &text.rho_xc)?);
    let (ei, gj, ip) = (q("ei", &text.ei)?, q("gj", &text.gj)?, q("ip", &text.ip)?);
    let c = WingConstants { span, rho, rho_xc, ei, gj, ip };
    c.validate().map_err(from_enclosure_error)?;
    Ok((text, c))
}

/// Float data for the wing: shifts from the N_I pencil with relative margins `margins`, the
/// test vector from the lowest eigenvector of the N_R pencil.
fn float_certificate(
    text: &WingText,
    w: &WingConstants,
    plan: &Plan,
    margins: &[f64],
) -> Result<Omega1Certificate, CertifyError> {
    let numerical = |what: &'static str| move |cause| CertifyError::Numerical { what, cause };
    let p = pencil(w, plan.inertia_elements);
    let (k, m) = (Band::from_exact(&p.stiffness), Band::from_exact(&p.mass));
    if unknowns(plan.inertia_elements) < plan.modes {
        return Err(invalid(
            "modes",
            format!("the inertia mesh has {} modes, {} needed", unknowns(plan.inertia_elements), plan.modes),
        ));
    }
    let mu = float::eigenvalue_upper_ends(&k, &m, plan.modes).map_err(numerical("the Galerkin eigenvalues"))?;
    let shifts = (2..=plan.modes).map(|i| decimal_up(mu[i - 1] * (1.0 + margins[i - 2]), SHIFT_DIGITS)).collect();
    let p = pencil(w, plan.rayleigh_elements);
    let (k, m) = (Band::from_exact(&p.stiffness), Band::from_exact(&p.mass));
    let mu1 = float::eigenvalue_upper_ends(&k, &m, 1).map_err(numerical("the fundamental Galerkin eigenvalue"))?[0];
    let v = float::fundamental_vector(&k, &m, mu1).map_err(numerical("the fundamental eigenvector"))?;
    let h = to_f64(&w.span) / plan.rayleigh_elements as f64;
    let mut nodal = Vec::with_capacity(4 * (plan.rayleigh_elements + 1));
    for node in 0..=plan.rayleigh_elements {
        for field in 0..4 {
            let x = unknown_index(node, field).map_or(0.0, |i| v[i]);
            nodal.push(if field % 2 == 1 { x / h } else { x });
        }
    }
    let scale = nodal.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if !(scale.is_finite() && scale > 0.0) {
        return Err(CertifyError::Numerical {
            what: "the test vector",
            cause: NumericsError::DegenerateVector("zero or non-finite"),
        });
    }
    let vector = nodal
        .iter()
        .map(|x| {
            // Entries below 1e-20 of the largest are written as 0 (e.g. the torsion part of an
            // uncoupled bending mode, ~1e-86): R(v) is computed exactly for the vector written,
            // so this can only cost width, ~1e-40 relative, never validity.
            let y = x / scale;
            if y.abs() < 1e-20 {
                "0".to_string()
            } else {
                format!("{y:.*e}", VECTOR_DIGITS - 1)
            }
        })
        .collect();
    Ok(Omega1Certificate {
        format: FORMAT.into(),
        version: VERSION,
        id: ID.into(),
        fact: FactKind::Omega1Enclosure,
        wing: text.clone(),
        modes: plan.modes,
        inertia_elements: plan.inertia_elements,
        shifts,
        rayleigh_elements: plan.rayleigh_elements,
        vector,
    })
}

/// A certificate and its exactly checked enclosure (shared: [`compute_with`] caches it).
pub type Computed = Arc<(Omega1Certificate, Omega1Enclosure)>;

/// The certificate for `cfg`'s wing and its exactly checked enclosure (cached per wing: a pure
/// function of the wing's decimals other than ξ). A shift that the exact count refutes (float eigenvalue
/// error above its margin) gets a margin 100× larger, at most three times.
pub fn compute(cfg: &Config) -> Result<Computed, CertifyError> {
    compute_with(cfg, &PLAN)
}

/// The certificate of the coarsest plan of [`LADDER`] whose enclosure decides where the
/// configured a/b lies (below or above ω₁), or [`PLAN`]'s when none does (a/b inside even the
/// tightest, or b = 0): the enclosure the W-bounds row quotes, and the one a report's
/// certificate set carries. A plan whose computation fails is passed over.
pub fn deciding(cfg: &Config) -> Result<Computed, CertifyError> {
    if let Some(ratio) = config_ratio(cfg)? {
        for plan in &LADDER[..LADDER.len() - 1] {
            if let Ok(c) = compute_with(cfg, plan) {
                if matches!(c.1.position(&ratio), Position::Below | Position::Above) {
                    return Ok(c);
                }
            }
        }
    }
    compute(cfg)
}

/// [`compute`] with other sizes (refused beyond [`LIMITS`]).
pub fn compute_with(cfg: &Config, plan: &Plan) -> Result<Computed, CertifyError> {
    static CACHE: OnceLock<Mutex<HashMap<(String, Plan), Computed>>> = OnceLock::new();
    if plan.modes < 1
        || plan.modes > LIMITS.max_modes
        || !(1..=LIMITS.max_inertia_elements).contains(&plan.inertia_elements)
        || !(1..=LIMITS.max_rayleigh_elements).contains(&plan.rayleigh_elements)
    {
        return Err(invalid("plan", format!("{plan:?} outside the verifier's limits {LIMITS:?}")));
    }
    let (text, w) = wing_of(cfg)?;
    // ξ does not enter: one entry per undamped wing, the certificate re-labelled with the ξ
    // of the configuration at hand (the set checks every file's wing against its config).
    let key = (serde_json::to_string(&WingText { xi: String::new(), ..text.clone() }).expect("serialises"), *plan);
    let cache = CACHE.get_or_init(|| Mutex::new(HashMap::new()));
    if let Some(c) = cache.lock().expect("ω₁ enclosure cache").get(&key) {
        if c.0.wing == text {
            return Ok(c.clone());
        }
        let cert = Omega1Certificate { wing: text, ..c.0.clone() };
        return Ok(Arc::new((cert, c.1.clone())));
    }
    let mut margins = vec![SHIFT_MARGIN; plan.modes - 1];
    for attempt in 0.. {
        let cert = float_certificate(&text, &w, plan, &margins)?;
        let data = cert.data().map_err(|e| unrepresentable(cfg, e))?;
        match enclosure::check(&data, &LIMITS) {
            Ok(c) => {
                let e = cert.enclosure_from(c);
                let out = Arc::new((cert, e));
                cache.lock().expect("ω₁ enclosure cache").insert(key, out.clone());
                return Ok(out);
            }
            Err(EnclosureError::ShiftTooLow { mode, .. } | EnclosureError::SingularShift { mode, .. })
                if attempt < 3 =>
            {
                margins[mode - 2] *= 100.0;
            }
            Err(e) => return Err(from_enclosure_error(e)),
        }
    }
    unreachable!("the loop returns")
}

/// A computed certificate whose shifts or vector cannot be written in the certificate's number
/// format (at most 32 characters, |decimal exponent| ≤ 32): the error names the configuration's
/// keys that put them there, not the certificate's internal fields.
fn unrepresentable(cfg: &Config, e: CertifyError) -> CertifyError {
    match e {
        CertifyError::Invalid { field, message } if field.starts_with("shifts") || field.starts_with("vector") => {
            let what = if field.starts_with("shifts") {
                "its eigenvalue shifts (squared frequencies, 1/s²)"
            } else {
                "its test vector"
            };
            let w = &cfg.wing;
            let f = wingcheck_model::format_number;
            CertifyError::Invalid {
                field: "wing".into(),
                message: format!(
                    "the ω₁ enclosure of this wing cannot be written as a certificate: {what} fall outside the \
                     certificate numbers' range ({message}); they follow from wing.span = {}, wing.ei = {}, \
                     wing.gj = {}, wing.rho = {}, wing.ip = {}, wing.rho_xc = {} (squared frequencies scale as \
                     EI/(ρ span⁴))",
                    f(w.span),
                    f(w.ei),
                    f(w.gj),
                    f(w.rho),
                    f(w.ip),
                    f(w.rho_xc)
                ),
            }
        }
        other => other,
    }
}

/// The exact ratio a/b of a configuration (its decimals), if b > 0.
pub fn config_ratio(cfg: &Config) -> Result<Option<BigRational>, CertifyError> {
    let [a, b] = super::facts::config_params(cfg)?.weights;
    Ok(b.is_positive().then(|| a / b))
}
