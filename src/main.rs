//! `wingcheck`: simulate a flexible coupled wing under boundary control and check the claims
//! of "Vibration Suppression of a Coupled Aircraft Wing with Finite-Time Convergence".
//! This binary is a thin layer over the workspace crates.

mod cli;

use clap::Parser;

fn main() {
    let args = cli::Cli::parse();
    if let Err(e) = cli::run(args) {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}
