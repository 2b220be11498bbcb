//! certify and verify, for Python.

use std::path::PathBuf;

use pyo3::prelude::*;
use pyo3::types::PyDict;
use wingcheck_app::ops;

use crate::blocking::{self, Writes};
use crate::errors::dict;
use crate::functions::source;

/// `certify`: the certificate set into `out`: (files written, notes).
#[pyfunction]
#[pyo3(signature = (out, config_text=None, config_path=None, set=Vec::new()))]
pub fn certify(
    py: Python<'_>,
    out: PathBuf,
    config_text: Option<String>,
    config_path: Option<PathBuf>,
    set: Vec<String>,
) -> PyResult<(Vec<PathBuf>, Vec<String>)> {
    let base = source(config_text, config_path, set);
    blocking::run(py, None, Writes::Gated, move |cancel, _| {
        let cfg = base.load()?;
        let w = ops::certify(&cfg, &out, cancel)?;
        Ok((w.files, w.notes))
    })
}

/// `verify`: the verified set: its configuration (JSON) and hash, the certificates
/// (id, kind, statement), the conclusions (claim, text). With `pinned`, the set must have been
/// made for the given configuration.
#[pyfunction]
#[pyo3(signature = (path, pinned=false, config_text=None, config_path=None, set=Vec::new()))]
pub fn verify<'py>(
    py: Python<'py>,
    path: PathBuf,
    pinned: bool,
    config_text: Option<String>,
    config_path: Option<PathBuf>,
    set: Vec<String>,
) -> PyResult<Bound<'py, PyDict>> {
    let base = source(config_text, config_path, set);
    let (cfg_json, sha, certs, conclusions) = blocking::run(py, None, Writes::Nothing, move |_, _| {
        let expected = if pinned && !path.is_file() { Some(base.load()?) } else { None };
        let v = ops::verify(&path, expected.as_ref())?;
        let certs: Vec<(String, String, String)> = v
            .certs
            .iter()
            .map(|c| (c.role.id.to_string(), c.fact.kind.as_str().to_string(), c.fact.statement.clone()))
            .collect();
        Ok((
            serde_json::to_string(&v.config).unwrap_or_default(),
            v.config_sha256.clone(),
            certs,
            v.conclusions.clone(),
        ))
    })?;
    dict(
        py,
        vec![
            ("config", cfg_json.into_pyobject(py)?.into_any()),
            ("config_sha256", sha.into_pyobject(py)?.into_any()),
            ("certificates", certs.into_pyobject(py)?.into_any()),
            ("conclusions", conclusions.into_pyobject(py)?.into_any()),
        ],
    )
}
