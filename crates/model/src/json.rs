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

/// The first number token of JSON `text` (outside strings) whose magnitude is below the smallest
/// normal f64 but whose digits are not all zero: `1e-400` would be read as 0 and `1e-310` as a
/// subnormal with lost digits. Returns the token and the value it would be read as.
pub fn underflowing_number(text: &str) -> Option<(String, f64)> {
    let b = text.as_bytes();
    let (mut i, mut in_string) = (0, false);
    while i < b.len() {
        let c = b[i];
        if in_string {
            match c {
                b'\\' => i += 2,
                b'"' => {
                    in_string = false;
                    i += 1;
                }
                _ => i += 1,
            }
            continue;
        }
        if c == b'"' {
            in_string = true;
            i += 1;
            continue;
        }
        if c == b'-' || c.is_ascii_digit() {
            let start = i;
            while i < b.len() && matches!(b[i], b'0'..=b'9' | b'-' | b'+' | b'.' | b'e' | b'E') {
                i += 1;
            }
            let token = &text[start..i];
            if let Some(x) = underflows(token) {
                return Some((token.to_string(), x));
            }
            continue;
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
    let allowed = format!(
        "0 or a magnitude of at least {:e} (the smallest normal f64); {token} would silently be read as {read_as:e}",
        f64::MIN_POSITIVE
    );
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
