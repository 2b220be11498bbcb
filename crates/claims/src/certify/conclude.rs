//! What a verified set concludes: the manifest's claims checked against the verifier's
//! [`ROLES`](crate::spec::ROLES) table (every required fact listed, every listed fact present
//! and used), and the statements the verifier writes itself from the checked facts.

use std::collections::BTreeSet;

use num_rational::BigRational;
use num_traits::{Signed, Zero};

use super::facts::{mu3_system, show, CheckedFact, ExactParams};
use super::manifest::{bad, Manifest, VerifiedCert, INDEX};
use super::omega1::{self, Omega1Enclosure, Position};
use super::CertifyError;
use crate::spec::{role, ClaimId, ROLES};

const W_BOUNDS: ClaimId = ClaimId::WBounds;
const MU_CONDITIONS: ClaimId = ClaimId::MuConditions;

pub(super) fn find<'a>(certs: &'a [VerifiedCert], id: &str) -> Option<&'a CheckedFact> {
    certs.iter().find(|c| c.role.id == id).map(|c| &c.fact)
}

/// The ids the verifier requires for each claim, given the facts present and the config.
pub(super) fn required(
    cfg_params: &ExactParams,
    lower_lambda: Option<&BigRational>,
) -> Vec<(ClaimId, Vec<&'static str>)> {
    let mut w = vec!["w-bounds-lower", "w-bounds-upper", "w-bounds-ratio-above", "w-bounds-ratio-below", omega1::ID];
    if lower_lambda.is_none_or(|l| !l.is_positive()) {
        w.push("w-bounds-indefinite");
    }
    let mut out = vec![(W_BOUNDS, w)];
    let (_, c3) = mu3_system(cfg_params);
    if c3.is_negative() {
        out.push((MU_CONDITIONS, vec!["mu-conditions-infeasible"]));
    }
    out
}

pub(super) fn conclusions(
    manifest: &Manifest,
    cfg_params: &ExactParams,
    certs: &[VerifiedCert],
    omega1: Option<&Omega1Enclosure>,
) -> Result<Vec<(String, String)>, CertifyError> {
    let lower = find(certs, "w-bounds-lower").and_then(|f| f.lambda.clone());
    if let Some(f) = find(certs, "w-bounds-ratio-below") {
        if !f.lambda.as_ref().is_some_and(|l| l.is_positive()) {
            return Err(bad("w-bounds-ratio-below.json", "λ must be > 0 (it certifies W positive definite)"));
        }
    }
    check_claims(manifest, cfg_params, certs, lower.as_ref())?;
    Ok(statements(cfg_params, certs, lower, omega1))
}

/// The manifest's claim list on its own, before any arithmetic: every claim known, listed
/// once, each need listed once.
pub(super) fn check_claim_list(manifest: &Manifest) -> Result<(), CertifyError> {
    let known: BTreeSet<ClaimId> = ROLES.iter().map(|r| r.claim).collect();
    let mut claims_seen = BTreeSet::new();
    for c in &manifest.claims {
        if !known.contains(&c.claim) {
            return Err(bad(
                INDEX,
                format!(
                    "unknown claim {} (the verifier knows {})",
                    c.claim,
                    known.iter().map(|c| c.name()).collect::<Vec<_>>().join(", ")
                ),
            ));
        }
        if !claims_seen.insert(c.claim) {
            return Err(bad(INDEX, format!("claim {} is listed twice", c.claim)));
        }
        let mut needs = BTreeSet::new();
        if let Some(id) = c.needs.iter().find(|id| !needs.insert(id.as_str())) {
            return Err(bad(INDEX, format!("claim {} lists {id} twice in its needs", c.claim)));
        }
    }
    Ok(())
}

/// The manifest's claims against the roles table: [`check_claim_list`], every required fact listed, every listed fact present and supporting its claim, every
/// certificate used.
fn check_claims(
    manifest: &Manifest,
    cfg_params: &ExactParams,
    certs: &[VerifiedCert],
    lower: Option<&BigRational>,
) -> Result<(), CertifyError> {
    let mut used = BTreeSet::new();
    check_claim_list(manifest)?;
    for (claim, ids) in required(cfg_params, lower) {
        let entry = manifest
            .claims
            .iter()
            .find(|c| c.claim == claim)
            .ok_or_else(|| bad(INDEX, format!("claim {claim} is missing")))?;
        for id in ids {
            if !entry.needs.iter().any(|n| n == id) {
                return Err(bad(INDEX, format!("claim {claim} does not list {id}, which the verifier requires")));
            }
        }
    }
    for c in &manifest.claims {
        for id in &c.needs {
            let r = role(id).ok_or_else(|| bad(INDEX, format!("unknown certificate id {id:?}")))?;
            if r.claim != c.claim {
                return Err(bad(INDEX, format!("{id} supports {}, not {}", r.claim, c.claim)));
            }
            if find(certs, id).is_none() {
                return Err(bad(INDEX, format!("claim {} needs {id}, which is not in the set", c.claim)));
            }
            used.insert(id.as_str());
        }
    }
    if let Some(c) = certs.iter().find(|c| !used.contains(c.role.id)) {
        return Err(bad(INDEX, format!("{} is not needed by any claim", c.role.id)));
    }
    Ok(())
}

