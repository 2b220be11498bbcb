//! The front ends' error: every library error, the argument checks and the work guard, with
//! [`AppError::kind`] classifying it (the Python package raises one exception class per kind).

use std::path::PathBuf;

use wingcheck_claims::certify::CertifyError;
use wingcheck_claims::ClaimsError;
use wingcheck_model::work::{WorkEstimate, WorkRefused};
use wingcheck_model::ConfigError;
use wingcheck_report::ReportError;
use wingcheck_search::SearchError;
use wingcheck_sim::SimError;

/// A refused estimate with the estimate itself.
#[derive(Debug, Clone, thiserror::Error)]
#[error("{refused}")]
pub struct WorkLimit {
    /// The estimate that was refused.
    pub estimate: WorkEstimate,
    /// The refusal (what, the estimate in words, the limits, the override).
    pub refused: WorkRefused,
}

/// An error of a front end's operation.
#[derive(Debug, thiserror::Error)]
pub enum AppError {
    /// The configuration (or an override) is invalid.
    #[error(transparent)]
    Config(#[from] ConfigError),
    /// A configuration file is invalid (the file named).
    #[error("in config {}", path.display())]
    ConfigFile {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        #[source]
        source: ConfigError,
    },
    /// An argument of the operation is outside its allowed values (the message names the
    /// argument as the front end spells it, and the allowed range).
    #[error("{message}")]
    Argument {
        /// The argument (snake_case).
        name: &'static str,
        /// The message.
        message: String,
    },
    /// An output path cannot be written (checked before any work).
    #[error("{message}")]
    OutputPath {
        /// The path.
        path: PathBuf,
        /// The message.
        message: String,
    },
    /// The estimated work is above the limits.
    #[error(transparent)]
    WorkLimit(Box<WorkLimit>),
    /// A simulation failed (diverged, numerical failure, cancelled).
    #[error(transparent)]
    Sim(#[from] SimError),
    /// Writing a simulation's output failed.
    #[error(transparent)]
    SimOutput(#[from] wingcheck_sim::output::OutputError),
    /// The claim checker failed.
    #[error(transparent)]
    Claims(#[from] ClaimsError),
    /// A search failed or was refused.
    #[error(transparent)]
    Search(#[from] SearchError),
    /// The report failed.
    #[error(transparent)]
    Report(#[from] ReportError),
    /// `certify` failed (the directory named).
    #[error("certify into {}", out.display())]
    Certify {
        /// The output directory.
        out: PathBuf,
        /// What failed.
        #[source]
        source: CertifyError,
    },
    /// A certificate set was rejected by `verify` (the directory named).
    #[error("REJECTED {}", path.display())]
    Rejected {
        /// The set's directory.
        path: PathBuf,
        /// Why.
        #[source]
        source: CertifyError,
    },
    /// A chart could not be drawn (a bug: the data are checked before).
    #[error(transparent)]
    Chart(#[from] wingcheck_chart::ChartError),
    /// An output file could not be written.
    #[error(transparent)]
    Write(#[from] wingcheck_io::IoError),
    /// The operation was stopped through its cancel token.
    #[error(transparent)]
    Cancelled(#[from] wingcheck_model::Cancelled),
    /// A panic inside the library (a bug), caught at the front end's boundary.
    #[error("internal error (a bug in wingcheck; please report it): {0}")]
    Internal(String),
}

/// What kind of failure an [`AppError`] is, for a front end to choose its presentation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ErrorKind {
    /// Bad input: configuration, override, argument (a `ValueError` in Python).
    Config,
    /// Above the work limits.
    WorkLimit,
    /// A numerical step failed.
    Numerical,
    /// The closed loop diverged at time `t` (s).
    Diverged {
        /// Time of detection (s).
        t: f64,
    },
    /// A controller of the user's failed or returned bad inputs at time `t` (s; `None`: its
    /// continuous part was refused before the run).
    Controller {
        /// Time of the failing sample (s).
        t: Option<f64>,
    },
    /// A search is malformed or its directory does not fit.
    Search,
    /// An input file or directory cannot be read.
    Input,
    /// An output cannot be written.
    Output,
    /// A certificate set was rejected.
    Verification,
    /// Stopped through the cancel token.
    Cancelled,
    /// A bug.
    Internal,
}

impl AppError {
    /// The kind of failure (the innermost cause decides: a simulation that diverged inside the
    /// report is [`ErrorKind::Diverged`]).
    pub fn kind(&self) -> ErrorKind {
        match self {
            AppError::Config(ConfigError::Read { .. }) => ErrorKind::Input,
            AppError::Config(_) | AppError::ConfigFile { .. } | AppError::Argument { .. } => ErrorKind::Config,
            AppError::OutputPath { .. } | AppError::SimOutput(_) | AppError::Write(_) => ErrorKind::Output,
            AppError::Chart(_) => ErrorKind::Internal,
            AppError::WorkLimit(_) => ErrorKind::WorkLimit,
            AppError::Sim(e) => sim_kind(e),
            AppError::Claims(e) => claims_kind(e),
            AppError::Search(e) => search_kind(e),
            AppError::Report(e) => report_kind(e),
            AppError::Certify { source, .. } => certify_kind(source, ErrorKind::Numerical),
            AppError::Rejected { source, .. } => certify_kind(source, ErrorKind::Verification),
            AppError::Cancelled(_) => ErrorKind::Cancelled,
            AppError::Internal(_) => ErrorKind::Internal,
        }
    }
}

fn sim_kind(e: &SimError) -> ErrorKind {
    match e {
        SimError::Config(ConfigError::Read { .. }) => ErrorKind::Input,
        SimError::Config(_) | SimError::HorizonEnded { .. } => ErrorKind::Config,
        SimError::Numerical(_)
        | SimError::NoModalBasis { .. }
        | SimError::ExponentialNeedsModal(_)
        | SimError::RefinementScheme { .. }
        | SimError::EndedEarlier { .. }
        | SimError::Thread(_) => ErrorKind::Numerical,
        SimError::Diverged { t, .. } => ErrorKind::Diverged { t: *t },
        SimError::Cancelled(_) => ErrorKind::Cancelled,
        SimError::Control(c) => ErrorKind::Controller { t: control_time(c) },
    }
}

/// When a controller's failure happened (s).
fn control_time(e: &wingcheck_control::ControlError) -> Option<f64> {
    use wingcheck_control::ControlError as E;
    match e {
        E::NonFinite { t, .. } | E::Shape { t, .. } | E::Failed { t, .. } | E::Detached { t } => Some(*t),
        E::Continuous { .. } => None,
    }
}

fn claims_kind(e: &ClaimsError) -> ErrorKind {
    match e {
        ClaimsError::Sim(s) => sim_kind(s),
        ClaimsError::Numerical { .. } => ErrorKind::Numerical,
        ClaimsError::Cancelled(_) => ErrorKind::Cancelled,
        ClaimsError::Panicked(_) => ErrorKind::Internal,
    }
}

fn search_kind(e: &SearchError) -> ErrorKind {
    match e {
        SearchError::TooLarge { .. } => ErrorKind::WorkLimit,
        SearchError::Read { .. }
        | SearchError::NotText { .. }
        | SearchError::FileSystem { .. }
        | SearchError::Manifest { .. }
        | SearchError::Serialise { .. }
        | SearchError::OutOfOrder { .. }
        | SearchError::PointCount { .. }
        | SearchError::HeatmapCells { .. }
        | SearchError::Heatmap { .. }
        | SearchError::Output(_) => ErrorKind::Output,
        SearchError::Theory { .. } | SearchError::Omega1(_) => ErrorKind::Numerical,
        SearchError::Cancelled(_) => ErrorKind::Cancelled,
        SearchError::Config(ConfigError::Read { .. }) => ErrorKind::Input,
        SearchError::Config(_) => ErrorKind::Config,
        SearchError::Simulation(e) => sim_kind(e),
        SearchError::ThreadPool { .. } => ErrorKind::Internal,
        SearchError::Axis { .. }
        | SearchError::ChunkSize
        | SearchError::RefineTolerance { .. }
        | SearchError::WindowOrder { .. }
        | SearchError::WindowOutsideHorizon { .. }
        | SearchError::LyapunovElements { .. }
        | SearchError::ControllerName
        | SearchError::ControllerMissing { .. }
        | SearchError::ControllerUnexpected
        | SearchError::MergeOwnController { .. }
        | SearchError::Shard { .. }
        | SearchError::Threads { .. }
        | SearchError::MergeNothing
        | SearchError::Chunk { .. }
        | SearchError::Mismatch { .. }
        | SearchError::MissingChunks { .. } => ErrorKind::Search,
    }
}

fn report_kind(e: &ReportError) -> ErrorKind {
    match e {
        ReportError::NotAReport { .. } | ReportError::Output(_) | ReportError::Io { .. } => ErrorKind::Output,
        ReportError::InvalidOutDir(_) => ErrorKind::Output,
        ReportError::Config { .. } => ErrorKind::Config,
        ReportError::Sim { source, .. } | ReportError::Claims(source) => claims_kind(source),
        ReportError::Cancelled(_) => ErrorKind::Cancelled,
        ReportError::Region(_) | ReportError::RegionTooLarge { .. } => ErrorKind::Search,
        ReportError::Evidence { .. } | ReportError::Chart { .. } | ReportError::Template(_) => ErrorKind::Internal,
    }
}

/// `certify`'s failures are numerical or about writing; `verify`'s are a rejection (`other`)
/// unless the set cannot be read.
fn certify_kind(e: &CertifyError, other: ErrorKind) -> ErrorKind {
    match e {
        CertifyError::Io { .. } => ErrorKind::Input,
        CertifyError::Write(_) => ErrorKind::Output,
        CertifyError::Numerical { .. } => ErrorKind::Numerical,
        CertifyError::Cancelled(_) => ErrorKind::Cancelled,
        CertifyError::Invalid { .. } | CertifyError::Refuted(_) | CertifyError::SelfCheck(_) => other,
    }
}
