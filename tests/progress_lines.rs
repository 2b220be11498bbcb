//! Long work in a log file is not silent: with stderr not a terminal (a Slurm log, CI, a pipe),
//! `search`, `report` and `check` print plain progress lines once the work has run for
//! `WINGCHECK_PROGRESS_SECONDS` (default 5; set small here so that short runs show them), and
//! stdout is unchanged.

use std::process::{Command, Output};

fn logged(args: &[&str], interval: &str) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wingcheck"))
        .args(args)
        .env("WINGCHECK_PROGRESS_SECONDS", interval)
        .output()
        .expect("binary runs")
}

fn lines(o: &Output, prefix: &str) -> Vec<String> {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stderr).lines().filter(|l| l.starts_with(prefix)).map(str::to_string).collect()
}

#[test]
fn a_search_logs_its_points_and_its_end() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("s");
    let o = logged(
        &[
            "search",
            "--over",
            "control.a=0.1..10:log:6",
            "--over",
            "control.b=1,10",
            "--set",
            "horizon.t_end=4",
            "--threads",
            "1",
            "--out",
            out.to_str().unwrap(),
        ],
        "0.001",
    );
    let l = lines(&o, "search: ");
    assert!(l.iter().any(|l| l.contains("% done (") && l.contains(" of 12 points)")), "{l:?}");
    assert!(l.last().is_some_and(|l| l.starts_with("search: done, ")), "{l:?}");
    // the percentages never go back
    let pct: Vec<f64> = l.iter().filter_map(|l| l.split('%').next()?.rsplit(' ').next()?.parse().ok()).collect();
    assert!(pct.windows(2).all(|w| w[0] <= w[1]), "{pct:?}");
}

#[test]
fn check_logs_that_it_is_running_and_its_json_is_unchanged() {
    let o = logged(&["check", "--json", "--set", "horizon.t_end=4"], "0.05");
    let l = lines(&o, "check: running, ");
    assert!(!l.is_empty(), "no progress line: {}", String::from_utf8_lossy(&o.stderr));
    assert!(l[0].contains("(estimated "), "{l:?}");
    let ledger: serde_json::Value = serde_json::from_slice(&o.stdout).expect("stdout is the ledger alone");
    assert!(ledger["rows"].is_array());
}

#[test]
fn a_report_logs_its_stages() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("r");
    let o = logged(&["report", "--set", "horizon.t_end=4", "--out", out.to_str().unwrap()], "0.001");
    let l = lines(&o, "report: ");
    assert!(l.len() >= 3 && l.iter().any(|l| l.contains("% done, ")), "{l:?}");
    assert!(l.last().is_some_and(|l| l.starts_with("report: done, ")), "{l:?}");
}

#[test]
fn short_work_under_the_default_interval_prints_nothing_on_stderr() {
    let o = Command::new(env!("CARGO_BIN_EXE_wingcheck"))
        .args(["simulate", "--set", "horizon.t_end=1"])
        .env_remove("WINGCHECK_PROGRESS_SECONDS")
        .output()
        .unwrap();
    assert!(o.status.success());
    assert!(o.stderr.is_empty(), "{}", String::from_utf8_lossy(&o.stderr));
}
