//! Search axes: `key=lo..hi:log:N`, `key=lo..hi:lin:N` or `key=v1,v2,v3`, parsed into a typed
//! [`Axis`] and validated against a base configuration before any work starts.

use serde::{Deserialize, Serialize};
use wingcheck_model::{apply_overrides, Config};

use crate::SearchError;

/// How an axis' values are spaced.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum Spacing {
    /// `n` values lo·(hi/lo)^(i/(n−1)), i = 0..n−1 (endpoints exact); lo, hi > 0.
    Log {
        /// First value (in the key's unit).
        lo: f64,
        /// Last value.
        hi: f64,
        /// Number of values (≥ 1; 1 gives lo).
        n: usize,
    },
    /// `n` values lo + (hi − lo)·i/(n−1) (endpoints exact).
    Lin {
        /// First value (in the key's unit).
        lo: f64,
        /// Last value.
        hi: f64,
        /// Number of values (≥ 1; 1 gives lo).
        n: usize,
    },
    /// Explicit values, applied verbatim as `key=value` (numbers, or words like `fd`).
    List {
        /// The values as typed.
        values: Vec<String>,
    },
}

/// One search axis: a config key and its values.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Axis {
    /// Dotted config key, e.g. `control.a`.
    pub key: String,
    /// The values.
    pub spacing: Spacing,
    /// The key holds an integer (e.g. `discretisation.elements`): grid values are rounded to
    /// the nearest integer, and the axis is not bisected. Set by [`Axis::detect_integer`].
    #[serde(default)]
    pub integer: bool,
}

fn axis_err(spec: &str, reason: impl Into<String>) -> SearchError {
    SearchError::Axis { axis: spec.to_string(), reason: reason.into() }
}

fn parse_f64(spec: &str, what: &str, s: &str) -> Result<f64, SearchError> {
    let x: f64 = s.trim().parse().map_err(|_| axis_err(spec, format!("{what} `{s}` is not a number")))?;
    if !x.is_finite() {
        return Err(axis_err(spec, format!("{what} `{s}` is not finite")));
    }
    check_representable(spec, what, s, x)?;
    Ok(x)
}

/// Refuse a number whose text is not zero but whose f64 is 0 or subnormal (e.g. `1e-400`,
/// which parses to 0 and would be echoed as such): |x| must be 0 or ≥ f64::MIN_POSITIVE.
fn check_representable(spec: &str, what: &str, s: &str, x: f64) -> Result<(), SearchError> {
    let mantissa = s.trim().split(['e', 'E']).next().unwrap_or("");
    let nonzero_text = mantissa.chars().any(|c| c.is_ascii_digit() && c != '0');
    if (x == 0.0 && nonzero_text) || (x != 0.0 && x.abs() < f64::MIN_POSITIVE) {
        return Err(axis_err(
            spec,
            format!("{what} `{}` is below the smallest normal f64 ({:e}) in magnitude", s.trim(), f64::MIN_POSITIVE),
        ));
    }
    Ok(())
}

impl Axis {
    /// Parse `key=lo..hi:log:N`, `key=lo..hi:lin:N` or `key=v1,v2,...` (syntax only; see
    /// [`validate_axes`] for the checks against a configuration).
    pub fn parse(spec: &str) -> Result<Axis, SearchError> {
        let (key, rhs) =
            spec.split_once('=').ok_or_else(|| axis_err(spec, "expected key=lo..hi:log|lin:N or key=v1,v2,..."))?;
        let key = key.trim();
        if key.is_empty() {
            return Err(axis_err(spec, "empty key"));
        }
        let rhs = rhs.trim();
        if rhs.is_empty() {
            return Err(axis_err(spec, "empty range: no values given"));
        }
        let spacing = if let Some((range, rest)) = rhs.split_once(':') {
            let (lo, hi) = range.split_once("..").ok_or_else(|| axis_err(spec, "expected lo..hi before `:`"))?;
            let (kind, n) =
                rest.split_once(':').ok_or_else(|| axis_err(spec, "expected :log:N or :lin:N after the range"))?;
            let n: usize = n
                .trim()
                .parse()
                .map_err(|_| axis_err(spec, format!("number of points `{n}` is not a whole number")))?;
            let (lo, hi) = (parse_f64(spec, "lower bound", lo)?, parse_f64(spec, "upper bound", hi)?);
            match kind.trim() {
                "log" => Spacing::Log { lo, hi, n },
                "lin" => Spacing::Lin { lo, hi, n },
                other => return Err(axis_err(spec, format!("unknown spacing `{other}`: use log or lin"))),
            }
        } else if rhs.contains("..") {
            return Err(axis_err(spec, "a range needs a spacing and a count: lo..hi:log:N or lo..hi:lin:N"));
        } else {
            let values: Vec<String> = rhs.split(',').map(|v| v.trim().to_string()).collect();
            if values.iter().any(String::is_empty) {
                return Err(axis_err(spec, "empty value in the list"));
            }
            for v in &values {
                if let Ok(x) = v.parse::<f64>() {
                    check_representable(spec, "value", v, x)?;
                }
            }
            Spacing::List { values }
        };
        let axis = Axis { key: key.to_string(), spacing, integer: false };
        axis.check_shape()?;
        Ok(axis)
    }

