//! Reported numbers with their unit and their error or basis: the one vocabulary every crate
//! uses to hand a number to a reader (the ledger's evidence, the report, the search's outputs).
//!
//! A [`Quantity`] is a labelled value with a [`Unit`] and an [`Accuracy`]: either an error
//! estimate (± an absolute bound on |value − exact| covering the named [`ErrorSource`]s) or the
//! [`ValueBasis`] it rests on when no error is estimated (exact, configured, a closed form, a
//! re-verified solver, a simulation at the configured grid, a one-sided bound, …). Units are a
//! closed enum, so a ratio is [`Unit::Dimensionless`] by construction and never prints "m".
//!
//! [`format_value`] is the one number format: significant digits matched to the stated error
//! (two significant digits of the error), four significant digits without one.

use serde::{Deserialize, Serialize};

/// A value with an estimated bound on its absolute error (same units as the value).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Estimate {
    /// The value.
    pub value: f64,
    /// Estimated bound on |value − exact| (≥ 0; 0 means exact up to rounding).
    pub error: f64,
}

impl Estimate {
    /// Relative error bound error/|value| (∞ for a zero value with a nonzero error).
    pub fn relative_error(&self) -> f64 {
        if self.error == 0.0 {
            0.0
        } else {
            self.error / self.value.abs()
        }
    }

    /// True if `other` lies within this estimate's error bar.
    pub fn contains(&self, other: f64) -> bool {
        (other - self.value).abs() <= self.error
    }
}

/// The unit of a reported number. Serialised as its symbol (`"1"` for dimensionless).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, schemars::JsonSchema)]
pub enum Unit {
    /// A pure number (ratios, relative differences, exponents).
    #[serde(rename = "1")]
    Dimensionless,
    /// A pure number in percent (relative differences).
    #[serde(rename = "%")]
    Percent,
    /// A count of cases, points, elements.
    #[serde(rename = "count")]
    Count,
    /// Metre (bending displacement q).
    #[serde(rename = "m")]
    Metre,
    /// Radian (twist θ).
    #[serde(rename = "rad")]
    Radian,
    /// Second.
    #[serde(rename = "s")]
    Second,
    /// 1/s (decay rates, the ratio a/b of the control law's weights).
    #[serde(rename = "1/s")]
    PerSecond,
    /// rad/s (natural frequencies, twist rate).
    #[serde(rename = "rad/s")]
    RadianPerSecond,
    /// m/s (bending rate).
    #[serde(rename = "m/s")]
    MetrePerSecond,
    /// Newton (τ1, g1, σ1).
    #[serde(rename = "N")]
    Newton,
    /// Newton metre (τ2, g2, σ2).
    #[serde(rename = "N m")]
    NewtonMetre,
    /// N/s (rate of g1).
    #[serde(rename = "N/s")]
    NewtonPerSecond,
    /// N m/s (rate of g2).
    #[serde(rename = "N m/s")]
    NewtonMetrePerSecond,
    /// N/m (the distributed load g_h).
    #[serde(rename = "N/m")]
    NewtonPerMetre,
    /// Joule (the wing's energy).
    #[serde(rename = "J")]
    Joule,
    /// Joule second (⟨x, Mv⟩, the cross term of the Lyapunov function).
    #[serde(rename = "J s")]
    JouleSecond,
    /// 1/m² (the tip shear term q'''(s,t) of the boundary condition).
    #[serde(rename = "1/m²")]
    PerSquareMetre,
    /// rad/m (the tip twist slope θ'(s,t)).
    #[serde(rename = "rad/m")]
    RadianPerMetre,
    /// The units of the Lyapunov function W and its constants (λ1, λ2, λ3, ε, W(0)): the paper
    /// mixes kinetic, elastic and cross terms weighted by a and b, so these carry no single
    /// physical unit; they are stated "in W units".
    #[serde(rename = "W units")]
    LyapunovUnits,
    /// Configuration values of different physical units compared as numbers in SI, as the
    /// paper does (e.g. min{ρ, I_p, EI, GJ} against 2ρx_c).
    #[serde(rename = "SI, mixed")]
    MixedSi,
}

