//! Options shared by all commands: the configuration source and overrides.

use std::io::IsTerminal;
use std::path::PathBuf;

use clap::Args;
use wingcheck_model::{apply_overrides, Config};

/// Where the configuration comes from.
#[derive(Debug, Clone, Args)]
pub struct ConfigArgs {
    /// JSON configuration file (default: the embedded configs/paper.json).
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// Override a key, e.g. `--set control.a=0.05` (repeatable).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
}

impl ConfigArgs {
    /// Load, override and validate.
    pub fn load(&self) -> anyhow::Result<Config> {
        let base = match &self.config {
            None => Config::paper(),
            Some(p) => Config::from_file(p).map_err(|e| match e {
                wingcheck_model::ConfigError::Read { .. } => anyhow::Error::new(e),
                other => anyhow::Error::new(other).context(format!("in config {}", p.display())),
            })?,
        };
        Ok(apply_overrides(&base, &self.set)?)
    }
}

/// The work guard shared by simulate, check, report and modes.
#[derive(Debug, Clone, Args)]
pub struct WorkArgs {
    /// Run even if the estimated work exceeds the limits (10 min of computing, 4 GiB of
    /// memory, 1 GiB of output).
    #[arg(long)]
    pub allow_large: bool,
}

impl WorkArgs {
    /// Refuse `est` above the default limits unless `--allow-large` was given.
    pub fn guard(&self, est: &wingcheck_model::work::WorkEstimate) -> anyhow::Result<()> {
        if self.allow_large {
            return Ok(());
        }
        Ok(est.within(&wingcheck_model::work::DEFAULT_LIMITS)?)
    }
}

/// A progress bar on stderr when it is a terminal; `None` otherwise (quiet).
pub fn progress_bar(len: u64, what: &str) -> Option<indicatif::ProgressBar> {
    if !std::io::stderr().is_terminal() {
        return None;
    }
    let bar = indicatif::ProgressBar::new(len);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{msg} [{bar:40}] {percent}% ({elapsed} / eta {eta})")
            .expect("valid template")
            .progress_chars("=> "),
    );
    bar.set_message(what.to_string());
    Some(bar)
}
