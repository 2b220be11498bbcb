//! The claim table: one spec per claim of the paper (its id, the paper's equations and theorem,
//! the claim in words) and the certificate roles each claim can rest on ([`ROLES`]). Every place
//! that names a claim — the ledger rows, the report, `certify`/`verify`'s manifest, an
//! inconclusive row, docs/ledger.md — reads it from here.

use serde::{Deserialize, Deserializer, Serialize};

use crate::certify::facts::FactKind;
use crate::certify::omega1;

/// The claims of the paper, in the paper's order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, schemars::JsonSchema)]
pub enum ClaimId {
    /// Theorem 1, (22)–(28).
    #[serde(rename = "W-bounds")]
    WBounds,
    /// (29)–(32).
    #[serde(rename = "mu-conditions")]
    MuConditions,
    /// Theorem 2, (33)–(37).
    #[serde(rename = "UUB")]
    Uub,
    /// Theorem 3, (38).
    #[serde(rename = "finite-time-1")]
    FiniteTime1,
    /// Theorem 4, (39).
    #[serde(rename = "finite-time-2")]
    FiniteTime2,
    /// Lemmas 1–3, (11)–(14).
    #[serde(rename = "lemmas")]
    Lemmas,
    /// Section 4: FTDO vs DOBC (57).
    #[serde(rename = "ftdo-vs-dobc")]
    FtdoVsDobc,
}

impl<'de> Deserialize<'de> for ClaimId {
    /// Reads a claim by its printed name; an unknown name is refused as an unknown claim,
    /// listing the known ones (from [`CLAIMS`]).
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let name = String::deserialize(deserializer)?;
        ClaimId::from_name(&name).ok_or_else(|| {
            let known: Vec<&str> = CLAIMS.iter().map(|spec| spec.name).collect();
            serde::de::Error::custom(format!("unknown claim `{name}` (the claims are {})", known.join(", ")))
        })
    }
}

/// What the ledger knows about one claim before checking it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ClaimSpec {
    /// The claim.
    pub id: ClaimId,
    /// The id as printed (`W-bounds`).
    pub name: &'static str,
    /// The paper's equations (`(22)–(28)`).
    pub equations: &'static str,
    /// The theorem, lemma or section (`Theorem 1`).
    pub theorem: &'static str,
    /// The claim in words.
    pub claim: &'static str,
}

/// Every claim, in the paper's order.
pub const CLAIMS: [ClaimSpec; 7] = [
    ClaimSpec {
        id: ClaimId::WBounds,
        name: "W-bounds",
        equations: "(22)–(28)",
        theorem: "Theorem 1",
        claim: "0 ≤ λ2 κ ≤ W ≤ λ1 κ with the printed λ1, λ2, y1–y3",
    },
    ClaimSpec {
        id: ClaimId::MuConditions,
        name: "mu-conditions",
        equations: "(29)–(32)",
        theorem: "Theorem 2's conditions",
        claim: "conditions on the gains and the η's make Ẇ ≤ −λW + ε with the printed λ, ε",
    },
    ClaimSpec {
        id: ClaimId::Uub,
        name: "UUB",
        equations: "(33)–(37)",
        theorem: "Theorem 2",
        claim: "q, θ are uniformly ultimately bounded, with the printed bound",
    },
    ClaimSpec {
        id: ClaimId::FiniteTime1,
        name: "finite-time-1",
        equations: "(38)",
        theorem: "Theorem 3",
        claim: "g̃1 reaches 0 no later than t_f1, if κ2 ≥ ζ1",
    },
    ClaimSpec {
        id: ClaimId::FiniteTime2,
        name: "finite-time-2",
        equations: "(39)",
        theorem: "Theorem 4",
        claim: "g̃2 reaches 0 no later than t_f2, if κ5 ≥ ζ2",
    },
    ClaimSpec {
        id: ClaimId::Lemmas,
        name: "lemmas",
        equations: "(11)–(14)",
        theorem: "Lemmas 1–3",
        claim: "the inequalities used in the proofs",
    },
    ClaimSpec {
        id: ClaimId::FtdoVsDobc,
        name: "ftdo-vs-dobc",
        equations: "(57)",
        theorem: "Section 4, Figs 3–20",
        claim: "the proposed FTDO controller suppresses vibration better than DOBC",
    },
];

