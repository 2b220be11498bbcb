//! The top of the page: what was run (the keys that differ from the embedded default
//! `configs/paper.json`, the command), and the layout helpers that keep numbers whole (a
//! sentence split into text and number tokens, each number drawn unbreakable).

use serde::Serialize;
use serde_json::Value;
use wingcheck_model::Config;

/// One configuration key whose value differs from `configs/paper.json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ConfigChange {
    /// The key as `--set` takes it (`control.a`).
    pub key: String,
    /// The value run: a number in the one number format ([`number_text`]), else the JSON text.
    pub value: String,
    /// The value of `configs/paper.json`, likewise.
    pub paper: String,
}

/// The leaves of a JSON object as (dotted key, value text), in document order.
fn leaves(prefix: &str, v: &Value, out: &mut Vec<(String, String)>) {
    match v {
        Value::Object(m) => {
            for (k, x) in m {
                let key = if prefix.is_empty() { k.clone() } else { format!("{prefix}.{k}") };
                leaves(&key, x, out);
            }
        }
        Value::String(s) => out.push((prefix.to_string(), s.clone())),
        Value::Number(n) => out.push((prefix.to_string(), number_text(n))),
        other => out.push((prefix.to_string(), other.to_string())),
    }
}

/// A configured number in the one number format: its shortest decimal
/// ([`wingcheck_model::format::exact`]: `9.77×10⁶`, `3000`, `0.3`, never the JSON float
/// `9770000.0`); an integer beyond f64's exact range as its digits.
fn number_text(n: &serde_json::Number) -> String {
    match n.as_f64() {
        Some(v) if v.is_finite() && (n.is_f64() || v.abs() <= 2f64.powi(53)) => wingcheck_model::format::exact(v),
        _ => n.to_string(),
    }
}

/// The keys of `cfg` whose typed values differ from the embedded default `configs/paper.json`
/// (compared as the serialised typed values, so `1` and `1.0` are the same), in the config's
/// order.
pub fn config_changes(cfg: &Config) -> Vec<ConfigChange> {
    let json = |c: &Config| serde_json::to_value(c).expect("config serialises");
    let (mut run, mut paper) = (Vec::new(), Vec::new());
    leaves("", &json(cfg), &mut run);
    leaves("", &json(&Config::paper()), &mut paper);
    run.into_iter()
        .filter_map(|(key, value)| {
            let p = paper.iter().find(|(k, _)| *k == key).map(|(_, v)| v.clone()).unwrap_or_else(|| "—".into());
            (p != value).then_some(ConfigChange { key, value, paper: p })
        })
        .collect()
}

/// The command as a user would type it again: the program's file name instead of its path,
/// arguments with spaces or quotes in single quotes. Arguments are taken as the OS gave them
/// (`std::env::args_os`): one that is not UTF-8 is shown with U+FFFD for its invalid bytes.
pub fn command_text<A: AsRef<std::ffi::OsStr>>(args: &[A]) -> String {
    let mut out: Vec<String> = Vec::with_capacity(args.len());
    for (i, a) in args.iter().enumerate() {
        let a = a.as_ref();
        if i == 0 {
            let name = std::path::Path::new(a).file_name().unwrap_or(a);
            out.push(name.to_string_lossy().into_owned());
            continue;
        }
        let a = a.to_string_lossy().into_owned();
        if a.is_empty() || a.contains([' ', '\'', '"', '\\', '$', '*', '?']) {
            out.push(format!("'{}'", a.replace('\'', "'\\''")));
        } else {
            out.push(a);
        }
    }
    out.join(" ")
}

/// A piece of a sentence: text, a number token drawn unbreakable, or a configuration key
/// (`horizon.field_points`) drawn as code.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Piece {
    /// The text.
    pub text: String,
    /// Whether it is a number token (`-4.15405`, `3.3e-4`, `1e-3`).
    pub num: bool,
    /// Whether it is a configuration key (`section.key`, `section.*`).
    pub key: bool,
    /// Whether it is an exponent, drawn raised (`e^(−λt)` → e with −λt raised; `z^k`).
    pub sup: bool,
}

/// The configuration's section names (`wing`, `control`, …), from its typed JSON.
fn sections() -> Vec<String> {
    match serde_json::to_value(Config::paper()) {
        Ok(Value::Object(m)) => m.keys().cloned().collect(),
        _ => Vec::new(),
    }
}

