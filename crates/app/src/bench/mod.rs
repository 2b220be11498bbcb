//! `bench`: the tool's measurements of itself, as one typed document (`bench --json`,
//! docs/schema/bench.schema.json) that the command line prints as text. Every timing carries
//! wall and CPU time ([`wingcheck_io::clock`]); every ratio is formed from CPU time where the
//! platform gives it (it does not move with other processes' load), and the machine's cores
//! and load at the start and the end are recorded beside them.

mod check;
mod estimate;
mod report;
mod sim;

use serde::Serialize;
use wingcheck_io::clock::MachineLoad;
use wingcheck_model::Config;

pub use check::{CheckBench, EnclosureTiming, RowTiming};
pub use estimate::bench_estimate;
pub use report::{ReportBench, StageTiming};
pub use sim::{OtherTiming, SimBench};

use crate::{AppError, WorkPolicy};

/// What `bench` measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum BenchKind {
    /// The simulator: the configured run, the other stepper and basis, the explicit FTDO,
    /// the error estimate, `modes`, grid and horizon scaling.
    Sim,
    /// The claim checker, per row, with certify and the exact re-verification.
    Check,
    /// The report, per stage.
    Report,
    /// The search on the paper's 32 × 32 (a, b) grid with 1 and 2 threads.
    Search,
}

impl BenchKind {
    /// The name `--what` takes.
    pub fn name(self) -> &'static str {
        match self {
            BenchKind::Sim => "sim",
            BenchKind::Check => "check",
            BenchKind::Report => "report",
            BenchKind::Search => "search",
        }
    }
}

/// The arguments of `bench`.
#[derive(Debug, Clone, Copy)]
pub struct BenchRequest {
    /// What to measure.
    pub what: BenchKind,
    /// Repetitions per timed configuration (1..=1000; medians are reported).
    pub repeats: usize,
}

/// The `bench --json` document (docs/schema/bench.schema.json): exactly one of `sim`,
/// `check`, `report`, `search` is present, the one `what` names.
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct BenchDocument {
    /// Layout version ([`wingcheck_io::SCHEMA_VERSION`]).
    pub schema_version: u32,
    /// Tool build and the configuration's SHA-256.
    pub provenance: wingcheck_io::Provenance,
    /// What was measured.
    pub what: BenchKind,
    /// Repetitions per timed configuration.
    pub repeats: usize,
    /// Cores and the machine's load at the start and the end.
    pub machine: MachineLoad,
    /// The simulator's timings.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sim: Option<SimBench>,
    /// The claim checker's timings.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub check: Option<CheckBench>,
    /// The report's timings.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub report: Option<ReportBench>,
    /// The search's timings.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub search: Option<wingcheck_search::bench::SearchBench>,
}

impl BenchRequest {
    /// Measure, refused before any work above `policy`'s limits ([`bench_estimate`]).
    pub fn run(&self, cfg: &Config, policy: WorkPolicy) -> Result<BenchDocument, AppError> {
        if !(1..=1000).contains(&self.repeats) {
            return Err(AppError::Argument {
                name: "repeats",
                message: format!("{} {}: use an integer in [1, 1000]", policy.front.arg("repeats"), self.repeats),
            });
        }
        policy.guard(&bench_estimate(cfg, self.what, self.repeats))?;
        let mut machine = MachineLoad::at_start();
        let mut doc = BenchDocument {
            schema_version: wingcheck_io::SCHEMA_VERSION,
            provenance: wingcheck_io::Provenance::new(&cfg.sha256(), Vec::new()),
            what: self.what,
            repeats: self.repeats,
            machine: machine.clone(),
            sim: None,
            check: None,
            report: None,
            search: None,
        };
        match self.what {
            BenchKind::Sim => doc.sim = Some(sim::bench_sim(cfg, self.repeats)?),
            BenchKind::Check => doc.check = Some(check::bench_check(cfg, self.repeats)?),
            BenchKind::Report => doc.report = Some(report::bench_report(cfg, self.repeats)?),
            BenchKind::Search => {
                use wingcheck_search::bench::{bench_search, GRID_POINTS, THREAD_COUNTS};
                doc.search = Some(bench_search(cfg, GRID_POINTS, &THREAD_COUNTS)?)
            }
        }
        machine.finish();
        doc.machine = machine;
        Ok(doc)
    }
}
