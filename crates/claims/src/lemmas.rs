//! Lemmas 1–3: the inequalities used in the proofs.

use wingcheck_model::Config;

use crate::{ClaimRow, ClaimsError};

/// Check Lemmas 1–3.
pub fn check(_cfg: &Config) -> Result<ClaimRow, ClaimsError> {
    Ok(ClaimRow::inconclusive("lemmas", "Lemmas 1–3, (11)–(14)", "the inequalities used in the proofs", "not yet computed"))
}
