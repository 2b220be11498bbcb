//! The claim checker: for each claim of the paper (table at the end of
//! `docs/model.md`) a verdict with evidence, the basis it rests on, and the
//! assumptions made where the paper is silent.
//!
//! Rows: `W-bounds` and `mu-conditions` ([`wbounds`], [`mu`]) rest on convex optimisation and
//! exact certificates; `UUB` ([`uub`]) combines them with simulation; `finite-time-1/2`
//! ([`finite_time`]), `lemmas` ([`lemmas`]) and `ftdo-vs-dobc` ([`comparison`]) on simulation
//! and adversarial search.

pub mod certify;
pub mod comparison;
pub mod convex;
pub mod finite_time;
mod ledger;
pub mod lemmas;
pub mod lyapunov;
pub mod mu;
pub mod sdp;
pub mod socp;
pub mod study;
pub mod theory;
pub mod uub;
pub mod wbounds;

pub use ledger::{
    evidence_map, Basis, ClaimId, ClaimRow, Ledger, Line, PlotData, Reached, SettleTime, Verdict, NEVER_SETTLED,
    NOT_REACHED,
};
pub use study::Study;

use sha2::{Digest, Sha256};
use wingcheck_model::Config;

/// Errors of the claim checker (a failed claim is a verdict, not an error).
#[derive(Debug, thiserror::Error)]
pub enum ClaimsError {
    /// A simulation needed as evidence failed.
    #[error(transparent)]
    Sim(#[from] wingcheck_sim::SimError),
    /// A numerical step failed.
    #[error("numerical failure in {what}: {detail}")]
    Numerical {
        /// Which computation.
        what: String,
        /// What happened.
        detail: String,
    },
}

/// SHA-256 (hex) of the configuration's JSON (struct field order, so stable).
pub fn config_sha256(cfg: &Config) -> String {
    let mut h = Sha256::new();
    h.update(serde_json::to_string(cfg).expect("config serialises").as_bytes());
    h.finalize().iter().map(|b| format!("{b:02x}")).collect()
}

/// Run every check on `cfg` and assemble the ledger, in the paper's order, with a fresh
/// [`Study`] (each distinct simulation runs once).
pub fn check_all(cfg: &Config) -> Result<Ledger, ClaimsError> {
    check_all_with(cfg, &Study::new())
}

fn isolate(id: ClaimId, claim: &str, r: Result<ClaimRow, ClaimsError>) -> ClaimRow {
    r.unwrap_or_else(|e| ClaimRow::inconclusive(id, claim, &format!("not decided: {e}")))
}

/// [`check_all`] with a caller's study (e.g. shared with the report's own runs). A row whose
/// computation fails becomes `inconclusive` with the reason; the other rows are still
/// computed, so this only returns `Ok`.
pub fn check_all_with(cfg: &Config, study: &Study) -> Result<Ledger, ClaimsError> {
    const UUB_CLAIM: &str = "q, θ uniformly ultimately bounded, with the printed bound";
    // Two independent groups of rows on two threads (each row is deterministic, so the
    // ledger does not depend on the schedule; the study's cache is thread-safe).
    let (theory_rows, sim_rows) = std::thread::scope(|scope| {
        let sims = scope.spawn(|| {
            [
                isolate(
                    ClaimId::FiniteTime1,
                    "finite-time convergence of g̃1 within (38)",
                    finite_time::check(cfg, finite_time::Channel::Bending),
                ),
                isolate(
                    ClaimId::FiniteTime2,
                    "finite-time convergence of g̃2 within (39)",
                    finite_time::check(cfg, finite_time::Channel::Torsion),
                ),
                isolate(
                    ClaimId::FtdoVsDobc,
                    "FTDO gives clearly better vibration suppression than DOBC",
                    comparison::check(cfg, study),
                ),
            ]
        });
        let w = wbounds::check(cfg);
        let m = mu::check(cfg, study);
        let uub_row = match (&w, &m) {
            (Ok(w), Ok(m)) => isolate(ClaimId::Uub, UUB_CLAIM, uub::check(cfg, w, m, study)),
            _ => ClaimRow::inconclusive(
                ClaimId::Uub,
                UUB_CLAIM,
                "not decided: it needs the W-bounds and mu-conditions rows, which could not be computed",
            ),
        };
        let theory = [
            isolate(ClaimId::WBounds, "0 ≤ λ2 κ ≤ W ≤ λ1 κ with the printed λ1, λ2, y1–y3", w.map(|w| w.row)),
            isolate(ClaimId::MuConditions, "conditions on the gains and the η's make Ẇ ≤ −λW + ε", m.map(|m| m.row)),
            uub_row,
            isolate(ClaimId::Lemmas, "Lemmas 1–3", lemmas::check(cfg)),
        ];
        let sims = sims.join().unwrap_or_else(|_| {
            [ClaimId::FiniteTime1, ClaimId::FiniteTime2, ClaimId::FtdoVsDobc]
                .map(|id| ClaimRow::inconclusive(id, id.name(), "not decided: the computation panicked"))
        });
        (theory, sims)
    });
    let [w_row, m_row, uub_row, lemmas_row] = theory_rows;
    let [ft1, ft2, cmp] = sim_rows;
    let rows = vec![w_row, m_row, uub_row, ft1, ft2, lemmas_row, cmp];
    let mut ledger =
        Ledger { tool: format!("wingcheck {}", env!("CARGO_PKG_VERSION")), config_sha256: config_sha256(cfg), rows };
    // A non-finite value is a bug of the row that produced it: never print it, say so instead.
    for i in 0..ledger.rows.len() {
        let one = Ledger { tool: String::new(), config_sha256: String::new(), rows: vec![ledger.rows[i].clone()] };
        let bad = one.non_finite();
        if !bad.is_empty() {
            let r = &ledger.rows[i];
            ledger.rows[i] = ClaimRow::inconclusive(
                r.id,
                &r.claim,
                &format!("internal error: the computation produced non-finite values at {}", bad.join(", ")),
            );
        }
    }
    Ok(ledger)
}
