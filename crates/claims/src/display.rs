//! The one display path of the evidence: every evidence struct is made of labelled leaves —
//! [`Quantity`] (a number with its unit and error or basis), [`Flag`] (yes/no), [`Text`] (a
//! fact in words, e.g. an exact rational) — and [`Table`]s of records of leaves. Serialised,
//! that is the row's `evidence` in `check --json`; [`nodes`] reads the same serialisation back
//! into display [`Node`]s, which the report lays out. So the page and the JSON agree field by
//! field, every value carries its own label and unit, and no meaning is recovered from a key.

use std::sync::Arc;

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

/// A symbol of the ledger's and the report's text with its meaning (the report's notation
/// box): every symbol a sentence, label or legend uses is one of these.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Symbol {
    /// The symbol as printed (`T_s`, `t_end`, `ω₁`).
    pub symbol: &'static str,
    /// What it is, with its unit and, where it is an input, the configured value.
    pub meaning: String,
}

/// The notation of the text, with the values of `cfg` where a symbol is an input. Time:
/// `t_end` is the horizon, `T_s` the observer's sample (hold) period, `dt` the integrator step,
/// `t_f1`/`t_f2` the bounds (38)/(39), `t_reach` the time σ reaches 0 (the finite-time rows'
/// Filippov time), `t_band` when a simulated |g̃| enters its threshold band; never a bare `T`.
/// Units follow from the definitions: W = b·E + a·⟨x, Mv⟩ is in J s.
pub fn notation(cfg: &wingcheck_model::Config) -> Vec<Symbol> {
    let v = wingcheck_model::format::exact;
    let (w, c, o, h) = (&cfg.wing, &cfg.control, &cfg.observer, &cfg.horizon);
    let sym = |symbol: &'static str, meaning: String| Symbol { symbol, meaning };
    vec![
        sym("t", "time (s)".into()),
        sym("t_end", format!("the horizon of the runs: t ∈ [0, t_end], here t_end = {} s", v(h.t_end))),
        sym("T_s", format!("the observer's sample (hold) period, here {} s", v(o.sample_period))),
        sym("dt", format!("the integrator step, here {} s", v(cfg.discretisation.dt))),
        sym("t_f1, t_f2, t_f", "the bounds (38), (39) on the time σ1, σ2 take to reach 0 (s); t_f: either".into()),
        sym("t_reach", "when σ reaches 0 (and with it g̃ = σ̇, (55)): the Filippov reaching time of the finite-time rows, from the continuous-time limit of the observer (s)".into()),
        sym("t_band", "from when a simulated |g̃| stays below the threshold, measured at full rate (every integrator step, both sides of every sample's jump) (s)".into()),
        sym("s, z", format!("span and position along it, z ∈ [0, s], here s = {} m", v(w.span))),
        sym("q(z,t), θ(z,t)", "bending displacement (m) and twist (rad); q(s,t), θ(s,t) at the tip".into()),
        sym("ρ, I_p", format!("mass (kg/m) and polar inertia (kg m) per length, here {}, {}", v(w.rho), v(w.ip))),
        sym("EI, GJ", format!("bending and torsion rigidity, here {} N m², {} N m²", v(w.ei), v(w.gj))),
        sym("ρx_c, x_c, x_ac", format!("mass–elastic-axis coupling (kg; x_c the offset, m) and aerodynamic offset (m), here {}, {}", v(w.rho_xc), v(w.x_ac))),
        sym("ξ", format!("Kelvin–Voigt damping coefficient (s), here {}", v(w.xi))),
        sym("ω₁; ω̲₁, ω̄₁", "the wing's fundamental angular frequency (rad/s = 1/s); certified lower and upper bounds of it".into()),
        sym("τ1, τ2", "boundary control force (N) and moment (N m) at the tip, law (15)".into()),
        sym("a, b", format!("weights of the tip deflection (dimensionless) and its rate (s) in (15), here a = {}, b = {} s; a/b in 1/s", v(c.a), v(c.b))),
        sym("k1, k2", format!("boundary gains of (15), here {} N/m, {} N m", v(c.k1), v(c.k2))),
        sym("g1, g2; g_h, g_hmax", "tip disturbances (N, N m); the distributed disturbance (N/m) and its largest |g_h| over the run".into()),
        sym("ĝ, g̃", "the observer's estimate of g, held over T_s; its error g̃ = g − ĝ".into()),
        sym("σ_k, ĝ_k, τ_k", "values at the k-th observer sample; Δĝ, Δτ: their change from one sample to the next".into()),
        sym("σ1, σ2; ν1, ν2", "the observer's sliding variables (N, N m) and internal states".into()),
        sym("κ1 … κ6", format!("observer gains (20)–(21); κ2 = {}, κ5 = {} are the switching gains", v(o.kappa2), v(o.kappa5))),
        sym("ζ1 … ζ4", "sup |g1|, sup |g2| (the theorems' hypotheses κ2 ≥ ζ1, κ5 ≥ ζ2); sup |g̃1|, sup |g̃2| in ε".into()),
        sym("p", "the observer exponent ratio a1/a2 (dimensionless)".into()),
        sym("W = W_a + W_o, κ", "the Lyapunov function (22)–(23) (its energy part W_a and cross part W_o) and the norm (25) it is compared with".into()),
        sym("E, ⟨x, Mv⟩", "the simulated wing's mechanical energy (J) and the mass-weighted product of its displacement and velocity (J s); along a run W = b·E + a·⟨x, Mv⟩".into()),
        sym("units of W", "W = b·E + a·⟨x, Mv⟩ is in J s, and so are W(0) and the bound (35); ε (a rate of W) is in J. κ (25) adds terms of different SI units as numbers, as the paper does, so λ1, λ2, y1…y3 (W/κ) are in J s and λ3, μ3…μ6 in J per SI unit of κ".into()),
        sym("y1, y2, y3; λ1, λ2", "the paper's constants (26)–(28): printed bounds λ2 κ ≤ W ≤ λ1 κ".into()),
        sym("λ1*, λ2*", "the tight bounds sup W/κ and inf W/κ; λ1(N), λ2(N) on N Galerkin elements".into()),
        sym("μ1 … μ6, η", "the conditions (29)–(32) and their free parameters η".into()),
        sym("λ3, λ3*, λ, ε", "λ3 = min μ3…μ6, its sup λ3* over the η's; the decay rate λ (1/s) and constant ε of (33)".into()),
        sym("r*", "the largest a/b for which (32) can hold (1/s)".into()),
        sym("f, ω", "the lemmas' span (f = s) and test function ω(z)".into()),
        sym("Q, Q0; φ1, φ2, φ3, ψ", "Lemma 3's comparison ODE (13)–(14): Q = σ²/2 from Q0 = Q(0), with coefficients φ1…φ3 and a disturbance term ψ".into()),
        sym("a1, a2; b1, b2", format!("the observer's odd exponent integers, here {}, {}; {}, {}; sig^r(x) = sign(x)|x|^r", o.a1, o.a2, o.b1, o.b2)),
        sym("N", "number of elements of a Galerkin or simulation grid".into()),
    ]
}

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

