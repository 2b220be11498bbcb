//! Theorem 2, (33)–(37): uniform ultimate boundedness and the printed bound.

use wingcheck_model::Config;

use crate::mu::MuResult;
use crate::wbounds::WBounds;
use crate::{ClaimRow, ClaimsError};

/// Check Theorem 2.
pub fn check(_cfg: &Config, _w: &WBounds, _m: &MuResult) -> Result<ClaimRow, ClaimsError> {
    Ok(ClaimRow::inconclusive("UUB", "(33)–(37), Theorem 2", "q, θ uniformly ultimately bounded, with the printed bound", "not yet computed"))
}
