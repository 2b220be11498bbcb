//! The command line as a user meets it: determinism, outputs, and clear errors for bad input
//! (nonzero exit, no panic, no partial file).

use std::path::Path;
use std::process::{Command, Output};

fn wingcheck(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wingcheck")).args(args).output().expect("binary runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn assert_clean_failure(o: &Output, must_mention: &str) {
    let err = stderr(o);
    assert!(!o.status.success(), "expected failure, got success; stderr: {err}");
    assert!(!err.contains("panicked"), "panic instead of an error: {err}");
    assert!(err.contains(must_mention), "error should mention `{must_mention}`: {err}");
}

const SHORT: [&str; 2] = ["--set", "horizon.t_end=2"];

#[test]
fn same_input_gives_bit_identical_output() {
    let dir = tempfile::tempdir().unwrap();
    let mut files = Vec::new();
    for i in 0..2 {
        let p = dir.path().join(format!("run{i}.json"));
        let o = wingcheck(&["simulate", SHORT[0], SHORT[1], "--out", p.to_str().unwrap()]);
        assert!(o.status.success(), "{}", stderr(&o));
        files.push(std::fs::read(&p).unwrap());
    }
    // Wall times are in `stats`; everything else must match bit for bit.
    let strip = |b: &[u8]| {
        let mut v: serde_json::Value = serde_json::from_slice(b).unwrap();
        v.as_object_mut().unwrap().remove("stats");
        v.to_string()
    };
    assert_eq!(strip(&files[0]), strip(&files[1]));
    let csv: Vec<Vec<u8>> = (0..2)
        .map(|i| {
            let p = dir.path().join(format!("run{i}.csv"));
            assert!(wingcheck(&["simulate", SHORT[0], SHORT[1], "--out", p.to_str().unwrap()]).status.success());
            std::fs::read(&p).unwrap()
        })
        .collect();
    assert_eq!(csv[0], csv[1]);
}

#[test]
fn json_output_holds_series_and_fields() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("run.json");
    let o = wingcheck(&["simulate", "--controller", "dobc", SHORT[0], SHORT[1], "--out", p.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&p).unwrap()).unwrap();
    for col in [
        "t",
        "q_tip",
        "theta_tip",
        "q_tip_rate",
        "theta_tip_rate",
        "tau1",
        "tau2",
        "g1",
        "g2",
        "g1_hat",
        "g2_hat",
        "sigma1",
        "sigma2",
        "energy",
    ] {
        assert_eq!(v["series"][col].as_array().unwrap().len(), 201, "column {col}");
    }
    assert_eq!(v["fields"]["q"].as_array().unwrap().len(), 201);
    assert_eq!(v["fields"]["z"].as_array().unwrap().len(), 21);
    // the field at the tip is the tip series (same state, interpolation exact at nodes)
    let q_last = v["fields"]["q"][200].as_array().unwrap().last().unwrap().as_f64().unwrap();
    let tip_last = v["series"]["q_tip"][200].as_f64().unwrap();
    assert!((q_last - tip_last).abs() < 1e-15, "{q_last} vs {tip_last}: {:e}", q_last - tip_last);
    assert_eq!(v["config"]["control"]["kind"], "dobc");
}

