//! One source of truth from computation to page, at configurations off the paper's point: for
//! each, `wingcheck check --json`, `wingcheck report` and `wingcheck certify` are run as a user
//! runs them, and
//! - the report's `ledger.json` is `check --json`, byte for byte;
//! - the ledger table's line per claim is the JSON's deciding comparison, and every decisive
//!   number and every evidence value of the claim's section is the JSON's, with its label, unit
//!   and error or basis;
//! - no sentence carries text that is only true at the paper's point;
//! - the certificates a row cites are files `certify` writes for that configuration;
//! - ratios and relative differences are dimensionless.

mod common;

use std::path::Path;
use std::process::{Command, Output};

use serde_json::Value;
use wingcheck_model::Quantity;

fn wingcheck(args: &[String]) -> Output {
    let o = Command::new(env!("CARGO_BIN_EXE_wingcheck")).args(args).output().expect("binary runs");
    assert!(o.status.success(), "wingcheck {args:?}: {}", String::from_utf8_lossy(&o.stderr));
    o
}

fn text(n: roxmltree::Node) -> String {
    n.descendants().filter(|d| d.is_text()).map(|d| d.text().unwrap_or("")).collect()
}

/// The six configurations of the issue: the paper's, strong tip damping, the explicit observer,
/// another span, another gain, an SI-scale wing (each on a 4-s horizon to stay cheap).
fn configurations() -> Vec<(&'static str, Vec<&'static str>)> {
    let mut si = common::SI_WING.to_vec();
    si.push("initial.shape=cantilever");
    vec![
        ("paper", vec![]),
        ("a = 1, b = 3000", vec!["control.a=1", "control.b=3000"]),
        ("explicit observer", vec!["observer.rule=explicit"]),
        ("span 3 m", vec!["wing.span=3"]),
        ("k1 = 5", vec!["control.k1=5"]),
        ("SI-scale wing", si),
    ]
}

/// Every labelled quantity in a JSON value (evidence or decisive numbers).
fn quantities(v: &Value, out: &mut Vec<Quantity>) {
    match v {
        Value::Object(m) if m.contains_key("label") && m.get("value").is_some_and(Value::is_number) => {
            out.push(serde_json::from_value(v.clone()).expect("a quantity deserialises"))
        }
        Value::Object(m) => m.values().for_each(|x| quantities(x, out)),
        Value::Array(a) => a.iter().for_each(|x| quantities(x, out)),
        _ => {}
    }
}

/// Sentences that are true only at the paper's point (its span, its weights, its sweep).
fn paper_only(name: &str) -> Vec<&'static str> {
    let mut v = vec!["(0.5, 1), (1, 0.5), (2, 2)", "the paper's point", "of Section 4"];
    if name == "span 3 m" || name == "SI-scale wing" {
        v.extend(["16 > f∫ω² = 64/5", "on [0, 2 m]", "ω = z² "]);
    }
    if name == "a = 1, b = 3000" {
        v.extend(["a = 1, b = 1 s", "configured a/b = 1 1/s"]);
    }
    if name == "explicit observer" {
        v.push("FTDO's (implicit rule) disturbance error");
    }
    v
}

fn check_one(name: &str, sets: &[&str], dir: &Path) {
    let mut args: Vec<String> = vec!["--set".into(), "horizon.t_end=4".into()];
    for s in sets {
        args.extend(["--set".to_string(), s.to_string()]);
    }
    let with =
        |cmd: &[&str]| -> Vec<String> { cmd.iter().map(|s| s.to_string()).chain(args.iter().cloned()).collect() };
    let json_text = String::from_utf8(wingcheck(&with(&["check", "--json"])).stdout).unwrap();
    let ledger: Value = serde_json::from_str(&json_text).unwrap();
    let out = dir.join("report");
    let proofs = dir.join("proofs");
    wingcheck(&with(&["report", "--out", out.to_str().unwrap()]));
    wingcheck(&with(&["certify", "--out", proofs.to_str().unwrap()]));

    // ledger.json is check --json
    let written = std::fs::read_to_string(out.join("ledger.json")).unwrap();
    assert_eq!(written.trim_end(), json_text.trim_end(), "{name}: ledger.json differs from check --json");

    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    let doc = roxmltree::Document::parse_with_options(
        &html,
        roxmltree::ParsingOptions { allow_dtd: true, ..Default::default() },
    )
    .expect("well-formed");
    let rows = ledger["rows"].as_array().unwrap();
    for row in rows {
        let id = row["id"].as_str().unwrap();
        // the ledger table's line: the deciding comparison, as in the JSON
        let tr =
            doc.descendants().find(|n| n.attribute("id") == Some(&format!("ledger-claim-{id}"))).expect("ledger row");
        let deciding = row["deciding"].as_str().unwrap();
        assert!(text(tr).contains(deciding), "{name}, {id}: the ledger table lacks «{deciding}»: {}", text(tr));
        // the row's section: the decisive numbers (label, value with unit, error or basis) and the
        // finding, as in the JSON
        let section = doc.descendants().find(|n| n.attribute("id") == Some(&format!("claim-{id}"))).expect("section");
        let shown = text(section);
        for q in row["decisive"].as_array().unwrap() {
            let q: Quantity = serde_json::from_value(q.clone()).unwrap();
            let decisive = format!("{}: {} ({})", q.label, q.value_text(), q.accuracy_text());
            assert!(shown.contains(&decisive), "{name}, {id}: the section lacks «{decisive}»");
        }
        for s in row["finding"].as_array().unwrap() {
            assert!(shown.contains(s.as_str().unwrap()), "{name}, {id}: finding not shown");
        }
        // every evidence quantity is shown in the row's section with the JSON's value and unit
        let mut all = Vec::new();
        quantities(&row["evidence"], &mut all);
        for q in &all {
            assert!(shown.contains(&q.label), "{name}, {id}: evidence label «{}» not shown", q.label);
            assert!(shown.contains(&q.number_text()), "{name}, {id}: «{}» = {} not shown", q.label, q.number_text());
        }
        // ratios and relative differences carry no dimension
        quantities(&row["decisive"], &mut all);
        for q in &all {
            let l = q.label.to_lowercase();
            if l.contains(" / ") || l.contains("ratio") || l.contains("relative") || l.contains("(dobc − ftdo)/ftdo")
            {
                assert!(q.unit.is_dimensionless(), "{name}, {id}: ratio «{}» in {:?}", q.label, q.unit);
            }
        }
        // no sentence that only the paper's point makes true
        let words: Vec<String> = ["finding", "details"]
            .iter()
            .flat_map(|k| row[*k].as_array().unwrap().iter().map(|s| s.as_str().unwrap().to_string()))
            .chain(row["correction"].as_str().map(String::from))
            .collect();
        for w in &words {
            for bad in paper_only(name) {
                assert!(!w.contains(bad), "{name}, {id}: «{bad}» in «{w}»");
            }
        }
        // the certificates cited are files certify wrote for this configuration
        for c in row["certificates"].as_array().unwrap() {
            let f = c.as_str().unwrap();
            assert!(proofs.join(f).is_file(), "{name}, {id}: cites {f}, which certify did not write");
        }
    }
}

#[test]
fn check_json_report_and_certify_agree_at_six_configurations() {
    let tmp = tempfile::tempdir().unwrap();
    for (i, (name, sets)) in configurations().iter().enumerate() {
        let dir = tmp.path().join(format!("c{i}"));
        std::fs::create_dir_all(&dir).unwrap();
        check_one(name, sets, &dir);
    }
}