/// The verifier's own statements per claim, from the checked facts (W-bounds, μ-conditions).
fn statements(
    cfg_params: &ExactParams,
    certs: &[VerifiedCert],
    lower: Option<BigRational>,
    omega1: Option<&Omega1Enclosure>,
) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let weights = format!("a = {}, b = {}", show(&cfg_params.weights[0]), show(&cfg_params.weights[1]));
    let w_text = {
        let l = lower.expect("required above");
        let u = find(certs, "w-bounds-upper").and_then(|f| f.lambda.clone()).expect("required above");
        let n = find(certs, "w-bounds-lower").and_then(|f| f.elements).unwrap_or(0);
        let negative = find(certs, "w-bounds-indefinite").and_then(|f| f.elements);
        let definite = match (l.is_positive(), negative) {
            (true, None) => "W is positive definite on that space".to_string(),
            (true, Some(m)) => format!(
                "yet a state on the {m}-element space has W(x) < 0 exactly, so W is not positive definite on the \
                 PDE's state space (its positivity on the {n}-element space does not carry over) and the printed \
                 λ2 > 0 cannot exist"
            ),
            (false, _) => {
                "W is not positive definite (exact negative direction), so the printed λ2 > 0 cannot exist".to_string()
            }
        };
        let above = find(certs, "w-bounds-ratio-above").map(|f| show(&f.params.weights[0])).expect("required");
        let below = find(certs, "w-bounds-ratio-below").map(|f| show(&f.params.weights[0])).expect("required");
        let mut text = format!(
            "at {weights}: {} < min W/κ and max W/κ < {} on the {n}-element Galerkin space; {definite}; \
             W is indefinite for a/b = {above} and positive definite on the Galerkin space for a/b = {below}",
            show(&l),
            show(&u)
        );
        if let Some(e) = omega1 {
            text.push_str("; ");
            text.push_str(&enclosure_conclusion(e, cfg_params));
        }
        text
    };
    out.push((W_BOUNDS.name().to_string(), w_text));
    if find(certs, "mu-conditions-infeasible").is_some() {
        out.push((
            MU_CONDITIONS.name().to_string(),
            format!("at {weights}: μ3 ≥ 0 is infeasible, so (32) cannot hold"),
        ));
    } else {
        let (_, c3) = mu3_system(cfg_params);
        out.push((
            MU_CONDITIONS.name().to_string(),
            format!(
                "no certificate: at {weights} the constant term bξEI/(2s⁴) − aρ = {} of μ3 is ≥ 0, so μ3 alone does not refute (32)",
                show(&c3)
            ),
        ));
    }
    out
}

/// What the enclosure decides at the set's a/b, for the continuous model (W ≻ 0 iff a/b < ω₁,
/// docs/model.md "W ≻ 0 iff a/b < ω₁").
fn enclosure_conclusion(e: &Omega1Enclosure, p: &ExactParams) -> String {
    let [a, b] = &p.weights;
    let interval = format!(
        "{} ≤ ω₁ ≤ {} rad/s for the continuous wing",
        omega1::exact_decimal(&e.lower),
        omega1::exact_decimal(&e.upper)
    );
    if b.is_zero() {
        // no ratio a/b to place (and no division by zero)
        return format!("{interval}; with b = 0 there is no ratio a/b to place against it, so it decides nothing about W ≻ 0 at these weights");
    }
    let ratio = a / b;
    let head = format!("{interval}, so ");
    match e.position(&ratio) {
        Position::Below => {
            format!("{head}a/b = {} < ω̲₁: W is positive definite for the continuous model", show(&ratio))
        }
        Position::Above => format!(
            "{head}a/b = {} > ω̄₁: W is not positive definite for the continuous model (W(v, −(a/b)v) < 0 for the \
             certificate's test state v)",
            show(&ratio)
        ),
        Position::Inside => format!(
            "{head}a/b = {} lies inside the certified interval: the certificates do not decide W ≻ 0 there",
            show(&ratio)
        ),
    }
}
