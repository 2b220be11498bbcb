//! The range of every numeric configuration key that does not depend on another key: the one
//! table that [`Config::validate`](crate::Config::validate) checks and that the configuration's
//! JSON Schema states ([`config_schema`]), so the schema refuses what the tool refuses field by
//! field. Rules between keys (ρ·I_p > (ρx_c)², a1 < a2 < 2·a1, dt dividing the sample period,
//! t_end ≥ the sample period, …) stay in `validate`; the schema states the widest range such a
//! key can have ([`RELATIVE_ENVELOPES`]).

use serde_json::{json, Value};

/// Largest magnitude of a physical parameter (ρ, ρx_c, EI, GJ, I_p, gains, weights): products
/// of a few of them stay far from f64 overflow. SI-scale wings (EI ~ 1e7) are well inside.
pub const MAX_MAGNITUDE: f64 = 1e12;
/// Smallest positive physical parameter (ρ, EI, GJ, I_p).
pub const MIN_POSITIVE: f64 = 1e-12;

/// What kind of number a key holds, and how its range is read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BoundKind {
    /// A real number in [min, max].
    Real,
    /// A real number in (min, max]: the lower end excluded, for the reason given.
    RealAbove(&'static str),
    /// An integer in [min, max].
    Integer,
    /// An odd integer in [min, max].
    OddInteger,
}

/// The range of one key (dotted path as `--set` takes it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FieldBound {
    /// `section.key` (or `section.sub.key`).
    pub path: &'static str,
    /// Lower end (units of the key).
    pub min: f64,
    /// Upper end (units of the key).
    pub max: f64,
    /// Real or integer, and whether `min` is included.
    pub kind: BoundKind,
}

const fn real(path: &'static str, min: f64, max: f64) -> FieldBound {
    FieldBound { path, min, max, kind: BoundKind::Real }
}

const fn integer(path: &'static str, min: f64, max: f64) -> FieldBound {
    FieldBound { path, min, max, kind: BoundKind::Integer }
}

const fn odd(path: &'static str) -> FieldBound {
    FieldBound { path, min: 1.0, max: 999.0, kind: BoundKind::OddInteger }
}

/// The reaching-time bounds (38), (39) divide by the observer's linear and fractional gains.
const DIVIDES: &str = "the reaching-time bound (38)/(39) divides by it";

const fn gain_above_zero(path: &'static str) -> FieldBound {
    FieldBound { path, min: 0.0, max: 1e6, kind: BoundKind::RealAbove(DIVIDES) }
}

/// Every key's own range, in the order `validate` checks them (the first violation is reported).
pub const FIELD_BOUNDS: &[FieldBound] = &[
    real("wing.span", 1e-6, 1e6),
    real("wing.rho", MIN_POSITIVE, MAX_MAGNITUDE),
    real("wing.ei", MIN_POSITIVE, MAX_MAGNITUDE),
    real("wing.gj", MIN_POSITIVE, MAX_MAGNITUDE),
    real("wing.ip", MIN_POSITIVE, MAX_MAGNITUDE),
    real("wing.rho_xc", -MAX_MAGNITUDE, MAX_MAGNITUDE),
    real("wing.x_ac", -1e6, 1e6),
    real("wing.xi", 0.0, 1e3),
    real("control.k1", 0.0, MAX_MAGNITUDE),
    real("control.k2", 0.0, MAX_MAGNITUDE),
    real("control.a", 0.0, MAX_MAGNITUDE),
    real("control.b", 0.0, MAX_MAGNITUDE),
    real("observer.sample_period", 1e-7, 0.1),
    gain_above_zero("observer.kappa1"),
    real("observer.kappa2", 0.0, 1e6),
    gain_above_zero("observer.kappa3"),
    gain_above_zero("observer.kappa4"),
    real("observer.kappa5", 0.0, 1e6),
    gain_above_zero("observer.kappa6"),
    odd("observer.a1"),
    odd("observer.a2"),
    odd("observer.b1"),
    odd("observer.b2"),
    real("observer.nu1_0", -MAX_MAGNITUDE, MAX_MAGNITUDE),
    real("observer.nu2_0", -MAX_MAGNITUDE, MAX_MAGNITUDE),
    real("disturbance.distributed.mean", -1e6, 1e6),
    real("disturbance.distributed.cos_amp", -1e6, 1e6),
    real("disturbance.distributed.cos_freq", -1e6, 1e6),
    real("disturbance.distributed.sin_amp", -1e6, 1e6),
    real("disturbance.distributed.sin_freq", -1e6, 1e6),
    real("disturbance.distributed.slope", -1e6, 1e6),
    real("disturbance.tip_bending.mean", -1e6, 1e6),
    real("disturbance.tip_bending.amp", -1e6, 1e6),
    real("disturbance.tip_bending.freq", -1e6, 1e6),
    real("disturbance.tip_torsion.mean", -1e6, 1e6),
    real("disturbance.tip_torsion.amp", -1e6, 1e6),
    real("disturbance.tip_torsion.freq", -1e6, 1e6),
    real("initial.q_tip", -1e3, 1e3),
    real("initial.theta_tip", -1e3, 1e3),
    integer("discretisation.elements", 2.0, 4000.0),
    real("discretisation.grading", 0.0, 0.9),
    integer("discretisation.fd_points", 2.0, 4000.0),
    integer("horizon.field_points", 2.0, 2001.0),
];

/// Keys whose range depends on another key, checked by `validate` (dt ∈ [1e-9, the sample
/// period], t_end ∈ [the sample period, 1e5], sample_every ∈ [the sample period, t_end]); the
/// schema states the widest range each can have over every valid sample period.
pub fn relative_envelopes() -> [FieldBound; 3] {
    let period = bound("observer.sample_period");
    [
        real("discretisation.dt", DT_MIN, period.max),
        real("horizon.t_end", period.min, T_END_MAX),
        real("horizon.sample_every", period.min, T_END_MAX),
    ]
}

