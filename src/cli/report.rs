//! `wingcheck report`: the self-contained HTML report.

use std::path::PathBuf;

use clap::Args;
use wingcheck_report::{Overall, ReportOptions};

use super::common::ConfigArgs;
use super::progress::Progress;

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
    // One bar over the whole report (per mille of the overall fraction): it never restarts.
    let shown = Progress::new("report");
    let on_progress = |p: Overall| shown.set((p.fraction * 1000.0).round() as u64, 1000, "", p.stage);
    let command_line = wingcheck_report::command_text(&std::env::args_os().collect::<Vec<_>>());
    let opts = ReportOptions { overall: Some(&on_progress), command_line: Some(&command_line), ..Default::default() };
    let summary = wingcheck_app::ops::report(&cfg, &a.out, a.work.policy(), &opts)?;
    shown.finish();
    println!("report written to {}/index.html ({} files)", summary.out_dir.display(), summary.files.len());
    for t in &summary.timings {
        println!("  {:<12} {:>7.3} s", t.name, t.seconds);
    }
    Ok(())
}
