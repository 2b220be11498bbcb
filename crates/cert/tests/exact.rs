//! Tests for exact rational parsing/conversion.

use num_bigint::BigInt;
use num_rational::BigRational;
use proptest::prelude::*;
use wingcheck_cert::exact::*;

#[test]
fn parses_decimals_exactly() {
    // 0.35 = 35/100 = 7/20 (reduced by hand).
    assert_eq!(parse_rational("0.35").unwrap(), frac(7, 20));
    // -1.5e-3 = -15/10000 = -3/2000.
    assert_eq!(parse_rational("-1.5e-3").unwrap(), frac(-3, 2000));
    // "2/3" is the fraction itself.
    assert_eq!(parse_rational("2/3").unwrap(), frac(2, 3));
    // 4/6 reduces to 2/3.
    assert_eq!(parse_rational(" -4/6 ").unwrap(), frac(-2, 3));
    // 1E+3 = 1000.
    assert_eq!(parse_rational("1E+3").unwrap(), int(1000));
    // ".5" and "5." are 1/2 and 5.
    assert_eq!(parse_rational(".5").unwrap(), frac(1, 2));
    assert_eq!(parse_rational("+5.").unwrap(), int(5));
    assert_eq!(parse_rational("42").unwrap(), int(42));
}

#[test]
fn rejects_garbage() {
    for s in ["", "abc", "1/0", "nan", "inf", "1e", "1.2.3", "0x10", "--1", "1/2/3", "e5", "."] {
        assert!(parse_rational(s).is_err(), "{s:?} should be rejected");
    }
    assert!(matches!(parse_rational("1/0"), Err(ExactError::ZeroDenominator(_))));
    assert!(parse_rational("1e999999999").is_err());
}

#[test]
fn f64_to_exact_dyadic() {
    // 0.1 as a double is 3602879701896397 / 2^55 (IEEE 754 binary64, well known).
    let expect = BigRational::new(BigInt::from(3602879701896397u64), BigInt::from(1u64) << 55usize);
    assert_eq!(from_f64_exact(0.1).unwrap(), expect);
    assert_eq!(from_f64_exact(-0.0).unwrap(), int(0));
    assert_eq!(from_f64_exact(0.75).unwrap(), frac(3, 4));
    // Smallest subnormal is 2^-1074 (IEEE 754).
    let tiny = from_f64_exact(f64::from_bits(1)).unwrap();
    assert_eq!(tiny, BigRational::new(BigInt::from(1), BigInt::from(1) << 1074usize));
    assert!(matches!(from_f64_exact(f64::NAN), Err(ExactError::NonFinite(_))));
    assert!(from_f64_exact(f64::INFINITY).is_err());
    assert!(from_f64_exact(f64::NEG_INFINITY).is_err());
}

#[test]
fn nearest_f64() {
    // 1/3 rounds to the double Rust parses "0.3333333333333333" to (correctly rounded).
    assert_eq!(to_f64(&frac(1, 3)), 1.0 / 3.0);
    assert_eq!(to_f64(&frac(7, 20)), 0.35);
    assert_eq!(to_f64(&frac(-3, 2000)), -1.5e-3);
    assert_eq!(to_f64(&int(0)), 0.0);
    // 2^1024 overflows to +inf; 2^-1080 underflows to 0 (below half the smallest subnormal).
    let big = BigRational::from_integer(BigInt::from(1) << 1024usize);
    assert_eq!(to_f64(&big), f64::INFINITY);
    let small = BigRational::new(BigInt::from(1), BigInt::from(1) << 1080usize);
    assert_eq!(to_f64(&small), 0.0);
    // 1 + 2^-53 is a tie between 1 and 1 + 2^-52: ties to even gives 1.
    let tie = BigRational::new((BigInt::from(1) << 53usize) + 1, BigInt::from(1) << 53usize);
    assert_eq!(to_f64(&tie), 1.0);
}

#[test]
fn fraction_string_round_trip() {
    assert_eq!(to_fraction_string(&frac(-7, 20)), "-7/20");
    assert_eq!(to_fraction_string(&int(3)), "3/1");
    assert_eq!(from_fraction_string("-7/20").unwrap(), frac(-7, 20));
}

proptest! {
    #[test]
    fn f64_round_trips(bits in any::<u64>()) {
        let x = f64::from_bits(bits);
        prop_assume!(x.is_finite());
        let r = from_f64_exact(x).unwrap();
        prop_assert_eq!(to_f64(&r).to_bits(), if x == 0.0 { 0.0f64.to_bits() } else { x.to_bits() });
        prop_assert_eq!(from_fraction_string(&to_fraction_string(&r)).unwrap(), r);
    }

    #[test]
    fn to_f64_matches_std_division(p in -1_000_000_000i64..1_000_000_000, q in 1i64..1_000_000_000) {
        // Both p and q are exact in f64 and IEEE division is correctly rounded.
        prop_assert_eq!(to_f64(&frac(p, q)), p as f64 / q as f64);
    }

    #[test]
    fn decimal_text_matches_std_parse(x in any::<f64>()) {
        prop_assume!(x.is_finite());
        // Rust's shortest round-trip formatting; parsing it exactly then rounding
        // must give back x (std's parser is correctly rounded too).
        let s = format!("{x:e}");
        prop_assert_eq!(to_f64(&parse_rational(&s).unwrap()), s.parse::<f64>().unwrap());
    }
}

