//! The one display path of the evidence: every evidence struct is made of labelled leaves —
//! [`Quantity`] (a number with its unit and error or basis), [`Flag`] (yes/no), [`Text`] (a
//! fact in words, e.g. an exact rational) — and [`Table`]s of records of leaves. Serialised,
//! that is the row's `evidence` in `check --json`; [`nodes`] reads the same serialisation back
//! into display [`Node`]s, which the report lays out. So the page and the JSON agree field by
//! field, every value carries its own label and unit, and no meaning is recovered from a key.

use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};
use wingcheck_model::{Quantity, Unit};

/// A labelled fact that is not a number: a yes/no ([`Flag`]), a text ([`Text`], e.g. an exact
/// rational or a function), or a typed decision (serialised as its name).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Fact<T> {
    /// What it is, in words.
    pub label: String,
    /// The fact.
    pub value: T,
}

impl<T> Fact<T> {
    /// A labelled fact.
    pub fn new(label: impl Into<String>, value: T) -> Fact<T> {
        Fact { label: label.into(), value }
    }
}

/// A yes/no fact.
pub type Flag = Fact<bool>;

/// A fact in words.
pub type Text = Fact<String>;

impl Text {
    /// A labelled text.
    pub fn text(label: impl Into<String>, value: impl Into<String>) -> Text {
        Fact { label: label.into(), value: value.into() }
    }
}

/// How a value that exists only once something happened (σ reached zero, a signal settled) is
/// written when it has not.
pub const NOT_REACHED: &str = "not reached within the run";
/// How a settling time that is not reached before the horizon is written.
pub const NEVER_SETTLED: &str = "never within the horizon";

/// A number that may not exist (a reaching or settling time never reached, a ratio whose
/// denominator vanishes): the quantity, or a labelled text saying why not.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(untagged)]
pub enum Maybe {
    /// The number.
    Value(Quantity),
    /// Why there is none.
    Missing(Text),
}

impl Maybe {
    /// `q`, or the text `missing()` when there is none.
    pub fn of(q: Option<Quantity>, missing: impl FnOnce() -> Text) -> Maybe {
        match q {
            Some(q) => Maybe::Value(q),
            None => Maybe::Missing(missing()),
        }
    }

    /// The quantity, if there is one.
    pub fn quantity(&self) -> Option<&Quantity> {
        match self {
            Maybe::Value(q) => Some(q),
            Maybe::Missing(_) => None,
        }
    }

    /// The value with its error and unit, or the text.
    pub fn text(&self) -> String {
        match self {
            Maybe::Value(q) => q.pm_text(),
            Maybe::Missing(t) => t.value.clone(),
        }
    }
}

/// Records of leaves, shown as a table (one row per record, one column per field).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Table<T> {
    /// What the table shows.
    pub label: String,
    /// The records.
    pub rows: Vec<T>,
}

impl<T> Table<T> {
    /// A labelled table.
    pub fn new(label: impl Into<String>, rows: Vec<T>) -> Table<T> {
        Table { label: label.into(), rows }
    }
}

/// A column of a displayed table.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
pub struct Column {
    /// The field's label.
    pub label: String,
    /// Its unit symbol ("" for dimensionless).
    pub unit: String,
}

/// A formatted cell: the value and its error or basis.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
pub struct Cell {
    /// The value (numbers with digits matched to their error; no unit: it is in the column).
    pub value: String,
    /// `± …` or the basis, or "".
    pub accuracy: String,
}

/// One displayed piece of evidence.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Node {
    /// A number.
    Quantity(Quantity),
    /// A yes/no fact.
    Flag(Flag),
    /// A fact in words.
    Text(Text),
    /// A table of records.
    Table {
        /// What it shows.
        label: String,
        /// Its columns.
        columns: Vec<Column>,
        /// Its rows (one cell per column).
        rows: Vec<Vec<Cell>>,
    },
}

/// A leaf read back from its serialisation.
fn leaf(v: &Map<String, Value>) -> Option<Node> {
    match v.get("value")? {
        Value::Number(_) => serde_json::from_value(Value::Object(v.clone())).ok().map(Node::Quantity),
        Value::Bool(b) => Some(Node::Flag(Flag::new(v.get("label")?.as_str()?, *b))),
        Value::String(s) => Some(Node::Text(Text::text(v.get("label")?.as_str()?, s.clone()))),
        _ => None,
    }
}

fn cell(n: &Node) -> (Column, Cell) {
    match n {
        Node::Quantity(q) => (
            Column { label: q.label.clone(), unit: q.unit.symbol().into() },
            Cell { value: q.number_text(), accuracy: q.accuracy_text() },
        ),
        Node::Flag(f) => (
            Column { label: f.label.clone(), unit: String::new() },
            Cell { value: if f.value { "yes" } else { "no" }.into(), accuracy: String::new() },
        ),
        Node::Text(t) => (
            Column { label: t.label.clone(), unit: String::new() },
            Cell { value: t.value.clone(), accuracy: String::new() },
        ),
        Node::Table { label, .. } => (
            Column { label: label.clone(), unit: String::new() },
            Cell { value: "(table)".into(), accuracy: String::new() },
        ),
    }
}