impl Unit {
    /// The symbol as printed after a number ("" for dimensionless: a ratio prints no unit).
    pub fn symbol(self) -> &'static str {
        match self {
            Unit::Dimensionless | Unit::Count => "",
            Unit::Percent => "%",
            Unit::Metre => "m",
            Unit::Radian => "rad",
            Unit::Second => "s",
            Unit::PerSecond => "1/s",
            Unit::RadianPerSecond => "rad/s",
            Unit::MetrePerSecond => "m/s",
            Unit::Newton => "N",
            Unit::NewtonMetre => "N m",
            Unit::NewtonPerSecond => "N/s",
            Unit::NewtonMetrePerSecond => "N m/s",
            Unit::NewtonPerMetre => "N/m",
            Unit::Joule => "J",
            Unit::JouleSecond => "J s",
            Unit::PerSquareMetre => "1/m²",
            Unit::RadianPerMetre => "rad/m",
            Unit::LyapunovUnits => "W units",
            Unit::MixedSi => "(SI, mixed)",
        }
    }

    /// The suffix of a CSV column in this unit (`q_tip_m`, `tau2_N_m`; "" for a dimensionless
    /// column): letters, digits and `_` only, so numpy's structured loaders keep the name.
    /// Listed with every column in docs/outputs.md.
    pub fn column_suffix(self) -> &'static str {
        match self {
            Unit::Dimensionless | Unit::Count => "",
            Unit::Percent => "pct",
            Unit::Metre => "m",
            Unit::Radian => "rad",
            Unit::Second => "s",
            Unit::PerSecond => "per_s",
            Unit::RadianPerSecond => "rad_per_s",
            Unit::MetrePerSecond => "m_per_s",
            Unit::Newton => "N",
            Unit::NewtonMetre => "N_m",
            Unit::NewtonPerSecond => "N_per_s",
            Unit::NewtonMetrePerSecond => "N_m_per_s",
            Unit::NewtonPerMetre => "N_per_m",
            Unit::Joule => "J",
            Unit::JouleSecond => "J_s",
            Unit::PerSquareMetre => "per_m2",
            Unit::RadianPerMetre => "rad_per_m",
            Unit::LyapunovUnits => "Wu",
            Unit::MixedSi => "si_mixed",
        }
    }

    /// True for units that carry no dimension (ratios and counts).
    pub fn is_dimensionless(self) -> bool {
        matches!(self, Unit::Dimensionless | Unit::Count | Unit::Percent)
    }
}

/// What an error estimate covers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum ErrorSource {
    /// The spatial grid (h-refinement).
    Grid,
    /// The time step (dt-refinement).
    TimeStep,
    /// Floating-point round-off (a relative floor from the conditioning of the computation).
    RoundOff,
    /// Extrapolation to the limit (Richardson/Romberg truncation of the series).
    Extrapolation,
    /// An iterative solver's stopping tolerance.
    Solver,
    /// The sample times of a time series (an extreme between samples).
    Sampling,
    /// A statistical spread (e.g. sensitivity to the start of a chattering observer).
    Spread,
}

impl ErrorSource {
    /// The source in words, as a sentence names it.
    pub fn text(self) -> &'static str {
        match self {
            ErrorSource::Grid => "the grid",
            ErrorSource::TimeStep => "the time step",
            ErrorSource::RoundOff => "round-off",
            ErrorSource::Extrapolation => "the extrapolation",
            ErrorSource::Solver => "the solver's tolerance",
            ErrorSource::Sampling => "the sample times",
            ErrorSource::Spread => "the spread over starts",
        }
    }
}

/// What a number without an error estimate rests on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum ValueBasis {
    /// Exact: rational arithmetic, an integer count, or a definition.
    Exact,
    /// An input value of the configuration (or one derived from it by a definition).
    Configured,
    /// A closed form evaluated in floating point (round-off only, relative ~1e-15).
    ClosedForm,
    /// A floating-point solver's answer re-verified against its constraints.
    Solver,
    /// A simulation at the configured grid and time step (no error estimate).
    Simulation,
    /// The maximum over a finite search: a lower bound on the supremum.
    SearchMaximum,
    /// Derived from other reported numbers (a ratio, an observed order); see theirs.
    Derived,
    /// An upper bound of the true value (the true value is ≤ this number).
    UpperBound,
    /// A lower bound of the true value (the true value is ≥ this number).
    LowerBound,
}

