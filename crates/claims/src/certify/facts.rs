//! The facts a wingcheck certificate can prove, and how the verifier re-derives each one.
//!
//! A certificate file holds *parameters* (the wing's decimals, the weights a, b, the Galerkin
//! element count, λ as a rational) and a *witness*; never a matrix, a linear system or a
//! sentence. The verifier rebuilds W and κ of (22)–(25) (or the μ3 system of (32)) from the
//! parameters in exact rational arithmetic, checks the witness against them and writes the
//! statement itself from the numbers it checked.
//!
//! Every input is bounded before any arithmetic: the file's size ([`MAX_FILE_BYTES`]), the
//! element count ([`MAX_ELEMENTS`]), the witness length (fixed by the fact) and every number's
//! text ([`NumberLimits::CERTIFICATE`]: ≤ 32 characters, |decimal exponent| ≤ 32). With these
//! bounds the slowest possible set (three exact LDLᵀ of dimension 44 with 32-character entries)
//! verifies in ≈ 0.3 s on one core.

use std::fmt::Write as _;

use num_rational::BigRational;
use num_traits::{Signed, Zero};
use serde::{Deserialize, Serialize};
use wingcheck_cert::exact::{parse_rational_bounded, to_f64, to_fraction_string, NumberLimits};
use wingcheck_cert::lp::{check_farkas, FarkasCertificate, LinearSystem};
use wingcheck_cert::psd::check_positive_definite;
use wingcheck_cert::RationalMatrix;

use super::CertifyError;
use wingcheck_theory::lyapunov::{self, Coupling, LyapunovParams};

/// Value of the `"format"` field of a certificate file.
pub const FORMAT: &str = "wingcheck-certificate";
/// Version of the certificate files written and read here.
pub const VERSION: u64 = 2;
/// Largest certificate or manifest file read (bytes).
pub const MAX_FILE_BYTES: u64 = 1 << 20;
/// Largest Galerkin element count accepted in a certificate (dimension 11·N; the verifier's
/// exact LDLᵀ grows like N⁴–N⁵ with big-rational entries: ≈ 0.08 s at N = 4, 0.7 s at N = 6,
/// 2 s at N = 8 with 32-character parameters). `certify` uses [`super::CERT_ELEMENTS`] = 4.
pub const MAX_ELEMENTS: usize = 4;
/// Largest Galerkin element count of a negative-direction certificate: its check is one exact
/// quadratic form xᵀWx (no LDLᵀ), so a finer space costs little; `certify` uses it when W's
/// negative directions for a/b just above ω₁ show only on finer spaces
/// ([`super::NEGATIVE_DIRECTION_ELEMENTS`]).
pub const MAX_NEGATIVE_ELEMENTS: usize = 32;

/// The kinds of fact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum FactKind {
    /// W − λκ ≻ 0 on the Galerkin space V_N: min W/κ > λ there.
    WLowerBound,
    /// λκ − W ≻ 0 on V_N: max W/κ < λ there.
    WUpperBound,
    /// W(x) < 0 for the witness state x ∈ V_N: W is not positive definite.
    WNegativeDirection,
    /// μ3 ≥ 0 of (32) has no solution η1, η5 ≥ 0 (Farkas multipliers y).
    Mu3Infeasible,
    /// ω̲₁ ≤ ω₁ ≤ ω̄₁ for the continuous wing (its own file format, [`super::omega1`]).
    Omega1Enclosure,
}

impl FactKind {
    /// Kebab-case name as written in files.
    pub fn as_str(self) -> &'static str {
        match self {
            FactKind::WLowerBound => "w-lower-bound",
            FactKind::WUpperBound => "w-upper-bound",
            FactKind::WNegativeDirection => "w-negative-direction",
            FactKind::Mu3Infeasible => "mu3-infeasible",
            FactKind::Omega1Enclosure => "omega1-enclosure",
        }
    }
}

/// The wing parameters a certificate depends on, as exact decimals (config units: m, kg/m,
/// kg, N m², N m², kg m, s).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct WingText {
    /// Span s.
    pub span: String,
    /// ρ.
    pub rho: String,
    /// ρx_c.
    pub rho_xc: String,
    /// EI.
    pub ei: String,
    /// GJ.
    pub gj: String,
    /// I_p.
    pub ip: String,
    /// Kelvin–Voigt ξ.
    pub xi: String,
}

/// Weights a, b of (15)/(23) as exact decimals or fractions.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct WeightsText {
    /// a.
    pub a: String,
    /// b.
    pub b: String,
}

