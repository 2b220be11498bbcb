//! `wingcheck simulate`.

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use serde::Serialize;
use wingcheck_model::{ControllerKind, Method, ObserverRule};
use wingcheck_sim::{output, simulate_with_error, RunOptions, SubStepCheck, TIP_TOLERANCE};
use wingcheck_sim::{simulate, EstimatedRun};

use super::common::{progress_bar, ConfigArgs};

/// Arguments of `wingcheck simulate`.
#[derive(Debug, Args)]
pub struct SimulateArgs {
    #[command(flatten)]
    config: ConfigArgs,
    #[command(flatten)]
    work: super::common::WorkArgs,
    /// Controller: none, pd, ftdo, dobc (default: control.kind of the config).
    #[arg(long)]
    controller: Option<ControllerKind>,
    /// Observer rule: implicit (set-valued, default) or explicit (chatters).
    #[arg(long)]
    observer: Option<ObserverRule>,
    /// Spatial discretisation: fd or fe. `fd` implies a uniform grid (discretisation.grading=0)
    /// unless the grading is set explicitly, which FD then refuses.
    #[arg(long)]
    method: Option<Method>,
    /// Also estimate the discretisation error of every tip value and peak by one refinement in
    /// h (2N) and one in dt (dt/2), Richardson order 2 (about 5× the work of the run).
    #[arg(long)]
    error_estimate: bool,
    /// Output file: .csv (time series) or .json (series, fields q(z,t), θ(z,t), config, stats).
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Output sampling interval (s).
    #[arg(long, value_name = "SECONDS")]
    sample_every: Option<f64>,
    /// Print a JSON summary to stdout.
    #[arg(long)]
    json: bool,
    /// Times at which the summary reports the tip values (comma-separated, s; default 5,10,20,
    /// those beyond the horizon dropped, or the horizon's end when none is left).
    #[arg(long, value_delimiter = ',')]
    sample_times: Option<Vec<f64>>,
}

