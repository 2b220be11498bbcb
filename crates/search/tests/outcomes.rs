//! A diverging simulation is a recorded outcome of its point, not a crash.

use wingcheck_model::{apply_overrides, Config};
use wingcheck_search::{modal::RunCache, Search, SearchOptions, Status, TheoryCache};

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
    assert_eq!(bad.metric("rms_q_tip"), None);
    // the theory does not depend on κ1 and is still reported
    assert_eq!(bad.metric("lambda2"), ok.metric("lambda2"));
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
    assert_eq!(lines[0], "index,observer.kappa1,status,message");
    assert!(lines[1].starts_with("1,1e5,diverged,") && lines[1].contains("diverged at t ="), "{}", lines[1]);
}
