//! simulate, check, search, report, modes, the configuration and the build, for Python.

use std::path::PathBuf;

use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use wingcheck_app::{ops, AppError, ConfigSource, Front, ModesRequest, SimulateRequest, SimulateSummary, WorkPolicy};
use wingcheck_model::ControllerKind;
use wingcheck_sim::{ControllerFactory, Series};

use crate::blocking::{self, Writes};
use crate::controller::Shared;
use crate::errors::{argument, dict};

/// The configuration source of a call: JSON text or a file (the Python layer turns a dict, a
/// `Config` or a path into one of them), then `key=value` overrides.
pub fn source(config_text: Option<String>, config_path: Option<PathBuf>, set: Vec<String>) -> ConfigSource {
    ConfigSource { file: config_path, text: config_text, set }
}

/// A keyword's value as one of the configuration's names (`"ftdo"`, `"fd"`, …), through the
/// configuration's own serde names.
fn parse_name<T: serde::de::DeserializeOwned>(
    py: Python<'_>,
    name: &'static str,
    v: Option<String>,
) -> PyResult<Option<T>> {
    v.map(|s| serde_json::from_value(serde_json::Value::String(s)).map_err(|e| argument(py, name, e))).transpose()
}

fn policy(allow_large: bool) -> WorkPolicy {
    WorkPolicy { allow_large, front: Front::Python }
}

/// A run: the columns of run.csv as float64 arrays under their CSV names, their units, the
/// `simulate --json` document, the configuration and, if asked for, the fields.
#[pyfunction]
#[pyo3(signature = (config_text=None, config_path=None, set=Vec::new(), controller=None, observer=None, method=None,
    sample_every=None, error_estimate=false, fields=false, sample_times=None, out=None, allow_large=false, progress=None,
    controller_object=None, continuous=None))]
#[allow(clippy::too_many_arguments)]
pub fn simulate<'py>(
    py: Python<'py>,
    config_text: Option<String>,
    config_path: Option<PathBuf>,
    set: Vec<String>,
    controller: Option<String>,
    observer: Option<String>,
    method: Option<String>,
    sample_every: Option<f64>,
    error_estimate: bool,
    fields: bool,
    sample_times: Option<Vec<f64>>,
    out: Option<PathBuf>,
    allow_large: bool,
    progress: Option<Bound<'py, PyAny>>,
    controller_object: Option<Py<PyAny>>,
    continuous: Option<[f64; 4]>,
) -> PyResult<Bound<'py, PyDict>> {
    let shared = controller_object.map(|obj| Shared::new(py, obj, continuous.unwrap_or([0.0; 4]))).transpose()?;
    let own = shared.clone();
    let req = SimulateRequest {
        controller: parse_name(py, "controller", controller)?,
        observer: parse_name(py, "observer", observer)?,
        method: parse_name(py, "method", method)?,
        sample_every,
        error_estimate,
        fields,
        sample_times,
        out,
    };
    let base = source(config_text, config_path, set);
    let run_req = req.clone();
    // The output file goes into place through the cancel token's gate (app::simulate): a stop
    // raises at once. A run with a Python controller is waited for: its worker calls back
    // into the interpreter until it reaches its next checkpoint.
    let writes = if own.is_some() { Writes::Files } else { Writes::Gated };
    let (cfg, result) = blocking::run(py, progress.as_ref(), writes, move |cancel, sink| {
        let req = run_req;
        let cfg = req.config(&base)?;
        let mut on_progress = |f: f64| sink.set(f, "simulate");
        let make = own.map(|s| move || s.controller());
        let factory = make.as_ref().map(|f| f as ControllerFactory<'_>);
        let mut run = || {
            wingcheck_app::simulate::run_with(&cfg, &req, policy(allow_large), Some(&mut on_progress), cancel, factory)
        };
        let r = if factory.is_some() { crate::controller::with_thread_state(run)? } else { run()? };
        Ok((cfg, r))
    })
    // an exception inside the user's controller is raised as it is, with its traceback
    .map_err(|e| shared.as_ref().and_then(|s| s.take_error()).unwrap_or(e))?;
    let series = &result.output.series;
    let columns = PyDict::new(py);
    let units = PyDict::new(py);
    for ((name, col), (_, unit)) in Series::csv_header().into_iter().zip(series.columns()).zip(Series::COLUMNS) {
        columns.set_item(&name, PyArray1::from_slice(py, col))?;
        units.set_item(&name, unit.symbol())?;
    }
    let field_arrays = match &result.output.fields {
        Some(f) => {
            let q = PyArray2::from_vec2(py, &f.q).map_err(|e| argument(py, "fields", e))?;
            let theta = PyArray2::from_vec2(py, &f.theta).map_err(|e| argument(py, "fields", e))?;
            dict(
                py,
                vec![
                    ("z_m", PyArray1::from_slice(py, &f.z).into_any()),
                    ("q_m", q.into_any()),
                    ("theta_rad", theta.into_any()),
                ],
            )?
            .into_any()
        }
        None => py.None().into_bound(py),
    };
    let summary = SimulateSummary::of(&cfg, &result, req.out.as_deref());
    let summary = serde_json::to_string(&summary).map_err(|e| argument(py, "summary", e))?;
    dict(
        py,
        vec![
            ("columns", columns.into_any()),
            ("units", units.into_any()),
            ("summary", summary.into_pyobject(py)?.into_any()),
            ("config", serde_json::to_string(&cfg).unwrap_or_default().into_pyobject(py)?.into_any()),
            ("fields", field_arrays),
        ],
    )
}

