//! The one number format for people: every number the ledger's text, `check`, the report and
//! its figures print goes through [`number`] (re-exported as `wingcheck_model::format`).
//! Machine outputs — CSV, JSON, certificates — keep round-trip numbers ([`crate::number`]).
//!
//! The rules, in one place:
//! - **digits from the stated error**: a number with an error is written to the decade of the
//!   error's second significant digit ([`Digits::Error`]: `0.120859922046612 ± 3.4e-13` →
//!   `0.12085992204661`); without one, four significant digits ([`Digits::Significant`]); an
//!   exact or configured value as its shortest decimal ([`Digits::Shortest`]);
//! - **a real minus sign** `−` (U+2212), never the hyphen-minus;
//! - **exponents as ×10ⁿ**: fixed notation for 10⁻³ ≤ |v| < 10⁵ (trailing zeros kept: they are
//!   significant), else `1.23×10⁻⁵`;
//! - the decisions above a single number — a value whose ± reaches its size is *unresolved*
//!   and shown as its range ([`unresolved`]), an exact value with too many digits is shown
//!   rounded and says so — are made by `wingcheck_model::Quantity::shown`, which calls
//!   [`number`].
//!
//! [`parse`] reads the format back (tests, and readers of the text).

/// How many digits a number is shown with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Digits {
    /// To the decade of the second significant digit of this absolute error (≥ 0; 0 or not
    /// finite: 15 significant digits), at least one and at most 15 significant digits.
    Error(f64),
    /// This many significant digits (at least 1).
    Significant(usize),
    /// At most this many significant digits, trailing zeros dropped (axis ticks, round inputs:
    /// `0.25`, `2×10⁻⁴`).
    AtMost(usize),
    /// The shortest decimal that reads back to the same f64 (exact and configured values).
    Shortest,
}

/// The minus sign of prose (U+2212).
pub const MINUS: char = '−';

/// Fixed notation for a decimal exponent in this range (10⁻³ ≤ |v| < 10⁵), ×10ⁿ outside.
const FIXED_EXPONENTS: std::ops::Range<i32> = -3..5;

/// `value` as a person reads it ([`Digits`]; real minus sign; ×10ⁿ outside 10⁻³ ≤ |v| < 10⁵).
/// Deterministic; [`parse`] reads it back.
pub fn number(value: f64, digits: Digits) -> String {
    if !value.is_finite() {
        return if value.is_nan() {
            "NaN".into()
        } else if value > 0.0 {
            "∞".into()
        } else {
            format!("{MINUS}∞")
        };
    }
    if value == 0.0 {
        return "0".into();
    }
    let (mantissa, exp) = match digits {
        Digits::Shortest => {
            let sci = format!("{:e}", value.abs());
            let (m, e) = sci.split_once('e').expect("exponent");
            (m.to_string(), e.parse::<i32>().expect("integer exponent"))
        }
        other => {
            let n = match other {
                Digits::Error(e) => digits_for_error(value, e),
                Digits::Significant(n) | Digits::AtMost(n) => n.max(1),
                Digits::Shortest => unreachable!(),
            };
            let sci = format!("{:.*e}", n - 1, value.abs());
            let (m, e) = sci.split_once('e').expect("exponent");
            let m = if matches!(other, Digits::AtMost(_)) && m.contains('.') {
                m.trim_end_matches('0').trim_end_matches('.')
            } else {
                m
            };
            (m.to_string(), e.parse::<i32>().expect("integer exponent"))
        }
    };
    let sign = if value < 0.0 { MINUS.to_string() } else { String::new() };
    if FIXED_EXPONENTS.contains(&exp) {
        format!("{sign}{}", fixed(&mantissa, exp))
    } else {
        format!("{sign}{mantissa}×10{}", superscript(exp))
    }
}

/// Significant digits of `value` written to the decade of the second significant digit of the
/// absolute error `error` (1 to 15; 15 for an error that is 0 or not finite).
fn digits_for_error(value: f64, error: f64) -> usize {
    if !(error > 0.0 && error.is_finite()) {
        return 15;
    }
    let mag = value.abs().log10().floor() as i32;
    (mag - (error.log10().floor() as i32 - 1) + 1).clamp(1, 15) as usize
}

/// A mantissa `d.ddd` (digits and at most one point) times 10^exp in positional notation.
fn fixed(mantissa: &str, exp: i32) -> String {
    let digits: String = mantissa.chars().filter(char::is_ascii_digit).collect();
    let point = 1 + exp; // digits before the decimal point
    if point <= 0 {
        format!("0.{}{digits}", "0".repeat((-point) as usize))
    } else if point as usize >= digits.len() {
        format!("{digits}{}", "0".repeat(point as usize - digits.len()))
    } else {
        let (a, b) = digits.split_at(point as usize);
        format!("{a}.{b}")
    }
}

/// The integer `n` (any integer type, big integers included) in superscript digits (`⁻¹²`):
/// the one way a power is written in prose (`10⁻³`, `z²`), never with a caret.
pub fn superscript(n: impl std::fmt::Display) -> String {
    const SUP: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    n.to_string()
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            c => c.to_digit(10).map_or(c, |d| SUP[d as usize]),
        })
        .collect()
}

/// A number with an estimated absolute error: digits from the error ([`Digits::Error`]), or
/// four significant digits without one.
pub fn format_value(value: f64, error: Option<f64>) -> String {
    match error {
        Some(e) => number(value, Digits::Error(e)),
        None => number(value, Digits::Significant(4)),
    }
}