/// Smallest time step (s).
pub const DT_MIN: f64 = 1e-9;
/// Longest horizon (s).
pub const T_END_MAX: f64 = 1e5;

/// The bound of `path` in [`FIELD_BOUNDS`].
///
/// # Panics
/// If `path` is not in the table (a programming error: the paths are constants).
pub fn bound(path: &str) -> FieldBound {
    *FIELD_BOUNDS.iter().find(|b| b.path == path).unwrap_or_else(|| panic!("{path} has no bound"))
}

impl FieldBound {
    /// Whether `v` is inside the range (and of the right kind).
    pub fn admits(&self, v: f64) -> bool {
        let inside = match self.kind {
            BoundKind::RealAbove(_) => v > self.min && v <= self.max,
            _ => v >= self.min && v <= self.max,
        };
        let kind_ok = match self.kind {
            BoundKind::Integer => v.fract() == 0.0,
            BoundKind::OddInteger => v.fract() == 0.0 && v.rem_euclid(2.0) == 1.0,
            _ => true,
        };
        v.is_finite() && inside && kind_ok
    }

    /// The allowed range as error messages state it ("in [1e-12, 1e12]", "an integer in
    /// [2, 4000]", "> 0 (why) and ≤ 1e6").
    pub fn allowed(&self) -> String {
        let (lo, hi) = (crate::format_number(self.min), crate::format_number(self.max));
        match self.kind {
            BoundKind::Real => format!("in [{lo}, {hi}]"),
            BoundKind::RealAbove(why) => format!("> {lo} ({why}) and ≤ {hi}"),
            BoundKind::Integer => format!("an integer in [{lo}, {hi}]"),
            BoundKind::OddInteger => format!("an odd integer in [{lo}, {hi}]"),
        }
    }

    /// The JSON Schema keywords of the range.
    fn keywords(&self) -> Value {
        let mut k = match self.kind {
            BoundKind::Real => json!({"minimum": self.min, "maximum": self.max}),
            BoundKind::RealAbove(_) => json!({"exclusiveMinimum": self.min, "maximum": self.max}),
            BoundKind::Integer | BoundKind::OddInteger => {
                json!({"type": "integer", "minimum": self.min as i64, "maximum": self.max as i64})
            }
        };
        if self.kind == BoundKind::OddInteger {
            k["not"] = json!({"multipleOf": 2});
        }
        k
    }
}

/// The configuration's JSON Schema: the shape from the Rust types (schemars), then what the
/// tool accepts: every key optional (a file is merged over the default, so a partial file is
/// valid), the ranges of [`FIELD_BOUNDS`] and [`relative_envelopes`], and `"$schema"` (an
/// editor's pointer to this schema, ignored by the tool).
pub fn config_schema() -> schemars::Schema {
    let mut root: Value = schemars::schema_for!(crate::Config).into();
    drop_required(&mut root);
    // keys that share a definition (tip_bending and tip_torsion) must share their ranges
    let mut stated: std::collections::BTreeMap<String, Value> = Default::default();
    for b in FIELD_BOUNDS.iter().chain(relative_envelopes().iter()) {
        let (slot, id) = property(&mut root, b.path);
        let keywords = b.keywords();
        if let Some(old) = stated.insert(id, keywords.clone()).filter(|old| *old != keywords) {
            panic!("{}: range {keywords} but a key sharing its definition has {old}", b.path);
        }
        for (k, v) in keywords.as_object().into_iter().flatten() {
            slot[k] = v.clone();
        }
    }
    root["properties"]["$schema"] = json!({
        "description": "The URI or path of this schema, for an editor's completion and checks; the tool ignores it.",
        "type": "string"
    });
    root["description"] = json!(
        "A wingcheck configuration: every key optional (a file is merged over the embedded default, \
         configs/paper.json); each number's range as the tool checks it. Rules between keys (e.g. \
         ρ·I_p > (ρx_c)², a1 < a2 < 2·a1, dt dividing observer.sample_period) are checked by the tool only."
    );
    schemars::Schema::try_from(root).expect("the schema is a JSON object")
}

/// Removes every `required` list: each key has a default.
fn drop_required(v: &mut Value) {
    match v {
        Value::Object(m) => {
            m.remove("required");
            m.values_mut().for_each(drop_required);
        }
        Value::Array(a) => a.iter_mut().for_each(drop_required),
        _ => {}
    }
}

/// The schema object of the key `path` (following `$ref`s into `$defs`), and where it lives
/// (`definition/key`).
fn property<'a>(root: &'a mut Value, path: &str) -> (&'a mut Value, String) {
    let mut def: Option<String> = None;
    let keys: Vec<&str> = path.split('.').collect();
    for (i, key) in keys.iter().enumerate() {
        let holder = match &def {
            None => &root["properties"],
            Some(d) => &root["$defs"][d]["properties"],
        };
        let node = &holder[*key];
        assert!(node.is_object(), "{path}: no property {key} in the schema");
        if i + 1 == keys.len() {
            break;
        }
        let reference = node["$ref"].as_str().unwrap_or_else(|| panic!("{path}: {key} is not a $ref"));
        def = Some(reference.trim_start_matches("#/$defs/").to_string());
    }
    let last = keys[keys.len() - 1];
    match def {
        None => (&mut root["properties"][last], format!("/{last}")),
        Some(d) => {
            let id = format!("{d}/{last}");
            (&mut root["$defs"][d]["properties"][last], id)
        }
    }
}
