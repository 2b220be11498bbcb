//! The claim ledger: one row per claim of the paper with a verdict, the basis it rests on, a
//! short finding with its decisive numbers, the typed evidence, assumptions, certificates and
//! the data behind its figures. Wall times are kept apart from the reproducible content.

use serde::{Deserialize, Serialize};
use wingcheck_model::Quantity;

pub use crate::spec::ClaimId;
pub use wingcheck_chart::{Line, PlotData};

use crate::evidence::Evidence;
use crate::explain::Explain;
use crate::settings::CheckSettings;

/// What the check concluded. Never overclaims: see [`Basis`] for what it rests on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
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
    /// Part of the claim is reproduced and part is not; the finding says which.
    PartlyReproduced,
    /// Not decided (not computed, or the evidence is not strong enough); the row says why.
    Inconclusive,
}

impl Verdict {
    /// Every verdict, in the order of the legend.
    pub const ALL: [Verdict; 7] = [
        Verdict::Holds,
        Verdict::HoldsAfterCorrection,
        Verdict::PartlyReproduced,
        Verdict::TriviallyTrue,
        Verdict::Vacuous,
        Verdict::Fails,
        Verdict::Inconclusive,
    ];

    /// Kebab-case name as `check` and the JSON print it (a token, not prose: a page for people
    /// shows the verdict's [`Display`](std::fmt::Display) text).
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

    /// What the verdict means in a few words (the one-line legend at the top of the report).
    pub fn short(self) -> &'static str {
        match self {
            Verdict::Holds => "as printed",
            Verdict::Fails => "false as printed",
            Verdict::HoldsAfterCorrection => "after the correction",
            Verdict::Vacuous => "uninformative",
            Verdict::TriviallyTrue => "by a trivial hypothesis",
            Verdict::PartlyReproduced => "in part",
            Verdict::Inconclusive => "undecided",
        }
    }

    /// One line of the legend: what the verdict means.
    pub fn meaning(self) -> &'static str {
        match self {
            Verdict::Holds => "the claim holds as printed",
            Verdict::Fails => "false as printed: a counterexample or a violated condition is in the evidence",
            Verdict::HoldsAfterCorrection => "holds only after the stated correction",
            Verdict::Vacuous => "formally valid but uninformative",
            Verdict::TriviallyTrue => "true only because the hypothesis makes it trivial; nothing was tested",
            Verdict::PartlyReproduced => "part of the claim is reproduced, part is not",
            Verdict::Inconclusive => "not decided; the row says why",
        }
    }
}

/// The verdict in words, as a page for people shows it (`holds after correction`, `holds but
/// vacuous`); the one text of each verdict for prose (the report, its links and tallies).
impl std::fmt::Display for Verdict {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Verdict::Holds => "holds",
            Verdict::Fails => "fails",
            Verdict::HoldsAfterCorrection => "holds after correction",
            Verdict::Vacuous => "holds but vacuous",
            Verdict::TriviallyTrue => "trivially true",
            Verdict::PartlyReproduced => "partly reproduced",
            Verdict::Inconclusive => "inconclusive",
        })
    }
}

/// What a verdict rests on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum Basis {
    /// A certificate re-checked in exact rational arithmetic (proof, for the stated statement).
    ExactCertificate,
    /// A closed-form argument (stated in the row and the docs) whose conditions are evaluated in
    /// exact rational arithmetic from the configuration's decimals.
    Analytic,
    /// A floating-point solver's answer (SDP/LP/eigenvalues): evidence, not proof.
    FloatSolver,
    /// Floating-point computation without a solver (a search, an ODE integration, an exact
    /// counterexample beside float checks): evidence for the cases computed.
    Computation,
    /// Simulation of the closed loop: evidence for the simulated cases only.
    Simulation,
}

impl Basis {
    /// Every basis, in the order of the legend.
    pub const ALL: [Basis; 5] =
        [Basis::ExactCertificate, Basis::Analytic, Basis::FloatSolver, Basis::Computation, Basis::Simulation];

    /// Kebab-case name as `check` and the JSON print it (a page for people shows the basis's
    /// [`Display`](std::fmt::Display) text).
    pub fn name(self) -> &'static str {
        match self {
            Basis::ExactCertificate => "exact-certificate",
            Basis::Analytic => "analytic",
            Basis::FloatSolver => "float-solver",
            Basis::Computation => "computation",
            Basis::Simulation => "simulation",
        }
    }

    /// What it means, in a line.
    pub fn meaning(self) -> &'static str {
        match self {
            Basis::ExactCertificate => "proof: re-checked in exact rational arithmetic",
            Basis::Analytic => "a closed-form argument whose conditions are decided in exact arithmetic",
            Basis::FloatSolver => "a floating-point solver, re-verified: evidence, not proof",
            Basis::Computation => "floating-point searches and integrations: evidence for the cases computed",
            Basis::Simulation => "closed-loop simulation: evidence for the simulated cases",
        }
    }
}

