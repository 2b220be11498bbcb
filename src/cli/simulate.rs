//! `wingcheck simulate`.

use std::path::PathBuf;

use clap::Args;
use wingcheck_app::{Cancel, SimulateRequest, SimulateSummary};
use wingcheck_model::{ControllerKind, Method, ObserverRule};
use wingcheck_sim::{SubStepCheck, TIP_TOLERANCE};

use super::common::ConfigArgs;
use super::progress::Progress;

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
    let wants_fields = a.out.as_ref().is_some_and(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("json")));
    let req = SimulateRequest {
        controller: a.controller,
        observer: a.observer,
        method: a.method,
        sample_every: a.sample_every,
        error_estimate: a.error_estimate,
        fields: wants_fields,
        sample_times: a.sample_times.clone(),
        out: a.out.clone(),
    };
    let cfg = req.config(&a.config.source())?;
    let shown = Progress::new("simulate");
    let mut progress = |f: f64| shown.set((f * 1000.0).round() as u64, 1000, "", "");
    let result = wingcheck_app::simulate::run(&cfg, &req, a.work.policy(), Some(&mut progress), &Cancel::new())?;
    shown.finish();
    let (out, estimated, sample_times, wall) =
        (&result.output, result.estimate.as_ref(), &result.sample_times, result.wall_seconds);
    let s = &out.series;
    if a.json {
        let summary = SimulateSummary::of(&cfg, &result, a.out.as_deref());
        println!("{}", serde_json::to_string_pretty(&summary)?);
    } else {
        let loop_text = wingcheck_app::simulate::controller_phrase(&cfg);
        println!(
            "{loop_text}, {} with {} {}, dt = {} s ({}, {} basis): {} steps in {:.3} s",
            cfg.discretisation.method.name(),
            cfg.discretisation.grid_size(),
            if cfg.discretisation.method == Method::Fe { "elements" } else { "intervals" },
            cfg.discretisation.dt,
            out.stats.stepper,
            out.stats.basis,
            out.stats.steps,
            wall
        );
        match estimated {
            None => {
                println!("{:>8} {:>14} {:>14}", "t (s)", "q(s,t) (m)", "θ(s,t) (rad)");
                for &t in sample_times {
                    println!("{:>8} {:>14.6e} {:>14.6e}", t, s.at(&s.q_tip, t), s.at(&s.theta_tip, t));
                }
            }
            Some(e) => print_estimate(e, sample_times),
        }
        print_run_notes(out, estimated.is_some());
        if let Some(p) = &a.out {
            println!("wrote {}", p.display());
        }
    }
    Ok(())
}

/// The tip table's error columns, the horizon's largest errors and the full-rate peaks of an
/// error-estimated run.
fn print_estimate(e: &wingcheck_sim::EstimatedRun, sample_times: &[f64]) {
    println!("{:>8} {:>14} {:>9} {:>14} {:>9}", "t (s)", "q(s,t) (m)", "± error", "θ(s,t) (rad)", "± error");
    for &t in sample_times {
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
    let at = |t: f64| if t == 0.0 { "0".to_string() } else { wingcheck_model::quantity::with_significant(t, 4) };
    println!("full-rate peaks (± from h on N, 2N, 4N; dt; the initial layer; the sub-step probe; round-off):");
    for (name, peak, unit) in [
        ("|τ1|", &p.tau1, "N"),
        ("|τ2|", &p.tau2, "N m"),
        ("|q|", &p.q_tip, "m"),
        ("|θ|", &p.theta_tip, "rad"),
        ("|q̇|", &p.q_tip_rate, "m/s"),
        ("|θ̇|", &p.theta_tip_rate, "rad/s"),
    ] {
        println!("  {name} {} at {} s", peak.text(unit), at(peak.t));
    }
    if let wingcheck_sim::ThirdGrid::NotRun { reason } = &e.third_grid {
        println!("  (the peaks' 4N grid did not run: {reason}; no peak is called converged in the grid)");
    }
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

/// How the run's peaks were resolved: the initial layer's re-runs and the sub-step probe (or
/// why there is none).
fn print_run_notes(out: &wingcheck_sim::SimOutput, estimated: bool) {
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
    } else if !estimated && out.stats.stepper != wingcheck_model::TimeScheme::Exponential {
        println!(
            "peaks at the step ends (and the resolved initial layer): the {} scheme has no sub-step probe, so a transient shorter than dt after a later jump is not seen (--error-estimate checks for one with an exponential twin)",
            out.stats.stepper
        );
    }
}
