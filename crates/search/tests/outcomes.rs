//! A diverging simulation is a recorded outcome of its point, not a crash.

use wingcheck_model::{apply_overrides, Config};
use wingcheck_search::{modal::RunCache, Metric, Search, SearchOptions, Status, TheoryCache};

#[test]
fn diverging_points_are_recorded() {
    // Explicit sampling of the observer's linear term is a forward-Euler step of σ̇ = −κ1 σ + …
    // with T = 1 ms: stable only for κ1·T < 2, so κ1 = 1e5 (κ1·T = 100) diverges.
    let base = apply_overrides(&Config::paper(), &["horizon.t_end=1".into(), "observer.rule=explicit".into()]).unwrap();
    let s = Search::new(base, &["observer.kappa1=0.8,1e5".into()], SearchOptions::default()).unwrap();
    let cache = TheoryCache::new(8);
    let runs = RunCache::new();
    let ok = s.evaluate(0, &cache, &runs);
    assert_eq!(ok.status, Status::Ok, "{}", ok.message);
    let bad = s.evaluate(1, &cache, &runs);
    assert_eq!(bad.status, Status::Diverged);
    assert!(bad.message.contains("diverged"), "{}", bad.message);
    assert_eq!(bad.metric(Metric::RmsQTip), None);
    // the theory does not depend on κ1 and is still reported
    assert_eq!(bad.metric(Metric::Lambda2), ok.metric(Metric::Lambda2));
    assert_eq!(bad.w_positive_definite, ok.w_positive_definite);
}

#[test]
fn failed_points_are_counted_and_listed() {
    // the same two points through a whole run: the summary counts the diverged one and
    // failures.csv lists it with its reason
    let base = apply_overrides(&Config::paper(), &["horizon.t_end=1".into(), "observer.rule=explicit".into()]).unwrap();
    let s = Search::new(base, &["observer.kappa1=0.8,1e5".into()], SearchOptions::default()).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let sum = wingcheck_search::run(&s, dir.path(), Default::default()).unwrap();
    assert_eq!((sum.evaluated, sum.failed, sum.failed_total), (2, 1, Some((1, 0))));
    let failures = std::fs::read_to_string(dir.path().join("failures.csv")).unwrap();
    let lines: Vec<&str> = failures.lines().collect();
    assert_eq!(lines.len(), 2, "{failures}");
    // the swept key as a numpy-safe column (docs/outputs.md: `observer.kappa1` → `observer__kappa1`)
    assert_eq!(lines[0], "index,observer__kappa1,status,message");
    assert!(lines[1].starts_with("1,1e5,diverged,") && lines[1].contains("diverged at t ="), "{}", lines[1]);
}

#[test]
fn the_32_by_32_paper_grid_has_no_failed_point() {
    // The paper's gain grid a ∈ [1e-4, 10] × b ∈ [1e-2, 1e4], 32 × 32 log points, the full
    // paper configuration (T = 20 s). The first version failed 117 of these points in the
    // ε SOCP; every point must now be answered: status ok, both theory verdicts decided and
    // the closed-loop metrics present.
    let specs = ["control.a=1e-4..10:log:32".to_string(), "control.b=1e-2..1e4:log:32".to_string()];
    let s = Search::new(Config::paper(), &specs, SearchOptions::default()).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let sum = wingcheck_search::run(&s, dir.path(), Default::default()).unwrap();
    assert_eq!((sum.evaluated, sum.failed, sum.failed_total), (1024, 0, Some((0, 0))));
    let failures = std::fs::read_to_string(dir.path().join("failures.csv")).unwrap();
    assert_eq!(failures, "index,control__a,control__b,status,message\n", "header only");
    let results: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("results.json")).unwrap()).unwrap();
    let points = results["points"].as_array().unwrap();
    assert_eq!(points.len(), 1024);
    for p in points {
        assert_eq!(p["status"], "ok", "{p}");
        assert!(p["w_positive_definite"].is_boolean() && p["feasible_32"].is_boolean(), "{p}");
        assert!(p["w_decided"] == true && p["feasible_32_decided"] == true, "both verdicts decided: {p}");
        for m in [
            "lambda2_J_s",
            "lambda1_J_s",
            "lambda3_max_J",
            "rms_q_tip_m",
            "rms_theta_tip_rad",
            "tau1_peak_N",
            "energy_t_end_J",
        ] {
            assert!(p["metrics"][m].as_f64().is_some_and(f64::is_finite), "{m} missing: {p}");
        }
    }
}
