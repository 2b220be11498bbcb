//! The ledger table's digest of a claim row: one sentence of finding and the two or three
//! decisive numbers with units and their error or basis, derived from the row's evidence.
//!
//! Claims with typed evidence (W-bounds, mu-conditions, UUB) are read through their types
//! ([`WBoundsEvidence`], [`MuEvidence`], [`UubEvidence`], deserialised from the row's
//! evidence map with unknown fields denied), with the error estimates those types carry. The
//! other claims (finite-time, lemmas, ftdo-vs-dobc) still carry string-keyed evidence; their
//! numbers are read by key here, each optional: a missing key drops that number, and a row
//! without the keys its sentence needs falls back to the first sentence of its summary, so the
//! table never shows a raw identifier or a made-up value.

use serde::Serialize;
use wingcheck_claims::mu::MuEvidence;
use wingcheck_claims::theory::Decision;
use wingcheck_claims::uub::UubEvidence;
use wingcheck_claims::wbounds::WBoundsEvidence;
use wingcheck_claims::{ClaimId, ClaimRow};

use crate::stats::fmt_num;

/// One decisive number.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Quantity {
    /// What it is, in words.
    pub label: String,
    /// The value, formatted (4 significant digits), with its unit.
    pub value: String,
    /// Its error estimate (`± …`) or basis (`exact`, `solver`, `simulation`).
    pub error: String,
}

/// The digest of a row.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Digest {
    /// One sentence.
    pub finding: String,
    /// Two or three numbers.
    pub numbers: Vec<Quantity>,
}

/// (evidence key, label, unit, scale, basis when the evidence gives no error) of the decisive
/// numbers per claim id.
type Spec = (&'static str, &'static str, &'static str, f64, &'static str);

fn spec(id: &str) -> &'static [Spec] {
    match id {
        "finite-time-1" | "finite-time-2" => &[
            ("bound_s", "bound t_f", "s", 1.0, "formula"),
            ("measured_s", "Filippov reaching time", "s", 1.0, "ODE solve"),
            ("sweep_max_ratio", "worst reaching time / bound over the σ0 sweep", "", 1.0, "ODE solves"),
        ],
        "lemmas" => &[
            ("lemma1_max_ratio", "Lemma 1: max ab/(a²/p + pb²) (sharp ½)", "", 1.0, "search"),
            ("lemma2_corrected_max_ratio", "Lemma 2 corrected: max ratio (≤ 1)", "", 1.0, "search"),
            ("lemma3_max_rel_err", "Lemma 3 (14) vs RK4: max relative difference", "", 1.0, "RK4"),
        ],
        "ftdo-vs-dobc" => &[
            ("gtilde_ratio_late", "RMS g̃ late, DOBC / FTDO", "", 1.0, "simulation"),
            ("rel_diff_rms_q_late", "tip RMS q late, (DOBC − FTDO)/FTDO", "%", 100.0, "simulation"),
            ("max_abs_rel_diff_tip", "largest tip-RMS difference over the (a, b) sweep", "%", 100.0, "simulation"),
        ],
        _ => &[],
    }
}

/// The first sentence of a text (a period followed by a space and not inside a number).
fn first_sentence(s: &str) -> String {
    let bytes = s.as_bytes();
    for (i, c) in s.char_indices() {
        if c == '.' && bytes.get(i + 1) == Some(&b' ') && i > 0 && !bytes[i - 1].is_ascii_digit() {
            return s[..=i].to_string();
        }
    }
    s.to_string()
}

/// The finding sentence, from the row's numbers; None when a needed key is missing.
fn finding(r: &ClaimRow) -> Option<String> {
    let n = |k: &str| r.number(k);
    let b = |k: &str| r.evidence.get(k).and_then(|v| v.as_bool());
    Some(match r.id.name() {
        "finite-time-1" | "finite-time-2" => {
            let (bound, sweep) = (n("bound_s")?, n("sweep_max_ratio")?);
            let s0 = n("sigma0")?;
            if s0 == 0.0 || bound == 0.0 {
                format!(
                    "σ(0) = 0, so the bound is 0 s and met trivially; over a σ0 sweep the Filippov reaching time is at most {} × the bound.",
                    fmt_num(sweep)
                )
            } else {
                let m = n("measured_s")?;
                format!(
                    "The Filippov reaching time {} s is within the bound {} s (worst ratio {} over a σ0 sweep); only the implicit digital observer follows it.",
                    fmt_num(m),
                    fmt_num(bound),
                    fmt_num(sweep)
                )
            }
        }
        "lemmas" => {
            let l2 = b("lemma2_printed_holds")?;
            format!(
                "Lemma 1 holds (loosely), Lemma 2 {} as printed{}, Lemma 3's reaching time is exact.",
                if l2 { "holds" } else { "is false" },
                if l2 { "" } else { " (ω = z² on [0, 2]: 16 > 64/5) and holds after the correction" }
            )
        }
        "ftdo-vs-dobc" => {
            let (g, d) = (n("gtilde_ratio_late")?, n("max_abs_rel_diff_tip")?);
            let observers = if g >= 1.0 {
                format!("FTDO's disturbance error is {} × smaller than DOBC's late on", fmt_num(g))
            } else {
                format!("DOBC's disturbance error is {} × smaller than FTDO's late on", fmt_num(1.0 / g))
            };
            format!(
                "{observers}; the tip responses differ by at most {} % over the (a, b) sweep — the claimed clearly better suppression is not shown.",
                fmt_num(100.0 * d)
            )
        }
        _ => return None,
    })
}

