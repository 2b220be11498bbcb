//! Exact rational helpers built on [`BigRational`].
//!
//! Everything here is exact: decimal strings such as `"0.35"` become `7/20`,
//! not the nearest binary float; an `f64` becomes the dyadic rational it
//! denotes bit for bit; and [`to_f64`] rounds correctly (round half to even),
//! so it is only ever used for display, never for a decision.

use num_bigint::{BigInt, Sign};
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

/// Errors from parsing or converting exact rationals.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ExactError {
    /// The text is not a decimal number, an integer or a fraction `p/q`.
    #[error("not an exact number: {text:?} ({reason})")]
    Parse {
        /// The offending text.
        text: String,
        /// Why it was rejected.
        reason: String,
    },
    /// A fraction `p/q` with `q = 0`.
    #[error("zero denominator in {0:?}")]
    ZeroDenominator(String),
    /// `NaN` or an infinity has no rational value.
    #[error("non-finite float {0} has no rational value")]
    NonFinite(f64),
}

/// Largest decimal exponent accepted by [`parse_rational`] (guards against
/// `1e1000000000` allocating a gigantic integer).
pub const MAX_DECIMAL_EXPONENT: i64 = 100_000;

fn parse_err(text: &str, reason: &str) -> ExactError {
    ExactError::Parse { text: text.to_string(), reason: reason.to_string() }
}

/// Parses an optionally signed integer made of ASCII digits only.
fn parse_int(text: &str, whole: &str) -> Result<BigInt, ExactError> {
    let digits = text.strip_prefix(['+', '-']).unwrap_or(text);
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return Err(parse_err(whole, "expected digits"));
    }
    text.parse::<BigInt>().map_err(|e| parse_err(whole, &e.to_string()))
}

/// Bounds on the text of one exact number, checked before any big-integer arithmetic so that
/// a few bytes (`"-1e99999"`, a million-digit integer) cannot make a reader hang.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NumberLimits {
    /// Most characters of the whole text (digits, sign, `/`, `.`, `e`, exponent).
    pub max_chars: usize,
    /// Largest |decimal exponent| after the fraction digits are accounted for
    /// (`"1.5e-3"` has exponent −4).
    pub max_exponent: i64,
}

impl NumberLimits {
    /// The limits of certificate files: 32 characters, |exponent| ≤ 32 (config decimals have
    /// ≤ 24 characters and magnitudes in [1e-12, 1e12]; certificate fractions ≤ 20 characters).
    pub const CERTIFICATE: NumberLimits = NumberLimits { max_chars: 32, max_exponent: 32 };
}

/// [`parse_rational`] with the text's length and decimal exponent bounded by `limits`
/// *before* any digits are turned into big integers.
///
/// # Errors
/// [`ExactError::Parse`] naming the limit that was exceeded, or any error of
/// [`parse_rational`].
pub fn parse_rational_bounded(text: &str, limits: &NumberLimits) -> Result<BigRational, ExactError> {
    let s = text.trim();
    if s.len() > limits.max_chars {
        return Err(parse_err(
            &format!("{}…", s.chars().take(16).collect::<String>()),
            &format!("{} characters, at most {} allowed", s.len(), limits.max_chars),
        ));
    }
    if let Some(pos) = s.find(['e', 'E']) {
        let exp: i64 = s[pos + 1..].parse().map_err(|_| parse_err(text, "bad exponent"))?;
        let mantissa = &s[..pos];
        let frac_len = mantissa.split_once('.').map_or(0, |(_, f)| f.len());
        let m = limits.max_exponent;
        // checked and unsigned: `i64::MIN.abs()` wraps to i64::MIN in release builds, which
        // would pass any `≤ m` test
        match decimal_scale(exp, frac_len) {
            Some(scale) if scale.unsigned_abs() <= m.unsigned_abs() => {}
            Some(scale) => {
                return Err(parse_err(text, &format!("decimal exponent {scale} outside [-{m}, {m}]")));
            }
            None => return Err(parse_err(text, &format!("decimal exponent outside [-{m}, {m}]"))),
        }
    }
    parse_rational(text)
}

/// The power of ten of a decimal `d.ddd e exp` with `frac_len` fraction digits: `exp − frac_len`,
/// or `None` if that is not an `i64` (never wraps).
fn decimal_scale(exp: i64, frac_len: usize) -> Option<i64> {
    exp.checked_sub(i64::try_from(frac_len).ok()?)
}

