//! Reported numbers with their unit and their error or basis: the one vocabulary every crate
//! uses to hand a number to a reader (the ledger's evidence, the report, the search's outputs).
//!
//! A [`Quantity`] is a labelled value with a [`Unit`] and an [`Accuracy`]: either an error
//! estimate (± an absolute bound on |value − exact| covering the named [`ErrorSource`]s) or the
//! [`ValueBasis`] it rests on when no error is estimated (exact, configured, a closed form, a
//! re-verified solver, a simulation at the configured grid, a one-sided bound, …). Units are a
//! closed enum, so a ratio is [`Unit::Dimensionless`] by construction and never prints "m".
//!
//! Every number is printed through the one number format, [`crate::format::number`]; this
//! module decides what is shown around it ([`Quantity::shown`]): digits from the error, an
//! unresolved value as its range, an exact value with too many digits shown rounded.

use serde::{Deserialize, Serialize};

pub use crate::format::{format_error, format_resolved, format_value, resolution_of, with_significant};
use crate::format::{is_unresolved, number, unresolved, Digits};

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
    /// Joule (the wing's energy E; ε of (32), and λ3, μ3…μ6 per SI unit of κ (25)).
    #[serde(rename = "J")]
    Joule,
    /// Joule second (⟨x, Mv⟩; the Lyapunov function W = b·E + a·⟨x, Mv⟩ of (22) and its bounds
    /// W(0), (35); λ1, λ2, y1…y3 per SI unit of κ (25), whose terms are added as numbers).
    #[serde(rename = "J s")]
    JouleSecond,
    /// 1/m² (the tip shear term q'''(s,t) of the boundary condition).
    #[serde(rename = "1/m²")]
    PerSquareMetre,
    /// rad/m (the tip twist slope θ'(s,t)).
    #[serde(rename = "rad/m")]
    RadianPerMetre,
    /// Configuration values of different physical units compared as numbers in SI, as the
    /// paper does (e.g. min{ρ, I_p, EI, GJ} against 2ρx_c): printed without a unit, the label
    /// says so.
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
            Unit::MixedSi => "",
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

