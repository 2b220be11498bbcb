//! The claim checker: for each claim of the paper (table at the end of
//! `shared/spec/model.md`) a verdict with evidence, the basis it rests on, and the
//! assumptions made where the paper is silent.
//!
//! Rows: `W-bounds` and `mu-conditions` ([`wbounds`], [`mu`]) rest on convex optimisation and
//! exact certificates; `UUB` ([`uub`]) combines them with simulation; `finite-time-1/2`
//! ([`finite_time`]), `lemmas` ([`lemmas`]) and `ftdo-vs-dobc` ([`comparison`]) on simulation
//! and adversarial search.

pub mod certify;
pub mod comparison;
pub mod finite_time;
mod ledger;
pub mod lemmas;
pub mod lyapunov;
pub mod mu;
pub mod socp;
pub mod uub;
pub mod wbounds;

pub use ledger::{Basis, ClaimRow, Ledger, Line, PlotData, Verdict};

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

/// Run every check on `cfg` and assemble the ledger, in the paper's order.
pub fn check_all(cfg: &Config) -> Result<Ledger, ClaimsError> {
    let w = wbounds::check(cfg)?;
    let m = mu::check(cfg, &w)?;
    let rows = vec![
        w.row.clone(),
        m.row.clone(),
        uub::check(cfg, &w, &m)?,
        finite_time::check(cfg, finite_time::Channel::Bending)?,
        finite_time::check(cfg, finite_time::Channel::Torsion)?,
        lemmas::check(cfg)?,
        comparison::check(cfg)?,
    ];
    Ok(Ledger { tool: format!("wingcheck {}", env!("CARGO_PKG_VERSION")), config_sha256: config_sha256(cfg), rows })
}
