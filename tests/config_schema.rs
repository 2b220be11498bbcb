//! The configuration's JSON Schema (docs/schema/config.schema.json, checked against the
//! generated one by tests/outputs.rs) accepts and refuses what the tool accepts and refuses:
//! a partial file and an editor's `"$schema"` are valid for both, every key's own range is the
//! validator's (one table, `wingcheck_model::FIELD_BOUNDS`), and no configuration the tool
//! accepts is refused by the schema. The truth is the tool's own parser and validator
//! (`Config::from_json_str`, what `--config` runs); the schema is read with the `boon` validator.

use proptest::prelude::*;
use serde_json::{json, Value};
use wingcheck_model::{bounds::relative_envelopes, Config, FieldBound, FIELD_BOUNDS};

fn schema() -> (boon::Schemas, boon::SchemaIndex) {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/schema/config.schema.json");
    let value: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let mut schemas = boon::Schemas::new();
    let mut compiler = boon::Compiler::new();
    compiler.add_resource("file:///config.schema.json", value).unwrap();
    let index = compiler.compile("file:///config.schema.json", &mut schemas).unwrap();
    (schemas, index)
}

thread_local! {
    static SCHEMA: (boon::Schemas, boon::SchemaIndex) = schema();
}

fn schema_accepts(doc: &Value) -> bool {
    SCHEMA.with(|(s, i)| s.validate(doc, *i).is_ok())
}

/// The partial document `{"section": {"key": value}}` for a dotted path.
fn partial(path: &str, value: Value) -> Value {
    path.rsplit('.').fold(value, |inner, key| json!({ key: inner }))
}

/// `x` as JSON: an integer when the key holds integers and `x` is whole (serde refuses `24.0`
/// for an integer field, a schema reads it as an integer), a float otherwise.
fn number(b: &FieldBound, x: f64) -> Value {
    let integral =
        !matches!(b.kind, wingcheck_model::bounds::BoundKind::Real | wingcheck_model::bounds::BoundKind::RealAbove(_));
    if integral && x.fract() == 0.0 && x.abs() < 9e15 {
        json!(x as i64)
    } else {
        json!(x)
    }
}

#[test]
fn a_partial_file_with_a_schema_pointer_is_valid_for_both_and_runs_as_the_same_set() {
    let doc = json!({"$schema": "docs/schema/config.schema.json", "control": {"a": 0.5}});
    assert!(schema_accepts(&doc));
    let by_file = Config::from_json_str(&doc.to_string()).expect("the tool accepts it");
    let by_set = wingcheck_model::apply_overrides(&Config::paper(), &["control.a=0.5".into()]).unwrap();
    assert_eq!(by_file, by_set, "$schema is ignored, the rest merged over the default");
    // the empty document and the complete default are valid too
    assert!(schema_accepts(&json!({})));
    assert!(schema_accepts(&serde_json::to_value(Config::paper()).unwrap()));
}

#[test]
fn a_schema_pointer_that_is_not_a_string_is_refused_by_both() {
    let doc = json!({"$schema": 3, "control": {"a": 0.5}});
    assert!(!schema_accepts(&doc));
    let e = Config::from_json_str(&doc.to_string()).unwrap_err().to_string();
    assert!(e.contains("$schema"), "{e}");
}

