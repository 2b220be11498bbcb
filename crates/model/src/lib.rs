//! Wing model configuration for wingcheck.
//!
//! One JSON document holds every parameter of the coupled bending–torsion wing
//! (paper Section 2, eq. (9)–(10) as corrected in `docs/model.md`), the boundary
//! control law (15), the observer (16)–(21) or DOBC (57), the disturbances (56), the
//! initial condition, the discretisation and the horizon. [`Config::paper`] is the
//! embedded default (`configs/paper.json`); [`Config::from_json_str`] parses a user file
//! (unknown keys are rejected) and [`apply_override`] implements `--set path.to.key=value`.
//! [`Config::validate`] checks every field and returns a [`ConfigError`] naming the field
//! and the allowed range.

#![forbid(unsafe_code)]

pub mod bounds;
pub mod cancel;
mod config;
mod disturbance;
mod error;
pub use wingcheck_io::prose as format;
pub mod json;
pub mod oscillator;
mod overrides;
pub mod quantity;
mod scheme;
mod validate;
pub mod work;

pub use bounds::{config_schema, FieldBound, FIELD_BOUNDS, MAX_MAGNITUDE, MIN_POSITIVE};
pub use cancel::{Cancel, Cancelled};
pub use config::*;
pub use disturbance::{Distributed, Disturbance, MeanSteps, StepMeans, TipDisturbance, TipValues};
pub use error::{ConfigError, UnknownName};
pub use overrides::{apply_override, apply_overrides};
pub use quantity::{Accuracy, ErrorSource, Estimate, Quantity, Shown, Unit, ValueBasis};
pub use scheme::{
    StepBasis, TimeScheme, MODAL_AUTO_UNKNOWNS, MODAL_MAX_UNKNOWNS, MODAL_SETUP_SECONDS_PER_CUBE,
    NODAL_EXTRA_SECONDS_PER_UNKNOWN_STEP,
};

/// The paper's configuration (`configs/paper.json`), embedded at compile time.
pub const PAPER_JSON: &str = include_str!("../../../configs/paper.json");