/// The basis in words, as a page for people shows it (`exact certificate`, `float solver`).
impl std::fmt::Display for Basis {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Basis::ExactCertificate => "exact certificate",
            Basis::Analytic => "analytic",
            Basis::FloatSolver => "float solver",
            Basis::Computation => "computation",
            Basis::Simulation => "simulation",
        })
    }
}

/// One claim's row.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
pub struct ClaimRow {
    /// Claim id.
    pub id: ClaimId,
    /// Where in the paper (equations, theorem), from the claim table.
    pub equation: String,
    /// The claim in words, from the claim table.
    pub claim: String,
    /// Verdict.
    pub verdict: Verdict,
    /// What the verdict rests on.
    pub basis: Basis,
    /// The finding: at most three short sentences.
    pub finding: Vec<String>,
    /// The decisive numbers, each with its unit and error or basis.
    pub decisive: Vec<Quantity>,
    /// The one comparison that decides the verdict, in a few words with its numbers (one line
    /// of the report's first screen).
    pub deciding: String,
    /// Further sentences of explanation (the detail section).
    pub details: Vec<String>,
    /// The correction under which the claim holds (for `holds-after-correction`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub correction: Option<String>,
    /// The typed evidence: labelled quantities, flags, texts and tables ([`crate::display`]).
    pub evidence: Evidence,
    /// Assumptions made where the paper is silent.
    pub assumptions: Vec<String>,
    /// Certificate files (`<id>.json` in `wingcheck certify`'s output for this configuration)
    /// backing the row.
    pub certificates: Vec<String>,
    /// Data behind the row's figures.
    pub plots: Vec<PlotData>,
}

impl ClaimRow {
    /// A decided row: verdict, finding, numbers and correction from the evidence itself.
    pub fn decided<E: Explain + Into<Evidence>>(
        id: ClaimId,
        evidence: E,
        assumptions: Vec<String>,
        plots: Vec<PlotData>,
    ) -> ClaimRow {
        let (verdict, basis) = evidence.verdict();
        let spec = id.spec();
        ClaimRow {
            id,
            equation: id.equation(),
            claim: spec.claim.into(),
            verdict,
            basis,
            finding: evidence.finding(),
            decisive: evidence.decisive(),
            deciding: evidence.deciding(),
            details: evidence.details(),
            correction: evidence.correction(),
            evidence: evidence.into(),
            assumptions,
            certificates: Vec::new(),
            plots,
        }
    }

    /// A row that has not been decided, with the reason (and the basis the reason rests on).
    pub fn inconclusive(id: ClaimId, basis: Basis, reason: impl Into<String>) -> ClaimRow {
        let spec = id.spec();
        ClaimRow {
            id,
            equation: id.equation(),
            claim: spec.claim.into(),
            verdict: Verdict::Inconclusive,
            basis,
            finding: vec![reason.into()],
            decisive: Vec::new(),
            deciding: "not decided: see the finding".into(),
            details: Vec::new(),
            correction: None,
            evidence: Evidence::None,
            assumptions: Vec::new(),
            certificates: Vec::new(),
            plots: Vec::new(),
        }
    }

    /// The finding as one paragraph.
    pub fn finding_text(&self) -> String {
        self.finding.join(" ")
    }

    /// The evidence serialised (the row's `evidence` in `check --json`).
    pub fn evidence_json(&self) -> serde_json::Value {
        serde_json::to_value(&self.evidence).expect("evidence serialises")
    }

    /// Numeric evidence by its JSON path (`lambda2_tight`, `runs.ftdo.rms_q_full`): a
    /// quantity's value.
    pub fn number(&self, path: &str) -> Option<f64> {
        crate::display::number_at(&self.evidence_json(), path)
    }
}

/// A wall time (not reproducible content): what took how long.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
pub struct WallTime {
    /// What was timed (`W-bounds`, `W-bounds SDP cross-check N = 32`).
    pub what: String,
    /// Wall seconds.
    pub seconds: f64,
}

