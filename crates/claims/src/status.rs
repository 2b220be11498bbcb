//! What a solver call ended with, typed: clarabel's own status, or why it was not run.

use clarabel::solver::SolverStatus;
use serde::{Serialize, Serializer};

/// The outcome of one solver call.
#[derive(Debug, Clone, PartialEq)]
pub enum SolveStatus {
    /// clarabel ran and returned this status.
    Clarabel(SolverStatus),
    /// The problem could not be posed (the reason).
    NotRun(String),
}

impl SolveStatus {
    /// clarabel's `Solved` (full accuracy).
    pub fn is_solved(&self) -> bool {
        matches!(self, SolveStatus::Clarabel(SolverStatus::Solved))
    }

    /// The status as printed: clarabel's name (`Solved`, `AlmostSolved`, …) or `not run`.
    pub fn name(&self) -> String {
        match self {
            SolveStatus::Clarabel(s) => format!("{s:?}"),
            SolveStatus::NotRun(_) => "not run".into(),
        }
    }
}

impl std::fmt::Display for SolveStatus {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SolveStatus::Clarabel(s) => write!(f, "{s:?}"),
            SolveStatus::NotRun(why) => write!(f, "not run ({why})"),
        }
    }
}

impl Serialize for SolveStatus {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.name())
    }
}

impl schemars::JsonSchema for SolveStatus {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "SolveStatus".into()
    }
    fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
        schemars::json_schema!({
            "type": "string",
            "description": "clarabel's status name (Solved, AlmostSolved, MaxTime, …) or `not run`"
        })
    }
}