/// Length in bytes of the configuration key at the start of `s` (0 if none): a section name,
/// `.`, then `[a-z0-9_.*]` up to the last letter, digit or `*`.
fn key_len(s: &str, sections: &[String]) -> usize {
    for sec in sections {
        if let Some(rest) = s.strip_prefix(sec.as_str()).and_then(|r| r.strip_prefix('.')) {
            let n = rest
                .char_indices()
                .take_while(|(_, c)| c.is_ascii_lowercase() || c.is_ascii_digit() || matches!(c, '_' | '.' | '*'))
                .last()
                .map_or(0, |(i, c)| i + c.len_utf8());
            let n = rest[..n].trim_end_matches('.').len();
            if n > 0 {
                return sec.len() + 1 + n;
            }
        }
    }
    0
}

/// Length in bytes of the number token at the start of `s` (0 if none): an optional sign
/// (`-` or `−`), digits with at most one `.`, and an exponent `e[-]digits`.
fn number_len(s: &str) -> usize {
    let b = s.as_bytes();
    let mut i = 0;
    if s.starts_with('−') {
        i = '−'.len_utf8();
    } else if b.first() == Some(&b'-') {
        i = 1;
    }
    let digits_from = i;
    let mut dot = false;
    while i < b.len()
        && (b[i].is_ascii_digit() || (b[i] == b'.' && !dot && b.get(i + 1).is_some_and(u8::is_ascii_digit)))
    {
        dot |= b[i] == b'.';
        i += 1;
    }
    if i == digits_from {
        return 0;
    }
    if b.get(i) == Some(&b'e') {
        let mut j = i + 1;
        if b.get(j) == Some(&b'-') {
            j += 1;
        }
        let start = j;
        while j < b.len() && b[j].is_ascii_digit() {
            j += 1;
        }
        if j > start {
            i = j;
        }
    }
    i
}

/// Length in bytes of the caret power at the start of `s` (0 if none), and its exponent: `^`
/// then a bracketed group `(…)` or `{…}` (brackets balanced, dropped from the exponent) or a
/// run of letters and digits (`^2`, `^r`, `^K`).
fn power_len(s: &str) -> (usize, &str) {
    let Some(rest) = s.strip_prefix('^') else { return (0, "") };
    let open = rest.chars().next();
    if let Some(close) = match open {
        Some('(') => Some(')'),
        Some('{') => Some('}'),
        _ => None,
    } {
        let mut depth = 0usize;
        for (i, c) in rest.char_indices() {
            if Some(c) == open {
                depth += 1;
            } else if c == close {
                depth -= 1;
                if depth == 0 {
                    return (1 + i + 1, &rest[1..i]);
                }
            }
        }
        return (0, "");
    }
    let n: usize = rest.chars().take_while(|c| c.is_alphanumeric()).map(char::len_utf8).sum();
    if n == 0 {
        (0, "")
    } else {
        (1 + n, &rest[..n])
    }
}

/// `s` as text, number, key and exponent pieces (a caret power `x^(…)` is an exponent piece,
/// drawn raised: the page shows no caret). A number starts a token: at the start, or after a character
/// that is not a letter, digit or `_` (so `κ2`, `t_f1`, `10⁻³` are text).
pub fn pieces(s: &str) -> Vec<Piece> {
    let sections = sections();
    let mut out: Vec<Piece> = Vec::new();
    let mut text = String::new();
    let mut prev: Option<char> = None;
    let mut i = 0;
    while i < s.len() {
        let rest = &s[i..];
        // (a combining mark, like the tilde of g̃, belongs to the letter before it)
        let starts =
            prev.is_none_or(|p| !(p.is_alphanumeric() || p == '_' || p == '.' || ('\u{300}'..='\u{36f}').contains(&p)));
        let (p, exponent) = power_len(rest);
        if p > 0 {
            if !text.is_empty() {
                out.push(Piece { text: std::mem::take(&mut text), num: false, key: false, sup: false });
            }
            out.push(Piece { text: exponent.to_string(), num: false, key: false, sup: true });
            prev = rest[..p].chars().last();
            i += p;
            continue;
        }
        let k = if starts { key_len(rest, &sections) } else { 0 };
        let n = if starts && k == 0 { number_len(rest) } else { 0 };
        if n > 0 || k > 0 {
            if !text.is_empty() {
                out.push(Piece { text: std::mem::take(&mut text), num: false, key: false, sup: false });
            }
            let n = n.max(k);
            out.push(Piece { text: rest[..n].to_string(), num: k == 0, key: k > 0, sup: false });
            prev = rest[..n].chars().last();
            i += n;
        } else {
            let c = rest.chars().next().expect("non-empty");
            text.push(c);
            prev = Some(c);
            i += c.len_utf8();
        }
    }
    if !text.is_empty() {
        out.push(Piece { text, num: false, key: false, sup: false });
    }
    out
}

