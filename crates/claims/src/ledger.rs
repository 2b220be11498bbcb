//! The claim ledger: one row per claim of the paper with a verdict, the basis it rests on,
//! evidence numbers, assumptions, and the data behind its figures.

use std::collections::BTreeMap;

use serde::{Deserialize, Deserializer, Serialize, Serializer};
use serde_json::Value;
pub use wingcheck_chart::{Line, PlotData};

/// How a value that exists only once σ has reached zero (or its band) is written when it has
/// not: evidence and texts.
pub const NOT_REACHED: &str = "not reached within the run";
/// How a settling time that is not reached before the horizon is written in evidence and texts.
pub const NEVER_SETTLED: &str = "never within the horizon";

/// A number, or `None` written as a fixed text (never null).
macro_rules! number_or_text {
    ($(#[$doc:meta])* $name:ident, $text:expr) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq, Default)]
        pub struct $name(pub Option<f64>);

        impl Serialize for $name {
            fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                match self.0 {
                    Some(x) => s.serialize_f64(x),
                    None => s.serialize_str($text),
                }
            }
        }

        impl<'de> Deserialize<'de> for $name {
            fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                match Value::deserialize(d)? {
                    Value::Number(n) => Ok($name(n.as_f64())),
                    Value::String(t) if t == $text => Ok($name(None)),
                    v => Err(serde::de::Error::custom(format!("expected a number or \"{}\", got {v}", $text))),
                }
            }
        }

        impl std::fmt::Display for $name {
            /// `x.xxxxe±y <unit-less>` or the text.
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                match self.0 {
                    Some(x) => write!(f, "{x:.4e}"),
                    None => f.write_str($text),
                }
            }
        }
    };
}

number_or_text!(
    /// A value that exists only once σ reached zero or its band (a reaching time in s, or σ's
    /// magnitude after reaching); otherwise serialised as [`NOT_REACHED`].
    Reached,
    NOT_REACHED
);
number_or_text!(
    /// A settling time (s), or [`NEVER_SETTLED`] when the signal is still outside its threshold
    /// at the end of the horizon.
    SettleTime,
    NEVER_SETTLED
);

/// What the check concluded. Never overclaims: see [`Basis`] for what it rests on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Verdict {
    /// The claim holds as printed.
    Holds,
    /// The claim is false as printed (a counterexample or a violated condition is in the evidence).
    Fails,
    /// The claim holds only after the correction stated in the row.
    HoldsAfterCorrection,
    /// Formally valid but uninformative (e.g. a bound orders of magnitude above the truth).
    Vacuous,
    /// True, but only because the hypothesis makes it trivial (e.g. a reaching-time bound of 0 s
    /// when the observer error starts at zero); nothing was tested.
    TriviallyTrue,
    /// Part of the claim is reproduced and part is not; the summary says which.
    PartlyReproduced,
    /// Not decided (not computed, or the evidence is not strong enough); the row says why.
    Inconclusive,
}

impl Verdict {
    /// Kebab-case name as printed.
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Holds => "holds",
            Verdict::Fails => "fails",
            Verdict::HoldsAfterCorrection => "holds-after-correction",
            Verdict::Vacuous => "vacuous",
            Verdict::TriviallyTrue => "trivially-true",
            Verdict::PartlyReproduced => "partly-reproduced",
            Verdict::Inconclusive => "inconclusive",
        }
    }
}

/// What a verdict rests on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Basis {
    /// A certificate re-checked in exact rational arithmetic (proof, for the stated discretisation).
    ExactCertificate,
    /// A closed-form argument (stated in the row and the docs) whose conditions are evaluated in
    /// exact rational arithmetic from the configuration's decimals.
    Analytic,
    /// A floating-point solver's answer (SDP/LP/eigenvalues): evidence, not proof.
    FloatSolver,
    /// Simulation of the closed loop: evidence for the simulated cases only.
    Simulation,
}

impl Basis {
    /// Kebab-case name as printed.
    pub fn name(self) -> &'static str {
        match self {
            Basis::ExactCertificate => "exact-certificate",
            Basis::Analytic => "analytic",
            Basis::FloatSolver => "float-solver",
            Basis::Simulation => "simulation",
        }
    }
}

/// The claims of the paper, in the paper's order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub enum ClaimId {
    /// Theorem 1, (22)–(28).
    #[serde(rename = "W-bounds")]
    WBounds,
    /// (29)–(32).
    #[serde(rename = "mu-conditions")]
    MuConditions,
    /// Theorem 2, (33)–(37).
    #[serde(rename = "UUB")]
    Uub,
    /// Theorem 3, (38).
    #[serde(rename = "finite-time-1")]
    FiniteTime1,
    /// Theorem 3, (39).
    #[serde(rename = "finite-time-2")]
    FiniteTime2,
    /// Lemmas 1–3.
    #[serde(rename = "lemmas")]
    Lemmas,
    /// Section 4: FTDO vs DOBC.
    #[serde(rename = "ftdo-vs-dobc")]
    FtdoVsDobc,
}

impl ClaimId {
    /// Every claim, in the paper's order.
    pub const ALL: [ClaimId; 7] = [
        ClaimId::WBounds,
        ClaimId::MuConditions,
        ClaimId::Uub,
        ClaimId::FiniteTime1,
        ClaimId::FiniteTime2,
        ClaimId::Lemmas,
        ClaimId::FtdoVsDobc,
    ];

