//! Strict reading of configuration JSON, beyond what serde checks: one object of sections (never
//! a positional array), no number that silently underflows, and −0 read as 0 (so equal configs
//! hash equally).

use serde_json::Value;

use crate::ConfigError;

/// Refuses a JSON array anywhere in a configuration value. serde fills a struct from an array
/// positionally (`[{…wing…}, {…control…}, …]` would be accepted), and no configuration field is
/// a sequence, so an array is always a mistake.
pub fn reject_positional(v: &Value) -> Result<(), ConfigError> {
    fn walk(v: &Value, path: &mut Vec<String>) -> Result<(), ConfigError> {
        match v {
            Value::Array(_) => {
                let at = if path.is_empty() { "the document".to_string() } else { path.join(".") };
                Err(ConfigError::Parse(format!(
                    "{at} is a JSON array: a configuration is one JSON object of sections with named keys \
                     (like configs/paper.json), never positional"
                )))
            }
            Value::Object(m) => {
                for (k, x) in m {
                    path.push(k.clone());
                    walk(x, path)?;
                    path.pop();
                }
                Ok(())
            }
            _ => Ok(()),
        }
    }
    if !v.is_object() && !v.is_array() {
        return Err(ConfigError::Parse(
            "the document is not a JSON object: a configuration is one JSON object of sections (like configs/paper.json)"
                .into(),
        ));
    }
    walk(v, &mut Vec::new())
}

/// A number of a JSON text that f64 cannot hold as written.
#[derive(Debug, Clone, PartialEq)]
pub struct UnrepresentableNumber {
    /// The dotted key path of the value (`control.a`; array elements as `[i]`), when inside an
    /// object.
    pub field: Option<String>,
    /// The number as written (`1e5000`, `1e-400`).
    pub token: String,
    /// `Some(value read)` for a number below the smallest normal f64 (read as 0 or a
    /// subnormal); `None` for one beyond the largest (read as ∞).
    pub underflow: Option<f64>,
}

impl UnrepresentableNumber {
    /// The error naming the field and the number as written.
    pub fn error(&self) -> ConfigError {
        match self.underflow {
            Some(read_as) => underflow_error(self.field.as_deref(), &self.token, read_as),
            None => match &self.field {
                Some(f) => ConfigError::NotFinite { field: f.clone(), value: self.token.clone() },
                None => {
                    ConfigError::Parse(format!("the number {} is beyond the largest f64 (about 1.8e308)", self.token))
                }
            },
        }
    }
}

/// The key path of the scanner's position: one entry per open object (its current key) or
/// array (its current index).
enum Level {
    Object(Option<String>),
    Array(usize),
}

fn path_text(levels: &[Level]) -> Option<String> {
    let mut out = String::new();
    for l in levels {
        match l {
            Level::Object(Some(k)) => {
                if !out.is_empty() {
                    out.push('.');
                }
                out.push_str(k);
            }
            Level::Object(None) => return None,
            Level::Array(i) => out.push_str(&format!("[{i}]")),
        }
    }
    (!out.is_empty()).then_some(out)
}