    /// A list axis over the numbers `values` of `key` (a front end's grid, without going
    /// through text): each value is applied as `key=x` in scientific notation (`{x:e}`, which
    /// reads back as the same f64), checked as [`Axis::parse`] checks a typed list.
    pub fn of_numbers(key: &str, values: &[f64]) -> Result<Axis, SearchError> {
        let texts: Vec<String> = values.iter().map(|x| format!("{x:e}")).collect();
        let spec = format!("{key}={}", texts.join(","));
        if key.trim().is_empty() {
            return Err(axis_err(&spec, "empty key"));
        }
        for (v, &x) in texts.iter().zip(values) {
            if !x.is_finite() {
                return Err(axis_err(&spec, format!("value `{v}` is not finite")));
            }
            check_representable(&spec, "value", v, x)?;
        }
        let axis = Axis { key: key.to_string(), spacing: Spacing::List { values: texts }, integer: false };
        axis.check_shape()?;
        Ok(axis)
    }

    /// The axis as typed on the command line (canonical form).
    pub fn spec(&self) -> String {
        match &self.spacing {
            Spacing::Log { lo, hi, n } => format!("{}={lo}..{hi}:log:{n}", self.key),
            Spacing::Lin { lo, hi, n } => format!("{}={lo}..{hi}:lin:{n}", self.key),
            Spacing::List { values } => format!("{}={}", self.key, values.join(",")),
        }
    }

    fn check_shape(&self) -> Result<(), SearchError> {
        let spec = self.spec();
        match &self.spacing {
            Spacing::Log { lo, hi, n } | Spacing::Lin { lo, hi, n } => {
                if *n < 1 {
                    return Err(axis_err(&spec, "empty range: the number of points must be ≥ 1"));
                }
                if lo > hi {
                    return Err(axis_err(&spec, format!("lower bound {lo} > upper bound {hi}")));
                }
                if lo == hi && *n > 1 {
                    return Err(axis_err(&spec, format!("empty range {lo}..{hi} with {n} points")));
                }
                if matches!(self.spacing, Spacing::Log { .. }) && *lo <= 0.0 {
                    return Err(axis_err(&spec, format!("a log axis needs positive bounds, got lower bound {lo}")));
                }
            }
            Spacing::List { values } => {
                if values.is_empty() {
                    return Err(axis_err(&spec, "empty list"));
                }
            }
        }
        Ok(())
    }

    /// Number of values.
    pub fn len(&self) -> usize {
        match &self.spacing {
            Spacing::Log { n, .. } | Spacing::Lin { n, .. } => *n,
            Spacing::List { values } => values.len(),
        }
    }

    /// True if the axis has no values (never, after parsing).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// True for log-spaced axes.
    pub fn is_log(&self) -> bool {
        matches!(self.spacing, Spacing::Log { .. })
    }

    /// Numeric value i of a log/lin axis (None for lists).
    pub fn numeric(&self, i: usize) -> Option<f64> {
        match &self.spacing {
            Spacing::Log { lo, hi, n } => Some(if i == 0 {
                *lo
            } else if i + 1 == *n {
                *hi
            } else {
                (lo.ln() + (hi.ln() - lo.ln()) * i as f64 / (*n - 1) as f64).exp()
            }),
            Spacing::Lin { lo, hi, n } => Some(if i == 0 {
                *lo
            } else if i + 1 == *n {
                *hi
            } else {
                lo + (hi - lo) * i as f64 / (*n - 1) as f64
            }),
            Spacing::List { .. } => None,
        }
    }

    /// Value i as the text applied in the override `key=text` (Rust's shortest round-trip
    /// form for numbers, so the config receives exactly this f64; integers on integer keys).
    pub fn text(&self, i: usize) -> String {
        match &self.spacing {
            Spacing::List { values } => values[i].clone(),
            _ if self.integer => format!("{}", self.numeric(i).expect("numeric axis").round() as i64),
            _ => format!("{}", self.numeric(i).expect("numeric axis")),
        }
    }

    /// Mark the axis as integer-valued if the base configuration holds an integer at its key.
    pub fn detect_integer(&mut self, base: &Config) {
        let value = serde_json::to_value(base).expect("config serialises");
        let node = self.key.split('.').try_fold(&value, |v, part| v.get(part));
        self.integer = node.is_some_and(|v| v.is_u64() || v.is_i64());
    }