impl ValueBasis {
    /// The basis in words, as printed beside a number.
    pub fn text(self) -> &'static str {
        match self {
            ValueBasis::Exact => "exact",
            ValueBasis::Configured => "configured",
            ValueBasis::ClosedForm => "closed form",
            ValueBasis::Solver => "solver, re-verified",
            ValueBasis::Simulation => "simulation",
            ValueBasis::SearchMaximum => "max over a search",
            ValueBasis::Derived => "derived",
            ValueBasis::UpperBound => "upper bound",
            ValueBasis::LowerBound => "lower bound",
        }
    }
}

/// The error of a number, or the basis it rests on.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(untagged)]
pub enum Accuracy {
    /// ± `error` (absolute, ≥ 0, in the value's unit), covering the listed sources.
    Error {
        /// Estimated bound on |value − exact|.
        error: f64,
        /// The sources the bound covers.
        covers: Vec<ErrorSource>,
    },
    /// No error estimate; what the number rests on.
    Basis {
        /// The basis.
        basis: ValueBasis,
    },
}

/// A labelled number with its unit and its error or basis: the leaf of every reported
/// evidence table (serialised `{"label", "value", "unit", "error", "covers"}` or
/// `{"label", "value", "unit", "basis"}`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Quantity {
    /// What the number is, in words (symbols defined in the report's notation box).
    pub label: String,
    /// The value (finite).
    pub value: f64,
    /// Its unit.
    pub unit: Unit,
    /// Its error or basis.
    #[serde(flatten)]
    pub accuracy: Accuracy,
}

impl Quantity {
    /// A number resting on `basis`.
    pub fn based(label: impl Into<String>, value: f64, unit: Unit, basis: ValueBasis) -> Quantity {
        Quantity { label: label.into(), value: value + 0.0, unit, accuracy: Accuracy::Basis { basis } }
    }

    /// An exact number (rational arithmetic, a count, a definition).
    pub fn exact(label: impl Into<String>, value: f64, unit: Unit) -> Quantity {
        Self::based(label, value, unit, ValueBasis::Exact)
    }

    /// A count (exact, [`Unit::Count`]).
    pub fn count(label: impl Into<String>, n: usize) -> Quantity {
        Self::exact(label, n as f64, Unit::Count)
    }

    /// An input of the configuration.
    pub fn configured(label: impl Into<String>, value: f64, unit: Unit) -> Quantity {
        Self::based(label, value, unit, ValueBasis::Configured)
    }

    /// `value ± error` covering `covers`.
    pub fn with_error(
        label: impl Into<String>,
        value: f64,
        error: f64,
        unit: Unit,
        covers: &[ErrorSource],
    ) -> Quantity {
        Quantity {
            label: label.into(),
            value: value + 0.0,
            unit,
            accuracy: Accuracy::Error { error: error.abs() + 0.0, covers: covers.to_vec() },
        }
    }

    /// An [`Estimate`] covering `covers`.
    pub fn estimate(label: impl Into<String>, e: Estimate, unit: Unit, covers: &[ErrorSource]) -> Quantity {
        Self::with_error(label, e.value, e.error, unit, covers)
    }

    /// The error estimate, if there is one.
    pub fn error(&self) -> Option<f64> {
        match self.accuracy {
            Accuracy::Error { error, .. } => Some(error),
            Accuracy::Basis { .. } => None,
        }
    }

    /// The same quantity under another label.
    pub fn relabel(mut self, label: impl Into<String>) -> Quantity {
        self.label = label.into();
        self
    }

    /// The number as printed, without its unit: a count as an integer; an exact or configured
    /// value as its shortest decimal (`0.35`, `1e-3`) when that has at most 8 significant
    /// digits; a one-sided bound with 7 significant digits; otherwise digits matched to the
    /// error ([`format_value`]).
    pub fn number_text(&self) -> String {
        let exactish = matches!(self.accuracy, Accuracy::Basis { basis: ValueBasis::Exact | ValueBasis::Configured });
        if self.unit == Unit::Count && self.value.fract() == 0.0 && self.value.abs() < 1e15 {
            format!("{:.0}", self.value)
        } else if exactish && significant_digits(self.value) <= 8 {
            crate::format_number(self.value)
        } else if matches!(self.accuracy, Accuracy::Basis { basis: ValueBasis::UpperBound | ValueBasis::LowerBound }) {
            // a one-sided bound is compared with the value it bounds: show enough digits
            with_significant(self.value, 7)
        } else {
            format_value(self.value, self.error())
        }
    }

