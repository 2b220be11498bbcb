//! The serde context of the HTML template (`templates/index.html`). Everything the page
//! shows is computed here; the template only lays it out.

use serde::Serialize;
use serde_json::Value;
use wingcheck_claims::{ClaimRow, Ledger};
use wingcheck_model::Config;

use crate::accuracy::AccuracyRow;
use crate::figure::{Figure, Part};
use crate::stats::fmt_num;

/// Evidence entries shown in the ledger table's "key numbers" column.
const KEY_NUMBERS: usize = 4;

/// Root of the template context.
#[derive(Serialize)]
pub struct Page {
    /// Tool name and version.
    pub tool: String,
    /// SHA-256 of the configuration's canonical JSON.
    pub config_sha256: String,
    /// The configuration, pretty JSON.
    pub config_json: String,
    /// `os/arch`.
    pub platform: String,
    /// Ledger rows.
    pub rows: Vec<RowCtx>,
    /// Paper figure groups.
    pub groups: Vec<GroupCtx>,
    /// FTDO-vs-DOBC overlays.
    pub comparison: Vec<FigCtx>,
    /// Accuracy figure.
    pub accuracy_figure: FigCtx,
    /// Accuracy table.
    pub accuracy_rows: Vec<AccuracyRow>,
    /// Grid sizes of the accuracy table's columns.
    pub grids: Vec<usize>,
    /// Values the paper leaves out, and what was used.
    pub assumptions: Vec<Assumption>,
    /// Assumptions stated by the ledger rows.
    pub row_assumptions: Vec<RowAssumption>,
    /// Wall time per stage (the only non-reproducible content of the page).
    pub timings: Vec<Timing>,
}

/// A figure as the template sees it.
#[derive(Serialize)]
pub struct FigCtx {
    /// Anchor id.
    pub id: String,
    /// `Figure 9`, `Evidence E1`, …
    pub label: String,
    /// Short title (also the image's alt text).
    pub title: String,
    /// Caption parts.
    pub caption: Vec<Part>,
    /// SVG file name.
    pub svg: String,
    /// CSV file name.
    pub csv: String,
}

impl From<&Figure> for FigCtx {
    fn from(f: &Figure) -> Self {
        FigCtx {
            id: f.file.clone(),
            label: f.label.clone(),
            title: f.title.clone(),
            caption: f.caption.clone(),
            svg: format!("{}.svg", f.file),
            csv: format!("{}.csv", f.file),
        }
    }
}

/// A group of paper figures.
#[derive(Serialize)]
pub struct GroupCtx {
    /// Anchor id.
    pub id: String,
    /// Heading.
    pub title: String,
    /// Intro sentence.
    pub intro: String,
    /// Figures.
    pub figures: Vec<FigCtx>,
}

/// A key/value pair of evidence.
#[derive(Serialize)]
pub struct Kv {
    /// Key.
    pub key: String,
    /// Formatted value.
    pub value: String,
}

/// A ledger row.
#[derive(Serialize)]
pub struct RowCtx {
    /// Claim id.
    pub id: String,
    /// Anchor of its section.
    pub anchor: String,
    /// Paper equation / theorem.
    pub equation: String,
    /// Claim in words.
    pub claim: String,
    /// Verdict name.
    pub verdict: String,
    /// Basis name.
    pub basis: String,
    /// Summary.
    pub summary: String,
    /// Correction, if any.
    pub correction: Option<String>,
    /// First evidence entries.
    pub key_numbers: Vec<Kv>,
    /// All evidence.
    pub evidence: Vec<Kv>,
    /// Assumptions.
    pub assumptions: Vec<String>,
    /// Certificate files.
    pub certificates: Vec<String>,
    /// The row's plots.
    pub figures: Vec<FigCtx>,
}

/// A value the paper leaves out.
#[derive(Serialize)]
pub struct Assumption {
    /// What.
    pub what: String,
    /// The value used.
    pub used: String,
    /// Config key(s) to change it.
    pub key: String,
}

/// An assumption stated by a ledger row.
#[derive(Serialize)]
pub struct RowAssumption {
    /// Claim id.
    pub id: String,
    /// Anchor of the claim's section.
    pub anchor: String,
    /// The assumption.
    pub text: String,
}

/// Wall time of one stage.
#[derive(Serialize)]
pub struct Timing {
    /// Stage name.
    pub name: String,
    /// Seconds, formatted.
    pub seconds: String,
}

/// Anchor of a claim's section.
pub fn claim_anchor(id: &str) -> String {
    format!("claim-{}", crate::figure::safe_name(id))
}