/// A certificate file (version 2), field for field.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CertificateFile {
    /// Always [`FORMAT`].
    pub format: String,
    /// Always [`VERSION`].
    pub version: u64,
    /// Role of the certificate in the set, e.g. `w-bounds-lower`; the file is `<id>.json`.
    pub id: String,
    /// Which fact is claimed.
    pub fact: FactKind,
    /// Wing parameters.
    pub wing: WingText,
    /// Weights a, b.
    pub weights: WeightsText,
    /// Galerkin elements N (W facts only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub elements: Option<usize>,
    /// λ (bound facts only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lambda: Option<String>,
    /// The witness: the state x (11N coefficients) or the Farkas multipliers y (3).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub witness: Option<Vec<String>>,
}

/// Exact wing parameters and weights, parsed from a certificate or a config.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ExactParams {
    /// span, ρ, ρx_c, EI, GJ, I_p, ξ (in that order).
    pub wing: [BigRational; 7],
    /// a, b.
    pub weights: [BigRational; 2],
}

/// Names of [`ExactParams::wing`] entries.
pub const WING_FIELDS: [&str; 7] = ["span", "rho", "rho_xc", "ei", "gj", "ip", "xi"];

/// The exact parameters a configuration gives (its decimals as the user wrote them).
pub fn config_params(cfg: &wingcheck_model::Config) -> Result<ExactParams, CertifyError> {
    let w = &cfg.wing;
    let q = |field: &str, x: f64| {
        parse_rational_bounded(&super::format_decimal(x), &NumberLimits::CERTIFICATE)
            .map_err(|e| CertifyError::Invalid { field: field.into(), message: format!("cannot be certified: {e}") })
    };
    Ok(ExactParams {
        wing: [
            q("wing.span", w.span)?,
            q("wing.rho", w.rho)?,
            q("wing.rho_xc", w.rho_xc)?,
            q("wing.ei", w.ei)?,
            q("wing.gj", w.gj)?,
            q("wing.ip", w.ip)?,
            q("wing.xi", w.xi)?,
        ],
        weights: [q("control.a", cfg.control.a)?, q("control.b", cfg.control.b)?],
    })
}

/// What the verifier established, in its own words, with the numbers it checked.
#[derive(Debug, Clone, PartialEq)]
pub struct CheckedFact {
    /// The fact kind.
    pub kind: FactKind,
    /// The exact parameters it was checked at.
    pub params: ExactParams,
    /// λ for the bound facts.
    pub lambda: Option<BigRational>,
    /// Galerkin elements for the W facts.
    pub elements: Option<usize>,
    /// The statement, written from the checked numbers.
    pub statement: String,
}

fn number(field: &str, text: &str) -> Result<BigRational, CertifyError> {
    number_within(field, text, &NumberLimits::CERTIFICATE)
}

fn number_within(field: &str, text: &str, limits: &NumberLimits) -> Result<BigRational, CertifyError> {
    parse_rational_bounded(text, limits)
        .map_err(|e| CertifyError::Invalid { field: field.into(), message: e.to_string() })
}

/// Limits of the three Farkas multipliers of a μ3 certificate: they are products of the
/// config's decimals (y = (1, b, 2a|ρx_c|), exact, each up to 17 significant digits and
/// exponent ±28), longer than 32 characters, and enter one 3 × 2 system, so a longer text costs
/// nothing measurable.
pub const FARKAS_LIMITS: NumberLimits = NumberLimits { max_chars: 128, max_exponent: 64 };

fn invalid(field: &str, message: impl Into<String>) -> CertifyError {
    CertifyError::Invalid { field: field.into(), message: message.into() }
}

/// Short display of an exact rational: `p/q (≈ 1.234e-5)`, or the integer; integers of more
/// than 24 digits abbreviated ([`wingcheck_cert::exact::abbreviated`]).
pub fn show(r: &BigRational) -> String {
    if r.is_integer() || to_fraction_string(r).len() > 2 * wingcheck_cert::exact::SHOWN_DIGITS {
        wingcheck_cert::exact::abbreviated(r)
    } else {
        format!("{} (≈ {:.6e})", to_fraction_string(r), to_f64(r))
    }
}

impl CertificateFile {
    /// Parses certificate text (at most [`MAX_FILE_BYTES`]): JSON syntax, format, version and
    /// field types. No arithmetic happens here.
    pub fn parse(text: &str) -> Result<Self, CertifyError> {
        if text.len() as u64 > MAX_FILE_BYTES {
            return Err(invalid("file", format!("{} bytes, at most {MAX_FILE_BYTES} allowed", text.len())));
        }
        let f: CertificateFile =
            serde_json::from_str(text).map_err(|e| invalid("file", format!("not a version-2 certificate: {e}")))?;
        if f.format != FORMAT {
            return Err(invalid("format", format!("{:?}, expected {FORMAT:?}", f.format)));
        }
        if f.version != VERSION {
            return Err(invalid("version", format!("{}, this verifier reads version {VERSION}", f.version)));
        }
        Ok(f)
    }

