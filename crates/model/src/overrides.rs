//! `--set path.to.key=value` overrides applied to the JSON form of a configuration.

use serde_json::Value;

use crate::{Config, ConfigError};

/// Apply one override `path.to.key=value` to a JSON configuration value.
///
/// The value is parsed as JSON (`0.05`, `true`, `"fd"`); if that fails it is taken as a
/// string (so `--set discretisation.method=fd` works). The key path must already exist:
/// unknown keys are rejected with the list of keys allowed at that level.
pub fn apply_override(root: &mut Value, expr: &str) -> Result<(), ConfigError> {
    let err = |reason: String| ConfigError::Override { expr: expr.to_string(), reason };
    let (path, raw) = expr.split_once('=').ok_or_else(|| err("expected path.to.key=value".into()))?;
    let path = path.trim();
    if path.is_empty() {
        return Err(err("empty key".into()));
    }
    if let Ok(x) = raw.trim().parse::<f64>() {
        if !x.is_finite() {
            return Err(ConfigError::NotFinite { field: path.to_string(), value: raw.trim().to_string() });
        }
    }
    // `1e-400` parses to 0 (and `1e-310` to a subnormal): refused, not silently changed
    if let Some(x) = crate::json::underflows(raw) {
        return Err(crate::json::underflow_error(Some(path), raw.trim(), x));
    }
    let value: Value = serde_json::from_str(raw.trim()).unwrap_or_else(|_| Value::String(raw.trim().to_string()));
    let mut node = root;
    let parts: Vec<&str> = path.split('.').collect();
    for (i, part) in parts.iter().enumerate() {
        let obj = node.as_object_mut().ok_or_else(|| err(format!("`{}` is not a section", parts[..i].join("."))))?;
        if !obj.contains_key(*part) {
            let mut keys: Vec<&String> = obj.keys().collect();
            keys.sort();
            let keys: Vec<String> = keys.into_iter().cloned().collect();
            return Err(err(format!("unknown key `{}`; allowed here: {}", parts[..=i].join("."), keys.join(", "))));
        }
        node = obj.get_mut(*part).expect("checked above");
    }
    if node.is_object() {
        return Err(err(format!("`{path}` is a section, not a value")));
    }
    *node = value;
    Ok(())
}

/// Apply several overrides to a configuration and re-validate.
pub fn apply_overrides(cfg: &Config, exprs: &[String]) -> Result<Config, ConfigError> {
    if exprs.is_empty() {
        return Ok(cfg.clone());
    }
    let mut value = serde_json::to_value(cfg).map_err(|e| ConfigError::Parse(e.to_string()))?;
    for e in exprs {
        apply_override(&mut value, e)?;
    }
    Config::from_json_value(value).map_err(|e| as_typed(e, exprs))
}

/// A range error on a field that an override set names the value as the user typed it
/// (`control.a = 1.00000000000000000001e13`, not the f64's shortest form `1e13`).
fn as_typed(e: ConfigError, exprs: &[String]) -> ConfigError {
    let typed = |field: &str| {
        exprs.iter().rev().find_map(|x| x.split_once('=').filter(|(k, _)| k.trim() == field).map(|(_, v)| v.trim()))
    };
    match e {
        ConfigError::OutOfRange { field, value, allowed } => {
            let value = typed(&field).map_or(value, str::to_string);
            ConfigError::OutOfRange { field, value, allowed }
        }
        other => other,
    }
}
