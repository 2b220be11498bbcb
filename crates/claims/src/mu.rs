//! (29)–(32): conditions μ1…μ6 > 0 on the gains and the η's, λ3, λ = λ3/λ1 and ε.

use wingcheck_model::Config;

use crate::wbounds::WBounds;
use crate::{ClaimRow, ClaimsError};

/// Result of the μ-conditions check, reused by the UUB row.
#[derive(Debug, Clone)]
pub struct MuResult {
    /// The ledger row.
    pub row: ClaimRow,
    /// Best decay rate λ = λ3/λ1 (None if infeasible or not computed).
    pub lambda: Option<f64>,
    /// ε of (32) at the best point.
    pub epsilon: Option<f64>,
}

/// Check the μ-conditions.
pub fn check(_cfg: &Config, _w: &WBounds) -> Result<MuResult, ClaimsError> {
    Ok(MuResult {
        row: ClaimRow::inconclusive("mu-conditions", "(29)–(32)", "conditions on the gains and the η's make Ẇ ≤ −λW + ε with the printed λ, ε", "not yet computed"),
        lambda: None,
        epsilon: None,
    })
}
