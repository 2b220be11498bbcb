//! The report's error type: every I/O failure names the path it concerns.

use std::path::{Path, PathBuf};

/// Errors while producing a report.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// The output path exists and is not a report (no marker file) nor an empty directory:
    /// it is never overwritten.
    #[error(
        "refusing to overwrite {path}: it exists and is not a wingcheck report (no {marker} marker); \
         choose another --out or remove it"
    )]
    NotAReport {
        /// The output path.
        path: PathBuf,
        /// The marker file name that identifies a report directory.
        marker: &'static str,
    },
    /// Writing or swapping in the output directory failed, or the directory holds files the
    /// tool did not write (the previous report is unchanged).
    #[error(transparent)]
    Output(#[from] wingcheck_io::IoError),
    /// A file or directory could not be created, written, renamed or removed.
    #[error("cannot {action} {path}: {source}")]
    Io {
        /// What was attempted (`create directory`, `write`, `rename into place`, …).
        action: &'static str,
        /// The path concerned.
        path: PathBuf,
        /// Underlying error.
        #[source]
        source: std::io::Error,
    },
    /// The output path has no final component (e.g. `/` or `..`).
    #[error("invalid output directory {0}: it must name a directory, e.g. reports/paper")]
    InvalidOutDir(PathBuf),
    /// A configuration variant (override) was rejected.
    #[error("configuration variant `{variant}`: {source}")]
    Config {
        /// The variant (e.g. `control.kind=dobc`).
        variant: String,
        /// Underlying error.
        #[source]
        source: wingcheck_model::ConfigError,
    },
    /// A simulation behind a figure failed.
    #[error("simulation `{run}` failed: {source}")]
    Sim {
        /// Which run.
        run: String,
        /// Underlying error.
        #[source]
        source: wingcheck_claims::ClaimsError,
    },
    /// A row's evidence is not made of labelled values (a bug of the claim checker).
    #[error("the evidence of {claim} cannot be shown: {cause}")]
    Evidence {
        /// The claim.
        claim: String,
        /// Which value, and why.
        #[source]
        cause: wingcheck_claims::display::ShapeError,
    },
    /// The claim checker failed.
    #[error("claim checker failed: {0}")]
    Claims(#[from] wingcheck_claims::ClaimsError),
    /// A chart could not be drawn.
    #[error("cannot draw chart {name}: {cause}")]
    Chart {
        /// File stem of the chart.
        name: String,
        /// What went wrong.
        #[source]
        cause: wingcheck_chart::DrawError,
    },
    /// The (a, b) region map could not be set up (its search was refused).
    #[error("region map: {0}")]
    Region(#[source] wingcheck_search::SearchError),
    /// The (a, b) region map has more points than the work estimate counts.
    #[error("region map: {points} points, more than the {limit} counted")]
    RegionTooLarge {
        /// Points of the map.
        points: usize,
        /// The most the estimate counts ([`wingcheck_model::work::REGION_MAP_MAX_POINTS`]).
        limit: usize,
    },
    /// The report was stopped through [`crate::ReportOptions::cancel`]; nothing was written
    /// (the staging directory is removed, an earlier report is unchanged).
    #[error(transparent)]
    Cancelled(#[from] wingcheck_model::Cancelled),
    /// The HTML template failed to render.
    #[error("cannot render the HTML template: {0}")]
    Template(#[from] minijinja::Error),
}

impl ReportError {
    /// Shorthand for [`ReportError::Io`].
    pub(crate) fn io(action: &'static str, path: &Path) -> impl FnOnce(std::io::Error) -> ReportError {
        let path = path.to_path_buf();
        move |source| ReportError::Io { action, path, source }
    }
}

impl From<wingcheck_chart::ChartError> for ReportError {
    fn from(e: wingcheck_chart::ChartError) -> Self {
        ReportError::Chart { name: e.name, cause: e.cause }
    }
}
