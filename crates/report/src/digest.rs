//! The ledger table's digest of a claim row: one sentence of finding and the two or three
//! decisive numbers with units and their error or basis, derived from the row's evidence.
//!
//! The claim rows carry their evidence as a serialised key → value map; the keys read here are
//! the evidence fields of each claim (documented in the claims crate). Every key is optional:
//! a missing one drops that number, and a row without the needed keys falls back to the first
//! sentence of its summary, so the table never shows a raw identifier or a made-up value.

use serde::Serialize;
use wingcheck_claims::ClaimRow;

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
        "W-bounds" => &[
            ("lambda2_printed", "printed λ2 = y2 − y3", "", 1.0, "exact"),
            ("lambda2_tight", "tight λ2* = min W/κ at the configured a, b", "", 1.0, "Galerkin, O(h²)"),
            ("a_over_b_max", "W ≻ 0 iff a/b <", "1/s", 1.0, "closed form"),
        ],
        "mu-conditions" => &[
            ("lambda3_max", "best λ3 at the configured a, b", "", 1.0, "SOCP solver"),
            ("a_over_b_boundary_closed_form", "(32) feasible iff a/b <", "1/s", 1.0, "closed form"),
            ("best_lambda", "best decay rate λ where feasible", "1/s", 1.0, "SOCP solver"),
        ],
        "UUB" => &[
            ("bound_q_at_T", "bound (37) on |q| at T", "m", 1.0, "formula at solver η"),
            ("measured_max_abs_q_second_half", "simulated max |q|, second half", "m", 1.0, "simulation"),
            ("ratio_bound_over_measured_q", "bound / simulated", "", 1.0, "ratio"),
        ],
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
    Some(match r.id.to_string().as_str() {
        "W-bounds" => {
            let (l2p, l2t, rmax) = (n("lambda2_printed")?, n("lambda2_tight")?, n("a_over_b_max")?);
            let ab = n("a")? / n("b")?;
            let printed = if l2p < 0.0 {
                "The printed λ2 = y2 − y3 is negative, so 0 ≤ λ2κ ≤ W fails as printed"
            } else {
                "The printed λ2 is positive"
            };
            let here = if l2t < 0.0 {
                format!("; at the configured a/b = {} W itself is indefinite", fmt_num(ab))
            } else {
                String::new()
            };
            format!("{printed}; W ≻ 0 holds exactly for a/b < ω1 = {} 1/s{here}.", fmt_num(rmax))
        }
        "mu-conditions" => {
            let (l3, rs) = (n("lambda3_max")?, n("a_over_b_boundary_closed_form")?);
            if l3 < 0.0 {
                format!(
                    "(29)–(32) cannot hold at the configured gains (best λ3 < 0); they are satisfiable only for a/b < {}, where the guaranteed decay rate is {} 1/s.",
                    fmt_num(rs),
                    n("best_lambda").map_or("tiny".into(), fmt_num)
                )
            } else {
                format!("(29)–(32) are satisfiable at the configured gains (feasible for a/b < {}).", fmt_num(rs))
            }
        }
        "UUB" => {
            let ratio = n("ratio_bound_over_measured_q")?;
            let w0 = match (n("w0_16_elements"), n("w0_64_elements")) {
                (Some(a), Some(b)) if b > 1.5 * a => {
                    ", and infinite for the paper's initial shape (W(0) grows under refinement)"
                }
                _ => "",
            };
            format!("Where its hypotheses hold, the bound is {} × the simulated envelope{w0}.", fmt_num(ratio))
        }
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
            format!(
                "FTDO's disturbance error is {} × smaller than DOBC's late on, but the tip responses differ by at most {} % — not the clearly better suppression claimed.",
                fmt_num(g),
                fmt_num(100.0 * d)
            )
        }
        _ => return None,
    })
}

/// The digest of a row.
pub fn digest(r: &ClaimRow) -> Digest {
    let numbers = spec(&r.id.to_string())
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
