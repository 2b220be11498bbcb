//! "The paper says — we measured": every statement or number the paper prints that the ledger
//! tests, beside the measured value (with its error or basis) and a verdict on that statement,
//! each read from the typed evidence of its ledger row (so the table and `ledger.json` agree).

use serde::Serialize;
use wingcheck_claims::comparison::ComparisonEvidence;
use wingcheck_claims::finite_time::FiniteTimeEvidence;
use wingcheck_claims::lemmas::LemmasEvidence;
use wingcheck_claims::mu::MuEvidence;
use wingcheck_claims::uub::UubEvidence;
use wingcheck_claims::wbounds::WBoundsEvidence;
use wingcheck_claims::{Basis, ClaimId, ClaimRow, Evidence, Ledger, Verdict};
use wingcheck_model::Quantity;

use crate::figure::claim_anchor;

/// One statement of the paper against what was measured.
#[derive(Debug, Clone, Serialize)]
pub struct Statement {
    /// What the paper says, with where it says it.
    pub paper: String,
    /// What was measured: the number(s) with their error or basis.
    pub measured: String,
    /// The verdict on this statement (kebab-case name, as the ledger's).
    pub verdict: &'static str,
    /// The verdict in words.
    pub verdict_text: String,
    /// What the verdict on the statement rests on, in words.
    pub basis: String,
    /// The ledger row that tests it.
    pub claim: String,
    /// Its anchor.
    pub anchor: String,
}

/// Holds when `ok`, else fails, on `basis`.
fn holds_if(ok: bool, basis: Basis) -> (Verdict, Basis) {
    (if ok { Verdict::Holds } else { Verdict::Fails }, basis)
}

/// The row's own verdict and basis.
fn row_verdict(row: &ClaimRow) -> (Verdict, Basis) {
    (row.verdict, row.basis)
}

fn statement(row: &ClaimRow, paper: &str, measured: String, (verdict, basis): (Verdict, Basis)) -> Statement {
    Statement {
        paper: paper.into(),
        measured,
        verdict: verdict.name(),
        verdict_text: verdict.to_string(),
        basis: basis.to_string(),
        claim: row.id.to_string(),
        anchor: claim_anchor(row.id.name()),
    }
}

/// The statements of a row that computed nothing: the row's reason, inconclusive.
fn undecided(row: &ClaimRow, paper: &str) -> Statement {
    statement(row, paper, row.finding_text(), (Verdict::Inconclusive, row.basis))
}

fn w_bounds(row: &ClaimRow, e: &WBoundsEvidence) -> Vec<Statement> {
    let l2 = &e.lambda2_printed;
    let grid = format!(
        "holds at {} of {} (a, b) grid points; min{{ρ, I_p, EI, GJ}} = {} against 2ρx_c = {} (SI values as numbers)",
        e.grid_points_condition_holds.value_text(),
        e.grid_points_checked.value_text(),
        e.min_rho_ip_ei_gj.value_text(),
        e.two_rho_xc.value_text()
    );
    vec![
        statement(
            row,
            "λ2 = y2 − y3 (28) is a positive number, so 0 ≤ λ2 κ ≤ W (24)",
            format!("printed λ2 {} ({}) at the configured a, b", l2.equals_text(), l2.accuracy_text()),
            holds_if(l2.value > 0.0, Basis::Analytic),
        ),
        statement(
            row,
            "b can be chosen with b > 2y3/min{ρ, I_p, EI, GJ} (proof of Theorem 1)",
            grid,
            holds_if(e.printed_condition.value, Basis::Analytic),
        ),
        statement(
            row,
            "Theorem 1: W has the positive lower bound λ2 κ at the paper's weights",
            format!("tight λ2* = {}; {}", e.lambda2_tight.pm_text(), row.deciding),
            row_verdict(row),
        ),
    ]
}

fn mu(row: &ClaimRow, e: &MuEvidence) -> Vec<Statement> {
    let measured = match &e.lambda3_sup {
        Some(l) => format!("λ3* = {} ({}); {}", l.value_text(), l.accuracy_text(), row.deciding),
        None => row.deciding.clone(),
    };
    vec![statement(row, "(32): λ3 = min{μ3, μ4, μ5, μ6} > 0 with the paper's gains", measured, row_verdict(row))]
}

fn uub(row: &ClaimRow, e: &UubEvidence) -> Vec<Statement> {
    let q = &e.config_max_abs_q_tip_second_half_m;
    vec![
        statement(
            row,
            "Theorem 2: q(z,t), θ(z,t) are uniformly ultimately bounded",
            format!(
                "max |q(s,t)| over [t_end/2, t_end] = {}, max |θ(s,t)| there = {} ({}, configured gains)",
                q.value_text(),
                e.config_max_abs_theta_tip_second_half_rad.value_text(),
                q.accuracy_text()
            ),
            (Verdict::Holds, Basis::Simulation),
        ),
        statement(row, "(37): |q(z,t)| ≤ √(s³/λ2 (W(0)e^(−λt) + ε/λ))", row.deciding.clone(), row_verdict(row)),
    ]
}

