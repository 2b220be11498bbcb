//! The work guard: every command's work is estimated before it starts and refused above the
//! documented limits ([`wingcheck_model::work::DEFAULT_LIMITS`]) unless the user overrides them.

use wingcheck_model::work::{WorkEstimate, DEFAULT_LIMITS};

use crate::{AppError, Front};

/// Whether the limits apply, and how the front end names the override in a refusal.
#[derive(Debug, Clone, Copy)]
pub struct WorkPolicy {
    /// Run even above the limits (`--allow-large`, `allow_large=True`).
    pub allow_large: bool,
    /// The front end (spells the override in the refusal).
    pub front: Front,
}

impl WorkPolicy {
    /// Refuse `est` above the default limits unless `allow_large`.
    pub fn guard(&self, est: &WorkEstimate) -> Result<(), AppError> {
        if self.allow_large {
            return Ok(());
        }
        est.within(&DEFAULT_LIMITS).map_err(|mut refused| {
            refused.override_flag = self.front.allow_large().to_string();
            AppError::WorkLimit(Box::new(crate::error::WorkLimit { estimate: est.clone(), refused }))
        })
    }
}
