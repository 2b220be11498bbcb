//! The serde context of the HTML template (`templates/index.html`). Everything the page
//! shows is computed here; the template only lays it out.

use serde::Serialize;
use wingcheck_claims::display::{Cell, Column, Node};
use wingcheck_claims::{Basis, ClaimRow, Ledger, Verdict};
use wingcheck_model::{Config, Quantity};

use crate::accuracy::AccuracyRow;
use crate::figure::{claim_anchor, Figure, Part};
use crate::links::Link;
use crate::top::{pieces, Piece};
use crate::ReportError;

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
    /// Each verdict with its meaning (from the claims crate's vocabulary).
    pub verdict_legend: Vec<(String, &'static str)>,
    /// Each verdict in words with its meaning in a few words (the one-line legend at the top).
    pub verdict_short: Vec<(String, &'static str)>,
    /// Each basis in words with its meaning.
    pub basis_legend: Vec<(String, &'static str)>,
    /// The keys that differ from the embedded default `configs/paper.json`.
    pub changes: Vec<crate::top::ConfigChange>,
    /// The notation of the text (symbols and their meaning, with this run's values).
    pub notation: Vec<wingcheck_claims::display::Symbol>,
    /// The certificate set in `proofs/` (file names), or why there is none: the sentence the
    /// page prints (the typed `CertifyError` stays with the report's computation).
    pub proofs: Result<Vec<String>, String>,
    /// The certificates of `proofs/` with their statements and rows.
    pub certificates: Vec<crate::links::Certificate>,
    /// The verdict tally, in the legend's order (verdicts that occur only).
    pub tally: Vec<Tally>,
    /// How many verdicts rest on each basis (bases that occur only).
    pub basis_tally: Vec<Tally>,
    /// The paper's statements against the measured numbers.
    pub statements: Vec<crate::statements::Statement>,
    /// Whether its ω₁ enclosure is coarser than the one `wingcheck certify` writes.
    pub coarser_enclosure: bool,
}

/// Build and run provenance.
#[derive(Serialize)]
pub struct Build {
    /// Git commit of the checkout the tool was built from, or `unknown`.
    pub git_commit: String,
    /// Whether that tree was clean, dirty (uncommitted changes) or unknown (no git checkout).
    pub tree: String,
    /// rustc version.
    pub rustc: String,
    /// UTC date of the run (volatile).
    pub date: String,
    /// The command line (volatile).
    pub command_line: String,
    /// Total wall time (s, volatile).
    pub total_seconds: String,
    /// The machine of the run (volatile).
    pub machine: Option<crate::provenance::Machine>,
}

/// How many of something (a verdict, a basis), in words.
#[derive(Serialize)]
pub struct Tally {
    /// The verdict's or basis's name (kebab-case: the CSS class).
    pub name: &'static str,
    /// How many.
    pub count: usize,
    /// `2 fail`, `1 holds after correction`, `3 on simulation`.
    pub text: String,
}

/// The verdict tally of the ledger, in [`Verdict::ALL`]'s order.
pub fn tally(ledger: &Ledger) -> Vec<Tally> {
    Verdict::ALL
        .iter()
        .filter_map(|v| {
            let count = ledger.rows.iter().filter(|r| r.verdict == *v).count();
            (count > 0).then(|| Tally { name: v.name(), count, text: format!("{count} {}", verdict_words(*v, count)) })
        })
        .collect()
}

/// A verdict in words ([`Verdict`]'s display text), its leading verb agreeing with a count
/// (`1 holds`, `2 hold`; `2 fail`; `2 hold after correction`).
pub fn verdict_words(v: Verdict, count: usize) -> String {
    let words = v.to_string();
    if count == 1 {
        return words;
    }
    let (first, rest) = words.split_once(' ').unwrap_or((words.as_str(), ""));
    match first {
        "holds" | "fails" => {
            let verb = first.trim_end_matches('s');
            if rest.is_empty() {
                verb.to_string()
            } else {
                format!("{verb} {rest}")
            }
        }
        _ => words,
    }
}

/// How many verdicts rest on each basis, in [`Basis::ALL`]'s order.
pub fn basis_tally(ledger: &Ledger) -> Vec<Tally> {
    Basis::ALL
        .iter()
        .filter_map(|b| {
            let count = ledger.rows.iter().filter(|r| r.basis == *b).count();
            (count > 0).then(|| Tally { name: b.name(), count, text: format!("{count} on {}", basis_words(*b)) })
        })
        .collect()
}

/// A basis in words (`exact certificate`, `analytic argument`).
pub fn basis_words(b: Basis) -> &'static str {
    match b {
        Basis::ExactCertificate => "exact certificates",
        Basis::Analytic => "analytic arguments",
        Basis::FloatSolver => "float solvers",
        Basis::Computation => "computation",
        Basis::Simulation => "simulation",
    }
}

/// A figure as the template sees it.
#[derive(Serialize, Clone)]
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
    /// Data file name.
    pub csv: String,
    /// How the data link reads.
    pub data_label: String,
    /// Where in `ledger.json` the data is, for a row's plot (an attribute, not shown).
    pub data_path: Option<String>,
    /// The ledger rows that rest on it (links back).
    pub claims: Vec<Link>,
}