pub fn run(a: SimulateArgs) -> anyhow::Result<()> {
    let mut set = a.config.set.clone();
    if a.method == Some(Method::Fd) && !set.iter().any(|s| s.trim_start().starts_with("discretisation.grading")) {
        set.insert(0, "discretisation.grading=0".into());
    }
    if let Some(c) = a.controller {
        set.push(format!("control.kind={}", c.name()));
    }
    if let Some(o) = a.observer {
        set.push(format!("observer.rule={}", o.name()));
    }
    if let Some(m) = a.method {
        set.push(format!("discretisation.method={}", m.name()));
    }
    if let Some(s) = a.sample_every {
        set.push(format!("horizon.sample_every={s}"));
    }
    let cfg = super::ConfigArgs { config: a.config.config.clone(), set }.load()?;
    let sample_times: Vec<f64> = match &a.sample_times {
        Some(v) => v.clone(),
        None => {
            let within: Vec<f64> = [5.0, 10.0, 20.0].into_iter().filter(|&t| t <= cfg.horizon.t_end).collect();
            if within.is_empty() {
                vec![cfg.horizon.t_end]
            } else {
                within
            }
        }
    };
    for &t in &sample_times {
        if !(t.is_finite() && (0.0..=cfg.horizon.t_end).contains(&t)) {
            anyhow::bail!("--sample-times: {t} is outside the horizon [0, {}]", cfg.horizon.t_end);
        }
    }
    let json_out = a.out.as_ref().map(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("json")));
    let estimate = if a.error_estimate {
        wingcheck_model::work::WorkEstimate::simulation_with_error(&cfg, json_out == Some(true), json_out)
    } else {
        wingcheck_model::work::WorkEstimate::simulation(&cfg, json_out == Some(true), json_out)
    };
    a.work.guard(&estimate)?;
    if let Some(path) = &a.out {
        check_writable(path)?;
    }
    let bar = progress_bar(1000, "simulate");
    let mut progress = |f: f64| {
        if let Some(b) = &bar {
            b.set_position((f * 1000.0) as u64);
        }
    };
    let wants_fields = a.out.as_ref().is_some_and(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("json")));
    let start = Instant::now();
    let opts = RunOptions { fields: wants_fields, progress: Some(&mut progress), ..Default::default() };
    let (out, estimated): (_, Option<EstimatedRun>) = if a.error_estimate {
        let e = simulate_with_error(&cfg, opts)?;
        (e.output.clone(), Some(e))
    } else {
        (simulate(&cfg, opts)?, None)
    };
    let wall = start.elapsed().as_secs_f64();
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    if let Some(path) = &a.out {
        output::write_run(path, &cfg, &out)?;
    }
    let s = &out.series;
    if a.json {
        let summary = summary(&cfg, &out, &sample_times, wall, a.out.as_deref(), estimated.as_ref());
        println!("{}", serde_json::to_string_pretty(&summary)?);
    } else {
        println!(
            "{} controller, {} observer, {} with {} {}, dt = {} s ({}, {} basis): {} steps in {:.3} s",
            cfg.control.kind.name(),
            cfg.observer.rule.name(),
            cfg.discretisation.method.name(),
            cfg.discretisation.grid_size(),
            if cfg.discretisation.method == Method::Fe { "elements" } else { "intervals" },
            cfg.discretisation.dt,
            out.stats.stepper,
            out.stats.basis,
            out.stats.steps,
            wall
        );
        match &estimated {
            None => {
                println!("{:>8} {:>14} {:>14}", "t (s)", "q(s,t) (m)", "θ(s,t) (rad)");
                for &t in &sample_times {
                    println!("{:>8} {:>14.6e} {:>14.6e}", t, s.at(&s.q_tip, t), s.at(&s.theta_tip, t));
                }
            }
            Some(e) => {
                println!(
                    "{:>8} {:>14} {:>9} {:>14} {:>9}",
                    "t (s)", "q(s,t) (m)", "± error", "θ(s,t) (rad)", "± error"
                );
                for &t in &sample_times {
                    let (q, th) = e.tip_at(t);
                    println!("{:>8} {:>14.6e} {:>9.1e} {:>14.6e} {:>9.1e}", t, q.value, q.error, th.value, th.error);
                }
                println!(
                    "max estimated error over the horizon: q {:.1e} m, θ {:.1e} rad (space {:.1e}, time {:.1e}; refined grid {}, dt {}, {}): {} the tolerance {:.0e}",
                    e.max_q_tip_error,
                    e.max_theta_tip_error,
                    e.max_space_error,
                    e.max_time_error,
                    e.refined_grid,
                    e.refined_dt,
                    e.refined_stepper,
                    if e.meets_tolerance { "within" } else { "EXCEEDS" },
                    TIP_TOLERANCE
                );
                let p = &e.peaks;
                println!(
                    "full-rate peaks: |τ1| {:.6} ± {:.1e} N at {:.3} s, |τ2| {:.6} ± {:.1e} N m at {:.3} s, |q| {:.6} ± {:.1e} m, |θ| {:.6} ± {:.1e} rad",
                    p.tau1.abs_max.value, p.tau1.abs_max.error, p.tau1.t,
                    p.tau2.abs_max.value, p.tau2.abs_max.error, p.tau2.t,
                    p.q_tip.abs_max.value, p.q_tip.abs_max.error,
                    p.theta_tip.abs_max.value, p.theta_tip.abs_max.error
                );
                println!(
                    "tip-rate peaks: |q̇| {:.4e} ± {:.1e} m/s at {:.3e} s{}, |θ̇| {:.4e} ± {:.1e} rad/s at {:.3e} s{}",
                    p.q_tip_rate.abs_max.value,
                    p.q_tip_rate.abs_max.error,
                    p.q_tip_rate.t,
                    if p.q_tip_rate.grid_converged { "" } else { " (not converged in the grid)" },
                    p.theta_tip_rate.abs_max.value,
                    p.theta_tip_rate.abs_max.error,
                    p.theta_tip_rate.t,
                    if p.theta_tip_rate.grid_converged { "" } else { " (not converged in the grid)" },
                );
                match &e.sub_step_check {
                    SubStepCheck::Probed => {}
                    SubStepCheck::Twin { raised } => println!(
                        "sub-step check: an exponential twin probed inside its steps after every jump; it raised the ± of {raised} peak(s)"
                    ),
                    SubStepCheck::Unavailable { reason } => {
                        println!("sub-step check: none ({reason}); a transient shorter than dt after a later jump is not covered")
                    }
                }
            }
        }
        if let Some(l) = &out.initial_layer {
            println!(
                "initial layer [0, {}] s re-run {} time(s) down to dt = {:e} s: {}{}",
                l.t_end,
                l.runs,
                l.finest_dt,
                if l.converged { "peaks converged" } else { "peaks NOT converged within the work budget" },
                if l.raised { "; a sub-step transient raised a peak above the base run's" } else { "" }
            );
        }
        let [probed, raised] = out.stats.sub_step_probes;
        if probed > 0 {
            println!(
                "sub-step probe: the exact solution inside the first step after each of {probed} jump(s) of the held inputs; {raised} raised a full-rate peak above the step ends"
            );
        } else if estimated.is_none() && out.stats.stepper != wingcheck_model::TimeScheme::Exponential {
            println!(
                "peaks at the step ends (and the resolved initial layer): the {} scheme has no sub-step probe, so a transient shorter than dt after a later jump is not seen (--error-estimate checks for one with an exponential twin)",
                out.stats.stepper
            );
        }
        if let Some(p) = &a.out {
            println!("wrote {}", p.display());
        }
    }
    Ok(())
}

