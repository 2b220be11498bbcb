//! The JSON records of a search's result files (`results.json`, `best.json`): typed, so their
//! JSON Schemas (docs/schema/) are generated from the same types that write them. No value is
//! null: a metric without a value is left out of `metrics` and named in `missing_metrics`;
//! an undecided verdict is `false` with its `*_decided` flag false.

use serde::Serialize;
use serde_json::{Map, Value};

use crate::metric::{Metric, METRICS, METRIC_UNITS};
use crate::point::{PointResult, Status};

/// One point of `results.json` / `best.json`.
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct PointRecord {
    /// Point index (row-major over the axes, first axis slowest).
    pub index: usize,
    /// The swept values by configuration key (`"control.a": 0.01`; units of the key,
    /// docs/outputs.md): the number or literal the value parses as, else its text.
    pub values: Map<String, Value>,
    /// Outcome: `ok`, `diverged` or `error`.
    pub status: Status,
    /// Why the point is not `ok` (empty when it is).
    pub message: String,
    /// Whether the W ≻ 0 verdict was decided.
    pub w_decided: bool,
    /// W ≻ 0 on the Galerkin space (false also when undecided).
    pub w_positive_definite: bool,
    /// Whether the (32) verdict was decided.
    pub feasible_32_decided: bool,
    /// (29)–(32) satisfiable (false also when undecided).
    pub feasible_32: bool,
    /// Both hypotheses of Theorem 2 decided and true.
    pub theorem_feasible: bool,
    /// Whether the tip settled within the horizon (`settling_time` has a value).
    pub settled: bool,
    /// The metrics without a value (not computed, e.g. after a failed simulation, or not
    /// defined, e.g. λ and ε where (32) is infeasible, the settling time of a tip that never settles).
    pub missing_metrics: Vec<String>,
    /// The metrics that have a value, by name (units: the document's `units`).
    #[schemars(with = "std::collections::BTreeMap<String, f64>")]
    pub metrics: Map<String, Value>,
}

/// A swept value as JSON: the number or literal it parses as, else a string.
fn value_json(text: &str) -> Value {
    serde_json::from_str(text).unwrap_or_else(|_| Value::String(text.to_string()))
}

impl PointRecord {
    /// The record of point `p` of a search over `keys`.
    pub fn new(keys: &[String], p: &PointResult) -> PointRecord {
        let values = keys.iter().zip(&p.values).map(|(k, v)| (k.clone(), value_json(v))).collect();
        let mut metrics = Map::new();
        let mut missing_metrics = Vec::new();
        for (name, m) in METRICS.iter().zip(&p.metrics) {
            match m {
                Some(x) => {
                    metrics.insert(name.to_string(), Value::from(*x));
                }
                None => missing_metrics.push(name.to_string()),
            }
        }
        PointRecord {
            index: p.index,
            values,
            status: p.status,
            message: p.message.clone(),
            w_decided: p.w_positive_definite.is_some(),
            w_positive_definite: p.w_positive_definite == Some(true),
            feasible_32_decided: p.feasible_32.is_some(),
            feasible_32: p.feasible_32 == Some(true),
            theorem_feasible: p.theorem_feasible() == Some(true),
            settled: p.metric(Metric::SettlingTime).is_some(),
            missing_metrics,
            metrics,
        }
    }
}

/// The unit of every metric, by column name (`"rms_q_tip_m": "m"`), in [`METRICS`] order.
pub fn metric_units() -> Map<String, Value> {
    METRICS.iter().zip(METRIC_UNITS).map(|(m, u)| (m.to_string(), Value::from(unit_text(u)))).collect()
}

/// A unit as written in JSON: its symbol, `1` for a dimensionless metric.
fn unit_text(u: wingcheck_model::Unit) -> &'static str {
    match u.symbol() {
        "" => "1",
        s => s,
    }
}

/// The shape of `results.json` (written streaming by [`crate::store::write_results_json`],
/// which serialises exactly these fields in this order).
#[derive(Debug, Serialize, schemars::JsonSchema)]
pub struct ResultsDocument {
    /// Layout version ([`wingcheck_io::SCHEMA_VERSION`]).
    pub schema_version: u32,
    /// Tool build and the base configuration's SHA-256.
    pub provenance: wingcheck_io::Provenance,
    /// The swept configuration keys, in axis order.
    pub axes: Vec<String>,
    /// The metric names, in column order.
    pub metrics: Vec<String>,
    /// Each metric's unit (`1`: dimensionless).
    #[schemars(with = "std::collections::BTreeMap<String, String>")]
    pub units: Map<String, Value>,
    /// Every point, in index order.
    pub points: Vec<PointRecord>,
}

/// `best.json`: the best `ok` points by one metric, overall and among the theorem-feasible ones.
#[derive(Debug, Serialize, schemars::JsonSchema)]
pub struct BestDocument {
    /// Layout version ([`wingcheck_io::SCHEMA_VERSION`]).
    pub schema_version: u32,
    /// The ranking metric.
    pub metric: String,
    /// `ascending` (minimised) or `descending` (maximised).
    pub order: String,
    /// Its unit (`1`: dimensionless).
    pub unit: String,
    /// The best points overall.
    pub best: Vec<PointRecord>,
    /// The best points where both hypotheses of Theorem 2 hold.
    pub best_theorem_feasible: Vec<PointRecord>,
}

impl BestDocument {
    /// The unit text of `metric`.
    pub fn unit_of(metric: Metric) -> String {
        unit_text(metric.unit()).to_string()
    }
}

/// The provenance of a search directory (`provenance.json`, and embedded in `results.json`):
/// this build, the base configuration's SHA-256 and the CSV files with what they hold.
pub fn provenance(search: &crate::Search) -> wingcheck_io::Provenance {
    let file = |f: &str, c: &str| wingcheck_io::FileRecord { file: f.into(), contents: c.into() };
    wingcheck_io::Provenance::new(
        &search.base.sha256(),
        vec![
            file("results.csv", "one row per point: axis values, status columns, metrics with unit-suffixed names (docs/outputs.md, results.csv)"),
            file("failures.csv", "the points whose status is not ok, with the reason"),
            file("boundary.csv", "verdict changes between grid neighbours, bisected with --refine"),
            file("timings.csv", "wall time per point (s); the only file that differs between identical runs"),
        ],
    )
}