    /// The value as printed ([`Quantity::number_text`]) with the unit (`0.12086 1/s`).
    pub fn value_text(&self) -> String {
        let v = self.number_text();
        match self.unit.symbol() {
            "" => v,
            u => format!("{v} {u}"),
        }
    }

    /// The value with its error and unit (`0.12085992204661 ± 3.4e-13 1/s`), or with its unit
    /// alone when it has no error estimate.
    pub fn pm_text(&self) -> String {
        let unit = match self.unit.symbol() {
            "" => String::new(),
            u => format!(" {u}"),
        };
        match self.error() {
            Some(e) => format!("{} ± {}{unit}", format_value(self.value, Some(e)), format_error(e)),
            None => format!("{}{unit}", self.number_text()),
        }
    }

    /// What the error covers, in words ("the grid, the time step and round-off"); `None` for a
    /// number without an error estimate.
    pub fn covers_text(&self) -> Option<String> {
        let Accuracy::Error { covers, .. } = &self.accuracy else { return None };
        let words: Vec<&str> = covers.iter().map(|c| c.text()).collect();
        Some(match words.as_slice() {
            [] => "nothing named".to_string(),
            [one] => one.to_string(),
            [init @ .., last] => format!("{} and {last}", init.join(", ")),
        })
    }

    /// The error or basis as printed (`± 3.4e-13`, `exact`, `simulation`).
    pub fn accuracy_text(&self) -> String {
        match &self.accuracy {
            Accuracy::Error { error, .. } => format!("± {}", format_error(*error)),
            Accuracy::Basis { basis } => basis.text().to_string(),
        }
    }

    /// Is the value (and the error) finite?
    pub fn is_finite(&self) -> bool {
        self.value.is_finite() && self.error().is_none_or(f64::is_finite)
    }
}

/// A number as printed: with an error, rounded to the decade of the error's second significant
/// digit (`0.120859922046612 ± 3.4e-13` → `0.12085992204661`), at least one and at most 15
/// significant digits; without one, 4 significant digits. Fixed notation for
/// 1e-3 ≤ |v| < 1e5, else scientific (`1.23e-5`). Deterministic; parses back as f64.
pub fn format_value(value: f64, error: Option<f64>) -> String {
    if !value.is_finite() {
        return format!("{value}");
    }
    if value == 0.0 {
        return match error {
            Some(e) if e > 0.0 => format!("0 (± {})", format_error(e)),
            _ => "0".into(),
        };
    }
    let mag = value.abs().log10().floor() as i32;
    let digits = match error {
        Some(e) if e > 0.0 && e.is_finite() => (mag - (e.log10().floor() as i32 - 1) + 1).clamp(1, 15),
        Some(_) => 15,
        None => 4,
    } as usize;
    with_significant(value, digits)
}

/// Significant digits of the shortest round-trip decimal of `x` (0 for 0).
fn significant_digits(x: f64) -> usize {
    let s = format!("{:e}", x.abs());
    let mantissa = s.split('e').next().unwrap_or("");
    mantissa.chars().filter(|c| c.is_ascii_digit()).count()
}

/// An error bar as printed: two significant digits (`3.4e-13`, `0.0021`).
pub fn format_error(error: f64) -> String {
    if error == 0.0 || !error.is_finite() {
        return format!("{error}");
    }
    with_significant(error, 2)
}

/// `value` with `digits` significant digits, fixed notation for 1e-3 ≤ |v| < 1e5 (trailing
/// zeros kept: they are significant), else scientific with a bare exponent (`1.2e-5`). A value
/// that is not finite prints as Rust prints it (`inf`, `NaN`): the ledger refuses to show such a
/// row's value (it becomes `inconclusive`, naming the quantity), but formatting never fails.
pub fn with_significant(value: f64, digits: usize) -> String {
    if !value.is_finite() {
        return format!("{value}");
    }
    let digits = digits.max(1);
    let sci = format!("{:.*e}", digits - 1, value);
    // The exponent after rounding (9.99 → 1.00e1 moves the decade).
    let (_, exp) = sci.split_once('e').expect("exponent");
    let exp: i32 = exp.parse().expect("integer exponent");
    if (-3..5).contains(&exp) {
        let decimals = (digits as i32 - 1 - exp).max(0) as usize;
        format!("{value:.decimals$}")
    } else {
        sci
    }
}