/// Fail before any work if the output cannot be written (bad extension, missing directory, a
/// name too long, a symlink or special file in the way: `wingcheck_io::check_output_file`).
fn check_writable(path: &std::path::Path) -> anyhow::Result<()> {
    let ext = path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase()).unwrap_or_default();
    if ext != "csv" && ext != "json" {
        anyhow::bail!("--out {}: use a .csv or .json file name", path.display());
    }
    let sidecar = (ext == "csv").then_some(wingcheck_io::SIDECAR_SUFFIX);
    anyhow::Context::context(wingcheck_io::check_output_file_with(path, sidecar), "--out")
}

/// `simulate --json`: the settings run, the cost, the tip values at the requested times and the
/// full-rate peaks (docs/schema/simulate.schema.json).
#[derive(Serialize, schemars::JsonSchema)]
pub struct SimulateSummary {
    /// Layout version ([`wingcheck_io::SCHEMA_VERSION`]).
    pub schema_version: u32,
    /// Tool build and the configuration's SHA-256 (the files listed: `--out`, if given).
    pub provenance: wingcheck_io::Provenance,
    /// What was run.
    pub settings: RunSettings,
    /// Wall time of the run (s; not reproducible).
    pub run_seconds: f64,
    /// Cost statistics.
    pub stats: wingcheck_sim::RunStats,
    /// The tip at the sample times.
    pub tip: TipValues,
    /// Full-rate peaks (every integrator step, both sides of each jump).
    pub peaks: wingcheck_sim::Peaks,
    /// How the initial layer was resolved (peaks within it from runs at finer steps).
    pub initial_layer: Option<wingcheck_sim::layer::InitialLayer>,
    /// The output file written, if any.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub out: Option<String>,
    /// With `--error-estimate`: the discretisation error estimate.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error_estimate: Option<ErrorSummary>,
}

/// The settings of a simulate run.
#[derive(Serialize, schemars::JsonSchema)]
pub struct RunSettings {
    /// Controller: none, pd, ftdo, dobc.
    pub controller: String,
    /// Observer rule: implicit or explicit.
    pub observer: String,
    /// Spatial discretisation: fe or fd.
    pub method: String,
    /// Elements (FE) or intervals (FD).
    pub elements: usize,
    /// Mesh grading (FE; 0 = uniform).
    pub grading: f64,
    /// Integrator step (s).
    pub dt: f64,
    /// The time scheme used.
    pub stepper: wingcheck_model::TimeScheme,
    /// Observer sample period (s).
    pub sample_period: f64,
    /// Horizon T (s).
    pub t_end: f64,
    /// Weight a of the control law (15) (dimensionless).
    pub a: f64,
    /// Weight b of the control law (15) (s).
    pub b: f64,
}

/// Tip values at the sample times, with their errors under `--error-estimate`.
#[derive(Serialize, schemars::JsonSchema)]
pub struct TipValues {
    /// Sample times (s).
    pub t: Vec<f64>,
    /// q(s,t) (m).
    pub q: Vec<f64>,
    /// θ(s,t) (rad).
    pub theta: Vec<f64>,
    /// Estimated error of each q (m), with `--error-estimate`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub q_error: Option<Vec<f64>>,
    /// Estimated error of each θ (rad), with `--error-estimate`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub theta_error: Option<Vec<f64>>,
}

