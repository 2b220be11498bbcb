//! The text of `bench --what search` (`wingcheck_search::bench::SearchBench`).

use wingcheck_search::bench::{SearchBench, RULE_ROUNDS};

/// Print the search bench: the per-thread-count table, the per-point costs and the ratios,
/// each ratio from CPU time where known, its wall-time twin beside it.
pub fn print(b: &SearchBench) {
    println!("search: {} points ({}), one run per thread count", b.points, b.axes.join(" × "));
    println!("threads  wall (s)  points/s  CPU (s)  points/CPU-s  closed loop Σ (s)  theory Σ (s)  failed points");
    for r in &b.runs {
        let cpu = r.cpu_seconds.map_or("-".to_string(), |c| format!("{c:.2}"));
        let per_cpu = r.cpu_seconds.map_or("-".to_string(), |c| format!("{:.1}", b.points as f64 / c));
        println!(
            "{:>7}  {:>8.2}  {:>8.1}  {:>7}  {:>12}  {:>17.2}  {:>12.2}  {:>13}",
            r.threads,
            r.wall_seconds,
            r.points_per_second,
            cpu,
            per_cpu,
            r.closed_loop_seconds,
            r.theory_seconds,
            r.failed
        );
    }
    println!("(Σ columns are wall times summed over points: they include time the threads were preempted)");
    println!(
        "one point's closed loop: {:.2} ms in the search vs {:.2} ms for the default `simulate` run (ratio {:.2}; CPU where known)",
        1e3 * b.modal_point_seconds,
        1e3 * b.simulator_point_seconds,
        b.modal_point_seconds / b.simulator_point_seconds
    );
    if let Some(r) = b.runs.last() {
        let walls: Vec<String> = b.most_threads_wall_seconds.iter().map(|w| format!("{w:.3}")).collect();
        match b.cpu_over_simulate_runs {
            Some(cpu) => println!(
                "ratio: search CPU / ({} × one default simulate run's CPU, timed just before and after each of {} \
                 runs at {} threads) = {cpu:.3}, the median of the runs' ratios (wall, which moves with load: {:.3}; \
                 walls {} s)",
                b.points,
                walls.len(),
                r.threads,
                b.wall_over_simulate_runs,
                walls.join(", ")
            ),
            None => println!(
                "ratio: search wall at {} threads ({} s) / ({} × one default simulate run) = {:.3}, the median of the \
                 runs' ratios (wall time: moves with the machine's load)",
                r.threads,
                walls.join(", "),
                b.points,
                b.wall_over_simulate_runs
            ),
        }
    }
    for r in &b.rules {
        let cpu = r.cpu_seconds_per_point.map_or("-".into(), |c| format!("{:.2}", 1e3 * c));
        println!(
            "observer.rule={} ({} scheme), {} points: {:.2} ms wall, {cpu} ms CPU per point (median of {} runs)",
            r.rule,
            r.scheme,
            r.points,
            1e3 * r.wall_seconds_per_point,
            RULE_ROUNDS
        );
    }
    let cpu = b.explicit_over_implicit_cpu.map_or("-".into(), |c| format!("{c:.2}"));
    println!(
        "ratio: explicit / implicit observer per point = {cpu} (CPU), {:.2} (wall); medians of the ratios of \
         {RULE_ROUNDS} back-to-back pairs",
        b.explicit_over_implicit_wall,
    );
    println!(
        "once per search: modal basis {:.2} ms, observer signal {:.2} ms (CPU where known); final files {:.2} s wall",
        1e3 * b.modal_basis_seconds,
        1e3 * b.input_signal_seconds,
        b.finalize_seconds
    );
    if let Some(r) = b.runs.last() {
        println!(
            "10 000 points at {} threads: ≈ {:.0} s wall at the measured {:.1} points/s (under this run's load)",
            r.threads,
            1e4 / r.points_per_second,
            r.points_per_second
        );
    }
}
