//! The work estimate bounds the work (issue 25, class 3): over random valid configurations —
//! spans 0.1 m to 1e5 m, sample periods down to 1e-7 s, element counts up to the limit of 4000
//! — `simulate`, `check` and `report` either finish within max(2 × their estimate, 5 s) or are
//! refused before starting, naming the estimate. Before this, `check` ran > 12 min on
//! `wing.span=1000, t_end=2` (Lemma 2's counterexample in exact rationals), > 15 min with
//! every period at 1e-7 s (the finite-time rows' digital runs ignore t_end) and 227 s at 4000
//! elements with t_end = 0.01 (estimate 0.1 s).
//!
//! Time is the command's CPU time (user + system over all its threads, from /proc/PID/stat),
//! because the estimates are for one core and wall time on a shared machine measures everyone
//! else's load too; a run is killed at 4 × its allowance of wall time. Cost in CI: the three
//! reproductions (≈ 15–25 s together) and 6 random cases (those estimated above 20 s but
//! inside the limits are redrawn; each takes ≤ max(2 × estimate, 5 s)), about a minute.

mod common;

use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use common::paper_with;
use proptest::prelude::*;
use wingcheck_model::work::{WorkEstimate, DEFAULT_LIMITS};
use wingcheck_model::{apply_overrides, Config};

/// Largest estimate (s) a random case is run for (the rest inside the limits are redrawn).
const RUN_BUDGET_S: f64 = 20.0;

/// CPU seconds (user + system, all threads) of a running process, from /proc/PID/stat.
fn cpu_seconds(pid: u32) -> Option<f64> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    let rest = &stat[stat.rfind(')')? + 2..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks: f64 = f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?;
    Some(ticks / 100.0) // USER_HZ is 100 on Linux
}

/// What happened to one command.
struct Outcome {
    refused: bool,
    cpu: f64,
    wall: f64,
    stderr: String,
}

/// Runs the command, polling its CPU time; kills it past `wall_limit`.
fn run_timed(mut cmd: Command, wall_limit: Duration) -> Outcome {
    let start = Instant::now();
    let mut child: Child = cmd.stdout(Stdio::null()).stderr(Stdio::piped()).spawn().expect("binary runs");
    let pid = child.id();
    let mut cpu = 0.0_f64;
    loop {
        if let Some(c) = cpu_seconds(pid) {
            cpu = cpu.max(c);
        }
        if child.try_wait().unwrap().is_some() {
            break;
        }
        if start.elapsed() > wall_limit {
            let _ = child.kill();
            let _ = child.wait();
            panic!(
                "killed after {:.1} s of wall time ({cpu:.1} s CPU): the estimate did not bound the work",
                start.elapsed().as_secs_f64()
            );
        }
        std::thread::sleep(Duration::from_millis(25));
    }
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    Outcome { refused: stderr.contains("refused before starting"), cpu, wall: start.elapsed().as_secs_f64(), stderr }
}

/// The estimate the command uses for its guard.
fn estimate(command: &str, cfg: &Config) -> WorkEstimate {
    match command {
        "simulate" => WorkEstimate::simulation(cfg, false, None),
        "check" => wingcheck_claims::plan::check_estimate(cfg, &Default::default()),
        "report" => wingcheck_report::report_estimate(cfg),
        other => panic!("{other}"),
    }
}

/// `command` on `cfg`: refused before starting if its estimate is above the limits, else done
/// within max(2 × estimate, 5 s) of CPU time. Returns (estimate, CPU s) when it ran.
fn assert_bounded(command: &str, cfg: &Config, dir: &Path) -> Option<(f64, f64)> {
    let est = estimate(command, cfg);
    let path = dir.join("cfg.json");
    std::fs::write(&path, cfg.to_json_pretty()).unwrap();
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_wingcheck"));
    cmd.arg(command).arg("--config").arg(&path);
    if command == "report" {
        cmd.arg("--out").arg(dir.join("report"));
    }
    if est.within(&DEFAULT_LIMITS).is_err() {
        let o = run_timed(cmd, Duration::from_secs(20));
        assert!(o.refused, "{command}: estimate {est:?} above the limits but not refused: {}", o.stderr);
        assert!(o.wall < 5.0, "{command}: the refusal took {:.1} s", o.wall);
        return None;
    }
    let allowed = (2.0 * est.seconds).max(5.0);
    let o = run_timed(cmd, Duration::from_secs_f64(4.0 * allowed + 5.0));
    assert!(!o.stderr.contains("panicked"), "{command}: {}", o.stderr);
    assert!(
        o.cpu <= allowed,
        "{command}: {:.2} s CPU ({:.2} s wall) > max(2 × estimate {:.3} s, 5 s); stderr: {}",
        o.cpu,
        o.wall,
        est.seconds,
        o.stderr
    );
    Some((est.seconds, o.cpu))
}

#[test]
fn the_issues_reproductions_finish_within_their_estimates() {
    let dir = tempfile::tempdir().unwrap();
    for sets in [
        &["wing.span=1000", "horizon.t_end=2"][..],
        &["observer.sample_period=1e-7", "discretisation.dt=1e-7", "horizon.t_end=1e-7", "horizon.sample_every=1e-7"],
        &["discretisation.elements=4000", "horizon.t_end=0.01"],
    ] {
        let cfg = paper_with(sets);
        let ran = assert_bounded("check", &cfg, dir.path());
        eprintln!("check {sets:?}: estimate and CPU time {ran:?}");
    }
}