impl From<&Figure> for FigCtx {
    fn from(f: &Figure) -> Self {
        FigCtx {
            id: f.file.clone(),
            label: f.label.clone(),
            title: f.title.clone(),
            caption: f.caption.clone(),
            svg: format!("{}.svg", f.file),
            csv: f.data_file(),
            data_label: f.data_label(),
            data_path: f.data_path(),
            claims: Vec::new(),
        }
    }
}

impl FigCtx {
    /// The figure with links back to the rows of `ledger` that rest on it
    /// ([`crate::links::paper_figures`]).
    pub fn with_claims(mut self, ledger: &Ledger) -> FigCtx {
        self.claims = ledger
            .rows
            .iter()
            .filter(|r| crate::links::paper_figures(r.id).contains(&self.id.as_str()))
            .map(|r| crate::links::row_link(ledger, r.id))
            .collect();
        self
    }

    /// The link to this figure: its label and title.
    pub fn link(&self) -> Link {
        Link { href: format!("#{}", self.id), text: crate::links::figure_link_text(&self.label, &self.title), id: None }
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
    /// The assumption, as text, number and key pieces.
    pub text: Vec<Piece>,
}

/// Wall time of one stage.
#[derive(Serialize)]
pub struct Timing {
    /// Stage name.
    pub name: String,
    /// Seconds, formatted.
    pub seconds: String,
}

/// A number as the page shows it: label, formatted value with its unit, error or basis.
#[derive(Serialize)]
pub struct NumberCtx {
    /// What it is.
    pub label: String,
    /// The value with its unit.
    pub value: String,
    /// `± …` or the basis.
    pub accuracy: String,
}

impl From<&Quantity> for NumberCtx {
    fn from(q: &Quantity) -> Self {
        NumberCtx { label: q.label.clone(), value: q.value_text(), accuracy: q.accuracy_text() }
    }
}

/// A table of evidence as the page shows it.
#[derive(Serialize)]
pub struct TableCtx {
    /// What it shows.
    pub label: String,
    /// Column headers (label, with the unit in brackets where there is one).
    pub columns: Vec<String>,
    /// Rows of cells (`value` and `accuracy`).
    pub rows: Vec<Vec<Cell>>,
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
    /// The verdict in words (`holds after correction`).
    pub verdict_text: String,
    /// Basis name.
    pub basis: String,
    /// The basis in words.
    pub basis_text: String,
    /// Where in the paper, short (`Theorem 1`).
    pub theorem: String,
    /// The one comparison that decides the verdict, as text and number pieces.
    pub deciding: Vec<Piece>,
    /// The finding: short sentences, as text and number pieces.
    pub finding: Vec<Vec<Piece>>,
    /// The decisive numbers.
    pub decisive: Vec<NumberCtx>,
    /// Further sentences.
    pub details: Vec<Vec<Piece>>,
    /// Correction, if any.
    pub correction: Option<Vec<Piece>>,
    /// The evidence's single values (numbers, yes/no facts, texts), in field order.
    pub evidence: Vec<NumberCtx>,
    /// The evidence's tables.
    pub tables: Vec<TableCtx>,
    /// The decisive figure (the row's first plot).
    pub lead_figure: Option<FigCtx>,
    /// Assumptions, as pieces.
    pub assumptions: Vec<Vec<Piece>>,
    /// The certificates of `proofs/` that support the row, with what each proves.
    pub certificates: Vec<(Link, String)>,
    /// Certificate files the ledger names that `proofs/` does not hold (when certify could not
    /// write the set).
    pub certificates_missing: Vec<String>,
    /// The row's other plots.
    pub figures: Vec<FigCtx>,
    /// Links to every figure the row rests on: its own plots, then the paper's figures.
    pub figure_links: Vec<Link>,
}

fn header(c: &Column) -> String {
    if c.unit.is_empty() {
        c.label.clone()
    } else {
        format!("{} ({})", c.label, c.unit)
    }
}

/// A table node as the page lays it out: a table of a few records with many fields (e.g. the
/// runs × metrics) is transposed, one row per field and one column per record, headed by the
/// records' first field when that is a text (the run's name).
fn table_ctx(label: &str, columns: &[Column], rows: &[Vec<Cell>]) -> TableCtx {
    let transpose = rows.len() <= 4 && columns.len() > 6;
    if !transpose {
        return TableCtx { label: label.into(), columns: columns.iter().map(header).collect(), rows: rows.to_vec() };
    }
    let named = rows.iter().all(|r| r.first().is_some_and(|c| c.accuracy.is_empty()));
    let skip = usize::from(named);
    let mut head = vec![String::new()];
    head.extend(rows.iter().enumerate().map(|(i, r)| if named { r[0].value.clone() } else { format!("{}", i + 1) }));
    let body = columns
        .iter()
        .enumerate()
        .skip(skip)
        .map(|(j, c)| {
            let mut cells = vec![Cell { value: header(c), accuracy: String::new() }];
            cells.extend(rows.iter().map(|r| r[j].clone()));
            cells
        })
        .collect();
    TableCtx { label: label.into(), columns: head, rows: body }
}

/// What a row links to besides its own plots: the ids of every figure of the page (links to a
/// figure that was not drawn are left out) and the files of `proofs/`.
pub struct RowLinks<'a> {
    /// Every figure id of the page.
    pub figure_ids: &'a [String],
    /// Every paper figure of the page, by id.
    pub figures: &'a [FigCtx],
    /// The files of `proofs/` (empty when certify could not write the set).
    pub proofs: &'a [String],
}

