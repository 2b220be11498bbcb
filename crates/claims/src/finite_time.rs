//! Theorems 3–4, bounds (38)–(39): finite-time convergence of σ (and g̃).

use wingcheck_model::Config;

use crate::{ClaimRow, ClaimsError};

/// Which observer channel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Channel {
    /// σ1, g̃1, bound (38), Theorem 3.
    Bending,
    /// σ2, g̃2, bound (39), Theorem 4.
    Torsion,
}

/// Check the finite-time claim of one channel.
pub fn check(_cfg: &Config, channel: Channel) -> Result<ClaimRow, ClaimsError> {
    Ok(match channel {
        Channel::Bending => ClaimRow::inconclusive(
            "finite-time-1",
            "(38), Theorem 3",
            "g̃1 reaches 0 no later than t_f1, if κ2 ≥ ζ1",
            "not yet computed",
        ),
        Channel::Torsion => ClaimRow::inconclusive(
            "finite-time-2",
            "(39), Theorem 4",
            "g̃2 reaches 0 no later than t_f2, if κ5 ≥ ζ2",
            "not yet computed",
        ),
    })
}
