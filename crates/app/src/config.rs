//! Where a configuration comes from: the embedded default, a JSON file or JSON text, merged
//! over the default, then `key=value` overrides (`--set`), validated — the one route of every
//! front end, with the same messages.

use std::path::PathBuf;

use wingcheck_model::{apply_overrides, Config};

use crate::AppError;

/// A configuration to load.
#[derive(Debug, Clone, Default)]
pub struct ConfigSource {
    /// A JSON file (complete or partial, merged over the default); none: the embedded
    /// configs/paper.json.
    pub file: Option<PathBuf>,
    /// JSON text (complete or partial, merged over the default), instead of a file.
    pub text: Option<String>,
    /// `key=value` overrides applied in order after the file or text (`--set`).
    pub set: Vec<String>,
}

impl ConfigSource {
    /// Load, override and validate. A file's parse or validation error names the file
    /// ([`AppError::ConfigFile`]).
    pub fn load(&self) -> Result<Config, AppError> {
        let base = match (&self.file, &self.text) {
            (Some(p), _) => Config::from_file(p).map_err(|e| match e {
                wingcheck_model::ConfigError::Read { .. } => AppError::Config(e),
                source => AppError::ConfigFile { path: p.clone(), source },
            })?,
            (None, Some(text)) => Config::from_json_str(text)?,
            (None, None) => Config::paper(),
        };
        Ok(apply_overrides(&base, &self.set)?)
    }

    /// The same source with `more` overrides placed before the user's own (a rule such as
    /// `method = fd` ⇒ `grading = 0`, which an explicit override then replaces).
    pub fn with_leading(&self, more: Vec<String>) -> ConfigSource {
        ConfigSource { set: more.into_iter().chain(self.set.iter().cloned()).collect(), ..self.clone() }
    }

    /// The same source with `more` overrides after the user's own.
    pub fn with_trailing(&self, more: Vec<String>) -> ConfigSource {
        ConfigSource { set: self.set.iter().cloned().chain(more).collect(), ..self.clone() }
    }

    /// Whether anything was given (a file, text or an override).
    pub fn is_given(&self) -> bool {
        self.file.is_some() || self.text.is_some() || !self.set.is_empty()
    }
}
