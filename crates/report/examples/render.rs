//! Render the report of the embedded paper configuration, with a progress bar:
//! `cargo run --release -p wingcheck-report --example render -- OUT_DIR [key=value ...]`.

use std::path::PathBuf;

use wingcheck_report::{write_report, Overall, ReportOptions};

fn main() {
    let mut args = std::env::args().skip(1);
    let out = PathBuf::from(args.next().unwrap_or_else(|| "reports/paper".into()));
    let sets: Vec<String> = args.collect();
    let cfg = wingcheck_model::apply_overrides(&wingcheck_model::Config::paper(), &sets).expect("valid overrides");
    let bar = indicatif::ProgressBar::new(1000);
    let on_progress = |p: Overall| {
        bar.set_message(p.stage.to_string());
        bar.set_position((p.fraction * 1000.0).round() as u64);
    };
    let result = write_report(&cfg, &out, &ReportOptions { overall: Some(&on_progress), ..Default::default() });
    bar.finish_and_clear();
    match result {
        Ok(s) => {
            for t in &s.timings {
                println!("{:<12} {:>7.3} s", t.name, t.seconds);
            }
            println!("{} files in {}", s.files.len(), s.out_dir.display());
        }
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    }
}