/// The resolution a number with error `error` is written to: the decade of the error's second
/// significant digit (the rule of [`format_value`]: 1.4e-4 → 1e-5). None for an error that is
/// 0 or not finite (then the shortest round-trip decimal is exact).
pub fn resolution_of(error: f64) -> Option<f64> {
    (error > 0.0 && error.is_finite()).then(|| 10f64.powi(error.log10().floor() as i32 - 1))
}

/// `value` written to `resolution` (a power of ten, [`resolution_of`]): in fixed notation with
/// the resolution's decimals (none for a resolution ≥ 1), trailing zeros dropped, `0` for a value that rounds to zero. The
/// data files' format (`0.04952` for 0.0495234… at 1e-5); deterministic, parses back as f64.
pub fn format_resolved(value: f64, resolution: f64) -> String {
    if !(value.is_finite() && resolution > 0.0 && resolution.is_finite()) {
        return format!("{value}");
    }
    let decimals = (-resolution.log10().round()).max(0.0) as usize;
    let s = format!("{value:.decimals$}");
    let s = if s.contains('.') { s.trim_end_matches('0').trim_end_matches('.') } else { s.as_str() };
    if s == "-0" || s.is_empty() {
        "0".into()
    } else {
        s.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn data_files_carry_the_digits_of_the_error() {
        // 1.4e-4 m (the default grid's tip error): two significant digits of it → 1e-5
        assert_eq!(resolution_of(1.4e-4), Some(1e-5));
        assert_eq!(resolution_of(0.0), None);
        assert_eq!(format_resolved(0.0495234750843, 1e-5), "0.04952");
        assert_eq!(format_resolved(-3.2e-9, 1e-5), "0");
        assert_eq!(format_resolved(0.9999999999999876, 1e-5), "1");
        assert_eq!(format_resolved(-1.5, 1e-5), "-1.5");
        assert_eq!(format_resolved(12345.678, 100.0), "12346");
        // rounding error of the written value ≤ half the resolution
        for v in [0.12345678, -0.98765432, 3.3333333] {
            let back: f64 = format_resolved(v, 1e-5).parse().unwrap();
            assert!((back - v).abs() <= 0.5e-5 + 1e-15);
        }
    }

    #[test]
    fn digits_follow_the_error() {
        // ω₁ of the paper wing with its Romberg error: down to the error's second digit (1e-14).
        assert_eq!(format_value(0.120859922046612, Some(3.4e-13)), "0.12085992204661");
        assert_eq!(format_value(-4.15400123, Some(3.3e-4)), "-4.15400");
        assert_eq!(format_value(-215.9000001, None), "-215.9");
        assert_eq!(format_value(1.5e-5, None), "1.500e-5");
        assert_eq!(format_value(9.9996, None), "10.00");
        assert_eq!(format_value(123456.0, None), "1.235e5");
        assert_eq!(format_error(3.39e-13), "3.4e-13");
        assert_eq!(format_error(0.0021), "0.0021");
        // Every printed number parses back.
        for v in [0.1208599220466, -215.9, 1.5e-5, 3.1e7] {
            assert!(format_value(v, None).parse::<f64>().is_ok());
        }
        // a value that is not finite is printed, never a panic (`check` exited 101 at
        // control.a = 1e-300, control.b = 1e12 formatting UUB's infinite bound)
        assert_eq!(with_significant(f64::INFINITY, 3), "inf");
        assert_eq!(with_significant(f64::NAN, 2), "NaN");
        assert_eq!(format_value(f64::NEG_INFINITY, Some(1e-3)), "-inf");
    }

    #[test]
    fn ratios_print_no_unit_and_serialise_their_basis() {
        let q = Quantity::exact("printed λ2", -215.9, Unit::LyapunovUnits);
        assert_eq!(q.value_text(), "-215.9 W units");
        let r = Quantity::based("DOBC / FTDO", 2094.0, Unit::Dimensionless, ValueBasis::Simulation);
        assert_eq!(r.value_text(), "2094");
        let json = serde_json::to_value(&r).unwrap();
        assert_eq!(json["unit"], "1");
        assert_eq!(json["basis"], "simulation");
        let e = Quantity::with_error("ω₁", 0.12, 1e-9, Unit::PerSecond, &[ErrorSource::Grid]);
        let json = serde_json::to_value(&e).unwrap();
        assert_eq!(json["error"], 1e-9);
        assert_eq!(json["covers"][0], "grid");
        let back: Quantity = serde_json::from_value(json).unwrap();
        assert_eq!(back, e);
    }
}