/// The first number of JSON `text` (outside strings) that f64 cannot hold as written: a
/// magnitude below the smallest normal f64 whose digits are not all zero (`1e-400` would be
/// read as 0, `1e-310` as a subnormal with lost digits), or beyond the largest (`1e5000`), with
/// the key path where it stands. A scan of the text (serde_json has already parsed it, or
/// reports its own syntax errors).
pub fn unrepresentable_number(text: &str) -> Option<UnrepresentableNumber> {
    let b = text.as_bytes();
    let (mut i, mut levels, mut last_string) = (0, Vec::<Level>::new(), None::<String>);
    while i < b.len() {
        match b[i] {
            b'"' => {
                let start = i + 1;
                i += 1;
                while i < b.len() && b[i] != b'"' {
                    i += if b[i] == b'\\' { 2 } else { 1 };
                }
                last_string = text.get(start..i.min(b.len())).map(str::to_string);
                i += 1;
                continue;
            }
            b'{' => levels.push(Level::Object(None)),
            b'[' => levels.push(Level::Array(0)),
            b'}' | b']' => {
                levels.pop();
            }
            b':' => {
                if let Some(Level::Object(k)) = levels.last_mut() {
                    *k = last_string.take();
                }
            }
            b',' => {
                if let Some(Level::Array(n)) = levels.last_mut() {
                    *n += 1;
                }
            }
            c if c == b'-' || c.is_ascii_digit() => {
                let start = i;
                while i < b.len() && matches!(b[i], b'0'..=b'9' | b'-' | b'+' | b'.' | b'e' | b'E') {
                    i += 1;
                }
                let token = &text[start..i];
                let overflow = token.parse::<f64>().is_ok_and(|x| !x.is_finite());
                let underflow = underflows(token);
                if overflow || underflow.is_some() {
                    return Some(UnrepresentableNumber {
                        field: path_text(&levels),
                        token: token.to_string(),
                        underflow,
                    });
                }
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    None
}

/// `Some(value read)` if the number text `token` is nonzero but reads below the smallest normal
/// f64 in magnitude.
pub fn underflows(token: &str) -> Option<f64> {
    let x: f64 = token.trim().parse().ok()?;
    let mantissa = token.trim().split(['e', 'E']).next().unwrap_or("");
    let nonzero = mantissa.bytes().any(|d| (b'1'..=b'9').contains(&d));
    (nonzero && x.is_finite() && x.abs() < f64::MIN_POSITIVE).then_some(x)
}

/// The error for an underflowing number (`field` when known).
pub fn underflow_error(field: Option<&str>, token: &str, read_as: f64) -> ConfigError {
    let why = if read_as == 0.0 {
        format!("{token} would be read as 0")
    } else {
        format!("{token} is below it: a subnormal f64 keeps fewer significant digits than the 16 of a normal one")
    };
    let allowed = format!("0 or a magnitude of at least {:e} (the smallest normal f64); {why}", f64::MIN_POSITIVE);
    match field {
        Some(f) => ConfigError::OutOfRange { field: f.to_string(), value: token.to_string(), allowed },
        None => ConfigError::Parse(format!("the number {token} is out of range: allowed {allowed}")),
    }
}

/// Replaces every −0 in a JSON value by 0 (−0 and 0 are the same parameter, so they must give
/// the same configuration text and hash).
pub fn normalise_zeros(v: &mut Value) {
    match v {
        Value::Number(n) if n.as_f64() == Some(0.0) && n.as_f64().is_some_and(|x| x.is_sign_negative()) => {
            *v = Value::from(0.0);
        }
        Value::Array(a) => a.iter_mut().for_each(normalise_zeros),
        Value::Object(m) => m.values_mut().for_each(normalise_zeros),
        _ => {}
    }
}

/// The first key that occurs twice in one JSON object of `text` (as `path.key`), if any. serde
/// rejects duplicate fields of typed structs, but the manifest's `config` is read as a JSON value,
/// where the last of two equal keys would silently win (a certificate
/// manifest's `config`, a partial `--config` file merged over the default).
pub fn duplicate_key(text: &[u8]) -> Option<String> {
    use serde::de::{DeserializeSeed, Deserializer, MapAccess, SeqAccess, Visitor};
    struct Walk<'a> {
        path: &'a str,
        found: &'a std::cell::RefCell<Option<String>>,
    }
    impl<'de> DeserializeSeed<'de> for Walk<'_> {
        type Value = ();
        fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<(), D::Error> {
            d.deserialize_any(self)
        }
    }
    impl<'de> Visitor<'de> for Walk<'_> {
        type Value = ();
        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            f.write_str("any JSON value")
        }
        fn visit_bool<E>(self, _: bool) -> Result<(), E> {
            Ok(())
        }
        fn visit_i64<E>(self, _: i64) -> Result<(), E> {
            Ok(())
        }
        fn visit_u64<E>(self, _: u64) -> Result<(), E> {
            Ok(())
        }
        fn visit_f64<E>(self, _: f64) -> Result<(), E> {
            Ok(())
        }
        fn visit_str<E>(self, _: &str) -> Result<(), E> {
            Ok(())
        }
        fn visit_unit<E>(self) -> Result<(), E> {
            Ok(())
        }
        fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<(), A::Error> {
            let mut i = 0;
            while seq.next_element_seed(Walk { path: &format!("{}[{i}]", self.path), found: self.found })?.is_some() {
                i += 1;
            }
            Ok(())
        }
        fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<(), A::Error> {
            let mut seen = std::collections::BTreeSet::new();
            while let Some(key) = map.next_key::<String>()? {
                let path = if self.path.is_empty() { key.clone() } else { format!("{}.{key}", self.path) };
                if !seen.insert(key) && self.found.borrow().is_none() {
                    *self.found.borrow_mut() = Some(path.clone());
                }
                map.next_value_seed(Walk { path: &path, found: self.found })?;
            }
            Ok(())
        }
    }
    let found = std::cell::RefCell::new(None);
    let mut de = serde_json::Deserializer::from_slice(text);
    let _ = Walk { path: "", found: &found }.deserialize(&mut de);
    found.into_inner()
}