/// The ledger row's context; `figures` are the row's plots already turned into figures.
pub fn row_ctx(r: &ClaimRow, figures: &[Figure], links: &RowLinks) -> Result<RowCtx, ReportError> {
    let id = r.id.to_string();
    let nodes = r.evidence.nodes().map_err(|e| ReportError::Evidence { claim: id.clone(), cause: e })?;
    let (mut evidence, mut tables) = (Vec::new(), Vec::new());
    for n in &nodes {
        match n {
            Node::Quantity(q) => evidence.push(NumberCtx::from(q)),
            Node::Flag(f) => evidence.push(NumberCtx {
                label: f.label.clone(),
                value: if f.value { "yes" } else { "no" }.into(),
                accuracy: String::new(),
            }),
            Node::Text(t) => {
                evidence.push(NumberCtx { label: t.label.clone(), value: t.value.clone(), accuracy: String::new() })
            }
            Node::Table { label, columns, rows } => tables.push(table_ctx(label, columns, rows)),
        }
    }
    let own_link = |f: &FigCtx| Link {
        href: format!("#{}", f.id),
        text: crate::links::figure_link_text(&f.label, &f.title),
        id: None,
    };
    let back = Link { href: format!("#{}", claim_anchor(&id)), text: format!("{} ({})", id, r.verdict), id: None };
    let own: Vec<FigCtx> = figures.iter().map(|f| FigCtx { claims: vec![back.clone()], ..FigCtx::from(f) }).collect();
    let mut figure_links: Vec<Link> = own.iter().map(own_link).collect();
    figure_links.extend(
        crate::links::paper_figures(r.id)
            .iter()
            .filter(|f| links.figure_ids.iter().any(|id| id == *f))
            .filter_map(|f| links.figures.iter().find(|g| g.id == *f).map(FigCtx::link)),
    );
    let certificates = crate::links::row_certificates(r.id, links.proofs);
    let certificates_missing =
        r.certificates.iter().filter(|c| !links.proofs.contains(c)).cloned().collect::<Vec<String>>();
    let mut figs = own.into_iter();
    let lead_figure = figs.next();
    Ok(RowCtx {
        anchor: claim_anchor(&id),
        id,
        equation: r.equation.clone(),
        claim: r.claim.clone(),
        verdict: r.verdict.name().into(),
        verdict_text: verdict_words(r.verdict, 1),
        basis: r.basis.name().into(),
        basis_text: r.basis.to_string(),
        theorem: r.id.spec().theorem.to_string(),
        deciding: pieces(&r.deciding),
        finding: r.finding.iter().map(|s| pieces(s)).collect(),
        decisive: r.decisive.iter().map(NumberCtx::from).collect(),
        details: r.details.iter().map(|s| pieces(s)).collect(),
        correction: r.correction.as_deref().map(pieces),
        evidence,
        tables,
        lead_figure,
        assumptions: r.assumptions.iter().map(|a| pieces(a)).collect(),
        certificates,
        certificates_missing,
        figures: figs.collect(),
        figure_links,
    })
}

