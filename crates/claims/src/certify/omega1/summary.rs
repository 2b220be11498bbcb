//! The enclosure as the W-bounds row records it ([`EnclosureSummary`]): the bounds as exact
//! decimals and nearest f64s, the plan's sizes, and where the configured a/b lies.

use serde::{Deserialize, Serialize};
use wingcheck_model::Config;

use super::{compute_with, config_ratio, deciding, exact_decimal, Computed, Plan, Position, PLAN};
use crate::certify::CertifyError;

/// The enclosure as the W-bounds row records it (typed evidence).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(tag = "status", rename_all = "kebab-case", deny_unknown_fields)]
pub enum EnclosureSummary {
    /// Certified: ω̲₁ ≤ ω₁ ≤ ω̄₁, re-checked in exact arithmetic.
    Certified {
        /// ω̲₁ (rad/s), nearest f64 (display; the bound is `lower_exact`).
        lower: f64,
        /// ω̄₁ (rad/s), nearest f64 (display; the bound is `upper_exact`).
        upper: f64,
        /// ω̲₁ as an exact decimal.
        lower_exact: String,
        /// ω̄₁ as an exact decimal.
        upper_exact: String,
        /// (ω̄₁ − ω̲₁)/ω̲₁.
        relative_width: f64,
        /// k.
        modes: usize,
        /// N_I.
        inertia_elements: usize,
        /// N_R.
        rayleigh_elements: usize,
        /// The configured a/b against the enclosure (absent for b = 0).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        position: Option<Position>,
    },
    /// No certificate for this wing (the reason); W ≻ 0 then rests on the float ω₁.
    NotCertified {
        /// Why.
        reason: String,
    },
}

impl EnclosureSummary {
    /// The enclosure of `cfg`'s wing ([`super::compute`], the tightest plan) and where the configured
    /// a/b lies.
    pub fn of(cfg: &Config) -> Self {
        Self::with_plan(cfg, &PLAN)
    }

    /// The coarsest enclosure of [`super::LADDER`] that decides where the configured a/b lies (below
    /// or above ω₁), or [`PLAN`]'s when none does (a/b inside even the tightest, or b = 0).
    pub fn deciding(cfg: &Config) -> Self {
        Self::summarise(cfg, deciding(cfg))
    }

    /// The enclosure with `plan` and where the configured a/b lies.
    pub fn with_plan(cfg: &Config, plan: &Plan) -> Self {
        Self::summarise(cfg, compute_with(cfg, plan))
    }

    fn summarise(cfg: &Config, computed: Result<Computed, CertifyError>) -> Self {
        let r = computed.and_then(|c| Ok((c, config_ratio(cfg)?)));
        match r {
            Ok((c, ratio)) => {
                let e = &c.1;
                EnclosureSummary::Certified {
                    lower: e.lower_f64(),
                    upper: e.upper_f64(),
                    lower_exact: exact_decimal(&e.lower),
                    upper_exact: exact_decimal(&e.upper),
                    relative_width: e.relative_width(),
                    modes: e.modes,
                    inertia_elements: e.inertia_elements,
                    rayleigh_elements: e.rayleigh_elements,
                    position: ratio.map(|r| e.position(&r)),
                }
            }
            Err(e) => EnclosureSummary::NotCertified { reason: e.to_string() },
        }
    }

    /// The configured a/b's position, when certified.
    pub fn position(&self) -> Option<Position> {
        match self {
            EnclosureSummary::Certified { position, .. } => *position,
            EnclosureSummary::NotCertified { .. } => None,
        }
    }

    /// (ω̲₁, ω̄₁) as f64, when certified.
    pub fn bounds(&self) -> Option<(f64, f64)> {
        match self {
            EnclosureSummary::Certified { lower, upper, .. } => Some((*lower, *upper)),
            EnclosureSummary::NotCertified { .. } => None,
        }
    }
}
