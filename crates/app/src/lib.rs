//! The operations of wingcheck's front ends, front-end neutral: the command line (`src/cli`)
//! and the Python extension (`python/`) both call these functions and only parse arguments
//! and present results.
//!
//! - [`ConfigSource`]: the configuration from the embedded default, a file or JSON text,
//!   then `key=value` overrides — one route, one set of messages.
//! - [`SimulateRequest`]: the simulate options and their mapping onto the configuration
//!   (`method = fd` implies `discretisation.grading = 0`), the default sample times, the run
//!   ([`simulate::run`]) and its `simulate --json` document ([`SimulateSummary`]).
//! - [`WorkPolicy`]: the work guard (`--allow-large` / `allow_large=True`).
//! - [`ModesRequest`]: the `modes` arguments' checks and the `modes --json` document.
//! - [`ops`]: check, report, search, certify, verify with the guard and a [`Cancel`] token.
//! - [`bench`]: the tool's measurements of itself (`bench --json`), wall and CPU time, load.
//! - [`schemas`]: every JSON Schema of docs/schema/.
//! - [`build_info`]: the build's provenance (git commit, dirty flag, rustc), from this crate's
//!   build script.
//!
//! Every error is an [`AppError`]; [`AppError::kind`] classifies it for a front end (the
//! Python exception classes).

#![forbid(unsafe_code)]

pub mod bench;
mod build_info;
pub mod compare;
mod compare_view;
mod config;
mod error;
pub mod modes;
pub mod ops;
mod schema;
pub mod simulate;
mod summary;
mod work;

pub use build_info::{build_info, register_build};
pub use config::ConfigSource;
pub use error::{AppError, ErrorKind, WorkLimit};
pub use modes::{ModesDocument, ModesRequest};
pub use schema::{schema_text, schemas};
pub use simulate::{SimulateRequest, SimulateResult};
pub use summary::{ErrorSummary, RunSettings, SimulateSummary, TipValues};
pub use wingcheck_model::{Cancel, Cancelled};
pub use work::WorkPolicy;

/// Which front end is asking: the library's messages name its arguments the way that front
/// end spells them (`--sample-times` on the command line, `sample_times` in Python).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Front {
    /// The `wingcheck` command line.
    Cli,
    /// The Python package.
    Python,
}

impl Front {
    /// The argument `name` (snake_case, as Python spells it) in this front end's spelling.
    pub fn arg(self, name: &str) -> String {
        match self {
            Front::Cli => format!("--{}", name.replace('_', "-")),
            Front::Python => name.to_string(),
        }
    }

    /// How this front end runs a computation above the work limits.
    pub fn allow_large(self) -> &'static str {
        match self {
            Front::Cli => wingcheck_model::work::ALLOW_LARGE_FLAG,
            Front::Python => "allow_large=True",
        }
    }
}