#[test]
fn json_summary_reports_tip_values_at_requested_times() {
    let o = wingcheck(&["simulate", "--json", "--sample-times", "0.5,1", SHORT[0], SHORT[1]]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["tip"]["t"], serde_json::json!([0.5, 1.0]));
    assert_eq!(v["tip"]["q"].as_array().unwrap().len(), 2);
    assert!(v["run_seconds"].as_f64().unwrap() > 0.0);
    // a horizon shorter than every default time: the summary reports its end, not nothing
    let o = wingcheck(&["simulate", "--json", SHORT[0], SHORT[1]]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let end = v["tip"]["t"].as_array().unwrap();
    assert_eq!(end.len(), 1, "{end:?}");
    assert!(end[0].as_f64().unwrap() < 5.0, "{end:?}");
}

#[test]
fn modes_json_has_coupled_frequencies() {
    let o = wingcheck(&["modes", "--json", "--count", "4"]);
    assert!(o.status.success());
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let f = v["coupled_rad_s"].as_array().unwrap();
    assert_eq!(f.len(), 4);
    // Reference: FD/FE extrapolated first coupled frequency 0.1208599 rad/s (tests/modes.rs);
    // the default 16-element graded FE mesh is within 1e-5 of it.
    assert!((f[0].as_f64().unwrap() - 0.1208599).abs() < 1e-5, "{f:?}");
}

#[test]
fn bad_values_name_the_field_and_range() {
    assert_clean_failure(&wingcheck(&["simulate", "--set", "wing.ei=-0.2"]), "wing.ei");
    assert_clean_failure(&wingcheck(&["simulate", "--set", "wing.ei=-0.2"]), "allowed in [1e-12, 1e12]");
    assert_clean_failure(&wingcheck(&["simulate", "--set", "wing.gj=NaN"]), "wing.gj");
    assert_clean_failure(&wingcheck(&["simulate", "--set", "discretisation.dt=0"]), "discretisation.dt");
    assert_clean_failure(&wingcheck(&["simulate", "--set", "discretisation.dt=-1e-3"]), "discretisation.dt");
    assert_clean_failure(&wingcheck(&["simulate", "--set", "wing.rho_xc=4"]), "ρ·I_p > (ρx_c)²");
    assert_clean_failure(&wingcheck(&["simulate", "--set", "wing.nope=1"]), "unknown key `wing.nope`");
    assert_clean_failure(&wingcheck(&["simulate", "--set", "control.a=-1"]), "control.a");
    assert_clean_failure(&wingcheck(&["simulate", "--set", "observer.a2=30"]), "observer.a2");
    assert_clean_failure(&wingcheck(&["simulate", "--set", "discretisation.dt=0.0007"]), "whole multiple");
}

#[test]
fn unreadable_or_malformed_config_is_a_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("missing.json");
    assert_clean_failure(&wingcheck(&["simulate", "--config", missing.to_str().unwrap()]), "cannot read config");
    let bad = dir.path().join("bad.json");
    std::fs::write(&bad, "{ \"wing\": { \"span\": 2.0, ").unwrap();
    assert_clean_failure(&wingcheck(&["simulate", "--config", bad.to_str().unwrap()]), "line");
    let unknown = dir.path().join("unknown.json");
    let mut v: serde_json::Value = serde_json::from_str(wingcheck_model::PAPER_JSON).unwrap();
    v["wing"]["stiffness"] = serde_json::json!(1.0);
    std::fs::write(&unknown, v.to_string()).unwrap();
    assert_clean_failure(&wingcheck(&["simulate", "--config", unknown.to_str().unwrap()]), "unknown field `stiffness`");
}

#[test]
fn unwritable_output_fails_before_work_and_leaves_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("no/such/dir/out.csv");
    assert_clean_failure(&wingcheck(&["simulate", "--out", target.to_str().unwrap()]), "--out");
    let wrong_ext = dir.path().join("out.txt");
    assert_clean_failure(&wingcheck(&["simulate", "--out", wrong_ext.to_str().unwrap()]), ".csv or .json");
    assert!(!wrong_ext.exists());
    // A failing run (bad config) never leaves an output or temp file behind.
    let out = dir.path().join("x.csv");
    assert_clean_failure(&wingcheck(&["simulate", "--set", "wing.ei=0", "--out", out.to_str().unwrap()]), "wing.ei");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "stray files in {}", Path::new(dir.path()).display());
}

#[test]
fn a_diverging_run_stops_with_when_and_why() {
    // The explicit digital FTDO is the map σ_{k+1} = σ_k − T φ(σ_k) + ∫g, unstable once
    // T·κ1 > 2 (|1 − Tκ1| > 1): with T = 1 ms, κ1 = 5000 the estimate grows like 4^k.
    let o = wingcheck(&["simulate", "--observer", "explicit", "--set", "observer.kappa1=5000", SHORT[0], SHORT[1]]);
    assert_clean_failure(&o, "simulation diverged at t = ");
}