    /// Pretty JSON text with a trailing newline (what `certify` writes).
    pub fn to_text(&self) -> String {
        let mut s = serde_json::to_string_pretty(self).expect("certificate serialises");
        s.push('\n');
        s
    }

    /// The exact wing parameters and weights (bounded parsing).
    pub fn exact_params(&self) -> Result<ExactParams, CertifyError> {
        let w = &self.wing;
        let texts = [&w.span, &w.rho, &w.rho_xc, &w.ei, &w.gj, &w.ip, &w.xi];
        let mut wing: [BigRational; 7] = Default::default();
        for (k, t) in texts.iter().enumerate() {
            wing[k] = number(&format!("wing.{}", WING_FIELDS[k]), t)?;
        }
        // the ranges the configuration allows (validate.rs): span, ρ, EI, GJ, I_p > 0; ρx_c of
        // either sign (the offset's direction); ξ, a, b ≥ 0
        for (k, v) in wing.iter().enumerate().take(6) {
            if k != 2 && !v.is_positive() {
                return Err(invalid(&format!("wing.{}", WING_FIELDS[k]), "must be > 0"));
            }
        }
        if wing[6].is_negative() {
            return Err(invalid("wing.xi", "must be ≥ 0"));
        }
        let weights = [number("weights.a", &self.weights.a)?, number("weights.b", &self.weights.b)?];
        if weights[0].is_negative() || weights[1].is_negative() {
            return Err(invalid("weights", "a and b must be ≥ 0"));
        }
        Ok(ExactParams { wing, weights })
    }

    /// The element count, checked against [`MAX_ELEMENTS`] ([`MAX_NEGATIVE_ELEMENTS`] for a
    /// negative direction) (W facts only).
    pub fn require_elements(&self) -> Result<usize, CertifyError> {
        let max = if self.fact == FactKind::WNegativeDirection { MAX_NEGATIVE_ELEMENTS } else { MAX_ELEMENTS };
        match self.elements {
            Some(n) if (1..=max).contains(&n) => Ok(n),
            Some(n) => Err(invalid("elements", format!("{n} outside [1, {max}]"))),
            None => Err(invalid("elements", format!("missing (required for {})", self.fact.as_str()))),
        }
    }

    fn require_lambda(&self) -> Result<BigRational, CertifyError> {
        match &self.lambda {
            Some(t) => number("lambda", t),
            None => Err(invalid("lambda", format!("missing (required for {})", self.fact.as_str()))),
        }
    }

    fn require_witness(&self, len: usize) -> Result<Vec<BigRational>, CertifyError> {
        self.require_witness_within(len, &NumberLimits::CERTIFICATE)
    }

    fn require_witness_within(&self, len: usize, limits: &NumberLimits) -> Result<Vec<BigRational>, CertifyError> {
        let w = self.witness.as_ref().ok_or_else(|| invalid("witness", "missing"))?;
        if w.len() != len {
            return Err(invalid(
                "witness",
                format!("{} entries, {} required for {}", w.len(), len, self.fact.as_str()),
            ));
        }
        w.iter().enumerate().map(|(i, t)| number_within(&format!("witness[{i}]"), t, limits)).collect()
    }

    fn forbid(&self, present: bool, field: &str) -> Result<(), CertifyError> {
        if present {
            return Err(invalid(field, format!("not part of a {} certificate", self.fact.as_str())));
        }
        Ok(())
    }

