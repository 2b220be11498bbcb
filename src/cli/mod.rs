//! Command-line interface.

mod bench;
mod bench_search;
mod check;
mod common;
mod compare;
mod modes;
mod progress;
mod proofs;
mod report;
mod schema;
mod search;
mod simulate;
mod table;

use clap::{Parser, Subcommand};

pub use common::ConfigArgs;

/// Simulate a flexible coupled bending–torsion wing under boundary control and check the
/// claims of the paper, with every assumption visible.
#[derive(Debug, Parser)]
#[command(name = "wingcheck", version, about)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Run the closed loop and write/print the time series.
    Simulate(simulate::SimulateArgs),
    /// Natural frequencies of the undamped, uncontrolled wing.
    Modes(modes::ModesArgs),
    /// Write the self-contained HTML report (claim ledger, Figures 3–20, accuracy, provenance).
    Report(report::ReportArgs),
    /// Map the gain region where the theorems' conditions hold and where the closed loop performs.
    ///
    /// Exit status: 0 every point ok, 3 finished with some points failed (failures.csv),
    /// 1 an error, 2 a usage error.
    Search(search::SearchArgs),
    /// Combine the output directories of `search --shard K/N` runs.
    ///
    /// Exit status: 0 every point ok, 3 merged with some points failed (failures.csv),
    /// 1 an error (e.g. missing chunks), 2 a usage error.
    Merge(search::MergeArgs),
    /// The claim ledger: one verdict per claim of the paper, with evidence and assumptions.
    Check(check::CheckArgs),
    /// Built-in controllers side by side: RMS and peak tip response, settling, control effort
    /// and energy, each with its error; `--svg` draws their tip responses and inputs.
    Compare(compare::CompareArgs),
    /// Write exact certificates for the definiteness/infeasibility facts (default: proofs/).
    Certify(proofs::CertifyArgs),
    /// Re-check certificates in exact rational arithmetic, independent of the solvers.
    Verify(proofs::VerifyArgs),
    /// Measure performance: simulator (time per step vs one sparse solve, scaling), check, report.
    Bench(bench::BenchArgs),
    /// Print the effective configuration (the embedded default, a --config file merged over it,
    /// then --set); `--diff`: only what differs from the default.
    Config(ConfigCmdArgs),
    /// Write the JSON Schemas of the configuration and of every JSON output (docs/schema/).
    Schema(schema::SchemaArgs),
}

/// Arguments of `wingcheck config`.
#[derive(Debug, clap::Args)]
pub struct ConfigCmdArgs {
    #[command(flatten)]
    config: ConfigArgs,
    /// Print only the keys whose values differ from the embedded default (configs/paper.json),
    /// each with the default value and the effective one.
    #[arg(long)]
    diff: bool,
}

impl ConfigCmdArgs {
    fn run(&self) -> anyhow::Result<()> {
        let cfg = self.config.load()?;
        if !self.diff {
            println!("{}", cfg.to_json_pretty());
            return Ok(());
        }
        let changes = wingcheck_model::Config::paper().diff(&cfg);
        if changes.is_empty() {
            println!("the effective configuration is the default (configs/paper.json)");
        }
        for (key, default, value) in changes {
            println!("{key}: {value} (default {default})");
        }
        Ok(())
    }
}

/// Dispatch a parsed command line.
pub fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Simulate(a) => simulate::run(a),
        Command::Modes(a) => modes::run(a),
        Command::Bench(a) => bench::run(a),
        Command::Check(a) => check::run(a),
        Command::Compare(a) => compare::run(a),
        Command::Report(a) => report::run(a),
        Command::Search(a) => search::run_search(a),
        Command::Merge(a) => search::run_merge(a),
        Command::Certify(a) => proofs::certify(a),
        Command::Verify(a) => proofs::verify(a),
        Command::Config(a) => a.run(),
        Command::Schema(a) => schema::run(a),
    }
}