/// The error estimate of `--error-estimate`.
#[derive(Serialize, schemars::JsonSchema)]
pub struct ErrorSummary {
    /// Elements (intervals) of the refined grid.
    pub refined_grid: usize,
    /// Integrator step of the refined run (s).
    pub refined_dt: f64,
    /// Time scheme of the refined runs.
    pub refined_stepper: wingcheck_model::TimeScheme,
    /// Largest estimated error of q(s,t) over the horizon (m).
    pub max_q_tip_error: f64,
    /// Largest estimated error of θ(s,t) over the horizon (rad).
    pub max_theta_tip_error: f64,
    /// Its spatial part (relative to the tip scale).
    pub max_space_error: f64,
    /// Its time-step part.
    pub max_time_error: f64,
    /// The tolerance the estimate is held against.
    pub tolerance: f64,
    /// Whether the estimates meet it.
    pub meets_tolerance: bool,
    /// Peaks with their errors.
    pub peaks: wingcheck_sim::PeakEstimates,
    /// How the peaks were checked for sub-step transients after the initial layer.
    pub sub_step_check: SubStepCheck,
    /// How the estimate is made.
    pub basis: String,
}

fn summary(
    cfg: &wingcheck_model::Config,
    out: &wingcheck_sim::SimOutput,
    sample_times: &[f64],
    wall: f64,
    path: Option<&std::path::Path>,
    estimated: Option<&EstimatedRun>,
) -> SimulateSummary {
    let s = &out.series;
    let tips: Option<Vec<_>> = estimated.map(|e| sample_times.iter().map(|&t| e.tip_at(t)).collect());
    let files = path
        .map(|p| wingcheck_io::FileRecord {
            file: p.display().to_string(),
            contents: "the run written by --out".into(),
        })
        .into_iter()
        .collect();
    SimulateSummary {
        schema_version: wingcheck_io::SCHEMA_VERSION,
        provenance: wingcheck_io::Provenance::new(&cfg.sha256(), files),
        settings: RunSettings {
            controller: cfg.control.kind.name().into(),
            observer: cfg.observer.rule.name().into(),
            method: cfg.discretisation.method.name().into(),
            elements: cfg.discretisation.grid_size(),
            grading: cfg.discretisation.grading,
            dt: cfg.discretisation.dt,
            stepper: out.stats.stepper,
            sample_period: cfg.observer.sample_period,
            t_end: cfg.horizon.t_end,
            a: cfg.control.a,
            b: cfg.control.b,
        },
        run_seconds: wall,
        stats: out.stats.clone(),
        tip: TipValues {
            t: sample_times.to_vec(),
            q: sample_times.iter().map(|&t| s.at(&s.q_tip, t)).collect(),
            theta: sample_times.iter().map(|&t| s.at(&s.theta_tip, t)).collect(),
            q_error: tips.as_ref().map(|v| v.iter().map(|x| x.0.error).collect()),
            theta_error: tips.as_ref().map(|v| v.iter().map(|x| x.1.error).collect()),
        },
        peaks: out.peaks,
        initial_layer: out.initial_layer,
        out: path.map(|p| p.display().to_string()),
        error_estimate: estimated.map(|e| ErrorSummary {
            refined_grid: e.refined_grid,
            refined_dt: e.refined_dt,
            refined_stepper: e.refined_stepper,
            max_q_tip_error: e.max_q_tip_error,
            max_theta_tip_error: e.max_theta_tip_error,
            max_space_error: e.max_space_error,
            max_time_error: e.max_time_error,
            tolerance: e.tolerance,
            meets_tolerance: e.meets_tolerance,
            peaks: e.peaks,
            sub_step_check: e.sub_step_check.clone(),
            basis: "Richardson, order 2 in h and dt, safety factor 1.25: (5/3)·|u(N) − u(2N)| + (5/3)·|u(dt) − u(dt/2)| per output sample, maximised over ±0.1 s; peaks at full rate with the initial layer resolved at finer steps (its last change), a 4N grid check inside the layer, the sub-step probe's resolution after later jumps (the exponential scheme's own, or an exponential twin's excess over a scheme without one), and a round-off floor of 256 ulp".into(),
        }),
    }
}