/// Why a serialised evidence struct is not made of labelled leaves and tables (a bug of the
/// evidence type); `path` is the JSON path of the offending value (`$.x`, `$.cases.rows[1]`).
#[derive(Debug, Clone, thiserror::Error)]
pub enum ShapeError {
    /// The evidence does not serialise to JSON.
    #[error("{0}")]
    Serialise(#[source] Arc<serde_json::Error>),
    /// A table row is not a record.
    #[error("{path} is not a record")]
    NotARecord {
        /// JSON path of the row.
        path: String,
    },
    /// A bare value (number, string) where a labelled value is needed.
    #[error("{path}: a bare value without a label")]
    Unlabelled {
        /// JSON path of the value.
        path: String,
    },
    /// A labelled value that is neither a quantity, a flag, a text nor a table.
    #[error("{path}: a labelled value of unknown shape")]
    UnknownShape {
        /// JSON path of the value.
        path: String,
    },
}

/// A record's leaves, in field order (nested unlabelled groups flattened).
fn record(path: &str, v: &Map<String, Value>, out: &mut Vec<Node>) -> Result<(), ShapeError> {
    for (k, x) in v {
        nodes_into(&format!("{path}.{k}"), x, out)?;
    }
    Ok(())
}

fn table(path: &str, label: &str, rows: &[Value]) -> Result<Node, ShapeError> {
    let mut columns: Vec<Column> = Vec::new();
    let mut parsed: Vec<Vec<(Column, Cell)>> = Vec::new();
    for (i, r) in rows.iter().enumerate() {
        let m = r.as_object().ok_or_else(|| ShapeError::NotARecord { path: format!("{path}.rows[{i}]") })?;
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

fn nodes_into(path: &str, v: &Value, out: &mut Vec<Node>) -> Result<(), ShapeError> {
    let m = v.as_object().ok_or_else(|| ShapeError::Unlabelled { path: path.into() })?;
    if let (Some(Value::String(label)), Some(Value::Array(rows))) = (m.get("label"), m.get("rows")) {
        out.push(table(path, label, rows)?);
    } else if m.contains_key("label") {
        out.push(leaf(m).ok_or_else(|| ShapeError::UnknownShape { path: path.into() })?);
    } else {
        record(path, m, out)?;
    }
    Ok(())
}

/// The display nodes of a serialised evidence struct, in field order. An error names the
/// JSON path of a value that is not a labelled leaf or table (a bug of the evidence type).
pub fn nodes<T: Serialize>(evidence: &T) -> Result<Vec<Node>, ShapeError> {
    let v = serde_json::to_value(evidence).map_err(|e| ShapeError::Serialise(Arc::new(e)))?;
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
            lambda: Quantity::with_error("λ", -4.154, 3.3e-4, Unit::JouleSecond, &[]),
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
        assert_eq!(nodes(&Bad { x: 1.0 }).unwrap_err().to_string(), "$.x: a bare value without a label");
        let q = Quantity::based("r", 2.0, Unit::Dimensionless, ValueBasis::Simulation);
        assert_eq!(number_at(&serde_json::json!({ "r": q }), "r"), Some(2.0));
    }
}