/// The whole ledger.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
pub struct Ledger {
    /// Layout version of the document ([`wingcheck_io::SCHEMA_VERSION`]; the JSON Schema is
    /// docs/schema/check.schema.json).
    pub schema_version: u32,
    /// Tool name and version.
    pub tool: String,
    /// SHA-256 of the configuration's canonical JSON.
    pub config_sha256: String,
    /// The tool's build (version, commit, tree state, rustc) and the configuration's SHA-256:
    /// the provenance record every JSON output carries (docs/schema/provenance.schema.json).
    pub provenance: wingcheck_io::Provenance,
    /// The checker's numerical settings (grids, tolerances, thresholds) used for every row.
    pub settings: CheckSettings,
    /// One row per claim, in the paper's order.
    pub rows: Vec<ClaimRow>,
    /// Wall times of the rows and their parts (they run concurrently, so they overlap). Not
    /// serialised: `check --json` is reproducible byte for byte; `check` and the report's
    /// provenance print them.
    #[serde(skip)]
    pub wall_seconds: Vec<WallTime>,
}

impl Ledger {
    /// The wall time (s) recorded under `what` ([`WallTime::what`]: a row's name,
    /// [`crate::SDP_CROSS_CHECK`], [`crate::DIGITAL_RUNS`], …), if any.
    pub fn wall_seconds_of(&self, what: &str) -> Option<f64> {
        self.wall_seconds.iter().find(|w| w.what == what).map(|w| w.seconds)
    }
}

/// `v` as indented JSON (two spaces, like `serde_json::to_string_pretty`) except that an
/// array of scalars — a plot's x or y, a grid list — is written on one line: the same document
/// in about half the bytes (a 2001-point series is one line instead of 2001).
fn write_json(v: &serde_json::Value, indent: usize, out: &mut String) {
    use serde_json::Value;
    let pad = |n: usize| "  ".repeat(n);
    match v {
        Value::Array(a) if a.is_empty() => out.push_str("[]"),
        Value::Array(a) if a.iter().all(|x| !x.is_array() && !x.is_object()) => {
            out.push('[');
            for (i, x) in a.iter().enumerate() {
                if i > 0 {
                    out.push_str(", ");
                }
                write_json(x, indent, out);
            }
            out.push(']');
        }
        Value::Array(a) => {
            out.push_str("[\n");
            for (i, x) in a.iter().enumerate() {
                out.push_str(&pad(indent + 1));
                write_json(x, indent + 1, out);
                out.push_str(if i + 1 < a.len() { ",\n" } else { "\n" });
            }
            out.push_str(&pad(indent));
            out.push(']');
        }
        Value::Object(m) if m.is_empty() => out.push_str("{}"),
        Value::Object(m) => {
            out.push_str("{\n");
            for (i, (k, x)) in m.iter().enumerate() {
                out.push_str(&pad(indent + 1));
                out.push_str(&serde_json::to_string(k).expect("a key serialises"));
                out.push_str(": ");
                write_json(x, indent + 1, out);
                out.push_str(if i + 1 < m.len() { ",\n" } else { "\n" });
            }
            out.push_str(&pad(indent));
            out.push('}');
        }
        scalar => out.push_str(&serde_json::to_string(scalar).expect("a scalar serialises")),
    }
}

impl Ledger {
    /// The ledger as `check --json` prints it and the report writes it (`ledger.json`):
    /// indented JSON with arrays of numbers on one line ([`write_json`]).
    pub fn to_json(&self) -> String {
        let v = serde_json::to_value(self).expect("the ledger serialises");
        let mut out = String::new();
        write_json(&v, 0, &mut out);
        out
    }

    /// Row by id.
    pub fn row(&self, id: ClaimId) -> Option<&ClaimRow> {
        self.rows.iter().find(|r| r.id == id)
    }

    /// JSON paths of every null, NaN or infinite value (and of texts printing NaN / "inf") in
    /// the ledger; empty for a valid ledger.
    pub fn non_finite(&self) -> Vec<String> {
        non_finite_paths(self)
    }
}

/// JSON paths of every null, NaN or infinite value (and of texts printing NaN / "inf") in the
/// serialisation of `v`.
pub fn non_finite_paths<T: Serialize>(v: &T) -> Vec<String> {
    let mut out = Vec::new();
    match serde_json::to_value(v) {
        Ok(v) => find_non_finite(&v, "$", &mut out),
        Err(e) => out.push(format!("$ (does not serialise: {e})")),
    }
    out
}

fn find_non_finite(v: &serde_json::Value, path: &str, out: &mut Vec<String>) {
    use serde_json::Value;
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