/// Parses an exact rational from text.
///
/// Accepted forms (surrounding whitespace is ignored):
/// * fractions `p/q` with integer `p`, `q` (e.g. `"2/3"`, `"-7/20"`);
/// * integers (`"42"`, `"-3"`);
/// * decimals with optional exponent (`"0.35"` → 7/20, `"-1.5e-3"` → −3/2000,
///   `".5"`, `"5."`, `"1E+3"`).
///
/// `inf`, `nan` and hexadecimal are rejected. The result is always reduced.
pub fn parse_rational(text: &str) -> Result<BigRational, ExactError> {
    let s = text.trim();
    if s.is_empty() {
        return Err(parse_err(text, "empty"));
    }
    if let Some((p, q)) = s.split_once('/') {
        let num = parse_int(p.trim(), text)?;
        let den = parse_int(q.trim(), text)?;
        if den.is_zero() {
            return Err(ExactError::ZeroDenominator(text.to_string()));
        }
        return Ok(BigRational::new(num, den));
    }
    let (negative, body) = match s.as_bytes()[0] {
        b'-' => (true, &s[1..]),
        b'+' => (false, &s[1..]),
        _ => (false, s),
    };
    let (mantissa, exponent) = match body.find(['e', 'E']) {
        Some(pos) => {
            let exp_text = &body[pos + 1..];
            let exp_digits = exp_text.strip_prefix(['+', '-']).unwrap_or(exp_text);
            if exp_digits.is_empty() || !exp_digits.bytes().all(|b| b.is_ascii_digit()) {
                return Err(parse_err(text, "bad exponent"));
            }
            let e: i64 = exp_text.parse().map_err(|_| parse_err(text, "exponent out of range"))?;
            (&body[..pos], e)
        }
        None => (body, 0),
    };
    let (int_part, frac_part) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    if int_part.is_empty() && frac_part.is_empty() {
        return Err(parse_err(text, "no digits"));
    }
    if !int_part.bytes().chain(frac_part.bytes()).all(|b| b.is_ascii_digit()) {
        return Err(parse_err(text, "expected a decimal number"));
    }
    let digits = format!("{int_part}{frac_part}");
    let mut num: BigInt = digits.parse().map_err(|_| parse_err(text, "bad digits"))?;
    if negative {
        num = -num;
    }
    let scale = decimal_scale(exponent, frac_part.len())
        .filter(|e| e.unsigned_abs() <= MAX_DECIMAL_EXPONENT.unsigned_abs())
        .ok_or_else(|| parse_err(text, "exponent out of range"))?;
    let power = usize::try_from(scale.unsigned_abs()).map_err(|_| parse_err(text, "exponent out of range"))?;
    let ten_pow = num_traits::pow(BigInt::from(10u32), power);
    Ok(if scale >= 0 { BigRational::from_integer(num * ten_pow) } else { BigRational::new(num, ten_pow) })
}

/// Digits of an integer that messages show in full ([`abbreviated`]).
pub const SHOWN_DIGITS: usize = 24;

/// A rational for messages: `p/q` (or `p`) in full when numerator and denominator have at most
/// [`SHOWN_DIGITS`] digits; longer ones as their first 8 and last 4 digits with their length
/// (`-18180890…8353 (250 digits)`), followed by the value (`≈ -1.254826e13`). An exact pivot of
/// a 44 × 44 LDLᵀ has hundreds of digits, which no reader can use.
pub fn abbreviated(r: &BigRational) -> String {
    fn int(n: &BigInt) -> String {
        let s = n.to_string();
        let digits = s.trim_start_matches('-').len();
        if digits <= SHOWN_DIGITS {
            return s;
        }
        let sign = if s.starts_with('-') { "-" } else { "" };
        let d = s.trim_start_matches('-');
        format!("{sign}{}…{} ({digits} digits)", &d[..8], &d[digits - 4..])
    }
    let full = r.numer().to_string().len() <= SHOWN_DIGITS && r.denom().to_string().len() <= SHOWN_DIGITS;
    match (r.is_integer(), full) {
        (true, true) => r.numer().to_string(),
        (true, false) => format!("{} (≈ {:.6e})", int(r.numer()), to_f64(r)),
        (false, _) => format!("{}/{} (≈ {:.6e})", int(r.numer()), int(r.denom()), to_f64(r)),
    }
}

/// Formats a rational as `"p/q"` (reduced, `q ≥ 1`, sign on `p`), e.g. `"-7/20"`,
/// `"3/1"`. This is the canonical form written into certificates.
pub fn to_fraction_string(r: &BigRational) -> String {
    format!("{}/{}", r.numer(), r.denom())
}

/// Inverse of [`to_fraction_string`]; accepts every form [`parse_rational`] does.
pub fn from_fraction_string(s: &str) -> Result<BigRational, ExactError> {
    parse_rational(s)
}

