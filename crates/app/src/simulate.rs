//! `simulate`: the options a front end offers, their mapping onto the configuration, the
//! default sample times, and the run itself (guarded, cancellable, written atomically).

use std::path::{Path, PathBuf};
use std::time::Instant;

use wingcheck_model::work::WorkEstimate;
use wingcheck_model::{Cancel, Config, ControllerKind, Method, ObserverRule};
use wingcheck_sim::{output, simulate, simulate_with_error, ControllerFactory, EstimatedRun, RunOptions, SimOutput};

use crate::{AppError, ConfigSource, Front, WorkPolicy};

/// The options of a simulate run beyond the configuration (`wingcheck simulate`'s flags,
/// `wingcheck.simulate`'s keyword arguments).
#[derive(Debug, Clone, Default)]
pub struct SimulateRequest {
    /// Controller (`control.kind`); none: the configuration's.
    pub controller: Option<ControllerKind>,
    /// Observer rule (`observer.rule`); none: the configuration's.
    pub observer: Option<ObserverRule>,
    /// Spatial discretisation (`discretisation.method`); `fd` implies a uniform grid
    /// (`discretisation.grading = 0`) unless an override sets the grading.
    pub method: Option<Method>,
    /// Output sampling interval (s) (`horizon.sample_every`).
    pub sample_every: Option<f64>,
    /// Also estimate the discretisation error (one refinement in h and one in dt).
    pub error_estimate: bool,
    /// Record q(z,t), θ(z,t) on the output grid.
    pub fields: bool,
    /// Times (s) at which the summary reports the tip; none: [`default_sample_times`].
    pub sample_times: Option<Vec<f64>>,
    /// Output file (`.csv`: the series; `.json`: series, fields, config, stats).
    pub out: Option<PathBuf>,
}

/// What [`run`] produced.
#[derive(Debug, Clone)]
pub struct SimulateResult {
    /// The run.
    pub output: SimOutput,
    /// The error estimate, if asked for.
    pub estimate: Option<EstimatedRun>,
    /// The checked sample times (s).
    pub sample_times: Vec<f64>,
    /// Wall time of the run (s; not reproducible).
    pub wall_seconds: f64,
}

impl SimulateRequest {
    /// The overrides these options stand for, around the user's own: `method = fd` puts
    /// `discretisation.grading=0` before them (unless they set the grading), the others follow
    /// them (an option wins over an override of the same key).
    pub fn source(&self, base: &ConfigSource) -> ConfigSource {
        let sets_grading = base.set.iter().any(|s| s.trim_start().starts_with("discretisation.grading"));
        let leading = if self.method == Some(Method::Fd) && !sets_grading {
            vec!["discretisation.grading=0".into()]
        } else {
            vec![]
        };
        let mut trailing = Vec::new();
        if let Some(c) = self.controller {
            trailing.push(format!("control.kind={}", c.name()));
        }
        if let Some(o) = self.observer {
            trailing.push(format!("observer.rule={}", o.name()));
        }
        if let Some(m) = self.method {
            trailing.push(format!("discretisation.method={}", m.name()));
        }
        if let Some(s) = self.sample_every {
            trailing.push(format!("horizon.sample_every={s}"));
        }
        base.with_leading(leading).with_trailing(trailing)
    }

    /// The configuration to run: `base` with [`SimulateRequest::source`]'s overrides.
    pub fn config(&self, base: &ConfigSource) -> Result<Config, AppError> {
        self.source(base).load()
    }

    /// The sample times, checked to lie in [0, t_end].
    pub fn sample_times(&self, cfg: &Config, front: Front) -> Result<Vec<f64>, AppError> {
        let times = self.sample_times.clone().unwrap_or_else(|| default_sample_times(cfg));
        for &t in &times {
            if !(t.is_finite() && (0.0..=cfg.horizon.t_end).contains(&t)) {
                return Err(AppError::Argument {
                    name: "sample_times",
                    message: format!(
                        "{}: {t} is outside the horizon [0, {}]",
                        front.arg("sample_times"),
                        cfg.horizon.t_end
                    ),
                });
            }
        }
        Ok(times)
    }

    /// Whether the output file is JSON (None: no output file).
    fn json_out(&self) -> Option<bool> {
        self.out.as_ref().map(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("json")))
    }

    /// The run's work estimate (with the error estimate's runs when asked for).
    pub fn estimate(&self, cfg: &Config) -> WorkEstimate {
        let json_out = self.json_out();
        if self.error_estimate {
            WorkEstimate::simulation_with_error(cfg, self.fields, json_out)
        } else {
            WorkEstimate::simulation(cfg, self.fields, json_out)
        }
    }
}

