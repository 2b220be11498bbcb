//! Section 4, Figs 3–20: the proposed FTDO controller against DOBC.

use wingcheck_model::Config;

use crate::{ClaimRow, ClaimsError};

/// Compare FTDO and DOBC.
pub fn check(_cfg: &Config) -> Result<ClaimRow, ClaimsError> {
    Ok(ClaimRow::inconclusive(
        "ftdo-vs-dobc",
        "Section 4, Figs 3–20",
        "the proposed controller suppresses vibration better than DOBC",
        "not yet computed",
    ))
}
