//! `wingcheck report`: the self-contained HTML report.

use std::path::PathBuf;

use clap::Args;
use wingcheck_report::{write_report, Progress, ReportOptions};

use super::common::{progress_bar, ConfigArgs};

/// Arguments of `wingcheck report`.
#[derive(Debug, Args)]
pub struct ReportArgs {
    #[command(flatten)]
    config: ConfigArgs,
    #[command(flatten)]
    work: super::common::WorkArgs,
    /// Output directory; an earlier report there is replaced atomically, anything else is refused.
    #[arg(long, value_name = "DIR", default_value = "reports/paper")]
    out: PathBuf,
}

pub fn run(a: ReportArgs) -> anyhow::Result<()> {
    let cfg = a.config.load()?;
    a.work.guard(&wingcheck_model::work::WorkEstimate::report(&cfg))?;
    let bar = progress_bar(1, "report");
    let on_progress = |p: Progress| {
        if let Some(b) = &bar {
            b.set_message(format!("report: {}", p.stage));
            b.set_length(p.total as u64);
            b.set_position(p.done as u64);
        }
    };
    let summary = write_report(&cfg, &a.out, &ReportOptions { progress: Some(&on_progress) })?;
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    println!("report written to {}/index.html ({} files)", summary.out_dir.display(), summary.files.len());
    for t in &summary.timings {
        println!("  {:<12} {:>7.3} s", t.name, t.seconds);
    }
    Ok(())
}