    /// Re-derives the fact: rebuilds the matrix or system from the parameters in exact
    /// arithmetic, checks the witness and writes the statement.
    pub fn check(&self) -> Result<CheckedFact, CertifyError> {
        let params = self.exact_params()?;
        let weights = format!("a = {}, b = {}", show(&params.weights[0]), show(&params.weights[1]));
        match self.fact {
            FactKind::WLowerBound | FactKind::WUpperBound => {
                let n = self.require_elements()?;
                let lambda = self.require_lambda()?;
                self.forbid(self.witness.is_some(), "witness")?;
                let forms = self.forms(n)?;
                let lk = forms.kappa.scale(&lambda);
                let (m, what) = if self.fact == FactKind::WLowerBound {
                    (forms.w.sub(&lk), "W − λκ")
                } else {
                    (lk.sub(&forms.w), "λκ − W")
                };
                let m = m.ok_or_else(|| invalid("elements", "dimension mismatch"))?;
                let report = check_positive_definite(&m)
                    .map_err(|e| CertifyError::Refuted(format!("{what} with λ = {}: {e}", show(&lambda))))?;
                let mut statement = format!(
                    "with {weights}: {what} is positive definite for λ = {} on the Galerkin space of {n} uniform elements \
                     (cubic Hermite q, linear θ, discontinuous cubic velocities; dimension {}), so ",
                    show(&lambda),
                    m.rows()
                );
                if self.fact == FactKind::WLowerBound {
                    statement.push_str("min W/κ > λ there");
                    if lambda.is_positive() {
                        statement.push_str(" and W is positive definite there");
                    }
                } else {
                    statement.push_str("max W/κ < λ there");
                }
                let _ = write!(statement, " (all {} exact LDLᵀ pivots > 0)", report.pivots.len());
                Ok(CheckedFact { kind: self.fact, params, lambda: Some(lambda), elements: Some(n), statement })
            }
            FactKind::WNegativeDirection => {
                let n = self.require_elements()?;
                self.forbid(self.lambda.is_some(), "lambda")?;
                let x = self.require_witness(11 * n)?;
                let forms = self.forms(n)?;
                let wx = lyapunov::quadratic_form(&forms.w, &x);
                if !wx.is_negative() {
                    return Err(CertifyError::Refuted(format!("W(x) = {} is not < 0 for the witness x", show(&wx))));
                }
                let statement = format!(
                    "with {weights}: the witness state x (a Galerkin state on {n} uniform elements, hence a state of the PDE) \
                     has W(x) = {} < 0 exactly, so W is not positive definite and no λ2 > 0 satisfies λ2 κ ≤ W",
                    show(&wx)
                );
                Ok(CheckedFact { kind: self.fact, params, lambda: None, elements: Some(n), statement })
            }
            FactKind::Omega1Enclosure => {
                Err(invalid("fact", "an omega1-enclosure certificate has its own format (modes, shifts, vector)"))
            }
            FactKind::Mu3Infeasible => {
                self.forbid(self.elements.is_some(), "elements")?;
                self.forbid(self.lambda.is_some(), "lambda")?;
                let y = self.require_witness_within(3, &FARKAS_LIMITS)?;
                let (sys, c3) = mu3_system(&params);
                let value = check_farkas(&sys, &FarkasCertificate { y, w: vec![] })
                    .map_err(|e| CertifyError::Refuted(format!("μ3 system: {e}")))?;
                let statement = format!(
                    "with {weights}: μ3 = bξEI/(2s⁴) − η1 b − aρ − 2a|ρx_c| η5 ≥ 0 has no solution η1, η5 ≥ 0 \
                     (constant term bξEI/(2s⁴) − aρ = {}; Farkas combination yᵀc = {} < 0), so μ1 … μ6 > 0 of (32) cannot all hold",
                    show(&c3),
                    show(&value)
                );
                Ok(CheckedFact { kind: self.fact, params, lambda: None, elements: None, statement })
            }
        }
    }

    fn forms(&self, n: usize) -> Result<lyapunov::ExactForms, CertifyError> {
        let w = &self.wing;
        let p = LyapunovParams {
            rho: w.rho.clone(),
            rho_xc: w.rho_xc.clone(),
            ei: w.ei.clone(),
            gj: w.gj.clone(),
            ip: w.ip.clone(),
            span: w.span.clone(),
            a: self.weights.a.clone(),
            b: self.weights.b.clone(),
            coupling: Coupling::Corrected,
            elements: n,
        };
        lyapunov::assemble(&p).map_err(|e| invalid("wing", e.to_string()))
    }
}

/// The μ3 ≥ 0 system of (32) in the variables (η1, η5) ≥ 0, built from the parameters:
/// rows `b η1 + 2a|ρx_c| η5 ≤ C3`, `−η1 ≤ 0`, `−η5 ≤ 0` with `C3 = bξEI/(2s⁴) − aρ` (the cross
/// term enters (29)–(32) through its magnitude, as in `theory::MuData`). Returns the system and C3.
pub fn mu3_system(p: &ExactParams) -> (LinearSystem, BigRational) {
    let [s, rho, rho_xc, ei, _gj, _ip, xi] = &p.wing;
    let rho_xc = &rho_xc.abs();
    let [a, b] = &p.weights;
    let two = BigRational::from_integer(2.into());
    let one = BigRational::from_integer(1.into());
    let zero = BigRational::zero();
    let s4 = s * s * s * s;
    let c3 = b * xi * ei / (&two * &s4) - a * rho;
    let coef5 = &two * a * rho_xc;
    let rows = vec![vec![b.clone(), coef5], vec![-one.clone(), zero.clone()], vec![zero.clone(), -one]];
    let sys = LinearSystem {
        a: RationalMatrix::from_rows(rows).expect("rectangular"),
        b: vec![c3.clone(), zero.clone(), zero],
        a_eq: RationalMatrix::zeros(0, 2),
        b_eq: vec![],
    };
    (sys, c3)
}