/// Exact value of a finite `f64`: every finite double is `m · 2^e` with integer
/// `m`, `e`, so the result is a dyadic rational equal to `x` bit for bit
/// (`0.1` gives 3602879701896397/36028797018963968). `-0.0` gives 0.
///
/// # Errors
/// [`ExactError::NonFinite`] for NaN and ±∞.
pub fn from_f64_exact(x: f64) -> Result<BigRational, ExactError> {
    if !x.is_finite() {
        return Err(ExactError::NonFinite(x));
    }
    let bits = x.to_bits();
    let negative = bits >> 63 == 1;
    let biased = ((bits >> 52) & 0x7ff) as i64;
    let frac = bits & ((1u64 << 52) - 1);
    // value = m * 2^e
    let (m, e) = if biased == 0 { (frac, -1074i64) } else { (frac | (1u64 << 52), biased - 1075) };
    let mut num = BigInt::from(m);
    if negative {
        num = -num;
    }
    Ok(if e >= 0 {
        BigRational::from_integer(num << (e as usize))
    } else {
        BigRational::new(num, BigInt::one() << ((-e) as usize))
    })
}

/// Nearest `f64` to `r` (round half to even; ±∞ beyond the double range,
/// gradual underflow to subnormals/±0). For display and diagnostics only.
pub fn to_f64(r: &BigRational) -> f64 {
    if r.is_zero() {
        return 0.0;
    }
    let negative = r.is_negative();
    let a = r.numer().abs();
    let b = r.denom().clone();
    let (a_bits, b_bits) = (a.bits() as i64, b.bits() as i64);
    // Choose k so that q = floor(a / (b 2^k)) lies in [2^52, 2^53].
    let quotient = |k: i64| -> (BigInt, BigInt, BigInt) {
        let (num, den) = if k >= 0 { (a.clone(), &b << (k as usize)) } else { (&a << ((-k) as usize), b.clone()) };
        let (q, rem) = num.div_rem(&den);
        (q, rem, den)
    };
    let mut k = a_bits - b_bits - 53;
    let two52 = BigInt::one() << 52usize;
    let two53 = BigInt::one() << 53usize;
    let (mut q, mut rem, mut den) = quotient(k);
    while q >= two53 {
        k += 1;
        (q, rem, den) = quotient(k);
    }
    while q < two52 && k > -1074 {
        k -= 1;
        (q, rem, den) = quotient(k);
    }
    if k < -1074 {
        k = -1074;
        (q, rem, den) = quotient(k);
    }
    // Round half to even.
    let twice = &rem << 1usize;
    let round_up = match twice.cmp(&den) {
        std::cmp::Ordering::Greater => true,
        std::cmp::Ordering::Equal => q.is_odd(),
        std::cmp::Ordering::Less => false,
    };
    if round_up {
        q += 1;
    }
    let mut m = q.to_u64().expect("mantissa fits in u64");
    if m == 1u64 << 53 {
        m >>= 1;
        k += 1;
    }
    let magnitude = if m < (1u64 << 52) {
        // Subnormal (k == -1074); m == 2^52 would be the smallest normal, which
        // the same bit pattern also encodes.
        f64::from_bits(m)
    } else {
        // value = m * 2^k with m in [2^52, 2^53) is (1.f) * 2^(E - 1023) with E = k + 1075.
        let biased = k + 1075;
        if biased >= 0x7ff {
            f64::INFINITY
        } else {
            f64::from_bits(((biased as u64) << 52) | (m - (1u64 << 52)))
        }
    };
    if negative {
        -magnitude
    } else {
        magnitude
    }
}

/// Least common multiple of the denominators of `values` (1 for an empty
/// iterator). Multiplying by it turns every value into an integer.
pub fn denominator_lcm<'a>(values: impl IntoIterator<Item = &'a BigRational>) -> BigInt {
    values.into_iter().fold(BigInt::one(), |acc, v| acc.lcm(v.denom()))
}

/// Sign of a rational as −1, 0 or +1.
pub fn sign(r: &BigRational) -> i8 {
    match r.numer().sign() {
        Sign::Minus => -1,
        Sign::NoSign => 0,
        Sign::Plus => 1,
    }
}

/// Shorthand for the integer `n` as a rational.
pub fn int(n: i64) -> BigRational {
    BigRational::from_integer(BigInt::from(n))
}

/// Shorthand for the reduced fraction `p/q`.
///
/// # Panics
/// If `q == 0`.
pub fn frac(p: i64, q: i64) -> BigRational {
    BigRational::new(BigInt::from(p), BigInt::from(q))
}