    /// The id as printed.
    pub fn name(self) -> &'static str {
        match self {
            ClaimId::WBounds => "W-bounds",
            ClaimId::MuConditions => "mu-conditions",
            ClaimId::Uub => "UUB",
            ClaimId::FiniteTime1 => "finite-time-1",
            ClaimId::FiniteTime2 => "finite-time-2",
            ClaimId::Lemmas => "lemmas",
            ClaimId::FtdoVsDobc => "ftdo-vs-dobc",
        }
    }

    /// Where in the paper.
    pub fn equation(self) -> &'static str {
        match self {
            ClaimId::WBounds => "(22)–(28), Theorem 1",
            ClaimId::MuConditions => "(29)–(32)",
            ClaimId::Uub => "(33)–(37), Theorem 2",
            ClaimId::FiniteTime1 => "(38), Theorem 3",
            ClaimId::FiniteTime2 => "(39), Theorem 3",
            ClaimId::Lemmas => "Lemmas 1–3, (12)–(14)",
            ClaimId::FtdoVsDobc => "Section 4, Figs 3–20",
        }
    }
}

impl std::fmt::Display for ClaimId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.pad(self.name())
    }
}

/// A typed evidence struct as the row's key → value map (its serde serialisation); every
/// value must be finite (checked by [`Ledger::non_finite`]).
pub fn evidence_map<T: Serialize>(e: &T) -> BTreeMap<String, Value> {
    match serde_json::to_value(e) {
        Ok(Value::Object(m)) => m.into_iter().collect(),
        _ => BTreeMap::new(),
    }
}

fn find_non_finite(v: &Value, path: &str, out: &mut Vec<String>) {
    match v {
        Value::Null => out.push(path.to_string()),
        Value::Number(n) if n.as_f64().is_none_or(|x| !x.is_finite()) => out.push(path.to_string()),
        Value::Array(a) => a.iter().enumerate().for_each(|(i, x)| find_non_finite(x, &format!("{path}[{i}]"), out)),
        Value::Object(m) => m.iter().for_each(|(k, x)| find_non_finite(x, &format!("{path}.{k}"), out)),
        Value::String(s) if s.contains("NaN") || s.split(|c: char| !c.is_alphanumeric()).any(|w| w == "inf") => {
            out.push(path.to_string())
        }
        _ => {}
    }
}

/// One claim's row.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ClaimRow {
    /// Claim id.
    pub id: ClaimId,
    /// Where in the paper (equation numbers, theorem).
    pub equation: String,
    /// The claim in words.
    pub claim: String,
    /// Verdict.
    pub verdict: Verdict,
    /// What the verdict rests on.
    pub basis: Basis,
    /// One-paragraph summary of the finding.
    pub summary: String,
    /// The correction under which the claim holds (for `holds-after-correction`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub correction: Option<String>,
    /// Key numbers and facts (stable keys; tests assert on them).
    pub evidence: BTreeMap<String, Value>,
    /// Evidence keys to show first (e.g. in the report's ledger table), most important first.
    #[serde(default)]
    pub highlights: Vec<String>,
    /// Assumptions made where the paper is silent.
    pub assumptions: Vec<String>,
    /// Certificate files backing the row (relative to the proofs directory).
    #[serde(default)]
    pub certificates: Vec<String>,
    /// Data behind the row's figures.
    #[serde(default)]
    pub plots: Vec<PlotData>,
    /// Wall time spent on this row (s); not part of the reproducible content.
    pub seconds: f64,
}

impl ClaimRow {
    /// A row that has not been decided, with the reason.
    pub fn inconclusive(id: ClaimId, claim: &str, reason: &str) -> ClaimRow {
        ClaimRow {
            id,
            equation: id.equation().into(),
            claim: claim.into(),
            verdict: Verdict::Inconclusive,
            basis: Basis::Simulation,
            summary: reason.into(),
            correction: None,
            evidence: BTreeMap::new(),
            highlights: Vec::new(),
            assumptions: Vec::new(),
            certificates: Vec::new(),
            plots: Vec::new(),
            seconds: 0.0,
        }
    }

    /// Numeric evidence value by key.
    pub fn number(&self, key: &str) -> Option<f64> {
        self.evidence.get(key).and_then(Value::as_f64)
    }
}

/// The whole ledger.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Ledger {
    /// Tool name and version.
    pub tool: String,
    /// SHA-256 of the configuration's canonical JSON.
    pub config_sha256: String,
    /// One row per claim, in the paper's order.
    pub rows: Vec<ClaimRow>,
}

impl Ledger {
    /// Row by id.
    pub fn row(&self, id: &str) -> Option<&ClaimRow> {
        self.rows.iter().find(|r| r.id.name() == id)
    }

    /// JSON paths of every null, NaN or infinite value (and of texts printing NaN / "= inf")
    /// in the ledger; empty for a valid ledger.
    pub fn non_finite(&self) -> Vec<String> {
        let mut out = Vec::new();
        match serde_json::to_value(self) {
            Ok(v) => find_non_finite(&v, "$", &mut out),
            Err(e) => out.push(format!("$ (does not serialise: {e})")),
        }
        for r in &self.rows {
            for (what, text) in
                [("summary", &r.summary), ("correction", r.correction.as_ref().unwrap_or(&String::new()))]
            {
                if text.contains("NaN") || text.split(|c: char| !c.is_alphanumeric()).any(|w| w == "inf") {
                    out.push(format!("{}.{what}", r.id));
                }
            }
            for p in &r.plots {
                if p.lines.iter().any(|l| l.x.iter().chain(&l.y).any(|v| !v.is_finite())) {
                    out.push(format!("{}.plots.{}", r.id, p.name));
                }
            }
        }
        out
    }
}