    /// The override expression `key=value` for value i.
    pub fn override_expr(&self, i: usize) -> String {
        format!("{}={}", self.key, self.text(i))
    }

    /// The override for an arbitrary numeric value (refinement).
    pub fn override_value(&self, x: f64) -> String {
        format!("{}={x}", self.key)
    }
}

/// Parse every axis spec, then [`validate_axes`].
pub fn parse_axes(base: &Config, specs: &[String]) -> Result<Vec<Axis>, SearchError> {
    let mut axes = specs.iter().map(|s| Axis::parse(s)).collect::<Result<Vec<_>, _>>()?;
    for a in &mut axes {
        a.detect_integer(base);
    }
    validate_axes(base, &axes)?;
    Ok(axes)
}

/// Check the axes against the base configuration before any work: at least one axis, no key
/// twice, every key known (via `apply_overrides` with the first value), every value of every
/// axis valid with the other axes at their first value, and every corner of the grid valid
/// (all corners up to 12 axes; beyond, the axis ends only).
pub fn validate_axes(base: &Config, axes: &[Axis]) -> Result<(), SearchError> {
    if axes.is_empty() {
        return Err(SearchError::Axis { axis: "(none)".into(), reason: "give at least one --over axis".into() });
    }
    for (i, a) in axes.iter().enumerate() {
        a.check_shape()?;
        if axes[..i].iter().any(|b| b.key == a.key) {
            return Err(axis_err(&a.spec(), format!("key `{}` is swept twice", a.key)));
        }
    }
    for a in axes.iter().filter(|a| a.integer) {
        if let Some(i) = (1..a.len()).find(|&i| a.text(i) == a.text(i - 1)) {
            return Err(axis_err(
                &a.spec(),
                format!("`{}` is an integer key and the grid repeats the value {}", a.key, a.text(i)),
            ));
        }
    }
    let first: Vec<String> = axes.iter().map(|a| a.override_expr(0)).collect();
    for (d, a) in axes.iter().enumerate() {
        let idx: Vec<usize> = match &a.spacing {
            Spacing::List { values } => (0..values.len()).collect(),
            _ => vec![0, a.len() - 1],
        };
        for i in idx {
            let mut ov = first.clone();
            ov[d] = a.override_expr(i);
            apply_overrides(base, &ov).map_err(|e| axis_err(&a.spec(), format!("value `{}`: {e}", a.text(i))))?;
        }
    }
    if axes.len() <= 12 {
        for mask in 0..(1usize << axes.len()) {
            let ov: Vec<String> = axes
                .iter()
                .enumerate()
                .map(|(d, a)| a.override_expr(if mask >> d & 1 == 1 { a.len() - 1 } else { 0 }))
                .collect();
            if let Err(e) = apply_overrides(base, &ov) {
                let d = (0..axes.len()).rev().find(|d| mask >> d & 1 == 1).unwrap_or(0);
                return Err(axis_err(&axes[d].spec(), format!("grid corner {} is invalid: {e}", ov.join(" "))));
            }
        }
    }
    Ok(())
}

/// Row-major grid over the axes: point index p ↔ multi-index, the **first axis slowest**.
#[derive(Debug, Clone)]
pub struct Grid {
    /// The axes.
    pub axes: Vec<Axis>,
    dims: Vec<usize>,
}

impl Grid {
    /// Grid over validated axes.
    pub fn new(axes: Vec<Axis>) -> Grid {
        let dims = axes.iter().map(Axis::len).collect();
        Grid { axes, dims }
    }

    /// Number of points (product of the axis lengths; saturates at `usize::MAX`, which the
    /// work limits refuse long before).
    pub fn len(&self) -> usize {
        self.dims.iter().fold(1usize, |acc, &n| acc.saturating_mul(n))
    }

    /// True if there are no points.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Axis lengths.
    pub fn dims(&self) -> &[usize] {
        &self.dims
    }

    /// Multi-index of point p.
    pub fn multi(&self, mut p: usize) -> Vec<usize> {
        let mut m = vec![0; self.dims.len()];
        for d in (0..self.dims.len()).rev() {
            m[d] = p % self.dims[d];
            p /= self.dims[d];
        }
        m
    }

    /// Point index of a multi-index.
    pub fn index(&self, m: &[usize]) -> usize {
        m.iter().zip(&self.dims).fold(0, |acc, (&i, &n)| acc * n + i)
    }

    /// Override expressions of point p, in axis order.
    pub fn overrides(&self, p: usize) -> Vec<String> {
        self.multi(p).iter().zip(&self.axes).map(|(&i, a)| a.override_expr(i)).collect()
    }

    /// Value texts of point p, in axis order.
    pub fn texts(&self, p: usize) -> Vec<String> {
        self.multi(p).iter().zip(&self.axes).map(|(&i, a)| a.text(i)).collect()
    }
}
