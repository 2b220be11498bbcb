//! `wingcheck simulate`.

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use serde_json::json;
use wingcheck_model::{ControllerKind, Method, ObserverRule};
use wingcheck_sim::{output, simulate_with_error, RunOptions, TIP_TOLERANCE};
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
    /// those beyond the horizon dropped).
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
        None => [5.0, 10.0, 20.0].into_iter().filter(|&t| t <= cfg.horizon.t_end).collect(),
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
    let opts = RunOptions { fields: wants_fields, progress: Some(&mut progress) };
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
        let summary = json!({
            "settings": {
                "controller": cfg.control.kind.name(),
                "observer": cfg.observer.rule.name(),
                "method": cfg.discretisation.method.name(),
                "elements": cfg.discretisation.grid_size(),
                "grading": cfg.discretisation.grading,
                "dt": cfg.discretisation.dt,
                "stepper": out.stats.stepper,
                "sample_period": cfg.observer.sample_period,
                "t_end": cfg.horizon.t_end,
                "a": cfg.control.a,
                "b": cfg.control.b,
            },
            "run_seconds": wall,
            "stats": out.stats,
            "tip": {
                "t": sample_times,
                "q": sample_times.iter().map(|&t| s.at(&s.q_tip, t)).collect::<Vec<_>>(),
                "theta": sample_times.iter().map(|&t| s.at(&s.theta_tip, t)).collect::<Vec<_>>(),
            },
            "peaks": out.peaks,
            "initial_layer": out.initial_layer,
        });
        let mut summary = summary;
        if let Some(p) = &a.out {
            summary["out"] = json!(p.display().to_string());
        }
        if let Some(e) = &estimated {
            let tips: Vec<_> = sample_times.iter().map(|&t| e.tip_at(t)).collect();
            summary["tip"]["q_error"] = json!(tips.iter().map(|x| x.0.error).collect::<Vec<_>>());
            summary["tip"]["theta_error"] = json!(tips.iter().map(|x| x.1.error).collect::<Vec<_>>());
            summary["error_estimate"] = json!({
                "refined_grid": e.refined_grid,
                "refined_dt": e.refined_dt,
                "refined_stepper": e.refined_stepper,
                "max_q_tip_error": e.max_q_tip_error,
                "max_theta_tip_error": e.max_theta_tip_error,
                "max_space_error": e.max_space_error,
                "max_time_error": e.max_time_error,
                "tolerance": e.tolerance,
                "meets_tolerance": e.meets_tolerance,
                "peaks": e.peaks,
                "basis": "Richardson, order 2 in h and dt, safety factor 1.25: (5/3)·|u(N) − u(2N)| + (5/3)·|u(dt) − u(dt/2)| per output sample, maximised over ±0.1 s; peaks at full rate",
            });
        }
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
        if let Some(p) = &a.out {
            println!("wrote {}", p.display());
        }
    }
    Ok(())
}

/// Fail before any work if the output cannot be written (missing directory, bad extension).
fn check_writable(path: &std::path::Path) -> anyhow::Result<()> {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    if ext != "csv" && ext != "json" {
        anyhow::bail!("--out {}: use a .csv or .json file name", path.display());
    }
    let dir = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(std::path::Path::new("."));
    let md = std::fs::metadata(dir)
        .map_err(|e| anyhow::anyhow!("--out {}: directory {}: {e}", path.display(), dir.display()))?;
    if !md.is_dir() {
        anyhow::bail!("--out {}: {} is not a directory", path.display(), dir.display());
    }
    if md.permissions().readonly() {
        anyhow::bail!("--out {}: directory {} is read-only", path.display(), dir.display());
    }
    Ok(())
}