/// Values the paper leaves out (or gets wrong) and what this report used, from the config.
pub fn assumptions(cfg: &Config) -> Vec<Assumption> {
    let o = &cfg.observer;
    let d = &cfg.discretisation;
    let v = wingcheck_model::format::exact;
    let a = |what: &str, used: String, key: &str| Assumption { what: what.into(), used, key: key.into() };
    vec![
        a(
            "weights a, b of the control law (15)",
            format!("a = {}, b = {} s", v(cfg.control.a), v(cfg.control.b)),
            "control.a, control.b",
        ),
        a(
            "observer sampling (digital observer, zero-order hold)",
            format!("T_s = {} s, {} rule", v(o.sample_period), o.rule.name()),
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
                v(cfg.initial.q_tip),
                v(cfg.initial.theta_tip)
            ),
            "initial.shape, initial.q_tip, initial.theta_tip",
        ),
        a(
            "initial observer states ν(0), p(0)",
            format!("ν1(0) = {}, ν2(0) = {}", v(o.nu1_0), v(o.nu2_0)),
            "observer.nu1_0, observer.nu2_0",
        ),
        a(
            "spatial grid and time step (the paper: \"finite differences\", no grid given)",
            format!(
                "{} with {} {}, grading {}, dt = {} s, time scheme {}",
                d.method.name().to_uppercase(),
                d.grid_size(),
                if d.method == wingcheck_model::Method::Fe { "elements" } else { "intervals" },
                v(d.grading),
                v(d.dt),
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
                "t_end = {} s, output every {} s, {} field points",
                v(cfg.horizon.t_end),
                v(cfg.horizon.sample_every),
                cfg.horizon.field_points
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
                text: pieces(a),
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_verdict_in_words_agrees_with_its_count() {
        // Reference: the verdicts' display text (Verdict's Display) with English agreement.
        assert_eq!(verdict_words(Verdict::HoldsAfterCorrection, 1), "holds after correction");
        assert_eq!(verdict_words(Verdict::HoldsAfterCorrection, 2), "hold after correction");
        assert_eq!(verdict_words(Verdict::Fails, 3), "fail");
        assert_eq!(verdict_words(Verdict::Vacuous, 2), "hold but vacuous");
        assert_eq!(verdict_words(Verdict::PartlyReproduced, 2), "partly reproduced");
        for v in Verdict::ALL {
            assert!(!verdict_words(v, 2).contains('-'), "{v}");
        }
    }
}