/// The claim ledger as `check --json` prints it (without its final newline).
#[pyfunction]
#[pyo3(signature = (config_text=None, config_path=None, set=Vec::new(), allow_large=false, progress=None))]
pub fn check(
    py: Python<'_>,
    config_text: Option<String>,
    config_path: Option<PathBuf>,
    set: Vec<String>,
    allow_large: bool,
    progress: Option<Bound<'_, PyAny>>,
) -> PyResult<String> {
    let base = source(config_text, config_path, set);
    blocking::run(py, progress.as_ref(), Writes::Nothing, move |cancel, _| {
        let cfg = base.load()?;
        Ok(ops::check(&cfg, policy(allow_large), cancel)?.to_json())
    })
}

/// A search into `out`: its summary (JSON text); the Python layer reads the files. With
/// `controller_object`, every point runs that controller of the user's (named
/// `controller_name` in the manifest); an exception inside it is that point's error, as a
/// diverged run is, and the search goes on.
#[pyfunction]
#[pyo3(signature = (over, out, config_text=None, config_path=None, set=Vec::new(), threads=None, refine=None,
    best=None, window=None, chunk_size=32, allow_large=false, progress=None, controller_object=None, continuous=None,
    controller_name=None))]
#[allow(clippy::too_many_arguments)]
pub fn search(
    py: Python<'_>,
    over: Vec<String>,
    out: PathBuf,
    config_text: Option<String>,
    config_path: Option<PathBuf>,
    set: Vec<String>,
    threads: Option<usize>,
    refine: Option<f64>,
    best: Option<String>,
    window: Option<(f64, f64)>,
    chunk_size: usize,
    allow_large: bool,
    progress: Option<Bound<'_, PyAny>>,
    controller_object: Option<Py<PyAny>>,
    continuous: Option<[f64; 4]>,
    controller_name: Option<String>,
) -> PyResult<String> {
    let best: wingcheck_search::Ranking = match best {
        Some(b) => b.parse().map_err(|e| argument(py, "best", e))?,
        None => Default::default(),
    };
    let own = controller_object.map(|obj| Shared::new(py, obj, continuous.unwrap_or([0.0; 4]))).transpose()?;
    // one Python object serves every point: run in parallel, the points would share (and mix)
    // the state it carries from call to call, so they run one at a time
    let threads = match (&own, threads) {
        (Some(_), Some(n)) if n > 1 => {
            return Err(argument(
                py,
                "threads",
                format!(
                    "threads = {n}: a search with your own controller runs one point at a time (the one \
                     object carries its state from call to call, which points run in parallel would share); \
                     pass threads=1 or leave it out"
                ),
            ))
        }
        (Some(_), _) => Some(1),
        (None, t) => t,
    };
    let controller = own.as_ref().map(|_| controller_name.unwrap_or_else(|| "your own".into()));
    let options =
        wingcheck_search::SearchOptions { window, chunk_size, refine, best, controller, ..Default::default() };
    let base = source(config_text, config_path, set);
    blocking::run(py, progress.as_ref(), Writes::Files, move |cancel, sink| {
        let cfg = base.load()?;
        let on_progress = |p: wingcheck_search::Progress| {
            sink.set(if p.total == 0 { 1.0 } else { p.done as f64 / p.total as f64 }, "search")
        };
        let make = own.map(|s| move || s.controller());
        let ctl = wingcheck_search::RunControl {
            progress: Some(&on_progress),
            threads,
            cancel: cancel.clone(),
            controller: make.as_ref().map(|f| f as ControllerFactory<'_>),
            ..Default::default()
        };
        let s = ops::search(cfg, &over, options, &out, policy(allow_large), ctl)?;
        Ok(serde_json::to_string(&s).unwrap_or_default())
    })
}

/// What `report` returns: (directory, files, stage timings as (name, s), ledger JSON).
type ReportParts = (PathBuf, Vec<String>, Vec<(String, f64)>, String);

/// The HTML report into `out`: (directory, files, stage timings as (name, s), ledger JSON).
#[pyfunction]
#[pyo3(signature = (out, config_text=None, config_path=None, set=Vec::new(), allow_large=false, progress=None))]
pub fn report(
    py: Python<'_>,
    out: PathBuf,
    config_text: Option<String>,
    config_path: Option<PathBuf>,
    set: Vec<String>,
    allow_large: bool,
    progress: Option<Bound<'_, PyAny>>,
) -> PyResult<ReportParts> {
    let base = source(config_text, config_path, set);
    blocking::run(py, progress.as_ref(), Writes::Gated, move |cancel, sink| {
        let cfg = base.load()?;
        let on_progress = |p: wingcheck_report::Overall| sink.set(p.fraction, p.stage);
        let opts = wingcheck_report::ReportOptions {
            overall: Some(&on_progress),
            command_line: Some("wingcheck.report (Python)"),
            cancel: Some(cancel),
            ..Default::default()
        };
        let s = ops::report(&cfg, &out, policy(allow_large), &opts)?;
        let timings = s.timings.iter().map(|t| (t.name.clone(), t.seconds)).collect();
        Ok((s.out_dir, s.files, timings, s.ledger.to_json()))
    })
}

/// The `modes --json` document (JSON text).
#[pyfunction]
#[pyo3(signature = (config_text=None, config_path=None, set=Vec::new(), count=5, method=None, tol=None))]
pub fn modes(
    py: Python<'_>,
    config_text: Option<String>,
    config_path: Option<PathBuf>,
    set: Vec<String>,
    count: usize,
    method: Option<String>,
    tol: Option<f64>,
) -> PyResult<String> {
    let req = ModesRequest {
        count,
        method: parse_name(py, "method", method)?,
        tol: tol.unwrap_or(ModesRequest::default().tol),
    };
    let base = source(config_text, config_path, set);
    blocking::run(py, None, Writes::Nothing, move |_, _| {
        let cfg = base.load()?;
        let doc = req.run(&cfg, WorkPolicy { allow_large: false, front: Front::Python })?;
        Ok(serde_json::to_string(&doc).unwrap_or_default())
    })
}

/// The effective configuration: (pretty JSON, SHA-256), validated.
#[pyfunction]
#[pyo3(signature = (config_text=None, config_path=None, set=Vec::new()))]
pub fn load_config(
    py: Python<'_>,
    config_text: Option<String>,
    config_path: Option<PathBuf>,
    set: Vec<String>,
) -> PyResult<(String, String)> {
    let cfg = source(config_text, config_path, set).load().map_err(|e| crate::errors::to_py(py, &e))?;
    Ok((cfg.to_json_pretty(), cfg.sha256()))
}

/// The build's provenance: version, commit, tree (clean, dirty, unknown), describe, rustc.
#[pyfunction]
pub fn build_info(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let b = wingcheck_app::build_info();
    let tree = match b.tree {
        wingcheck_io::TreeState::Clean => "clean",
        wingcheck_io::TreeState::Dirty => "dirty",
        wingcheck_io::TreeState::Unknown => "unknown",
    };
    dict(
        py,
        vec![
            ("version", b.version.into_pyobject(py)?.into_any()),
            ("commit", b.commit.into_pyobject(py)?.into_any()),
            ("tree", tree.into_pyobject(py)?.into_any()),
            ("describe", b.describe.into_pyobject(py)?.into_any()),
            ("rustc", b.rustc.into_pyobject(py)?.into_any()),
        ],
    )
}

/// One contestant of `compare` from Python: (name, built-in kind or None, own object or None,
/// its continuous part (k1, k2, a, b)).
type PyEntrant = (String, Option<String>, Option<Py<PyAny>>, Option<[f64; 4]>);

/// Controllers side by side (`wingcheck_app::compare`), as JSON text.
#[pyfunction]
#[pyo3(signature = (entrants, config_text=None, config_path=None, set=Vec::new(), allow_large=false, progress=None))]
pub fn compare(
    py: Python<'_>,
    entrants: Vec<PyEntrant>,
    config_text: Option<String>,
    config_path: Option<PathBuf>,
    set: Vec<String>,
    allow_large: bool,
    progress: Option<Bound<'_, PyAny>>,
) -> PyResult<String> {
    let mut parsed = Vec::with_capacity(entrants.len());
    let mut shared = Vec::new();
    for (name, kind, obj, continuous) in entrants {
        let which = match (kind, obj) {
            (Some(k), _) => {
                Ok(parse_name::<ControllerKind>(py, "controllers", Some(k))?.unwrap_or(ControllerKind::Ftdo))
            }
            (None, Some(obj)) => {
                let s = Shared::new(py, obj, continuous.unwrap_or([0.0; 4]))?;
                shared.push(s.clone());
                Err(s)
            }
            (None, None) => return Err(argument(py, "controllers", format!("{name}: no controller"))),
        };
        parsed.push((name, which));
    }
    let base = source(config_text, config_path, set);
    let text = blocking::run(py, progress.as_ref(), Writes::Nothing, move |cancel, _sink| {
        let cfg = base.load()?;
        let makers: Vec<_> = parsed
            .iter()
            .map(|(_, w)| {
                w.as_ref().err().map(|s| {
                    let s = s.clone();
                    move || s.controller()
                })
            })
            .collect();
        // a row without a maker is a built-in one (its kind parsed above)
        let entrants: Vec<(String, wingcheck_app::compare::Entrant<'_>)> = parsed
            .iter()
            .zip(&makers)
            .map(|((name, w), m)| {
                let e = match m {
                    Some(f) => wingcheck_app::compare::Entrant::Own(f as ControllerFactory<'_>),
                    None => wingcheck_app::compare::Entrant::BuiltIn(w.as_ref().map_or(ControllerKind::None, |k| *k)),
                };
                (name.clone(), e)
            })
            .collect();
        let compared = || wingcheck_app::compare::compare(&cfg, &entrants, policy(allow_large), cancel);
        let c = if makers.iter().any(Option::is_some) {
            crate::controller::with_thread_state(compared)?
        } else {
            compared()?
        };
        serde_json::to_string(&c).map_err(|e| AppError::Internal(format!("compare as JSON: {e}")))
    })
    .map_err(|e| shared.iter().find_map(|s| s.take_error()).unwrap_or(e))?;
    Ok(text)
}
