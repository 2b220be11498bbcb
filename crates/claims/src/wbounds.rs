//! Theorem 1, (22)–(28): bounds λ2 κ ≤ W ≤ λ1 κ of the Lyapunov function.

use wingcheck_model::Config;

use crate::{ClaimRow, ClaimsError};

/// Result of the W-bounds check, reused by the μ-conditions and UUB rows.
#[derive(Debug, Clone)]
pub struct WBounds {
    /// The ledger row.
    pub row: ClaimRow,
    /// Tightest λ1* = sup W/κ (None if not computed).
    pub lambda1_tight: Option<f64>,
    /// Tightest λ2* = inf W/κ.
    pub lambda2_tight: Option<f64>,
}

/// Check Theorem 1.
pub fn check(_cfg: &Config) -> Result<WBounds, ClaimsError> {
    Ok(WBounds {
        row: ClaimRow::inconclusive("W-bounds", "(22)–(28), Theorem 1", "0 ≤ λ2 κ ≤ W ≤ λ1 κ with the printed λ1, λ2, y1–y3", "not yet computed"),
        lambda1_tight: None,
        lambda2_tight: None,
    })
}