#[test]
fn check_json_is_the_ledger_and_honours_overrides() {
    let o = wingcheck(&["check", "--json", "--set", "control.a=0.05"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let rows = v["rows"].as_array().unwrap();
    let ids: Vec<&str> = rows.iter().map(|r| r["id"].as_str().unwrap()).collect();
    assert_eq!(ids, ["W-bounds", "mu-conditions", "UUB", "finite-time-1", "finite-time-2", "lemmas", "ftdo-vs-dobc"]);
    // a/b = 0.05 < ω₁ ≈ 0.121: W is positive definite after the correction (tests/claims_lyapunov.rs)
    assert_eq!(rows[0]["verdict"], "holds-after-correction");
    for key in ["lambda1_printed", "lambda2_printed", "lambda1_tight", "lambda2_tight", "a_over_b_max"] {
        let q = &rows[0]["evidence"][key];
        assert!(q["value"].is_number() && q["label"].is_string() && q["unit"].is_string(), "missing {key}: {q}");
    }
}

#[test]
fn verify_rejects_a_tampered_certificate_with_nonzero_exit() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path().to_str().unwrap();
    assert!(wingcheck(&["certify", "--out", d]).status.success());
    let ok = wingcheck(&["verify", d]);
    assert!(ok.status.success(), "{}", String::from_utf8_lossy(&ok.stdout));
    let f = dir.path().join("mu-conditions-infeasible.json");
    let text = std::fs::read_to_string(&f).unwrap();
    std::fs::write(&f, text.replacen("\"1/1\"", "\"2/1\"", 1)).unwrap();
    let bad = wingcheck(&["verify", d]);
    assert!(!bad.status.success());
    let err = stderr(&bad);
    assert!(err.contains("REJECTED") && err.contains("mu-conditions-infeasible.json"), "{err}");
    // A single file is not a set: refused with the reason.
    assert_clean_failure(&wingcheck(&["verify", f.to_str().unwrap()]), "verify takes a certificate set directory");
}

#[test]
fn certify_names_the_real_cause_of_io_errors() {
    let dir = tempfile::tempdir().unwrap();
    let blocker = dir.path().join("blocker");
    std::fs::write(&blocker, "").unwrap();
    // refused before any arithmetic, naming the file in the way (issue 46)
    let o = wingcheck(&["certify", "--out", blocker.join("proofs").to_str().unwrap()]);
    assert_clean_failure(&o, "blocker is a regular file, not a directory");
    assert!(!stderr(&o).contains("numerical"), "{}", stderr(&o));
    let o = wingcheck(&["certify", "--out", blocker.to_str().unwrap()]);
    assert_clean_failure(&o, "exists and is a regular file, not a directory");
    assert_eq!(std::fs::read(&blocker).unwrap(), b"", "the file is untouched");
    let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(names.len(), 1, "no staging directory left: {names:?}");
}

#[test]
fn a_shard_asks_a_person_to_merge_only_when_no_script_does() {
    // issue 24: every shard of scripts/parallel-search.sh said "combine with wingcheck merge",
    // although the script merges. The script sets WINGCHECK_MERGED_BY; a shard run by hand
    // (or a Slurm task, whose merge job a person submits) still gets the hint.
    let dir = tempfile::tempdir().unwrap();
    let run = |out: &str, merged_by: Option<&str>| {
        let mut c = Command::new(env!("CARGO_BIN_EXE_wingcheck"));
        c.args([
            "search",
            "--over",
            "control.a=0.1,1",
            "--shard",
            "1/2",
            "--chunk-size",
            "1",
            "--set",
            "horizon.t_end=0.2",
        ]);
        c.args(["--out", dir.path().join(out).to_str().unwrap()]).env_remove("WINGCHECK_MERGED_BY");
        if let Some(by) = merged_by {
            c.env("WINGCHECK_MERGED_BY", by);
        }
        let o = c.output().unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
        String::from_utf8(o.stdout).unwrap()
    };
    let by_hand = run("a", None);
    assert!(by_hand.contains("combine the shard directories with `wingcheck merge"), "{by_hand}");
    let by_script = run("b", Some("scripts/parallel-search.sh"));
    assert!(!by_script.contains("wingcheck merge"), "{by_script}");
    assert!(by_script.contains("shard 1/2 done; scripts/parallel-search.sh merges the shards"), "{by_script}");
}

#[test]
fn bench_report_measures_the_explicit_observer_beside_the_configured_report() {
    // One sitting, alternating runs (issue: the explicit-observer report against the paper
    // report, as a ratio under one load). A 2-s horizon keeps the two reports short; the
    // reference is the JSON's own two medians (the ratio is their quotient), not a time.
    let o = wingcheck(&["bench", "--what", "report", "--repeats", "1", "--json", "--set", "horizon.t_end=2"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let (base, explicit) =
        (v["report_seconds"].as_f64().unwrap(), v["explicit_observer_report_seconds"].as_f64().unwrap());
    assert!(base > 0.0 && explicit > 0.0, "{v}");
    let ratio = v["explicit_over_configured"].as_f64().unwrap();
    assert!((ratio - explicit / base).abs() <= 1e-12 * ratio, "{v}");
    // a configuration that already uses the explicit observer has nothing to compare with
    let o = wingcheck(&[
        "bench",
        "--what",
        "report",
        "--repeats",
        "1",
        "--json",
        "--set",
        "horizon.t_end=2",
        "--set",
        "observer.rule=explicit",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(v.get("explicit_over_configured").is_none(), "{v}");
}

#[test]
fn simulate_names_the_loop_it_ran_and_an_observer_only_where_there_is_one() {
    let first_line = |controller: &str| {
        let o = wingcheck(&["simulate", "--controller", controller, SHORT[0], SHORT[1]]);
        assert!(o.status.success(), "{}", stderr(&o));
        String::from_utf8_lossy(&o.stdout).lines().next().unwrap_or_default().to_string()
    };
    let none = first_line("none");
    assert!(none.starts_with("open loop (no controller), "), "{none}");
    assert!(!none.contains("observer"), "{none}");
    assert!(first_line("pd").starts_with("pd controller (no observer), "));
    assert!(first_line("ftdo").starts_with("ftdo controller, implicit observer, "));
}