/// The default sample times: 5, 10 and 20 s, those beyond the horizon dropped, or the
/// horizon's end when none is left.
pub fn default_sample_times(cfg: &Config) -> Vec<f64> {
    let within: Vec<f64> = [5.0, 10.0, 20.0].into_iter().filter(|&t| t <= cfg.horizon.t_end).collect();
    if within.is_empty() {
        vec![cfg.horizon.t_end]
    } else {
        within
    }
}

/// Fail before any work if `path` cannot be written (bad extension, missing or read-only
/// directory, a name too long with its staging suffix or sidecar, a symlink or special file in
/// the way: `wingcheck_io::check_output_file_with`).
pub fn check_writable(path: &Path, front: Front) -> Result<(), AppError> {
    let arg = front.arg("out");
    let fail = |message: String| AppError::OutputPath { path: path.to_path_buf(), message };
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    if ext != "csv" && ext != "json" {
        return Err(fail(format!("{arg} {}: use a .csv or .json file name", path.display())));
    }
    let sidecar = (ext == "csv").then_some(wingcheck_io::SIDECAR_SUFFIX);
    wingcheck_io::check_output_file_with(path, sidecar).map_err(|e| fail(format!("{arg}: {e}")))?;
    let dir = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let md = std::fs::metadata(dir)
        .map_err(|e| fail(format!("{arg} {}: directory {}: {e}", path.display(), dir.display())))?;
    if !md.is_dir() {
        return Err(fail(format!("{arg} {}: {} is not a directory", path.display(), dir.display())));
    }
    if md.permissions().readonly() {
        return Err(fail(format!("{arg} {}: directory {} is read-only", path.display(), dir.display())));
    }
    Ok(())
}

/// Run `cfg` as `req` asks: check the sample times, guard the work, check the output path,
/// run (with the error estimate if asked; `progress` gets the fraction done, `cancel` is read at
/// every output sample), then write the output file atomically. A cancelled or failed run
/// writes nothing.
pub fn run(
    cfg: &Config,
    req: &SimulateRequest,
    policy: WorkPolicy,
    progress: Option<&mut dyn FnMut(f64)>,
    cancel: &Cancel,
) -> Result<SimulateResult, AppError> {
    run_with(cfg, req, policy, progress, cancel, None)
}

/// [`run`] under a controller of the user's in place of `control.kind` (`None`: the
/// configured one); see [`RunOptions::controller`].
pub fn run_with<'a>(
    cfg: &Config,
    req: &SimulateRequest,
    policy: WorkPolicy,
    progress: Option<&'a mut dyn FnMut(f64)>,
    cancel: &Cancel,
    controller: Option<ControllerFactory<'a>>,
) -> Result<SimulateResult, AppError> {
    let sample_times = req.sample_times(cfg, policy.front)?;
    policy.guard(&req.estimate(cfg))?;
    if let Some(path) = &req.out {
        check_writable(path, policy.front)?;
    }
    let start = Instant::now();
    let opts = RunOptions { fields: req.fields, progress, cancel: cancel.clone(), controller, ..Default::default() };
    let (output, estimate) = if req.error_estimate {
        let e = simulate_with_error(cfg, opts)?;
        (e.output.clone(), Some(e))
    } else {
        (simulate(cfg, opts)?, None)
    };
    let wall_seconds = start.elapsed().as_secs_f64();
    cancel.check()?;
    if let Some(path) = &req.out {
        // rendered first, then moved into place through the cancel token's gate: once
        // `cancel()` has returned, the files are either complete already or never appear
        let files = output::render_run(path, cfg, &output)?;
        cancel.commit(|| output::write_rendered(&files).map_err(AppError::from))?;
    }
    Ok(SimulateResult { output, estimate, sample_times, wall_seconds })
}

/// The closed loop in words, as every front end names it: "open loop (no controller)",
/// "pd controller (no observer)", "dobc controller (its linear observer (57))" or
/// "ftdo controller, implicit observer" (the observer's rule matters only to the FTDO).
pub fn controller_phrase(cfg: &Config) -> String {
    use wingcheck_model::ControllerKind;
    match cfg.control.kind {
        ControllerKind::None => "open loop (no controller)".to_string(),
        ControllerKind::Pd => "pd controller (no observer)".to_string(),
        ControllerKind::Dobc => "dobc controller (its linear observer (57))".to_string(),
        ControllerKind::Ftdo => format!("ftdo controller, {} observer", cfg.observer.rule.name()),
    }
}
