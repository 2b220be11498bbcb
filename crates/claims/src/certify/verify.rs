//! Verifying a certificate set: `index.json` read and checked ([`super::manifest`]), every
//! certificate re-derived in exact arithmetic ([`super::facts`], [`super::omega1`]), and the
//! conclusions the verifier draws from the checked facts (its conclude module).

use std::path::Path;

use wingcheck_model::Config;

use super::conclude;
use super::facts::config_params;
use super::manifest::{
    check_listing, check_one_discretisation, check_pinned, parse_certificates, parse_manifest, read_bounded,
    VerifiedCert, INDEX,
};
use super::omega1::Omega1Enclosure;
use super::CertifyError;

/// A verified set.
#[derive(Debug, Clone)]
pub struct VerifiedSet {
    /// The configuration (validated).
    pub config: Config,
    /// Its hash.
    pub config_sha256: String,
    /// The certificates, in manifest order.
    pub certs: Vec<VerifiedCert>,
    /// Per claim, the conclusion the verifier draws from its facts.
    pub conclusions: Vec<(String, String)>,
    /// The checked enclosure ω̲₁ ≤ ω₁ ≤ ω̄₁ (a set always has one; `None` only if absent,
    /// which [`verify_set`] refuses).
    pub omega1: Option<Omega1Enclosure>,
}

/// Verifies the certificate set in `dir` (the checks of [`super::manifest`]) for whatever
/// configuration its manifest names.
pub fn verify_set(dir: &Path) -> Result<VerifiedSet, CertifyError> {
    verify_set_for(dir, None)
}

/// [`verify_set`], and with `expected` the set must have been made for exactly that
/// configuration (its hash), else it is refused naming the keys that differ: any self-consistent
/// set of some configuration verifies, so only a pinned verify says the facts are about yours.
pub fn verify_set_for(dir: &Path, expected: Option<&Config>) -> Result<VerifiedSet, CertifyError> {
    let (manifest, cfg) = parse_manifest(&read_bounded(&dir.join(INDEX))?)?;
    if let Some(want) = expected {
        check_pinned(&manifest, &cfg, want)?;
    }
    // everything that needs no arithmetic first: the claim list, the listing
    conclude::check_claim_list(&manifest)?;
    let cfg_params = config_params(&cfg)?;
    check_listing(dir, &manifest)?;
    let (parsed, enclosure) = parse_certificates(dir, &manifest, &cfg_params)?;
    check_one_discretisation(&parsed)?;
    // Pass 2: the exact checks.
    let mut certs: Vec<VerifiedCert> = Vec::new();
    for (role, file, name) in parsed {
        let fact = file.check().map_err(|err| err.in_file(name))?;
        certs.push(VerifiedCert { role, fact });
    }
    let mut omega1 = None;
    if let Some((role, file, name)) = enclosure {
        let (fact, e) = file.check(&cfg_params.weights).map_err(|err| err.in_file(name))?;
        certs.push(VerifiedCert { role, fact });
        omega1 = Some(e);
    }
    let conclusions = conclude::conclusions(&manifest, &cfg_params, &certs, omega1.as_ref())?;
    Ok(VerifiedSet { config: cfg, config_sha256: manifest.config_sha256, certs, conclusions, omega1 })
}
