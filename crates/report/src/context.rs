//! The serde context of the HTML template (`templates/index.html`). Everything the page
//! shows is computed here; the template only lays it out.

use serde::Serialize;
use serde_json::Value;
use wingcheck_claims::{ClaimRow, Ledger};
use wingcheck_model::Config;

use crate::accuracy::AccuracyRow;
use crate::figure::{Figure, Part};
use crate::stats::fmt_num;

/// Root of the template context.
#[derive(Serialize)]
pub struct Page {
    /// Tool name and version.
    pub tool: String,
    /// Provenance: git commit, rustc, date, command line.
    pub build: Build,
    /// The (a, b) region map, when it could be computed.
    pub region: Option<FigCtx>,
    /// Why there is no region map (when there is none).
    pub region_missing: String,
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

/// Build and run provenance.
#[derive(Serialize)]
pub struct Build {
    /// Git commit of the checkout the tool was built from, or `unknown`.
    pub git_commit: String,
    /// rustc version.
    pub rustc: String,
    /// UTC date of the run (volatile).
    pub date: String,
    /// The command line (volatile).
    pub command_line: String,
    /// Total wall time (s, volatile).
    pub total_seconds: String,
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
    /// Unit (from the key's naming convention: `_s` seconds, `q` m, `theta` rad, …), or empty.
    pub unit: String,
}

/// Evidence with a common `label.` prefix pivoted into a table: one row per metric, one
/// column per label (e.g. controller × metric).
#[derive(Serialize)]
pub struct Pivot {
    /// Column labels.
    pub columns: Vec<String>,
    /// Rows: metric, unit, one value per column (`—` when missing).
    pub rows: Vec<(String, String, Vec<String>)>,
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
    /// The ledger's digest: finding sentence and decisive numbers.
    pub digest: crate::digest::Digest,
    /// Scalar evidence without a label prefix.
    pub evidence: Vec<Kv>,
    /// Evidence with label prefixes, pivoted.
    pub pivot: Option<Pivot>,
    /// Evidence values that are lists of records (e.g. the SDP cross-check per N, the (a, b)
    /// sweep), each as its own table.
    pub tables: Vec<EvidenceTable>,
    /// The decisive figure (the row's first plot).
    pub lead_figure: Option<FigCtx>,
    /// Assumptions.
    pub assumptions: Vec<String>,
    /// Certificate files.
    pub certificates: Vec<String>,
    /// The row's other plots.
    pub figures: Vec<FigCtx>,
}

/// A list-of-records evidence value as a table: one row per record, one column per field.
#[derive(Serialize)]
pub struct EvidenceTable {
    /// Evidence key (underscores as spaces).
    pub key: String,
    /// Field names, each with its unit in parentheses where the naming convention gives one.
    pub columns: Vec<String>,
    /// Formatted values, row by row.
    pub rows: Vec<Vec<String>>,
}

/// `v` as a table if it is an object (one row) or a non-empty array of objects (a row each):
/// one column per field (the union of the records' keys in first-seen order), a nested
/// object's fields flattened one level into `parent: field` columns.
fn evidence_table(key: &str, v: &Value) -> Option<EvidenceTable> {
    let records: Vec<&serde_json::Map<String, Value>> = match v {
        Value::Object(one) => vec![one],
        _ => v.as_array()?.iter().map(Value::as_object).collect::<Option<_>>()?,
    };
    if records.is_empty() {
        return None;
    }
    let flat: Vec<Vec<(String, &Value)>> = records
        .iter()
        .map(|r| {
            r.iter()
                .flat_map(|(k, v)| match v.as_object() {
                    Some(inner) => inner.iter().map(|(ik, iv)| (format!("{k}: {ik}"), iv)).collect::<Vec<_>>(),
                    None => vec![(k.clone(), v)],
                })
                .collect()
        })
        .collect();
    let mut fields: Vec<String> = Vec::new();
    for r in &flat {
        for (k, _) in r {
            if !fields.contains(k) {
                fields.push(k.clone());
            }
        }
    }
    let columns = fields
        .iter()
        .map(|f| match unit_of(f) {
            "" => f.replace('_', " "),
            u => format!("{} ({u})", f.replace('_', " ")),
        })
        .collect();
    let rows = flat
        .iter()
        .map(|r| {
            fields.iter().map(|f| r.iter().find(|(k, _)| k == f).map_or("—".into(), |(_, v)| value_text(v))).collect()
        })
        .collect();
    Some(EvidenceTable { key: key.replace('_', " "), columns, rows })
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

/// A value with sensible digits: integers as integers, other numbers to 4 significant digits,
/// arrays and objects compactly (numbers inside formatted the same way).
fn value_text(v: &Value) -> String {
    match v {
        Value::Number(n) => match (n.as_i64(), n.as_f64()) {
            (Some(i), _) => i.to_string(),
            (None, Some(f)) if f.fract() == 0.0 && f.abs() < 1e6 => format!("{f:.0}"),
            (None, Some(f)) => fmt_num(f),
            _ => n.to_string(),
        },
        Value::String(s) => s.clone(),
        Value::Bool(b) => if *b { "yes" } else { "no" }.into(),
        Value::Null => "—".into(),
        Value::Array(a) => format!("[{}]", a.iter().map(value_text).collect::<Vec<_>>().join(", ")),
        Value::Object(m) => {
            format!("{{{}}}", m.iter().map(|(k, v)| format!("{k}: {}", value_text(v))).collect::<Vec<_>>().join(", "))
        }
    }
}

/// The unit of an evidence key by the claims crate's naming convention, or "".
pub fn unit_of(key: &str) -> &'static str {
    let k = key.rsplit('.').next().unwrap_or(key);
    if k.ends_with("_rad_s") {
        "rad/s"
    } else if k.ends_with("_s") || k.contains("_s_T") || k == "seconds" {
        "s"
    } else if k.contains("gtilde1") || k.contains("tau1") {
        "N"
    } else if k.contains("gtilde2") || k.contains("tau2") {
        "N m"
    } else if k.contains("theta") {
        "rad"
    } else if k.contains("_q_")
        || k.ends_with("_q")
        || k.starts_with("rms_q")
        || k.starts_with("max_q")
        || k.ends_with("_m")
    {
        "m"
    } else {
        ""
    }
}

/// Evidence keys of the form `label.metric` pivoted (None if there are none).
fn pivot(r: &ClaimRow) -> Option<Pivot> {
    let mut columns: Vec<String> = Vec::new();
    let mut metrics: Vec<String> = Vec::new();
    for k in r.evidence.keys() {
        if let Some((l, m)) = k.split_once('.') {
            if !columns.iter().any(|c| c == l) {
                columns.push(l.to_string());
            }
            if !metrics.iter().any(|c| c == m) {
                metrics.push(m.to_string());
            }
        }
    }
    if columns.is_empty() {
        return None;
    }
    let rows = metrics
        .iter()
        .map(|m| {
            let vals =
                columns.iter().map(|c| r.evidence.get(&format!("{c}.{m}")).map_or("—".into(), value_text)).collect();
            (m.replace('_', " "), unit_of(m).to_string(), vals)
        })
        .collect();
    Some(Pivot { columns, rows })
}

/// The ledger row's context; `figures` are the row's plots already turned into figures,
/// `digest` its ledger digest.
pub fn row_ctx(r: &ClaimRow, figures: &[Figure], digest: crate::digest::Digest) -> RowCtx {
    let id = r.id.to_string();
    let (mut tables, mut evidence) = (Vec::new(), Vec::new());
    for (k, v) in r.evidence.iter().filter(|(k, _)| !k.contains('.')) {
        match evidence_table(k, v) {
            Some(table) => tables.push(table),
            None => evidence.push(Kv { key: k.replace('_', " "), value: value_text(v), unit: unit_of(k).into() }),
        }
    }
    let mut figs = figures.iter().map(FigCtx::from);
    let lead_figure = figs.next();
    RowCtx {
        anchor: claim_anchor(&id),
        id,
        equation: r.equation.clone(),
        claim: r.claim.clone(),
        verdict: r.verdict.name().into(),
        basis: r.basis.name().into(),
        summary: r.summary.clone(),
        correction: r.correction.clone(),
        digest,
        evidence,
        pivot: pivot(r),
        tables,
        lead_figure,
        assumptions: r.assumptions.clone(),
        certificates: r.certificates.clone(),
        figures: figs.collect(),
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
                "{} with {} {}, grading {}, dt = {} s, time scheme {}",
                d.method.name().to_uppercase(),
                d.grid_size(),
                if d.method == wingcheck_model::Method::Fe { "elements" } else { "intervals" },
                d.grading,
                d.dt,
                match d.stepper {
                    wingcheck_model::TimeScheme::Auto => {
                        "auto (TR-BDF2; the exponential scheme, exact for the held estimate, for the explicit-FTDO runs in the modal basis)".to_string()
                    }
                    s => s.name().to_string(),
                }
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
            "typos in the printed model (see model.md, the model as simulated)",
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
                anchor: claim_anchor(&r.id.to_string()),
                text: a.clone(),
            })
        })
        .collect()
}
