//! Every accepted value runs to an answer (issue 46, item 3 and "What it must show"): `check
//! --json` at every numeric config field's bounds and extremes — 0, the smallest and largest the
//! validator accepts, 1e-300 and the smallest normal where accepted — exits 0 or 1, never 101
//! (a panic), and prints no NaN, inf or null; a subnormal is refused for every float field.
//!
//! The fields are every number of configs/paper.json; each field's range is the one the
//! validator states when it refuses a value (`allowed in [lo, hi]`), so the test follows the
//! validator rather than a copy of its table. CI runs a sample of the (field, value) cases
//! chosen by proptest (`WINGCHECK_EXTREMES_CASES`, default 10); `WINGCHECK_EXTREMES_ALL=1` runs
//! every case: 240 cases in 544 s on 2 shared cores (2026-12-07), each 1–12 s, all passed.

use std::process::Command;

use proptest::prelude::*;
use serde_json::Value;
use wingcheck_model::{apply_overrides, Config, PAPER_JSON};

/// Dotted paths of every number in `v` (integers included).
fn numeric_fields(v: &Value, path: &str, out: &mut Vec<(String, bool)>) {
    match v {
        Value::Object(m) => {
            for (k, x) in m {
                let p = if path.is_empty() { k.clone() } else { format!("{path}.{k}") };
                numeric_fields(x, &p, out);
            }
        }
        Value::Number(n) => out.push((path.to_string(), n.is_f64())),
        _ => {}
    }
}

/// The sets of a case `key=token`: with the fields the validator ties it to, where alone it
/// would be refused for them (an output interval is a whole number of sample periods, dt ≤ the
/// sample period, the horizon a whole number of samples), or `None` when refused either way.
fn case_sets(key: &str, token: &str) -> Option<Vec<String>> {
    let alone = vec![format!("{key}={token}")];
    let tied: Vec<String> = match key {
        "observer.sample_period" => vec![format!("horizon.sample_every={token}"), format!("discretisation.dt={token}")],
        "horizon.sample_every" | "discretisation.dt" => {
            vec![
                format!("observer.sample_period={token}"),
                format!("horizon.sample_every={token}"),
                format!("discretisation.dt={token}"),
            ]
        }
        _ => Vec::new(),
    };
    let ok = |sets: &Vec<String>| apply_overrides(&Config::paper(), sets).is_ok();
    if ok(&alone) {
        return Some(alone);
    }
    let mut with = alone;
    with.extend(tied);
    with.sort();
    with.dedup();
    ok(&with).then_some(with)
}

/// The bounds the validator states for `key` when it refuses a huge value (`[lo, hi]`), and the
/// ends of its range in the validator's table (`wingcheck_model::FIELD_BOUNDS`: the messages of
/// an open lower end, κ1 > 0, have no `[lo, hi]`).
fn stated_bounds(key: &str) -> Vec<String> {
    let mut out: Vec<String> = wingcheck_model::FIELD_BOUNDS
        .iter()
        .filter(|b| b.path == key)
        .flat_map(|b| [wingcheck_model::format_number(b.min), wingcheck_model::format_number(b.max)])
        .collect();
    for probe in ["1e300", "-1e300", "99999999"] {
        if let Err(e) = apply_overrides(&Config::paper(), &[format!("{key}={probe}")]) {
            let msg = e.to_string();
            if let Some(inner) = msg.split("in [").nth(1).and_then(|r| r.split(']').next()) {
                out.extend(inner.split(", ").map(|s| s.trim().to_string()));
            }
        }
    }
    out
}

/// Every case: the accepted values among each field's stated bounds and the extremes, as the
/// `--set` expressions that run it.
fn cases() -> Vec<Vec<String>> {
    let paper: Value = serde_json::from_str(PAPER_JSON).unwrap();
    let mut fields = Vec::new();
    numeric_fields(&paper, "", &mut fields);
    let (mut out, mut missing) = (Vec::new(), Vec::new());
    for (key, _) in &fields {
        let mut tokens: Vec<String> =
            ["0", "1", "1e-300", "-1e-300", "2.2250738585072014e-308", "1e-12", "1e12", "-1e12"]
                .iter()
                .map(|s| s.to_string())
                .collect();
        tokens.extend(stated_bounds(key));
        tokens.sort();
        tokens.dedup();
        let before = out.len();
        out.extend(tokens.iter().filter_map(|t| case_sets(key, t)));
        if out.len() == before {
            missing.push(key.clone());
        }
    }
    // the fractional exponents are odd integers in [1, 999] in pairs lo < hi < 2·lo (paper, after
    // (21)): their extremes are pairs, the smallest (3, 5) and the largest (997, 999), (501, 999)
    for (lo, hi) in [("observer.a1", "observer.a2"), ("observer.b1", "observer.b2")] {
        for (x, y) in [(3, 5), (997, 999), (501, 999)] {
            let sets = vec![format!("{lo}={x}"), format!("{hi}={y}")];
            assert!(apply_overrides(&Config::paper(), &sets).is_ok(), "{sets:?}");
            out.push(sets);
        }
        missing.retain(|k| k != lo && k != hi);
    }
    assert!(missing.is_empty(), "no extreme accepted for {missing:?}");
    out
}

