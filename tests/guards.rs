//! Bounded work on every input: work estimates refuse huge runs before any work starts (with
//! the estimate and the override flag), and config input is bounded and strict.

mod common;

use std::process::{Command, Output};

use common::paper_with;
use wingcheck_model::work::{WorkEstimate, DEFAULT_LIMITS};
use wingcheck_model::Config;

fn wingcheck(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wingcheck")).args(args).output().expect("binary runs")
}

fn refused(args: &[&str], must_mention: &[&str]) {
    let o = wingcheck(args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{args:?} should be refused; stderr: {err}");
    assert!(!err.contains("panicked"), "{err}");
    for m in must_mention {
        assert!(err.contains(m), "{args:?}: error should mention {m:?}: {err}");
    }
}

#[test]
fn the_billion_step_run_is_refused_with_its_estimate_and_the_flag() {
    // t_end = 20 s / dt = 2e-8 s = 1e9 steps (exact division), plus the initial layer's
    // re-runs over 2 sample periods (2 ms): 1e5 steps at dt and 1e6 at dt/10 (dt/100 = 2e-10 s
    // is below the 1e-9 s floor) = 1.0011e9 steps in all.
    refused(&["simulate", "--set", "discretisation.dt=2e-8"], &["1.0011e9 steps", "--allow-large"]);
    refused(&["check", "--set", "discretisation.dt=2e-8"], &["check refused", "--allow-large"]);
    refused(&["report", "--set", "discretisation.dt=2e-8", "--out", "/nonexistent/never"], &["report refused"]);
}

#[test]
fn the_171_gb_output_is_refused_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run.json");
    refused(
        &[
            "simulate",
            "--set",
            "horizon.t_end=1e5",
            "--set",
            "horizon.sample_every=1e-3",
            "--out",
            out.to_str().unwrap(),
        ],
        &["GB of output", "GB of memory", "--allow-large"],
    );
    assert!(!out.exists());
    // The estimate itself: 1e8 + 1 samples × (16 series + 2 × 21 field values) × 32 bytes.
    let cfg = paper_with(&["horizon.t_end=1e5", "horizon.sample_every=1e-3"]);
    let est = WorkEstimate::simulation(&cfg, true, Some(true));
    assert!(est.output_bytes > 1.5e11 && est.output_bytes < 2.5e11, "{}", est.output_bytes);
    assert!(est.within(&DEFAULT_LIMITS).is_err());
}

#[test]
fn huge_modes_problems_are_refused() {
    // `modes` works on its own uniform meshes (16 … 2048 elements, sparse shift-invert), so its
    // work is bounded whatever discretisation.elements says; only --count and --tol are inputs.
    refused(&["modes", "--count", "1000000"], &["--count 1000000", "[1, 50]"]);
    refused(&["modes", "--tol", "0"], &["--tol 0", ">= 1e-13"]);
    refused(&["bench", "--repeats", "0"], &["0 is not in 1..=1000"]);
}

#[test]
fn default_work_is_far_inside_the_limits() {
    // The defaults and an SI-scale wing at 64 elements must never trip the guard.
    for cfg in [
        Config::paper(),
        paper_with(&[
            "wing.span=6",
            "wing.ei=1e7",
            "wing.gj=1e6",
            "wing.rho=100",
            "wing.ip=10",
            "discretisation.elements=64",
        ]),
    ] {
        for est in [
            WorkEstimate::simulation(&cfg, true, Some(true)),
            wingcheck_claims::plan::check_estimate(&cfg, &Default::default()),
            wingcheck_report::report_estimate(&cfg),
        ] {
            assert!(est.within(&DEFAULT_LIMITS).is_ok(), "{est:?}");
        }
    }
}

#[test]
fn config_input_is_bounded_and_strict() {
    // a device is never opened; a regular file is read up to 1 MiB
    refused(&["config", "--config", "/dev/zero"], &["it is a device, not a regular file"]);
    let dir = tempfile::tempdir().unwrap();
    let big = dir.path().join("big.json");
    std::fs::File::create(&big).unwrap().set_len(2 << 20).unwrap();
    refused(&["config", "--config", big.to_str().unwrap()], &["larger than 1048576 bytes"]);
    let p = dir.path().join("c.json");
    std::fs::write(&p, format!("{} {{\"x\": 1}}", wingcheck_model::PAPER_JSON)).unwrap();
    refused(&["config", "--config", p.to_str().unwrap()], &["trailing data"]);
    for field in ["rho", "ei", "gj", "ip"] {
        let set = format!("wing.{field}=1e308");
        refused(&["config", "--set", &set], &[&format!("wing.{field} = 1e308 is out of range"), "1e12"]);
    }
    refused(&["config", "--set", "control.k1=1e300"], &["control.k1 = 1e300"]);
}

#[test]
fn bench_is_guarded_like_the_commands_it_times() {
    // dt = 2e-8: 1e9 steps per timed run, repeated; t_end = 1e5: 1e8 steps and 13 GB of samples
    refused(&["bench", "--set", "discretisation.dt=2e-8"], &["bench refused before starting", "--allow-large"]);
    refused(&["bench", "--set", "horizon.t_end=1e5"], &["bench refused before starting"]);
    refused(&["bench", "--what", "check", "--set", "horizon.t_end=1e4"], &["bench refused before starting"]);
    // issue 46, item 2: `bench --what search` had no guard (2.31 GB RSS when killed at 40 s, five
    // unguarded simulate runs first); now its simulate timings and every search it runs are
    // estimated and refused together, before any work
    let start = std::time::Instant::now();
    refused(
        &["bench", "--what", "search", "--set", "horizon.t_end=1e5", "--set", "horizon.sample_every=1e-3"],
        &["bench refused before starting", "GB of memory", "--allow-large"],
    );
    assert!(start.elapsed().as_secs_f64() < 5.0, "refused before any run ({:?})", start.elapsed());
    // the default benchmark of each kind is within the limits (it runs); `report` times two
    // reports five times over and is refused at the defaults (its --repeats lowers it)
    let cfg = Config::paper();
    let search = wingcheck_search::bench::bench_estimate(
        &cfg,
        wingcheck_search::bench::GRID_POINTS,
        &wingcheck_search::bench::THREAD_COUNTS,
    )
    .unwrap();
    assert!(search.within(&DEFAULT_LIMITS).is_ok(), "{search:?}");
    assert!(WorkEstimate::modes(&cfg, cfg.discretisation.method, 50).within(&DEFAULT_LIMITS).is_ok());
    // `bench --what sim` times `modes` `repeats` times: counted at its worst case (every mesh
    // at the iteration limit)
    refused(&["bench", "--repeats", "1000"], &["bench refused before starting"]);
}