/// `s` as text and exponent pieces only ([`pieces`]'s caret powers raised, the rest plain
/// text: for text that was plain before, so the page does not grow by a span per number).
pub fn raised(s: &str) -> Vec<Piece> {
    let mut out: Vec<Piece> = Vec::new();
    for p in pieces(s) {
        match out.last_mut() {
            Some(last) if !p.sup && !last.sup => last.text.push_str(&p.text),
            _ if p.sup => out.push(p),
            _ => out.push(Piece { text: p.text, num: false, key: false, sup: false }),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_whole_tokens() {
        let p = pieces("max |g̃1| = 8.644e-7 N, λ2 = -215.9 W units; κ2 ≥ ζ1 at t_f1 (x2)");
        let nums: Vec<&str> = p.iter().filter(|p| p.num).map(|p| p.text.as_str()).collect();
        assert_eq!(nums, ["8.644e-7", "-215.9"]);
        // joined back, the sentence is unchanged
        let s = "ω₁ = 0.12085992204657 ± 3.4e-13 1/s, 1e-3 ≤ x";
        assert_eq!(pieces(s).iter().map(|p| p.text.as_str()).collect::<String>(), s);
        // 0.12085992204657, 3.4e-13, the 1 of 1/s, 1e-3
        assert_eq!(pieces(s).iter().filter(|p| p.num).count(), 4);
    }

    #[test]
    fn caret_powers_are_raised_exponents() {
        // Reference: the caret notation of the ledger's text (e^(−λt), Q0^((a2−a1)/a2), z^k).
        let p = pieces("W(0)e^(−λt) + ε/λ, Q0^((a2−a1)/a2), sig^r(σ), ω = z^2 and 2^p·4; a^ b");
        let sups: Vec<&str> = p.iter().filter(|p| p.sup).map(|p| p.text.as_str()).collect();
        assert_eq!(sups, ["−λt", "(a2−a1)/a2", "r", "2", "p"]);
        // no caret left but the lone one, which raises nothing
        let text: String = p.iter().filter(|p| !p.sup).map(|p| p.text.as_str()).collect();
        assert_eq!(text.matches('^').count(), 1, "{text}");
        // an unbalanced bracket is left as text
        assert!(pieces("x^(1 + y").iter().all(|p| !p.sup));
        // raised: the same text, numbers and keys merged back into plain text
        let r = raised("W(0)e^(−λt) + 2 control.a^2");
        let shape: Vec<(&str, bool)> = r.iter().map(|p| (p.text.as_str(), p.sup)).collect();
        assert_eq!(shape, [("W(0)e", false), ("−λt", true), (" + 2 control.a", false), ("2", true)]);
        assert!(r.iter().all(|p| !p.num && !p.key));
    }

    #[test]
    fn configuration_keys_are_code() {
        let p = pieces("grid in z (horizon.field_points); names discretisation.* and control.a, control.b.");
        let keys: Vec<&str> = p.iter().filter(|p| p.key).map(|p| p.text.as_str()).collect();
        assert_eq!(keys, ["horizon.field_points", "discretisation.*", "control.a", "control.b"]);
    }

    #[test]
    fn the_paper_config_changes_nothing_and_a_set_key_is_named() {
        assert!(config_changes(&Config::paper()).is_empty());
        let mut c = Config::paper();
        c.control.b = 3000.0;
        let d = config_changes(&c);
        assert_eq!(d, vec![ConfigChange { key: "control.b".into(), value: "3000".into(), paper: "1".into() }]);
        // the Goland wing's bending rigidity (tests/common GOLAND: 9.77e6 N m²) in the one
        // number format, not the JSON float 9770000.0; the paper's ei in it too
        let mut c = Config::paper();
        c.wing.ei = 9.77e6;
        let d = config_changes(&c);
        assert_eq!((d[0].key.as_str(), d[0].value.as_str()), ("wing.ei", "9.77×10⁶"));
        assert_eq!(wingcheck_model::format::parse(&d[0].paper), Some(Config::paper().wing.ei));
        let args: Vec<String> = ["/x/y/wingcheck", "report", "--set", "a b=1"].iter().map(|s| s.to_string()).collect();
        assert_eq!(command_text(&args), "wingcheck report --set 'a b=1'");
    }
}