fn value_text(v: &Value) -> String {
    match v {
        Value::Number(n) => n.as_f64().map(fmt_num).unwrap_or_else(|| n.to_string()),
        Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

/// Scalars fit the ledger table; arrays, objects and long strings stay in the claim's section.
fn is_key_number(v: &Value) -> bool {
    match v {
        Value::Number(_) | Value::Bool(_) => true,
        Value::String(s) => s.chars().count() <= 40,
        _ => false,
    }
}

/// The ledger row's context; `figures` are the row's plots already turned into figures.
pub fn row_ctx(r: &ClaimRow, figures: &[Figure]) -> RowCtx {
    let evidence: Vec<Kv> = r.evidence.iter().map(|(k, v)| Kv { key: k.clone(), value: value_text(v) }).collect();
    RowCtx {
        id: r.id.to_string(),
        anchor: claim_anchor(r.id.name()),
        equation: r.equation.clone(),
        claim: r.claim.clone(),
        verdict: r.verdict.name().into(),
        basis: r.basis.name().into(),
        summary: r.summary.clone(),
        correction: r.correction.clone(),
        key_numbers: if r.highlights.is_empty() {
            r.evidence
                .iter()
                .filter(|(_, v)| is_key_number(v))
                .take(KEY_NUMBERS)
                .map(|(k, v)| Kv { key: k.clone(), value: value_text(v) })
                .collect()
        } else {
            r.highlights
                .iter()
                .filter_map(|k| r.evidence.get(k).map(|v| Kv { key: k.clone(), value: value_text(v) }))
                .collect()
        },
        evidence,
        assumptions: r.assumptions.clone(),
        certificates: r.certificates.clone(),
        figures: figures.iter().map(FigCtx::from).collect(),
    }
}

/// Values the paper leaves out (or gets wrong) and what this report used, from the config.
pub fn assumptions(cfg: &Config) -> Vec<Assumption> {
    let o = &cfg.observer;
    let d = &cfg.discretisation;
    let a = |what: &str, used: String, key: &str| Assumption { what: what.into(), used, key: key.into() };
    vec![
        a(
            "weights a, b of the control law (15)",
            format!("a = {}, b = {}", cfg.control.a, cfg.control.b),
            "control.a, control.b",
        ),
        a(
            "observer sampling (digital observer, zero-order hold)",
            format!("period {} s, {} rule", o.sample_period, o.rule.name()),
            "observer.sample_period, observer.rule",
        ),
        a("analogue part −k(a·tip + b·tip rate) of (15)", "continuous (inside the implicit step)".into(), "—"),
        a(
            "initial condition q(z,0) = z/s (violates the clamp q'(0) = 0)",
            format!(
                "{} shape, q(s,0) = {} m, θ(s,0) = {} rad, clamp imposed at the root",
                match cfg.initial.shape {
                    wingcheck_model::InitialShape::Linear => "linear",
                    wingcheck_model::InitialShape::Cantilever => "cantilever",
                },
                cfg.initial.q_tip,
                cfg.initial.theta_tip
            ),
            "initial.shape, initial.q_tip, initial.theta_tip",
        ),
        a(
            "initial observer states ν(0), p(0)",
            format!("ν1(0) = {}, ν2(0) = {}", o.nu1_0, o.nu2_0),
            "observer.nu1_0, observer.nu2_0",
        ),
        a(
            "spatial grid and time step (the paper: \"finite differences\", no grid given)",
            format!(
                "{} with {} elements, grading {}, dt = {} s",
                d.method.name().to_uppercase(),
                d.elements,
                d.grading,
                d.dt
            ),
            "discretisation.*",
        ),
        a(
            "horizon and output sampling",
            format!(
                "T = {} s, every {} s, {} field points",
                cfg.horizon.t_end, cfg.horizon.sample_every, cfg.horizon.field_points
            ),
            "horizon.*",
        ),
        a(
            "typos in the model (shared/spec/model.md)",
            "tip third derivative q'''(s,t) in the boundary condition and observer; b q̇(s) in the DOBC law (57)".into(),
            "—",
        ),
    ]
}

/// Assumptions stated by the ledger rows, in row order.
pub fn row_assumptions(ledger: &Ledger) -> Vec<RowAssumption> {
    ledger
        .rows
        .iter()
        .flat_map(|r| {
            r.assumptions.iter().map(|a| RowAssumption {
                id: r.id.to_string(),
                anchor: claim_anchor(r.id.name()),
                text: a.clone(),
            })
        })
        .collect()
}