#[test]
fn the_values_a_new_user_tried_are_refused_by_both_naming_the_field() {
    // issue 44: these passed the old schema while the tool refused them
    for (path, v) in [
        ("control.a", json!(-1)),
        ("discretisation.elements", json!(0)),
        ("wing.rho", json!(1e13)),
        ("observer.a1", json!(4)),
        ("observer.kappa1", json!(0)),
        ("horizon.t_end", json!(1e6)),
    ] {
        let doc = partial(path, v.clone());
        assert!(!schema_accepts(&doc), "the schema accepts {path} = {v}");
        let e = Config::from_json_str(&doc.to_string()).unwrap_err().to_string();
        assert!(e.contains(path), "{path} = {v}: {e}");
    }
    // and unknown keys, by both
    assert!(!schema_accepts(&json!({"control": {"aa": 1}})));
    assert!(Config::from_json_str(r#"{"control": {"aa": 1}}"#).is_err());
}

/// Keys that also enter a rule between keys (so the tool may refuse a value the schema, which
/// states only each key's own range, accepts): the mass matrix, the exponent pairs, the sample
/// period (dt must divide it, t_end be a whole number of it).
const IN_A_RULE_BETWEEN_KEYS: &[&str] = &[
    "wing.rho",
    "wing.ip",
    "wing.rho_xc",
    "observer.a1",
    "observer.a2",
    "observer.b1",
    "observer.b2",
    "observer.sample_period",
];

/// Values around and far outside a bound: its ends, one step inside and outside, whole and
/// fractional numbers, both signs, many decades.
fn value_near(b: FieldBound) -> impl Strategy<Value = f64> {
    let span = (b.max - b.min).abs().max(1.0);
    prop_oneof![
        Just(b.min),
        Just(b.max),
        Just(b.min - span * 1e-9 - 1e-300),
        Just(b.max + span * 1e-9),
        Just(ulp_step(b.min, true)),
        Just(ulp_step(b.max, false)),
        Just(b.min - 1.0),
        Just(b.max + 1.0),
        (b.min..=b.max),
        (b.min..=b.max).prop_map(f64::round),
        (-15.0f64..15.0, any::<bool>()).prop_map(|(e, neg)| if neg { -(10f64.powf(e)) } else { 10f64.powf(e) }),
    ]
}

/// The next f64 after `x` upwards or downwards (at zero: the smallest normal number, since the
/// tool refuses subnormal input outright).
fn ulp_step(x: f64, up: bool) -> f64 {
    if x == 0.0 {
        return if up { f64::MIN_POSITIVE } else { -f64::MIN_POSITIVE };
    }
    let away_from_zero = (x > 0.0) == up;
    f64::from_bits(if away_from_zero { x.to_bits() + 1 } else { x.to_bits() - 1 })
}

fn any_bound() -> impl Strategy<Value = FieldBound> {
    (0..FIELD_BOUNDS.len()).prop_map(|i| FIELD_BOUNDS[i])
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    /// One key changed from the default: for a key in no rule between keys, the schema and the
    /// tool agree exactly, and a refusal names the key; for every key, nothing the tool accepts
    /// is refused by the schema.
    #[test]
    fn schema_and_tool_agree_on_each_keys_own_range((b, x) in any_bound().prop_flat_map(|b| (Just(b), value_near(b)))) {
        let doc = partial(b.path, number(&b, x));
        let by_schema = schema_accepts(&doc);
        let by_tool = Config::from_json_str(&doc.to_string());
        if by_tool.is_ok() {
            prop_assert!(by_schema, "{} = {x}: the tool accepts, the schema refuses", b.path);
        }
        if !IN_A_RULE_BETWEEN_KEYS.contains(&b.path) {
            prop_assert_eq!(by_schema, by_tool.is_ok(), "{} = {}: schema {} tool {:?}", b.path, x, by_schema, by_tool);
            if let Err(e) = by_tool {
                prop_assert!(e.to_string().contains(b.path), "{}", e);
            }
        }
    }

    /// Several keys at once, the keys whose range depends on another key included: whatever
    /// the tool accepts, the schema accepts.
    #[test]
    fn the_schema_never_refuses_a_configuration_the_tool_accepts(
        picks in proptest::collection::vec(
            (0..FIELD_BOUNDS.len() + 3).prop_flat_map(|i| {
                let b = FIELD_BOUNDS.get(i).copied().unwrap_or_else(|| relative_envelopes()[i - FIELD_BOUNDS.len()]);
                (Just(b), value_near(b))
            }),
            1..5,
        )
    ) {
        let mut doc = json!({});
        for (b, x) in &picks {
            let mut node = &mut doc;
            let keys: Vec<&str> = b.path.split('.').collect();
            for k in &keys[..keys.len() - 1] {
                node = node.as_object_mut().unwrap().entry(k.to_string()).or_insert_with(|| json!({}));
            }
            node[keys[keys.len() - 1]] = number(b, *x);
        }
        if Config::from_json_str(&doc.to_string()).is_ok() {
            prop_assert!(schema_accepts(&doc), "{doc}: the tool accepts, the schema refuses");
        }
    }
}

#[test]
fn every_numeric_key_of_the_configuration_has_a_stated_range() {
    // the default's numbers, path by path, against the table and the three relative keys
    fn numbers(v: &Value, at: &str, out: &mut Vec<String>) {
        match v {
            Value::Object(m) => m
                .iter()
                .for_each(|(k, x)| numbers(x, &if at.is_empty() { k.clone() } else { format!("{at}.{k}") }, out)),
            Value::Number(_) => out.push(at.to_string()),
            _ => {}
        }
    }
    let mut paths = Vec::new();
    numbers(&serde_json::to_value(Config::paper()).unwrap(), "", &mut paths);
    let stated: Vec<&str> = FIELD_BOUNDS.iter().chain(relative_envelopes().iter()).map(|b| b.path).collect();
    for p in &paths {
        assert!(stated.contains(&p.as_str()), "{p} has no range in FIELD_BOUNDS");
    }
    assert_eq!(paths.len(), stated.len(), "a bound for a key the configuration does not have");
}