impl ClaimId {
    /// Every claim, in the paper's order.
    pub const ALL: [ClaimId; 7] = [
        ClaimId::WBounds,
        ClaimId::MuConditions,
        ClaimId::Uub,
        ClaimId::FiniteTime1,
        ClaimId::FiniteTime2,
        ClaimId::Lemmas,
        ClaimId::FtdoVsDobc,
    ];

    /// The claim's spec.
    pub fn spec(self) -> &'static ClaimSpec {
        CLAIMS.iter().find(|s| s.id == self).expect("every claim has a spec")
    }

    /// The id as printed.
    pub fn name(self) -> &'static str {
        self.spec().name
    }

    /// Where in the paper: equations, then the theorem (`(22)–(28), Theorem 1`).
    pub fn equation(self) -> String {
        let s = self.spec();
        format!("{}, {}", s.equations, s.theorem)
    }

    /// Ids of the certificates (`<id>.json` in a proofs directory) the claim can rest on: the
    /// verifier's own roles for it ([`ROLES`]); which of them `certify` writes depends on the
    /// configuration.
    pub fn certificates(self) -> Vec<&'static str> {
        ROLES.iter().filter(|r| r.claim == self).map(|r| r.id).collect()
    }

    /// The claim by its printed id.
    pub fn from_name(name: &str) -> Option<ClaimId> {
        CLAIMS.iter().find(|s| s.name == name).map(|s| s.id)
    }
}

impl std::fmt::Display for ClaimId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.pad(self.name())
    }
}

/// Which weights a certificate of a role must carry.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WeightsRule {
    /// The configuration's a, b.
    Config,
    /// b = 1 and any a > 0 (a ratio a/b; W is linear in (a, b), so W(a, b) = b·W(a/b, 1)).
    Ratio,
    /// The fact does not depend on a, b and the file carries none (the ω₁ enclosure).
    Independent,
}

/// One role in the certificate set: its id, the claim it supports, its fact and weights.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Role {
    /// Certificate id (the file is `<id>.json`).
    pub id: &'static str,
    /// The paper's claim it supports.
    pub claim: ClaimId,
    /// The fact the certificate must prove.
    pub fact: FactKind,
    /// Which weights it must carry.
    pub weights: WeightsRule,
}

const W_BOUNDS: ClaimId = ClaimId::WBounds;
const MU_CONDITIONS: ClaimId = ClaimId::MuConditions;

/// Every role the verifier knows: the certificates each claim can rest on
/// ([`ClaimId::certificates`]).
pub const ROLES: [Role; 7] = [
    Role { id: "w-bounds-lower", claim: W_BOUNDS, fact: FactKind::WLowerBound, weights: WeightsRule::Config },
    Role { id: "w-bounds-upper", claim: W_BOUNDS, fact: FactKind::WUpperBound, weights: WeightsRule::Config },
    Role {
        id: "w-bounds-indefinite",
        claim: W_BOUNDS,
        fact: FactKind::WNegativeDirection,
        weights: WeightsRule::Config,
    },
    Role {
        id: "w-bounds-ratio-above",
        claim: W_BOUNDS,
        fact: FactKind::WNegativeDirection,
        weights: WeightsRule::Ratio,
    },
    Role { id: "w-bounds-ratio-below", claim: W_BOUNDS, fact: FactKind::WLowerBound, weights: WeightsRule::Ratio },
    Role {
        id: "mu-conditions-infeasible",
        claim: MU_CONDITIONS,
        fact: FactKind::Mu3Infeasible,
        weights: WeightsRule::Config,
    },
    Role { id: omega1::ID, claim: W_BOUNDS, fact: FactKind::Omega1Enclosure, weights: WeightsRule::Independent },
];

/// The role with this id.
pub fn role(id: &str) -> Option<&'static Role> {
    ROLES.iter().find(|r| r.id == id)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_has_one_spec_per_claim_in_order() {
        for (spec, id) in CLAIMS.iter().zip(ClaimId::ALL) {
            assert_eq!(spec.id, id);
            // the serialised id is the printed name
            assert_eq!(serde_json::to_value(id).unwrap(), spec.name);
            assert_eq!(ClaimId::from_name(spec.name), Some(id));
            assert_eq!(serde_json::from_value::<ClaimId>(serde_json::json!(spec.name)).unwrap(), id);
        }
    }
}
