//! `wingcheck compare`: built-in controllers side by side on the same wing, disturbances and
//! metrics (`wingcheck_app::compare`), as a table and optionally an SVG of their tip responses
//! and inputs on common axes.

use std::path::PathBuf;

use clap::Args;
use wingcheck_app::compare::{compare, Entrant};
use wingcheck_app::{Cancel, Front};
use wingcheck_model::ControllerKind;

use super::common::{ConfigArgs, WorkArgs};

/// Arguments of `wingcheck compare`.
#[derive(Debug, Args)]
pub struct CompareArgs {
    #[command(flatten)]
    config: ConfigArgs,
    #[command(flatten)]
    work: WorkArgs,
    /// The built-in controllers to compare, comma-separated, in table order: none, pd, ftdo,
    /// dobc (the configuration's observer rule).
    #[arg(long, value_delimiter = ',', default_value = "ftdo,dobc")]
    controllers: Vec<String>,
    /// Also write q, θ, τ1, τ2 of every controller against t on common axes to this .svg file
    /// (atomically).
    #[arg(long, value_name = "FILE")]
    svg: Option<PathBuf>,
}

pub fn run(a: CompareArgs) -> anyhow::Result<()> {
    let cfg = a.config.load()?;
    let mut entrants = Vec::with_capacity(a.controllers.len());
    for name in &a.controllers {
        let kind: ControllerKind = name.parse().map_err(|e| anyhow::anyhow!("--controllers {name}: {e}"))?;
        if entrants.iter().any(|(seen, _)| seen == name) {
            anyhow::bail!("--controllers: {name} is named twice (each controller once)");
        }
        entrants.push((name.clone(), Entrant::BuiltIn(kind)));
    }
    if let Some(path) = &a.svg {
        wingcheck_app::compare::check_svg_path(path, Front::Cli)?;
    }
    let per_row = wingcheck_app::SimulateRequest { error_estimate: true, ..Default::default() }.estimate(&cfg);
    let c = super::progress::while_running("compare", per_row.seconds * entrants.len() as f64, || {
        compare(&cfg, &entrants, a.work.policy(), &Cancel::new())
    })?;
    if let Some(path) = &a.svg {
        wingcheck_app::compare::write_svg(&c, path)?;
    }
    let (header, rows) = wingcheck_app::compare::table(&c);
    let header: Vec<&str> = header.iter().map(String::as_str).collect();
    print!("{}", super::table::text_table(&header, &rows, &[]));
    println!("errors: {}", c.error_rule);
    if let Some(path) = &a.svg {
        println!("wrote {}", path.display());
    }
    Ok(())
}
