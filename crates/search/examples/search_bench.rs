//! Benchmark: an N×N search over control.a (1e-4..10, log) × control.b (1e-2..1e4, log) on the
//! paper config (20-s FTDO closed loop per point, all metrics and the theory).
//!
//! `cargo run --release -p wingcheck-search --example search_bench -- [N] [t_end] [out_dir]`
//! (defaults 100, 20 and a temporary directory). Prints points/s and the share of time in simulation vs theory.

use std::time::Instant;

use wingcheck_model::Config;
use wingcheck_search::{run, RunControl, Search, SearchOptions};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(100);
    let t_end: f64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(20.0);
    let mut base = Config::paper();
    base.horizon.t_end = t_end;
    let specs = vec![format!("control.a=1e-4..10:log:{n}"), format!("control.b=1e-2..1e4:log:{n}")];
    let search =
        Search::new(base, &specs, SearchOptions { refine: Some(1e-3), ..Default::default() }).expect("valid search");
    let tmp = tempfile::tempdir().expect("temp dir");
    let dir = args.get(3).map(std::path::PathBuf::from).unwrap_or_else(|| tmp.path().to_path_buf());
    let start = Instant::now();
    let s = run(&search, &dir, RunControl::default()).expect("search runs");
    let wall = start.elapsed().as_secs_f64();
    let busy = s.sim_seconds + s.theory_seconds;
    println!(
        "{} points in {wall:.1} s on {} threads: {:.1} points/s; per point: simulation {:.2} ms, theory {:.2} ms; share of busy time: simulation {:.1} %, theory {:.1} %",
        s.evaluated,
        rayon::current_num_threads(),
        s.evaluated as f64 / wall,
        1e3 * s.sim_seconds / s.evaluated as f64,
        1e3 * s.theory_seconds / s.evaluated as f64,
        100.0 * s.sim_seconds / busy,
        100.0 * s.theory_seconds / busy,
    );
    let results = std::fs::read_to_string(dir.join("results.csv")).expect("results");
    let feasible = results.lines().filter(|l| l.contains(",true,true,true,")).count();
    println!("theorem-feasible points: {feasible}; files: {:?}", s.files);
}
