//! `wingcheck check`: the claim ledger.

use clap::Args;
use wingcheck_app::Cancel;

use super::common::ConfigArgs;

/// Arguments of `wingcheck check`.
#[derive(Debug, Args)]
pub struct CheckArgs {
    #[command(flatten)]
    config: ConfigArgs,
    #[command(flatten)]
    work: super::common::WorkArgs,
    /// Print the ledger as JSON (rows with evidence, assumptions and plot data).
    #[arg(long)]
    json: bool,
}

pub fn run(a: CheckArgs) -> anyhow::Result<()> {
    let cfg = a.config.load()?;
    let estimate = wingcheck_claims::plan::check_estimate(&cfg, &wingcheck_claims::CheckSettings::default());
    let ledger = super::progress::while_running("check", estimate.seconds, || {
        wingcheck_app::ops::check(&cfg, a.work.policy(), &Cancel::new())
    })?;
    if a.json {
        println!("{}", ledger.to_json());
        return Ok(());
    }
    println!("claim ledger ({}, config sha256 {})", ledger.tool, &ledger.config_sha256[..12]);
    let mut rows: Vec<Vec<String>> = ledger
        .rows
        .iter()
        .map(|r| {
            let seconds = ledger.wall_seconds_of(r.id.name()).unwrap_or(0.0);
            vec![
                r.id.to_string(),
                r.equation.to_string(),
                r.verdict.name().to_string(),
                r.basis.name().to_string(),
                format!("{seconds:.2} s"),
            ]
        })
        .collect();
    if let Some(seconds) = ledger.wall_seconds_of(wingcheck_claims::DIGITAL_RUNS) {
        let label = "(digital runs of both finite-time rows)".to_string();
        rows.push(vec![String::new(), label, String::new(), String::new(), format!("{seconds:.2} s")]);
    }
    print!("{}", super::table::text_table(&["id", "equation", "verdict", "basis", "wall time"], &rows, &[4]));
    println!("(wall times overlap: the rows and their parts run side by side on the thread pool)");
    for r in &ledger.rows {
        println!("\n[{}] {} ({}) — {}", r.id, r.verdict.name(), r.basis.name(), r.claim);
        println!("  decided by: {}", r.deciding);
        for s in &r.finding {
            println!("  {s}");
        }
        for q in &r.decisive {
            println!("  · {}: {} ({})", q.label, q.value_text(), q.accuracy_text());
        }
        for s in &r.details {
            println!("  {s}");
        }
        if let Some(c) = &r.correction {
            println!("  correction: {c}");
        }
        for s in &r.assumptions {
            println!("  assumed: {s}");
        }
        for c in &r.certificates {
            println!("  certificate: {c}");
        }
    }
    Ok(())
}
