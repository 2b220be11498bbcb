//! Links both ways: each ledger row to the figures it rests on and to its certificates in
//! `proofs/` (named as `wingcheck verify` names them), each figure and certificate back to its
//! row, with link text a person reads (a figure's label and title, a certificate's statement).

use serde::Serialize;
use wingcheck_claims::certify::facts::FactKind;
use wingcheck_claims::spec::{role, WeightsRule};
use wingcheck_claims::{ClaimId, Ledger};

use crate::figure::claim_anchor;

/// A link: where to and the words.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Link {
    /// The target (`#fig12-gtilde2-ftdo`, `proofs/w-bounds-lower.json`).
    pub href: String,
    /// The link text.
    pub text: String,
    /// The certificate's id as `verify` prints it (`w-bounds-lower`), for a certificate.
    pub id: Option<String>,
}

/// The paper's figures (file stems, the figures' anchors) a claim rests on besides its own
/// plots: the region map for the W ≻ 0 and (32) thresholds, the tips for the bounds, the
/// observer errors for the finite-time theorems, every FTDO/DOBC pair for the comparison.
pub fn paper_figures(id: ClaimId) -> &'static [&'static str] {
    match id {
        ClaimId::WBounds | ClaimId::MuConditions => &["region-map-ab"],
        ClaimId::Uub => &["fig09-q-tip-ftdo", "fig10-theta-tip-ftdo"],
        ClaimId::FiniteTime1 => &["fig11-gtilde1-ftdo"],
        ClaimId::FiniteTime2 => &["fig12-gtilde2-ftdo"],
        ClaimId::Lemmas => &[],
        ClaimId::FtdoVsDobc => &[
            "fig09-q-tip-ftdo",
            "fig17-q-tip-dobc",
            "fig10-theta-tip-ftdo",
            "fig18-theta-tip-dobc",
            "fig11-gtilde1-ftdo",
            "fig19-gtilde1-dobc",
            "fig12-gtilde2-ftdo",
            "fig20-gtilde2-dobc",
            "cmp-dq",
            "cmp-dtheta",
        ],
    }
}

/// What the certificate of role `id` proves, in words (None for a file that is not a
/// certificate, like the set's index).
pub fn certificate_statement(id: &str) -> Option<&'static str> {
    let r = role(id)?;
    Some(match (r.fact, r.weights) {
        (FactKind::WLowerBound, WeightsRule::Ratio) => {
            "W is positive definite at a ratio a/b just below ω₁ (W − λκ ≻ 0, exact LDLᵀ)"
        }
        (FactKind::WLowerBound, _) => "min W/κ lies above the stated λ at the configured a, b (exact LDLᵀ)",
        (FactKind::WUpperBound, _) => "max W/κ lies below the stated λ at the configured a, b (exact LDLᵀ)",
        (FactKind::WNegativeDirection, WeightsRule::Ratio) => {
            "W is indefinite at a ratio a/b just above ω₁ (an exact state with W < 0)"
        }
        (FactKind::WNegativeDirection, _) => "W is indefinite at the configured a, b (an exact state with W < 0)",
        (FactKind::Mu3Infeasible, _) => "μ3 ≥ 0 has no solution, so (32) cannot hold (Farkas multipliers)",
        (FactKind::Omega1Enclosure, _) => "ω̲₁ ≤ ω₁ ≤ ω̄₁ for the continuous wing (Rayleigh quotient and trace bound)",
    })
}

/// The claim a certificate file (`<id>.json`) supports, from the verifier's roles.
pub fn certificate_claim(file: &str) -> Option<ClaimId> {
    role(file.strip_suffix(".json")?).map(|r| r.claim)
}

/// A certificate of the report's `proofs/` with its statement and its row.
#[derive(Debug, Clone, Serialize)]
pub struct Certificate {
    /// The link to the file, its text the id `verify` prints.
    pub file: Link,
    /// What it proves.
    pub statement: String,
    /// The row it supports (a link back), if any.
    pub claim: Option<Link>,
}

