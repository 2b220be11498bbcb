//! Config edges (issue 25, class 7): what the configuration says is what runs. A
//! `sample_every` that is not a whole multiple of the sample period is refused (it used to be
//! rounded while `config` echoed the unrounded value); a number that underflows is refused (it
//! used to become 0); −0 is 0 (it used to hash differently); a JSON array is never a config
//! (serde filled the structs positionally).

use wingcheck_model::{apply_overrides, Config, ConfigError, PAPER_JSON};

fn set(exprs: &[&str]) -> Result<Config, ConfigError> {
    apply_overrides(&Config::paper(), &exprs.iter().map(|s| s.to_string()).collect::<Vec<_>>())
}

#[test]
fn sample_every_off_the_sample_grid_is_refused_with_the_allowed_values() {
    // 0.0015 / 0.001 = 1.5 observer samples: the nearest multiples are 0.001 and 0.002.
    let e = set(&["horizon.sample_every=0.0015"]).unwrap_err().to_string();
    for m in ["horizon.sample_every", "observer.sample_period", "0.0015", "0.001 and 0.002"] {
        assert!(e.contains(m), "{m:?} missing: {e}");
    }
    // whole multiples pass and are echoed exactly as used (10 samples of 1 ms)
    let cfg = set(&["horizon.sample_every=0.01"]).unwrap();
    assert_eq!(cfg.samples_per_output(), 10);
    assert_eq!(cfg.horizon.sample_every, 0.01);
    assert!(set(&["observer.sample_period=0.004", "horizon.sample_every=0.02"]).is_ok());
    assert!(set(&["observer.sample_period=0.004", "horizon.sample_every=0.01"]).is_err());
}

#[test]
fn numbers_that_underflow_are_refused_not_zeroed() {
    for v in ["1e-400", "-1e-400", "1e-310", "0.5e-320"] {
        let e = set(&[&format!("control.a={v}")]).unwrap_err().to_string();
        assert!(e.contains("control.a") && e.contains("smallest normal f64"), "{v}: {e}");
    }
    // zero written any way is zero, and the smallest normal itself passes
    for v in ["0", "0.0", "0e-400", "-0.0e7"] {
        assert_eq!(set(&[&format!("control.a={v}")]).unwrap().control.a, 0.0, "{v}");
    }
    assert!(set(&["wing.xi=2.2250738585072014e-308"]).is_ok());
    // in a config file (the token is found outside strings; a string "1e-400" is not a number)
    let text = PAPER_JSON.replace("\"xi\": 0.6", "\"xi\": 1e-400");
    let e = Config::from_json_str(&text).unwrap_err().to_string();
    assert!(e.contains("1e-400") && e.contains("smallest normal f64"), "{e}");
    let text = PAPER_JSON.replace("\"kind\": \"ftdo\"", "\"kind\": \"1e-400\"");
    let e = Config::from_json_str(&text).unwrap_err().to_string();
    assert!(e.contains("unknown variant"), "{e}");
}

#[test]
fn minus_zero_is_zero_in_the_text_and_the_hash_input() {
    let neg = set(&["control.a=-0", "observer.nu1_0=-0.0"]).unwrap();
    let pos = set(&["control.a=0", "observer.nu1_0=0"]).unwrap();
    assert!(neg.control.a.is_sign_positive() && neg.observer.nu1_0.is_sign_positive());
    // the hashed text (compact JSON in field order) is the same
    assert_eq!(serde_json::to_string(&neg).unwrap(), serde_json::to_string(&pos).unwrap());
    let text = PAPER_JSON.replace("\"nu1_0\": 0.0", "\"nu1_0\": -0.0");
    let file = Config::from_json_str(&text).unwrap();
    assert_eq!(serde_json::to_string(&file).unwrap(), serde_json::to_string(&Config::paper()).unwrap());
}

#[test]
fn a_json_array_is_never_a_configuration() {
    // The paper's sections in field order, as one array: serde would fill Config from it.
    let v: serde_json::Value = serde_json::from_str(PAPER_JSON).unwrap();
    let order = ["wing", "control", "observer", "disturbance", "initial", "discretisation", "horizon"];
    let positional = serde_json::Value::Array(order.iter().map(|k| v[k].clone()).collect());
    let e = Config::from_json_str(&positional.to_string()).unwrap_err().to_string();
    assert!(e.contains("the document is a JSON array") && e.contains("never positional"), "{e}");
    assert!(Config::from_json_value(positional).is_err());
    // one section given positionally
    let mut nested = v.clone();
    nested["wing"] = serde_json::json!([2.0, 10.0, 3.5, 0.2, 0.5, 1.5, 0.05, 0.6]);
    let e = Config::from_json_str(&nested.to_string()).unwrap_err().to_string();
    assert!(e.contains("wing is a JSON array"), "{e}");
    // a scalar document
    let e = Config::from_json_str("5").unwrap_err().to_string();
    assert!(e.contains("not a JSON object"), "{e}");
}

/// Issue 46, item 6: messages name the user's field and the value as typed — no "5e-324 would
/// silently be read as 5e-324", no `1e5000` echoed as `inf`, no range error quoting the f64's
/// shortest form instead of what was typed.
#[test]
fn messages_name_the_field_and_the_value_as_typed() {
    // a subnormal: below the smallest normal, with lost digits — not "read as itself"
    let e = set(&["control.a=5e-324"]).unwrap_err().to_string();
    assert!(e.contains("control.a = 5e-324") && e.contains("subnormal"), "{e}");
    assert!(!e.contains("read as 5e-324"), "{e}");
    let e = set(&["control.a=1e-400"]).unwrap_err().to_string();
    assert!(e.contains("1e-400 would be read as 0"), "{e}");
    // beyond the largest f64: the token, never `inf`
    for v in ["1e5000", "-1e5000"] {
        let e = set(&[&format!("control.a={v}")]).unwrap_err().to_string();
        assert!(e.contains(&format!("control.a = {v} is not a finite number")) && !e.contains("inf"), "{e}");
    }
    // out of range: the value as typed
    let e = set(&["control.a=1.00000000000000000001e13"]).unwrap_err().to_string();
    assert!(e.contains("control.a = 1.00000000000000000001e13 is out of range: allowed in [0, 1e12]"), "{e}");
    // in a file: the field's dotted path and the token, for both ends
    let text = PAPER_JSON.replace("\"a\": 1.0", "\"a\": 1e5000");
    let e = Config::from_json_str(&text).unwrap_err().to_string();
    assert!(e.contains("control.a = 1e5000 is not a finite number"), "{e}");
    let text = PAPER_JSON.replace("\"xi\": 0.6", "\"xi\": 5e-324");
    let e = Config::from_json_str(&text).unwrap_err().to_string();
    assert!(e.contains("wing.xi = 5e-324") && e.contains("subnormal"), "{e}");
    // a partial file, nested one level
    let e = Config::from_json_str("{\"horizon\": {\"t_end\": 1e400}}").unwrap_err().to_string();
    assert!(e.contains("horizon.t_end = 1e400"), "{e}");
}
