//! `wingcheck simulate`.

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use serde_json::json;
use wingcheck_model::{ControllerKind, Method, ObserverRule};
use wingcheck_sim::{output, simulate, RunOptions};

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
    /// Spatial discretisation: fd or fe.
    #[arg(long)]
    method: Option<Method>,
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
    a.work.guard(&wingcheck_model::work::WorkEstimate::simulation(&cfg, json_out == Some(true), json_out))?;
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
    let out = simulate(&cfg, RunOptions { fields: wants_fields, progress: Some(&mut progress) })?;
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
                "elements": cfg.discretisation.elements,
                "grading": if cfg.discretisation.method == Method::Fe { cfg.discretisation.grading } else { 0.0 },
                "dt": cfg.discretisation.dt,
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
            "out": a.out.as_ref().map(|p| p.display().to_string()),
        });
        println!("{}", serde_json::to_string_pretty(&summary)?);
    } else {
        println!(
            "{} controller, {} observer, {} with {} elements, dt = {} s: {} steps in {:.3} s",
            cfg.control.kind.name(),
            cfg.observer.rule.name(),
            cfg.discretisation.method.name(),
            cfg.discretisation.elements,
            cfg.discretisation.dt,
            out.stats.steps,
            wall
        );
        println!("{:>8} {:>14} {:>14}", "t (s)", "q(s,t) (m)", "θ(s,t) (rad)");
        let sample_times: Vec<f64> = match &a.sample_times {
            Some(v) => v.clone(),
            None => [5.0, 10.0, 20.0].into_iter().filter(|&t| t <= cfg.horizon.t_end).collect(),
        };
        for &t in &sample_times {
            println!("{:>8} {:>14.6e} {:>14.6e}", t, s.at(&s.q_tip, t), s.at(&s.theta_tip, t));
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