/// An error bar as printed: two significant digits (`3.4×10⁻¹³`, `0.0021`).
pub fn format_error(error: f64) -> String {
    number(error, Digits::Significant(2))
}

/// `value` with `digits` significant digits ([`number`]).
pub fn with_significant(value: f64, digits: usize) -> String {
    number(value, Digits::Significant(digits))
}

/// A configured or exact input in prose: its shortest decimal ([`Digits::Shortest`]).
pub fn exact(value: f64) -> String {
    number(value, Digits::Shortest)
}

/// Whether a value with absolute error `error` is unresolved: the error is at least half its
/// size (error ≥ |value|/2 > 0), so the range [value − error, value + error] spans a factor of
/// three or more and not even the leading digit is known ("3.7 ± 3.6 N", "0.35 ± 0.57 N").
pub fn is_unresolved(value: f64, error: f64) -> bool {
    error > 0.0 && error.is_finite() && 2.0 * error >= value.abs()
}

/// The range [value − error, value + error] of an unresolved value, each end with the digits
/// of the error (`−0.2 … 0.9`).
pub fn unresolved(value: f64, error: f64) -> String {
    format!("{} … {}", number(value - error, Digits::Error(error)), number(value + error, Digits::Error(error)))
}

/// Reads a number of this format (or a plain Rust float) back: `−` or `-`, digits, an optional
/// `×10ⁿ` or `e±n` exponent. None for anything else.
pub fn parse(text: &str) -> Option<f64> {
    let t = text.trim().replace(MINUS, "-");
    if let Some((m, e)) = t.split_once("×10") {
        let exp: String = e
            .chars()
            .map(|c| match c {
                '⁻' => Some('-'),
                c => "⁰¹²³⁴⁵⁶⁷⁸⁹".chars().position(|s| s == c).and_then(|d| char::from_digit(d as u32, 10)),
            })
            .collect::<Option<String>>()?;
        return format!("{m}e{exp}").parse().ok();
    }
    t.parse().ok()
}

/// The resolution a number with error `error` is written to: the decade of the error's second
/// significant digit (the rule of [`Digits::Error`]: 1.4e-4 → 1e-5). None for an error that is
/// 0 or not finite (then the shortest round-trip decimal is exact).
pub fn resolution_of(error: f64) -> Option<f64> {
    (error > 0.0 && error.is_finite()).then(|| 10f64.powi(error.log10().floor() as i32 - 1))
}

/// `value` written to `resolution` (a power of ten, [`resolution_of`]) for a data file (a
/// machine output: ASCII minus, no exponent): fixed notation with the resolution's decimals
/// (none for a resolution ≥ 1), trailing zeros dropped, `0` for a value that rounds to zero
/// (`0.04952` for 0.0495234… at 1e-5); deterministic, parses back as f64.
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
    fn digits_follow_the_error_with_a_real_minus_and_powers_of_ten() {
        // ω₁ of the paper wing with its Romberg error: down to the error's second digit (1e-14).
        assert_eq!(format_value(0.120859922046612, Some(3.4e-13)), "0.12085992204661");
        assert_eq!(format_value(-4.15400123, Some(3.3e-4)), "−4.15400");
        assert_eq!(format_value(-215.9000001, None), "−215.9");
        assert_eq!(format_value(1.5e-5, None), "1.500×10⁻⁵");
        assert_eq!(format_value(9.9996, None), "10.00");
        assert_eq!(format_value(123456.0, None), "1.235×10⁵");
        assert_eq!(format_value(4.8850000075351e6, Some(2.4e-6)), "4.8850000075351×10⁶");
        assert_eq!(format_error(3.39e-13), "3.4×10⁻¹³");
        assert_eq!(format_error(0.0021), "0.0021");
        assert_eq!(exact(0.35), "0.35");
        assert_eq!(exact(9.77e6), "9.77×10⁶");
        assert_eq!(exact(-1e-12), "−1×10⁻¹²");
        assert_eq!(exact(3000.0), "3000");
        assert_eq!(number(f64::NEG_INFINITY, Digits::Shortest), "−∞");
        assert_eq!(number(0.25, Digits::AtMost(4)), "0.25");
        assert_eq!(number(-2.0e-4, Digits::AtMost(4)), "−2×10⁻⁴");
        assert_eq!(number(20.0, Digits::AtMost(4)), "20");
        // Every printed number parses back to its rounded value.
        for v in [0.1208599220466, -215.9, 1.5e-5, 3.1e7, -6.787e29, 0.00123] {
            let s = format_value(v, None);
            let back = parse(&s).unwrap();
            assert!((back - v).abs() <= 5e-4 * v.abs(), "{s}");
            assert!(!s.contains('-') && !s.contains('e'), "{s}");
            assert_eq!(parse(&exact(v)), Some(v));
        }
    }

    #[test]
    fn a_bar_as_large_as_the_value_is_a_range() {
        // "explicit-rule RMS τ1 3.7 ± 3.6 N" (issue 47): not resolved, its range instead
        assert!(is_unresolved(3.7, 3.6) && is_unresolved(0.35, 0.57));
        assert!(is_unresolved(3.7, 1.85) && !is_unresolved(3.7, 1.8));
        assert_eq!(unresolved(0.35, 0.57), "−0.22 … 0.92");
        assert!(!is_unresolved(1.0, 0.0));
    }
}
