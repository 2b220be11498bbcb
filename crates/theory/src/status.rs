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
    /// Whether the status makes the point a candidate under [`worth_reverifying`] (`Solved` or
    /// `AlmostSolved`; the caller checks the point's coordinates and re-verifies it).
    pub fn is_candidate(&self) -> bool {
        matches!(self, SolveStatus::Clarabel(s) if worth_reverifying(*s, &[]))
    }

    /// The status as printed: clarabel's name (`Solved`, `AlmostSolved`, …) or `not run`.
    pub fn name(&self) -> String {
        match self {
            SolveStatus::Clarabel(s) => format!("{s:?}"),
            SolveStatus::NotRun(_) => "not run".into(),
        }
    }
}

/// The one acceptance rule for a solver's point: clarabel called it optimal — `Solved`, or
/// `AlmostSolved` (reduced accuracy) — and every coordinate is finite. Such a point is only a
/// candidate: every caller re-verifies it against the original constraints before using it
/// (an interrupted or failed solve's point means nothing and is never looked at).
pub fn worth_reverifying(status: SolverStatus, x: &[f64]) -> bool {
    matches!(status, SolverStatus::Solved | SolverStatus::AlmostSolved) && x.iter().all(|v| v.is_finite())
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The rule as documented: optimal statuses with a finite point only; an interrupted,
    /// stalled or infeasible solve's point is never re-verified.
    #[test]
    fn only_optimal_finite_points_are_worth_reverifying() {
        let ok = [1.0, -2.0];
        assert!(worth_reverifying(SolverStatus::Solved, &ok));
        assert!(worth_reverifying(SolverStatus::AlmostSolved, &ok));
        assert!(!worth_reverifying(SolverStatus::Solved, &[1.0, f64::NAN]));
        for other in [
            SolverStatus::MaxIterations,
            SolverStatus::MaxTime,
            SolverStatus::CallbackTerminated,
            SolverStatus::NumericalError,
            SolverStatus::PrimalInfeasible,
            SolverStatus::InsufficientProgress,
        ] {
            assert!(!worth_reverifying(other, &ok), "{other:?}");
        }
    }
}