/// The link to a ledger row, with its verdict.
pub fn row_link(ledger: &Ledger, id: ClaimId) -> Link {
    let verdict = ledger.row(id).map_or(String::new(), |r| r.verdict.to_string());
    Link { href: format!("#{}", claim_anchor(id.name())), text: format!("{} ({verdict})", id.name()), id: None }
}

/// The certificates of `proofs/` (file names) with their statements and rows; the index is
/// listed as the set's index.
pub fn certificates(ledger: &Ledger, files: &[String]) -> Vec<Certificate> {
    files
        .iter()
        .map(|f| {
            let stem = f.strip_suffix(".json").unwrap_or(f);
            Certificate {
                file: certificate_link(f),
                statement: certificate_statement(stem)
                    .unwrap_or("the set's index: the configuration, and which claim each certificate supports")
                    .into(),
                claim: certificate_claim(f).map(|id| row_link(ledger, id)),
            }
        })
        .collect()
}

/// The link to a certificate file of `proofs/`, its text the id `verify` prints.
pub fn certificate_link(file: &str) -> Link {
    let stem = file.strip_suffix(".json").unwrap_or(file);
    Link { href: format!("{}/{file}", crate::PROOFS), text: stem.into(), id: Some(stem.into()) }
}

/// The certificates of `proofs/` that support row `id`.
pub fn row_certificates(id: ClaimId, files: &[String]) -> Vec<(Link, String)> {
    files
        .iter()
        .filter(|f| certificate_claim(f) == Some(id))
        .map(|f| {
            let stem = f.strip_suffix(".json").unwrap_or(f);
            (certificate_link(f), certificate_statement(stem).unwrap_or_default().to_string())
        })
        .collect()
}

/// A figure's title shortened for a link: up to the first `;`, ` (` or `: `, at most 70
/// characters, cut at a word (never inside a number).
pub fn short_title(title: &str) -> String {
    let cut = ["; ", " (", ": "].iter().filter_map(|p| title.find(p)).min().unwrap_or(title.len());
    let t = title[..cut].trim_end_matches([',', '.', ' ']);
    if t.chars().count() <= 70 {
        return t.to_string();
    }
    let head: String = t.chars().take(69).collect();
    let at_word = head.rfind(' ').map_or(head.as_str(), |i| &head[..i]);
    format!("{}…", at_word.trim_end_matches([',', '.', ' ']))
}

/// The words of a link to a figure: its label and short title ([`short_title`]), or only the
/// longer of the two when one repeats the other (`W-bounds, λ2/λ1 against a/b`, not
/// `W-bounds, λ2/λ1 against a/b: λ2/λ1 against a/b`).
pub fn figure_link_text(label: &str, title: &str) -> String {
    let short = short_title(title);
    let tail = label.rsplit(", ").next().unwrap_or(label).to_lowercase();
    if short.to_lowercase().contains(&tail) || tail.contains(&short.to_lowercase()) {
        if label.chars().count() >= short.chars().count() {
            label.to_string()
        } else {
            short
        }
    } else {
        format!("{label}: {short}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn link_texts_are_short_whole_and_say_things_once() {
        // the titles of this report's figures (region.rs, wratio.rs, finite_time.rs)
        assert_eq!(
            figure_link_text("Region map", "(a, b) region map: hypotheses vs tip performance"),
            "(a, b) region map"
        );
        assert_eq!(
            figure_link_text("W-bounds, λ2/λ1 against a/b", "λ2/λ1 against a/b: tight and printed"),
            "W-bounds, λ2/λ1 against a/b"
        );
        assert_eq!(
            figure_link_text(
                "finite-time-2, plot 1",
                "|σ2(t)| on [0, 37.46 s]: the Filippov limit reaches 0 at t_reach = 12.49 s"
            ),
            "finite-time-2, plot 1: |σ2(t)| on [0, 37.46 s]"
        );
        let long = "word ".repeat(20) + "12.4879728586605";
        let s = short_title(&long);
        assert!(s.ends_with('…') && !s.contains("12") && s.chars().count() <= 70, "{s}");
    }
}
