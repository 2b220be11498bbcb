//! `wingcheck`: simulate a flexible coupled wing under boundary control and check the claims
//! of "Vibration Suppression of a Coupled Aircraft Wing with Finite-Time Convergence".
//! This binary is a thin layer over the workspace crates.

mod cli;

use clap::Parser;

fn main() {
    // `wingcheck check | head` closes stdout early: end quietly like other CLI tools instead of
    // reporting println!'s broken-pipe panic.
    let default_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let msg = info
            .payload()
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| info.payload().downcast_ref::<&str>().copied())
            .unwrap_or("");
        if msg.contains("failed printing to stdout") && msg.contains("Broken pipe") {
            std::process::exit(0);
        }
        default_hook(info);
    }));
    let args = cli::Cli::parse();
    if let Err(e) = cli::run(args) {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}