/// A [`Quantity`] as printed ([`Quantity::shown`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Shown {
    /// The number without its unit (`0.12085992204661`, `≈ 6.787000×10²⁹`,
    /// `unresolved: −0.22 … 0.92`).
    pub number: String,
    /// The error with its unit, or the basis (`± 3.4×10⁻¹³ 1/s`, `exact`,
    /// `exact, shown rounded`).
    pub accuracy: String,
    /// The unit as it follows a number (` 1/s`; empty for a pure number).
    pub unit: String,
    /// The error is at least half the value: the number is its range.
    pub unresolved: bool,
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

    /// The quantity as printed ([`Shown`]): the one place that decides what is shown around
    /// the number ([`crate::format::number`] writes the digits).
    ///
    /// - a count: an integer;
    /// - an exact or configured value: its shortest decimal when that has at most 8 significant
    ///   digits, else 7 significant digits after "≈" (and the basis says "shown rounded");
    /// - a one-sided bound: 7 significant digits (it is compared with the value it bounds);
    /// - a value with an error: digits from the error; unresolved (the error at least half the
    ///   value, [`crate::format::is_unresolved`]) it is shown as its range instead;
    /// - any other value: 4 significant digits.
    ///
    /// A typed status of a value beyond its error or basis (e.g. "not converged in the grid")
    /// belongs in the match of this function: [`Shown::accuracy`] carries it in words.
    pub fn shown(&self) -> Shown {
        let unit = match self.unit.symbol() {
            "" => String::new(),
            u => format!(" {u}"),
        };
        let v = self.value;
        let (number, accuracy, unresolved) = match &self.accuracy {
            Accuracy::Error { error, .. } if is_unresolved(v, *error) => (
                format!("unresolved: {}", unresolved(v, *error)),
                format!("± {}{unit}, at least half the value", format_error(*error)),
                true,
            ),
            Accuracy::Error { error, .. } if *error == 0.0 => {
                (number(v, Digits::Error(0.0)), format!("± 0{unit} (exact up to rounding)"), false)
            }
            Accuracy::Error { error, .. } => {
                (number(v, Digits::Error(*error)), format!("± {}{unit}", format_error(*error)), false)
            }
            Accuracy::Basis { basis } => {
                let exactish = matches!(basis, ValueBasis::Exact | ValueBasis::Configured);
                if self.unit == Unit::Count && v.fract() == 0.0 && v.abs() < 1e15 {
                    (format!("{v:.0}"), basis.text().to_string(), false)
                } else if exactish && significant_digits(v) <= 8 {
                    (number(v, Digits::Shortest), basis.text().to_string(), false)
                } else if exactish {
                    (
                        format!("≈ {}", number(v, Digits::Significant(7))),
                        format!("{}, shown rounded", basis.text()),
                        false,
                    )
                } else if matches!(basis, ValueBasis::UpperBound | ValueBasis::LowerBound) {
                    (number(v, Digits::Significant(7)), basis.text().to_string(), false)
                } else {
                    (number(v, Digits::Significant(4)), basis.text().to_string(), false)
                }
            }
        };
        Shown { number, accuracy, unit, unresolved }
    }

    /// The number as printed, without its unit ([`Quantity::shown`]).
    pub fn number_text(&self) -> String {
        self.shown().number
    }

    /// The value as printed ([`Quantity::number_text`]) with the unit (`0.12086 1/s`,
    /// `unresolved: −0.22 … 0.92 N`).
    pub fn value_text(&self) -> String {
        let s = self.shown();
        format!("{}{}", s.number, s.unit)
    }

    /// "= value unit" for a one-line summary (`= 1 1/s`), or "≈ value unit" with 4 significant
    /// digits for an exact or configured value shown rounded (`≈ 3.333×10⁻⁴ 1/s`).
    pub fn equals_text(&self) -> String {
        let s = self.shown();
        if s.number.starts_with('≈') {
            format!("≈ {}{}", number(self.value, Digits::Significant(4)), s.unit)
        } else {
            format!("= {}{}", s.number, s.unit)
        }
    }

    /// The value with its error and unit (`0.12085992204661 ± 3.4×10⁻¹³ 1/s`), an unresolved
    /// value as its range (`unresolved: −0.22 … 0.92 N`), or the value with its unit alone when
    /// it has no error estimate.
    pub fn pm_text(&self) -> String {
        let s = self.shown();
        match self.error() {
            Some(e) if !s.unresolved && e > 0.0 => format!("{} ± {}{}", s.number, format_error(e), s.unit),
            _ => format!("{}{}", s.number, s.unit),
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

    /// The error with its unit, or the basis, as printed (`± 3.4×10⁻¹³ 1/s`, `exact`,
    /// `simulation`; [`Quantity::shown`]).
    pub fn accuracy_text(&self) -> String {
        self.shown().accuracy
    }

    /// Is the value (and the error) finite?
    pub fn is_finite(&self) -> bool {
        self.value.is_finite() && self.error().is_none_or(f64::is_finite)
    }
}

/// Significant digits of the shortest round-trip decimal of `x` (0 for 0).
fn significant_digits(x: f64) -> usize {
    let s = format!("{:e}", x.abs());
    let mantissa = s.split('e').next().unwrap_or("");
    mantissa.chars().filter(|c| c.is_ascii_digit()).count()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ratios_print_no_unit_and_serialise_their_basis() {
        let q = Quantity::exact("printed λ2", -215.9, Unit::JouleSecond);
        assert_eq!(q.value_text(), "−215.9 J s");
        let big = Quantity::exact("ω(f)²", 6.787e29 + 1.234e22, Unit::Dimensionless);
        assert_eq!((big.number_text(), big.accuracy_text()), ("≈ 6.787000×10²⁹".into(), "exact, shown rounded".into()));
        let u = Quantity::with_error("RMS τ1", 0.35, 0.57, Unit::Newton, &[ErrorSource::Spread]);
        assert_eq!(u.pm_text(), "unresolved: −0.22 … 0.92 N");
        assert_eq!(u.accuracy_text(), "± 0.57 N, at least half the value");
        let w = Quantity::with_error("ω₁", 0.120859922046612, 3.4e-13, Unit::PerSecond, &[]);
        assert_eq!(w.pm_text(), "0.12085992204661 ± 3.4×10⁻¹³ 1/s");
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
