//! Every number `check --json` prints carries its error or its basis: over random valid
//! configurations, a number in the ledger is either the `value` of a labelled quantity with a
//! unit and an `error` (with the sources it `covers`) or a named `basis`, or the `error` of such
//! a quantity, or plot data (the samples behind a figure), or one of the checker's settings
//! (exact by definition: chosen values), or the layout version `schema_version` of the document
//! and of its provenance record. A schema-level walk of the JSON, not a spot check. In the
//! ftdo-vs-dobc, mu-conditions and finite-time rows every simulated value has a ± (from the
//! doubled grid and dt/2), not only the basis "simulation".

use proptest::prelude::*;
use serde_json::Value;
use wingcheck_model::{apply_overrides, Config};

const BASES: [&str; 9] = [
    "exact",
    "configured",
    "closed-form",
    "solver",
    "simulation",
    "search-maximum",
    "derived",
    "upper-bound",
    "lower-bound",
];

/// JSON paths of numbers that are neither a quantity's value/error nor exempt.
fn bare_numbers(v: &Value, path: &str, out: &mut Vec<String>) {
    match v {
        Value::Number(_) => out.push(path.to_string()),
        Value::Array(a) => a.iter().enumerate().for_each(|(i, x)| bare_numbers(x, &format!("{path}[{i}]"), out)),
        Value::Object(m) if m.contains_key("label") && m.get("value").is_some_and(Value::is_number) => {
            let ok_unit = m.get("unit").is_some_and(Value::is_string);
            let ok_error = m.get("error").is_some_and(|e| e.as_f64().is_some_and(|e| e >= 0.0 && e.is_finite()))
                && m.get("covers").is_some_and(Value::is_array);
            let ok_basis = m.get("basis").and_then(Value::as_str).is_some_and(|b| BASES.contains(&b));
            if !(ok_unit && (ok_error ^ ok_basis)) {
                out.push(format!("{path} (a quantity without unit, or without exactly one of error/basis)"));
            }
        }
        Value::Object(m) => {
            for (k, x) in m {
                // exempt: the checker's settings, the data behind the figures, and the layout
                // versions `schema_version` of the document and of its provenance record (an
                // identifier of a shape, not a number of the run)
                if (path == "$" && (k == "settings" || k == "schema_version"))
                    || (path == "$.provenance" && k == "schema_version")
                    || (k == "plots" && path.starts_with("$.rows"))
                {
                    continue;
                }
                bare_numbers(x, &format!("{path}.{k}"), out);
            }
        }
        _ => {}
    }
}

/// Paths of the simulated values without an error (basis "simulation" only) in the rows whose
/// every simulated value carries a ± from its refinements (the ftdo-vs-dobc comparison, ζ3, ζ4
/// in mu-conditions, the finite-time rows' digital runs).
fn simulated_without_error(ledger: &Value) -> Vec<String> {
    fn walk(v: &Value, path: &str, out: &mut Vec<String>) {
        match v {
            Value::Array(a) => a.iter().enumerate().for_each(|(i, x)| walk(x, &format!("{path}[{i}]"), out)),
            Value::Object(m) => {
                let quantity = m.contains_key("label") && m.get("value").is_some_and(Value::is_number);
                if quantity && m.get("basis").and_then(Value::as_str) == Some("simulation") {
                    out.push(format!("{path} ({})", m.get("label").and_then(Value::as_str).unwrap_or("?")));
                }
                for (k, x) in m {
                    if k != "plots" {
                        walk(x, &format!("{path}.{k}"), out);
                    }
                }
            }
            _ => {}
        }
    }
    let mut out = Vec::new();
    for (i, row) in ledger["rows"].as_array().expect("rows").iter().enumerate() {
        if ["ftdo-vs-dobc", "mu-conditions", "finite-time-1", "finite-time-2"].iter().any(|id| row["id"] == *id) {
            walk(row, &format!("$.rows[{i}]"), &mut out);
        }
    }
    out
}

fn ledger_json(sets: &[String]) -> Value {
    let cfg: Config = apply_overrides(&Config::paper(), sets).expect("valid overrides");
    serde_json::to_value(wingcheck_claims::check_all(&cfg).unwrap()).unwrap()
}

#[test]
fn the_paper_ledger_has_no_bare_number() {
    let v = ledger_json(&["horizon.t_end=2".into()]);
    let mut bare = Vec::new();
    bare_numbers(&v, "$", &mut bare);
    assert!(bare.is_empty(), "{bare:?}");
    let unbarred = simulated_without_error(&v);
    assert!(unbarred.is_empty(), "{unbarred:?}");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 4, ..ProptestConfig::default() })]

    /// Random weights, gains, damping, observer rule and an SI-scale wing or the paper's.
    #[test]
    fn no_bare_number_anywhere(
        la in -5.0f64..2.0, lr in 0.0f64..6.0, k1 in prop_oneof![Just(0.0), 0.1f64..10.0],
        xi in 0.0f64..1.5, explicit in any::<bool>(), si in any::<bool>(),
    ) {
        let a = 10f64.powf(la);
        let mut sets: Vec<String> = vec!["horizon.t_end=2".into(), format!("control.a={a}"),
            format!("control.b={}", a * 10f64.powf(lr)), format!("control.k1={k1}"), format!("wing.xi={xi}")];
        if explicit {
            sets.push("observer.rule=explicit".into());
        }
        if si {
            sets.extend(["wing.span=6", "wing.ei=1e7", "wing.gj=1e6", "wing.rho=100", "wing.ip=10"].map(String::from));
        }
        let v = ledger_json(&sets);
        let mut bare = Vec::new();
        bare_numbers(&v, "$", &mut bare);
        prop_assert!(bare.is_empty(), "{:?}", bare);
        let unbarred = simulated_without_error(&v);
        prop_assert!(unbarred.is_empty(), "{:?}", unbarred);
    }
}