/// A random valid configuration: the span, the sample period (down to 1e-7 s), the time step,
/// the horizon, the output interval, the grid (up to 4000 elements or intervals), the observer
/// rule and the controller.
fn config() -> impl Strategy<Value = Config> {
    (
        (-1.0f64..5.0).prop_map(|e| 10f64.powf(e)),
        prop_oneof![Just(1e-7), Just(1e-6), Just(1e-5), Just(1e-4), Just(1e-3), Just(1e-2)],
        prop_oneof![Just(1usize), Just(2), Just(5)],
        prop_oneof![Just(1usize), Just(3), Just(100), Just(2000), Just(20_000)],
        prop_oneof![Just(1usize), Just(10)],
        prop_oneof![Just(2usize), Just(24), Just(100), Just(101), Just(600), Just(4000)],
        any::<bool>(),
        prop_oneof![Just("implicit"), Just("explicit")],
        prop_oneof![Just("ftdo"), Just("dobc"), Just("pd"), Just("none")],
    )
        .prop_filter_map("valid", |(span, period, per, samples, every, n, fd, rule, kind)| {
            let sets = vec![
                format!("wing.span={span}"),
                format!("observer.sample_period={period}"),
                format!("discretisation.dt={}", period / per as f64),
                format!("horizon.t_end={}", period * samples as f64),
                format!("horizon.sample_every={}", period * every.min(samples) as f64),
                format!("discretisation.method={}", if fd { "fd" } else { "fe" }),
                "discretisation.grading=0".into(),
                format!("discretisation.elements={n}"),
                format!("discretisation.fd_points={n}"),
                format!("observer.rule={rule}"),
                format!("control.kind={kind}"),
            ];
            apply_overrides(&Config::paper(), &sets).ok()
        })
}

proptest! {
    // 6 cases unless PROPTEST_CASES asks for more (e.g. a longer local hunt)
    #![proptest_config(ProptestConfig {
        cases: std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(6),
        max_global_rejects: 10_000,
        ..ProptestConfig::default()
    })]
    #[test]
    fn every_command_finishes_within_its_estimate_or_is_refused(
        cfg in config(),
        command in prop_oneof![Just("simulate"), Just("check"), Just("report")],
    ) {
        let est = estimate(command, &cfg);
        // inside the limits but too long for a test run: draw another case
        prop_assume!(est.within(&DEFAULT_LIMITS).is_err() || est.seconds <= RUN_BUDGET_S);
        let dir = tempfile::tempdir().unwrap();
        let ran = assert_bounded(command, &cfg, dir.path());
        eprintln!("{command} span {} T {} dt {} t_end {} n {}: estimate and CPU time {ran:?}", cfg.wing.span,
            cfg.observer.sample_period, cfg.discretisation.dt, cfg.horizon.t_end, cfg.discretisation.grid_size());
    }
}

#[test]
fn lemma_2_at_huge_spans_is_decided_exactly_without_forming_f_to_the_2k() {
    use wingcheck_claims::lemmas;
    // k = ⌊(f² − 1)/2⌋ + 1 by hand: f = 66000 → f² = 4 356 000 000, k = 2 178 000 000 (2k
    // exceeds u32::MAX, where the exponent used to wrap and print "holds" on ω = z^0);
    // f = 1e5 → k = 5 000 000 000. ω(f)² > f∫ω² ⟺ 2k + 1 > f², true for both; the corrected
    // form holds (k² ≥ 2k − 1).
    // (written with superscript digits, the prose's one way to write a power)
    for (span, omega, lhs) in [("66000", "z²¹⁷⁸⁰⁰⁰⁰⁰⁰", "66000⁴³⁵⁶⁰⁰⁰⁰⁰⁰"), ("1e5", "z⁵⁰⁰⁰⁰⁰⁰⁰⁰⁰", "100000¹⁰⁰⁰⁰⁰⁰⁰⁰⁰⁰")]
    {
        let cfg = paper_with(&[&format!("wing.span={span}")]);
        let row = lemmas::check(&cfg, &wingcheck_claims::CheckSettings::default()).unwrap();
        let wingcheck_claims::Evidence::Lemmas(e) = &row.evidence else { panic!("lemmas evidence") };
        let cex = &e.lemma2_counterexample;
        assert_eq!(cex.omega.value, omega);
        assert_eq!(cex.lhs_omega_f_sq.value, lhs);
        assert!(cex.printed_violated.value);
        assert!(cex.corrected_holds.value);
        assert_eq!(row.verdict.name(), "holds-after-correction");
        assert!(row.finding_text().contains(lhs), "{}", row.finding_text());
    }
    // the paper's span keeps its exact digits: ω = z² on [0, 2], 16 > 64/5
    let row = lemmas::check(&paper_with(&[]), &wingcheck_claims::CheckSettings::default()).unwrap();
    let wingcheck_claims::Evidence::Lemmas(e) = &row.evidence else { panic!("lemmas evidence") };
    assert_eq!(e.lemma2_counterexample.rhs_printed.value, "64/5");
}
