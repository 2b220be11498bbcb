//! `wingcheck`: simulate a flexible coupled wing under boundary control and check the claims
//! of "Vibration Suppression of a Coupled Aircraft Wing with Finite-Time Convergence".
//! This binary is a thin layer over the workspace crates.

#![forbid(unsafe_code)]

mod cli;

use clap::Parser;

fn main() {
    wingcheck_io::tune_allocator();
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
    wingcheck_app::register_build();
    let args = cli::Cli::parse();
    if let Err(e) = cli::run(args) {
        eprintln!("error: {}", message(&e));
        std::process::exit(1);
    }
}

/// The error and its causes joined by ": ", each cause once: the crates' errors already write
/// their source into their own message ("cannot write P: No space left on device (os error
/// 28)"), so a cause whose text is already there is not repeated.
fn message(e: &anyhow::Error) -> String {
    let mut out = String::new();
    for cause in e.chain() {
        let text = cause.to_string();
        if out.contains(&text) {
            continue;
        }
        if !out.is_empty() {
            out.push_str(": ");
        }
        out.push_str(&text);
    }
    out
}