fn finite_time(row: &ClaimRow, e: &FiniteTimeEvidence) -> Vec<Statement> {
    let (n, theorem, eq) = if row.id == ClaimId::FiniteTime1 { (1, 3, 38) } else { (2, 4, 39) };
    let measured = match e.measured_s.quantity() {
        Some(m) => format!(
            "t_reach = {} (Filippov, {}); t_f{n} = {}",
            m.pm_text(),
            m.covers_text().unwrap_or_else(|| m.accuracy_text()),
            e.bound_s.value_text()
        ),
        None => format!("{}; t_f{n} = {}", e.measured_s.text(), e.bound_s.value_text()),
    };
    vec![statement(
        row,
        &format!("Theorem {theorem}: g̃{n} reaches zero before the bound t_f{n} of ({eq}) when κ{} ≥ ζ{n}", 3 * n - 1),
        measured,
        row_verdict(row),
    )]
}

fn lemmas(row: &ClaimRow, e: &LemmasEvidence) -> Vec<Statement> {
    let cx = &e.lemma2_counterexample;
    vec![
        statement(
            row,
            "Lemma 1 (11): xy ≤ x²/c + c y²",
            format!(
                "max xy/(x²/c + c y²) = {} ({})",
                e.lemma1_max_ratio.value_text(),
                e.lemma1_max_ratio.accuracy_text()
            ),
            holds_if(e.lemma1_holds.value, Basis::Computation),
        ),
        statement(
            row,
            "Lemma 2 (12): ω(f)² ≤ f∫ω² for ω(0) = 0",
            if cx.printed_violated.value {
                format!("ω = {} on [0, {}]: ω(f)² > f∫ω² (decided exactly)", cx.omega.value, cx.f.value_text())
            } else {
                "not refuted by the search".into()
            },
            holds_if(!cx.printed_violated.value && e.lemma2_printed_holds.value, Basis::Analytic),
        ),
        statement(
            row,
            "Lemma 3 (14): the reaching time of the comparison ODE",
            format!(
                "an independent RK4 agrees to {} ({}) over {} cases",
                e.lemma3_max_rel_err.value_text(),
                e.lemma3_max_rel_err.accuracy_text(),
                e.lemma3_cases.value_text()
            ),
            holds_if(e.lemma3_max_rel_err.value < 1e-6 && e.lemma3_violations.value == 0.0, Basis::Computation),
        ),
    ]
}

/// t_band of a run record's channel as text.
fn band(m: &wingcheck_claims::display::Maybe) -> String {
    m.quantity().map_or_else(|| m.text(), Quantity::value_text)
}

fn comparison(row: &ClaimRow, e: &ComparisonEvidence) -> Vec<Statement> {
    let ftdo = &e.runs.rows[0];
    let dobc = &e.runs.rows[1];
    let converged = ftdo.gtilde1_settle.quantity().is_some() && ftdo.gtilde2_settle.quantity().is_some();
    let g_ratio = e.gtilde_ratio_late.as_ref().map_or_else(|| "FTDO's g̃ vanishes".into(), Quantity::value_text);
    vec![
        statement(
            row,
            "Figs 11–12: the disturbance estimation errors converge to zero in a finite time",
            format!(
                "{}: t_band of |g̃1| {}, of |g̃2| {}; RMS g̃1 over [t_end/2, t_end] {}",
                ftdo.run.value,
                band(&ftdo.gtilde1_settle),
                band(&ftdo.gtilde2_settle),
                ftdo.rms_gtilde1_late.value_text()
            ),
            holds_if(converged, Basis::Simulation),
        ),
        statement(
            row,
            "Figs 13–20 against 5–12: with DOBC the displacements do not converge quickly; its effect is worse",
            format!(
                "tip RMS (DOBC − FTDO)/FTDO over [t_end/2, t_end]: q {}, θ {}; largest |difference| {}",
                e.rel.rel_diff_rms_q_late.value_text(),
                e.rel.rel_diff_rms_theta_late.value_text(),
                e.max_abs_rel_diff_tip.value_text()
            ),
            holds_if(e.tip_response_clearly_better.value, Basis::Simulation),
        ),
        statement(
            row,
            "Figs 19–20: DOBC's observers still leave a certain disturbance error",
            format!(
                "RMS g̃ over [t_end/2, t_end], DOBC / FTDO = {g_ratio}; DOBC's t_band of |g̃1| {}, of |g̃2| {}",
                band(&dobc.gtilde1_settle),
                band(&dobc.gtilde2_settle)
            ),
            holds_if(e.gtilde_clearly_smaller.value, Basis::Simulation),
        ),
        statement(
            row,
            "Section 4 and the conclusion: the proposed control performs better than DOBC",
            row.deciding.clone(),
            row_verdict(row),
        ),
    ]
}

/// The table, in the ledger's row order.
pub fn statements(ledger: &Ledger) -> Vec<Statement> {
    let mut out = Vec::new();
    for row in &ledger.rows {
        out.extend(match &row.evidence {
            Evidence::WBounds(e) => w_bounds(row, e),
            Evidence::Mu(e) => mu(row, e),
            Evidence::Uub(e) => uub(row, e),
            Evidence::FiniteTime(e) => finite_time(row, e),
            Evidence::Lemmas(e) => lemmas(row, e),
            Evidence::Comparison(e) => comparison(row, e),
            Evidence::None => vec![undecided(row, &row.claim)],
        });
    }
    out
}
