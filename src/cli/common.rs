//! Options shared by all commands: the configuration source and overrides.

use std::path::PathBuf;

use clap::Args;
use wingcheck_app::{ConfigSource, Front, WorkPolicy};
use wingcheck_model::Config;

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
    /// The configuration source these flags name.
    pub fn source(&self) -> ConfigSource {
        ConfigSource { file: self.config.clone(), text: None, set: self.set.clone() }
    }

    /// Load, override and validate.
    pub fn load(&self) -> anyhow::Result<Config> {
        Ok(self.source().load()?)
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
    /// The work policy these flags ask for.
    pub fn policy(&self) -> WorkPolicy {
        WorkPolicy { allow_large: self.allow_large, front: Front::Cli }
    }

    /// Refuse `est` above the default limits unless `--allow-large` was given.
    pub fn guard(&self, est: &wingcheck_model::work::WorkEstimate) -> anyhow::Result<()> {
        Ok(self.policy().guard(est)?)
    }
}