/// The row's evidence as its typed struct (None if it does not deserialise).
fn typed<T: serde::de::DeserializeOwned>(r: &ClaimRow) -> Option<T> {
    serde_json::from_value(serde_json::Value::Object(r.evidence.clone().into_iter().collect())).ok()
}

fn q(label: &str, value: f64, unit: &str, error: String) -> Quantity {
    let unit = if unit.is_empty() { String::new() } else { format!(" {unit}") };
    Quantity { label: label.into(), value: format!("{}{unit}", fmt_num(value)), error }
}

fn pm(e: f64) -> String {
    format!("± {}", fmt_num(e))
}

fn w_bounds(e: &WBoundsEvidence) -> Digest {
    let ab = e.a / e.b;
    let printed = if e.lambda2_printed < 0.0 {
        "The printed λ2 = y2 − y3 is negative, so 0 ≤ λ2κ ≤ W fails as printed"
    } else {
        "The printed λ2 = y2 − y3 is positive"
    };
    let here = match e.w_positive_definite {
        Decision::No => format!("; at the configured a/b = {} W itself is indefinite", fmt_num(ab)),
        Decision::Yes => format!("; the configured a/b = {} lies inside", fmt_num(ab)),
        Decision::Undecided => format!("; the configured a/b = {} is within the error of the boundary", fmt_num(ab)),
    };
    Digest {
        finding: format!("{printed}; W ≻ 0 holds exactly for a/b < ω1 = {} rad/s{here}.", fmt_num(e.a_over_b_max)),
        numbers: vec![
            q("printed λ2 = y2 − y3", e.lambda2_printed, "", "exact".into()),
            q("tight λ2* = min W/κ at the configured a, b", e.lambda2_tight, "", pm(e.lambda2_tight_error)),
            q("W ≻ 0 iff a/b < ω1", e.a_over_b_max, "rad/s", pm(e.a_over_b_max_error)),
        ],
    }
}

fn mu(e: &MuEvidence) -> Digest {
    let ab = e.a / e.b;
    let finding = if e.satisfiable {
        format!(
            "(29)–(32) are satisfiable at the configured a/b = {} (feasible for a/b < r* = {}).",
            fmt_num(ab),
            fmt_num(e.a_over_b_boundary)
        )
    } else {
        format!(
            "(29)–(32) cannot hold at the configured a/b = {}; they are satisfiable only for a/b < r* = {}{}.",
            fmt_num(ab),
            fmt_num(e.a_over_b_boundary),
            e.best.map_or(String::new(), |b| format!(", where the best decay rate is λ = {} 1/s", fmt_num(b.lambda)))
        )
    };
    let mut numbers = Vec::new();
    if let Some(l3) = e.lambda3_sup {
        numbers.push(q("sup over the η's of λ3 at the configured a, b", l3, "", "closed form".into()));
    }
    numbers.push(q("(32) feasible iff a/b < r*", e.a_over_b_boundary, "rad/s", "closed form".into()));
    if let Some(b) = e.best {
        numbers.push(q("best decay rate λ where feasible", b.lambda, "1/s", "SOCP, re-verified".into()));
    }
    Digest { finding, numbers }
}

fn uub(e: &UubEvidence) -> Digest {
    let w0 = if e.w0_diverges {
        ", and infinite for the paper's initial shape (W(0) grows without bound under refinement)"
    } else {
        ""
    };
    Digest {
        finding: format!(
            "Where its hypotheses hold (a = {}, b = {}), the bound is {} × the simulated envelope{w0}.",
            fmt_num(e.evaluated_at_a),
            fmt_num(e.evaluated_at_b),
            fmt_num(e.ratio_bound_over_measured_q)
        ),
        numbers: vec![
            q("bound (37) on |q| at T", e.bound_q_at_t_end_m, "m", "formula".into()),
            q("simulated max |q|, second half", e.measured_max_abs_q_second_half_m, "m", "simulation".into()),
            q("decay time 1/λ", e.decay_time_constant_s, "s", "SOCP".into()),
        ],
    }
}

/// The digest of a row.
pub fn digest(r: &ClaimRow) -> Digest {
    let typed_digest = match r.id {
        ClaimId::WBounds => typed::<WBoundsEvidence>(r).map(|e| w_bounds(&e)),
        ClaimId::MuConditions => typed::<MuEvidence>(r).map(|e| mu(&e)),
        ClaimId::Uub => typed::<UubEvidence>(r).map(|e| uub(&e)),
        _ => None,
    };
    if let Some(d) = typed_digest {
        return d;
    }
    let numbers = spec(r.id.name())
        .iter()
        .filter_map(|(key, label, unit, scale, basis)| {
            let v = r.number(key)?;
            let error = match r.number(&format!("{key}_error")) {
                Some(e) => format!("± {}", fmt_num(e * scale)),
                None => basis.to_string(),
            };
            let unit = if unit.is_empty() { String::new() } else { format!(" {unit}") };
            Some(Quantity { label: label.to_string(), value: format!("{}{unit}", fmt_num(v * scale)), error })
        })
        .collect();
    Digest { finding: finding(r).unwrap_or_else(|| first_sentence(&r.summary)), numbers }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn first_sentence_stops_at_a_full_stop_not_in_a_number() {
        assert_eq!(first_sentence("λ = 0.5 here. Then more."), "λ = 0.5 here.");
        assert_eq!(first_sentence("no full stop"), "no full stop");
    }
}