/// An exponent drawn over the whole i64 range, with its extremes (where `abs()` wraps) and the
/// values near the certificate bound ±32 drawn often.
fn exponent() -> impl Strategy<Value = i64> {
    prop_oneof![
        Just(i64::MIN),
        Just(i64::MIN + 1),
        Just(i64::MAX),
        Just(i64::MAX - 1),
        any::<i64>(),
        -40i64..=40,
        -100_010i64..=-99_990,
        99_990i64..=100_010,
    ]
}

/// A decimal of the parsers' grammar: sign, integer digits, optional `.` and fraction digits,
/// optional `e`/`E` with an optionally signed exponent; returns the text, its digits and the
/// power of ten of the last digit (exp − fraction length, in i128 so it never wraps).
fn decimal() -> impl Strategy<Value = (String, String, i128)> {
    (
        prop_oneof![Just(""), Just("-"), Just("+")],
        "[0-9]{0,12}",
        proptest::option::of("[0-9]{0,12}"),
        proptest::option::of((prop_oneof![Just("e"), Just("E")], prop_oneof![Just(""), Just("+")], exponent())),
    )
        .prop_filter("at least one digit", |(_, i, f, _)| !i.is_empty() || f.as_ref().is_some_and(|f| !f.is_empty()))
        .prop_map(|(sign, int, frac, exp)| {
            let mut text = format!("{sign}{int}");
            let frac = frac.unwrap_or_default();
            if !frac.is_empty() {
                text.push('.');
                text.push_str(&frac);
            }
            let e = match exp {
                Some((mark, plus, e)) => {
                    let plus = if e >= 0 { plus } else { "" };
                    text.push_str(&format!("{mark}{plus}{e}"));
                    e
                }
                None => 0,
            };
            let digits = format!("{sign}{int}{frac}").replace('+', "");
            (text, digits, e as i128 - frac.len() as i128)
        })
}

proptest! {
    /// Over the whole number grammar, exponents across the whole i64 range included: the bounded
    /// parser accepts exactly the texts within the limits (decided here in i128, where nothing
    /// wraps) and then returns the exact value — independently, its correctly rounded f64 is what
    /// std's parser makes of the text; everything else is refused (it never runs away: an
    /// exponent wrapping past the bound would build a 10^(2^63) integer).
    #[test]
    fn bounded_parser_over_the_number_grammar((text, digits, scale) in decimal()) {
        let limits = NumberLimits::CERTIFICATE;
        let within = text.len() <= limits.max_chars && scale.abs() <= limits.max_exponent as i128;
        match parse_rational_bounded(&text, &limits) {
            Ok(r) => {
                prop_assert!(within, "{text:?} accepted outside the limits");
                let ten = BigRational::from_integer(BigInt::from(10));
                let power = num_traits::pow(ten, scale.unsigned_abs() as usize);
                let mantissa = BigRational::from_integer(digits.parse::<BigInt>().unwrap());
                let want = if scale >= 0 { mantissa * power } else { mantissa / power };
                prop_assert_eq!(&r, &want);
                prop_assert_eq!(to_f64(&r), text.parse::<f64>().unwrap());
            }
            Err(e) => {
                prop_assert!(!within, "{text:?} refused within the limits: {e}");
                let m = e.to_string();
                prop_assert!(m.contains("exponent") || m.contains("characters"), "{m}");
            }
        }
        // the unbounded parser (its own guard |scale| ≤ MAX_DECIMAL_EXPONENT) likewise
        match parse_rational(&text) {
            Ok(r) => {
                prop_assert!(scale.abs() <= MAX_DECIMAL_EXPONENT as i128, "{text:?}");
                prop_assert_eq!(to_f64(&r), text.parse::<f64>().unwrap());
            }
            Err(_) => prop_assert!(scale.abs() > MAX_DECIMAL_EXPONENT as i128, "{text:?} refused"),
        }
    }

    /// Fractions p/q over the whole i64 range: exact when q ≠ 0 and the text fits, refused
    /// otherwise.
    #[test]
    fn bounded_parser_over_fractions(p in any::<i64>(), q in prop_oneof![Just(0i64), Just(i64::MIN), any::<i64>()]) {
        let text = format!("{p}/{q}");
        let limits = NumberLimits::CERTIFICATE;
        match parse_rational_bounded(&text, &limits) {
            Ok(r) => {
                prop_assert!(q != 0 && text.len() <= limits.max_chars);
                prop_assert_eq!(r, BigRational::new(BigInt::from(p), BigInt::from(q)));
            }
            Err(_) => prop_assert!(q == 0 || text.len() > limits.max_chars, "{text} refused"),
        }
    }
}

#[test]
fn the_i64_min_exponent_is_refused_at_once() {
    // The reproduction: 22 characters whose exponent − 0 fraction digits is i64::MIN,
    // whose abs() wraps to i64::MIN (< 32) in release builds.
    for text in
        ["1e-9223372036854775808", "-1e-9223372036854775808", "1.5e-9223372036854775807", "1e9223372036854775807"]
    {
        let e = parse_rational_bounded(text, &NumberLimits::CERTIFICATE).unwrap_err().to_string();
        assert!(e.contains("exponent"), "{text}: {e}");
        assert!(parse_rational(text).is_err(), "{text}");
    }
}
