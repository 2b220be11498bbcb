//! The claim ledger: one row per claim of the paper with a verdict, the basis it rests on,
//! evidence numbers, assumptions, and the data behind its figures.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};
use serde_json::Value;

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
            Basis::FloatSolver => "float-solver",
            Basis::Simulation => "simulation",
        }
    }
}

/// One line of a plot: y against x.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Line {
    /// Legend label.
    pub label: String,
    /// Abscissae.
    pub x: Vec<f64>,
    /// Ordinates (same length as x).
    pub y: Vec<f64>,
    /// Draw as points instead of a polyline.
    #[serde(default)]
    pub points: bool,
}

/// The data behind one evidence figure, ready to plot or export as CSV.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PlotData {
    /// File-name-safe identifier, unique within the ledger (e.g. `finite-time-sigma1`).
    pub name: String,
    /// Title / caption (numbers in it come from the run).
    pub title: String,
    /// x-axis label with units.
    pub x_label: String,
    /// y-axis label with units.
    pub y_label: String,
    /// Logarithmic x axis.
    #[serde(default)]
    pub log_x: bool,
    /// Logarithmic y axis.
    #[serde(default)]
    pub log_y: bool,
    /// The lines.
    pub lines: Vec<Line>,
}

impl PlotData {
    /// The data as CSV: one block per line (`label,x,y`).
    pub fn to_csv(&self) -> String {
        let mut out = format!("line,{},{}\n", csv_field(&self.x_label), csv_field(&self.y_label));
        for l in &self.lines {
            for (x, y) in l.x.iter().zip(&l.y) {
                out.push_str(&format!("{},{x},{y}\n", csv_field(&l.label)));
            }
        }
        out
    }
}

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// One claim's row.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ClaimRow {
    /// Claim id (`W-bounds`, `mu-conditions`, `UUB`, `finite-time-1`, `finite-time-2`, `lemmas`, `ftdo-vs-dobc`).
    pub id: String,
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
    pub fn inconclusive(id: &str, equation: &str, claim: &str, reason: &str) -> ClaimRow {
        ClaimRow {
            id: id.into(),
            equation: equation.into(),
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
        self.rows.iter().find(|r| r.id == id)
    }
}
