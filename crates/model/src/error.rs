use thiserror::Error;

/// A name that is not one of a setting's choices (`ControllerKind`, `ObserverRule`, `Method`,
/// `TimeScheme`, `StepBasis` parsed from text): the setting, the name given and the choices.
#[derive(Debug, Error, Clone, PartialEq, Eq)]
#[error("unknown {what} `{given}`: allowed {allowed}")]
pub struct UnknownName {
    /// The setting (`controller`, `time scheme`).
    pub what: &'static str,
    /// The name given.
    pub given: String,
    /// The allowed names, comma-separated.
    pub allowed: &'static str,
}

/// Everything that can be wrong with a configuration.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ConfigError {
    /// The JSON text could not be parsed into a configuration (syntax error, wrong type,
    /// unknown key, missing key). The message is serde_json's, with line and column.
    #[error("config is not valid: {0}")]
    Parse(String),
    /// The config file could not be read, or is too large or not UTF-8.
    #[error("cannot read config {path}: {reason}")]
    Read {
        /// The file.
        path: String,
        /// What went wrong.
        reason: String,
    },
    /// A numeric field is NaN or infinite, or a number beyond the largest f64 (`1e5000`).
    #[error("{field} = {value} is not a finite number (the largest f64 is about 1.8e308)")]
    NotFinite {
        /// Dotted path of the field, e.g. `wing.ei`.
        field: String,
        /// The offending value as the user typed it (`1e5000`, `NaN`).
        value: String,
    },
    /// A field lies outside its allowed range.
    #[error("{field} = {value} is out of range: allowed {allowed}")]
    OutOfRange {
        /// Dotted path of the field, e.g. `wing.ei`.
        field: String,
        /// The offending value (as text, so integers print as integers).
        value: String,
        /// The allowed range in words, e.g. `> 0`.
        allowed: String,
    },
    /// Several fields together violate a constraint (e.g. the mass matrix is not
    /// positive definite).
    #[error("{fields}: {reason}")]
    Inconsistent {
        /// The fields involved.
        fields: String,
        /// What is wrong and what is allowed.
        reason: String,
    },
    /// A `--set key=value` override is malformed or names an unknown key.
    #[error("override `{expr}`: {reason}")]
    Override {
        /// The override as given.
        expr: String,
        /// What is wrong.
        reason: String,
    },
}