/// `check --json --set …`: exit 0 or 1 (a failing claim or a refusal with its message), never
/// a panic; no NaN, inf or null in what it prints.
fn check_runs_to_an_answer(sets: &[String]) {
    let mut args = vec!["check".to_string(), "--json".to_string()];
    args.extend(sets.iter().flat_map(|s| ["--set".to_string(), s.clone()]));
    let o = Command::new(env!("CARGO_BIN_EXE_wingcheck")).args(&args).output().expect("binary runs");
    let (out, err) = (String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
    let case = sets.join(" ");
    assert!(matches!(o.status.code(), Some(0 | 1)), "{case}: exit {:?}\n{err}", o.status.code());
    assert!(!err.contains("panicked") && !err.contains("RUST_BACKTRACE"), "{case}: {err}");
    if out.trim().is_empty() {
        assert!(o.status.code() == Some(1) && err.contains("error"), "{case}: no output and no message: {err}");
        return;
    }
    let doc: Value = serde_json::from_str(&out).unwrap_or_else(|e| panic!("{case}: not JSON ({e})"));
    let mut bad = Vec::new();
    walk_non_finite(&doc, "", &mut bad);
    assert!(bad.is_empty(), "{case}: non-finite values at {bad:?}");
}

/// Paths of nulls and of strings holding a NaN or an infinity as a number token.
fn walk_non_finite(v: &Value, path: &str, bad: &mut Vec<String>) {
    match v {
        Value::Null => bad.push(path.to_string()),
        Value::String(s) => {
            let words = s.split(|c: char| !(c.is_alphanumeric() || c == '.' || c == '-' || c == '+'));
            if words
                .map(|w| w.trim_start_matches(['-', '+']))
                .any(|w| matches!(w, "NaN" | "nan" | "inf" | "Inf" | "infinity"))
            {
                bad.push(format!("{path}: {s}"));
            }
        }
        Value::Array(a) => a.iter().enumerate().for_each(|(i, x)| walk_non_finite(x, &format!("{path}[{i}]"), bad)),
        Value::Object(m) => m.iter().for_each(|(k, x)| walk_non_finite(x, &format!("{path}.{k}"), bad)),
        _ => {}
    }
}

#[test]
fn a_subnormal_is_refused_for_every_float_field() {
    let paper: Value = serde_json::from_str(PAPER_JSON).unwrap();
    let mut fields = Vec::new();
    numeric_fields(&paper, "", &mut fields);
    for (key, _) in fields.iter().filter(|(_, float)| *float) {
        let e = apply_overrides(&Config::paper(), &[format!("{key}=5e-324")]).unwrap_err().to_string();
        assert!(e.contains(key) && e.contains("5e-324"), "{key}: {e}");
    }
}

#[test]
fn every_numeric_field_has_accepted_extremes() {
    let all = cases();
    // the weights and gains reach 1e-300 and 1e12 (the validator allows [0, 1e12])
    for key in ["control.a", "control.b", "control.k1", "control.k2"] {
        for t in ["0", "1e-300", "1e12"] {
            let case = vec![format!("{key}={t}")];
            assert!(all.contains(&case), "{key}={t} not among the cases");
        }
    }
    assert!(all.len() > 100, "{} cases", all.len());
}

/// The issue's reproductions (exit 101 after 7.3 s and 4.8 s; a solver backtrace with exit 0).
#[test]
fn the_issues_extreme_gains_run_to_an_answer() {
    for sets in [
        ["control.a=1e-300", "control.b=1e12"],
        ["control.k1=1e-300", "control.k2=1e-300"],
        ["control.a=1e12", "control.b=1e-300"],
    ] {
        check_runs_to_an_answer(&sets.map(String::from));
    }
}

fn sampled_cases() -> u32 {
    std::env::var("WINGCHECK_EXTREMES_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(10)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: sampled_cases(), failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn check_at_a_fields_extreme_exits_0_or_1_and_prints_only_finite_numbers(i in 0usize..10_000) {
        if std::env::var("WINGCHECK_EXTREMES_ALL").is_ok() {
            return Ok(()); // every case is run by every_case_when_asked
        }
        let all = cases();
        check_runs_to_an_answer(&all[i % all.len()]);
    }
}

/// Every case, when `WINGCHECK_EXTREMES_ALL` is set (minutes: each accepted case is a `check`).
#[test]
fn every_case_when_asked() {
    if std::env::var("WINGCHECK_EXTREMES_ALL").is_err() {
        return;
    }
    for sets in cases() {
        let start = std::time::Instant::now();
        check_runs_to_an_answer(&sets);
        eprintln!("{}: {:.1} s", sets.join(" "), start.elapsed().as_secs_f64());
    }
}

/// docs/usage.md states the ranges of the physical parameters, gains and weights: they are the
/// ones the validator states when it refuses a value (the issue found the docs promising
/// [1e-12, 1e12] for weights the validator accepts from 0).
#[test]
fn the_documented_ranges_are_the_validators() {
    let docs = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/usage.md")).unwrap();
    let docs = docs.split_whitespace().collect::<Vec<_>>().join(" ");
    for (keys, said, range) in [
        (&["wing.rho", "wing.ei", "wing.gj", "wing.ip"][..], "ρ, EI, GJ and I_p in [1e-12, 1e12]", ["1e-12", "1e12"]),
        (&["wing.rho_xc"][..], "ρx_c in [-1e12, 1e12]", ["-1e12", "1e12"]),
        (&["control.k1", "control.k2", "control.a", "control.b"][..], "the weights a, b in [0, 1e12]", ["0", "1e12"]),
    ] {
        assert!(docs.contains(said), "docs/usage.md no longer says {said:?}");
        for key in keys {
            let stated = stated_bounds(key);
            assert_eq!(&stated[..2], &range.map(String::from)[..], "{key}: the validator states {stated:?}");
        }
    }
}
