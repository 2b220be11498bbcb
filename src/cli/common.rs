//! Options shared by all commands: the configuration source and overrides.

use std::io::IsTerminal;
use std::path::PathBuf;

use anyhow::Context;
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
            Some(p) => {
                let text = std::fs::read_to_string(p).with_context(|| format!("cannot read config {}", p.display()))?;
                Config::from_json_str(&text).with_context(|| format!("in config {}", p.display()))?
            }
        };
        Ok(apply_overrides(&base, &self.set)?)
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