/// A record's leaves, in field order (nested unlabelled groups flattened).
fn record(path: &str, v: &Map<String, Value>, out: &mut Vec<Node>) -> Result<(), String> {
    for (k, x) in v {
        nodes_into(&format!("{path}.{k}"), x, out)?;
    }
    Ok(())
}

fn table(path: &str, label: &str, rows: &[Value]) -> Result<Node, String> {
    let mut columns: Vec<Column> = Vec::new();
    let mut parsed: Vec<Vec<(Column, Cell)>> = Vec::new();
    for (i, r) in rows.iter().enumerate() {
        let m = r.as_object().ok_or_else(|| format!("{path}.rows[{i}] is not a record"))?;
        let mut leaves = Vec::new();
        record(&format!("{path}.rows[{i}]"), m, &mut leaves)?;
        let cells: Vec<(Column, Cell)> = leaves.iter().map(cell).collect();
        for (c, _) in &cells {
            if !columns.contains(c) {
                columns.push(c.clone());
            }
        }
        parsed.push(cells);
    }
    let rows = parsed
        .into_iter()
        .map(|cells| {
            columns
                .iter()
                .map(|c| {
                    cells
                        .iter()
                        .find(|(k, _)| k == c)
                        .map(|(_, v)| v.clone())
                        .unwrap_or(Cell { value: "—".into(), accuracy: String::new() })
                })
                .collect()
        })
        .collect();
    Ok(Node::Table { label: label.into(), columns, rows })
}

fn nodes_into(path: &str, v: &Value, out: &mut Vec<Node>) -> Result<(), String> {
    let m = v.as_object().ok_or_else(|| format!("{path}: a bare value without a label"))?;
    if let (Some(Value::String(label)), Some(Value::Array(rows))) = (m.get("label"), m.get("rows")) {
        out.push(table(path, label, rows)?);
    } else if m.contains_key("label") {
        out.push(leaf(m).ok_or_else(|| format!("{path}: a labelled value of unknown shape"))?);
    } else {
        record(path, m, out)?;
    }
    Ok(())
}

/// The display nodes of a serialised evidence struct, in field order. An error names the
/// JSON path of a value that is not a labelled leaf or table (a bug of the evidence type).
pub fn nodes<T: Serialize>(evidence: &T) -> Result<Vec<Node>, String> {
    let v = serde_json::to_value(evidence).map_err(|e| e.to_string())?;
    let mut out = Vec::new();
    nodes_into("$", &v, &mut out)?;
    Ok(out)
}

/// The number at `path` (dot-separated keys) of a serialised evidence struct: a
/// [`Quantity`]'s value, or a bare number (tests and tools read evidence by its JSON keys).
pub fn number_at(v: &Value, path: &str) -> Option<f64> {
    let mut x = v;
    for k in path.split('.') {
        x = x.get(k)?;
    }
    x.get("value").and_then(Value::as_f64).or_else(|| x.as_f64())
}

/// A ratio y/x of non-negative magnitudes as a dimensionless simulation quantity; None when
/// x = 0 (the ratio does not exist), so nothing saturates to f64::MAX.
pub fn ratio_of(label: impl Into<String>, y: f64, x: f64, basis: wingcheck_model::ValueBasis) -> Option<Quantity> {
    (x > 0.0 && y.is_finite()).then(|| Quantity::based(label, y / x, Unit::Dimensionless, basis))
}

#[cfg(test)]
mod tests {
    use super::*;
    use wingcheck_model::ValueBasis;

    #[derive(Serialize, schemars::JsonSchema)]
    struct Row {
        n: Quantity,
        ok: Flag,
    }

    #[derive(Serialize, schemars::JsonSchema)]
    struct Evidence {
        lambda: Quantity,
        holds: Flag,
        cases: Table<Row>,
    }

    #[test]
    fn evidence_reads_back_as_labelled_nodes_in_field_order() {
        let e = Evidence {
            lambda: Quantity::with_error("λ", -4.154, 3.3e-4, Unit::LyapunovUnits, &[]),
            holds: Flag::new("printed condition holds", false),
            cases: Table::new(
                "per N",
                vec![
                    Row { n: Quantity::count("elements N", 2), ok: Flag::new("accepted", true) },
                    Row { n: Quantity::count("elements N", 4), ok: Flag::new("accepted", false) },
                ],
            ),
        };
        let n = nodes(&e).unwrap();
        assert!(matches!(&n[0], Node::Quantity(q) if q.label == "λ"));
        assert!(matches!(&n[1], Node::Flag(f) if !f.value));
        match &n[2] {
            Node::Table { columns, rows, .. } => {
                assert_eq!(columns.len(), 2);
                assert_eq!(rows[1][0].value, "4");
                assert_eq!(rows[1][1].value, "no");
            }
            other => panic!("{other:?}"),
        }
        // a bare number is refused, naming its path
        #[derive(Serialize, schemars::JsonSchema)]
        struct Bad {
            x: f64,
        }
        assert_eq!(nodes(&Bad { x: 1.0 }).unwrap_err(), "$.x: a bare value without a label");
        let q = Quantity::based("r", 2.0, Unit::Dimensionless, ValueBasis::Simulation);
        assert_eq!(number_at(&serde_json::json!({ "r": q }), "r"), Some(2.0));
    }
}
