//! The certificate set: `index.json` and the verifier's own table of roles.
//!
//! `index.json` names the configuration the set was made for (the whole config and its
//! SHA-256), the claims and the facts each needs, and every certificate file with the SHA-256
//! of its bytes. [`verify_set`] accepts a directory only if
//! * it holds exactly `index.json` and the files it lists (nothing missing, nothing extra);
//! * every file is `<id>.json`, its `id` is the listed one and its bytes hash to the listed hash;
//! * every certificate was made for the manifest's configuration (its wing parameters, and the
//!   weights a, b where the role says so, equal the config's exactly);
//! * each claim lists at least the facts the verifier's own [`ROLES`] table requires, and every
//!   certificate re-derives (see [`super::facts`]).

use std::collections::BTreeSet;
use std::io::Read;
use std::path::Path;

use num_rational::BigRational;
use num_traits::{One, Signed};
use serde::{Deserialize, Serialize};
use wingcheck_cert::exact::{parse_rational_bounded, NumberLimits};
use wingcheck_model::Config;

use super::facts::{mu3_system, show, CertificateFile, CheckedFact, ExactParams, FactKind, MAX_FILE_BYTES};
use super::omega1::{self, Omega1Certificate, Omega1Enclosure, Position};
use super::{format_decimal, CertifyError};
use crate::spec::ClaimId;

/// File name of the manifest.
pub const INDEX: &str = "index.json";
/// Value of the manifest's `"format"` field.
pub const INDEX_FORMAT: &str = "wingcheck-proofs";
/// Version of the manifest.
pub const INDEX_VERSION: u64 = 1;

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
    /// The paper's claim (from the claim table, [`crate::spec`]).
    pub claim: ClaimId,
    /// The fact the certificate must prove.
    pub fact: FactKind,
    /// Which weights it must carry.
    pub weights: WeightsRule,
}

const W_BOUNDS: ClaimId = ClaimId::WBounds;
const MU_CONDITIONS: ClaimId = ClaimId::MuConditions;

/// Every role the verifier knows.
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

/// A claim and the certificate ids it needs.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ClaimEntry {
    /// The claim (one of the [`ROLES`] claims), by its id (`W-bounds`).
    pub claim: ClaimId,
    /// Certificate ids.
    pub needs: Vec<String>,
}

/// One certificate file in the manifest.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FileEntry {
    /// File name, `<id>.json`.
    pub file: String,
    /// Certificate id.
    pub id: String,
    /// Lowercase hex SHA-256 of the file's bytes.
    pub sha256: String,
}

/// `index.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    /// Always [`INDEX_FORMAT`].
    pub format: String,
    /// Always [`INDEX_VERSION`].
    pub version: u64,
    /// SHA-256 of the compact JSON of `config`.
    pub config_sha256: String,
    /// The configuration the set was made for.
    pub config: serde_json::Value,
    /// Claims and the certificates each needs.
    pub claims: Vec<ClaimEntry>,
    /// Certificate files.
    pub certificates: Vec<FileEntry>,
}

pub use wingcheck_io::sha256_hex;

/// SHA-256 of a configuration (its compact JSON, fields in declaration order).
pub fn config_hash(cfg: &Config) -> String {
    cfg.sha256()
}

/// The exact parameters a configuration gives (its decimals as the user wrote them).
pub fn config_params(cfg: &Config) -> Result<ExactParams, CertifyError> {
    let w = &cfg.wing;
    let q = |field: &str, x: f64| {
        parse_rational_bounded(&format_decimal(x), &NumberLimits::CERTIFICATE)
            .map_err(|e| CertifyError::Invalid { field: field.into(), message: format!("cannot be certified: {e}") })
    };
    Ok(ExactParams {
        wing: [
            q("wing.span", w.span)?,
            q("wing.rho", w.rho)?,
            q("wing.rho_xc", w.rho_xc)?,
            q("wing.ei", w.ei)?,
            q("wing.gj", w.gj)?,
            q("wing.ip", w.ip)?,
            q("wing.xi", w.xi)?,
        ],
        weights: [q("control.a", cfg.control.a)?, q("control.b", cfg.control.b)?],
    })
}

/// Reads at most [`MAX_FILE_BYTES`] of a regular file. The type is checked before the file is
/// opened (opening a FIFO for reading blocks until a writer appears) and again on the open file.
pub fn read_bounded(path: &Path) -> Result<Vec<u8>, CertifyError> {
    let io = |e| CertifyError::Io { path: path.to_path_buf(), source: e };
    let not_regular = || CertifyError::Invalid {
        field: path.display().to_string(),
        message: "not a regular file (a certificate set holds only regular files)".into(),
    };
    if !std::fs::metadata(path).map_err(io)?.is_file() {
        return Err(not_regular());
    }
    let f = std::fs::File::open(path).map_err(io)?;
    if !f.metadata().map_err(io)?.is_file() {
        return Err(not_regular());
    }
    let mut bytes = Vec::new();
    f.take(MAX_FILE_BYTES + 1).read_to_end(&mut bytes).map_err(io)?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(CertifyError::Invalid {
            field: path.display().to_string(),
            message: format!("larger than {MAX_FILE_BYTES} bytes"),
        });
    }
    Ok(bytes)
}

/// One verified certificate.
#[derive(Debug, Clone, PartialEq)]
pub struct VerifiedCert {
    /// Its role.
    pub role: &'static Role,
    /// What was checked.
    pub fact: CheckedFact,
}

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

fn bad(field: &str, message: impl Into<String>) -> CertifyError {
    CertifyError::Invalid { field: field.into(), message: message.into() }
}

pub use wingcheck_model::json::duplicate_key;

/// Parses and checks `index.json` text (no certificate is read).
pub fn parse_manifest(text: &[u8]) -> Result<(Manifest, Config), CertifyError> {
    if let Some(key) = duplicate_key(text) {
        return Err(bad(INDEX, format!("key {key} occurs twice (a JSON object has each key once)")));
    }
    let m: Manifest =
        serde_json::from_slice(text).map_err(|e| bad(INDEX, format!("not a wingcheck proofs manifest: {e}")))?;
    if m.format != INDEX_FORMAT || m.version != INDEX_VERSION {
        return Err(bad(
            INDEX,
            format!("format {:?} version {}, expected {INDEX_FORMAT:?} version {INDEX_VERSION}", m.format, m.version),
        ));
    }
    let cfg = Config::from_json_value(m.config.clone()).map_err(|e| bad("index.json config", e.to_string()))?;
    let hash = config_hash(&cfg);
    if hash != m.config_sha256 {
        return Err(bad("index.json config_sha256", format!("{} but the config hashes to {hash}", m.config_sha256)));
    }
    Ok((m, cfg))
}

/// The keys (dotted paths) whose values differ between two configurations, with both values.
pub fn config_differences(set: &Config, expected: &Config) -> Vec<String> {
    fn flat(prefix: &str, v: &serde_json::Value, out: &mut Vec<(String, String)>) {
        match v {
            serde_json::Value::Object(m) => {
                for (k, x) in m {
                    flat(&if prefix.is_empty() { k.clone() } else { format!("{prefix}.{k}") }, x, out);
                }
            }
            other => out.push((prefix.to_string(), other.to_string())),
        }
    }
    let (mut a, mut b) = (Vec::new(), Vec::new());
    flat("", &serde_json::to_value(set).expect("config serialises"), &mut a);
    flat("", &serde_json::to_value(expected).expect("config serialises"), &mut b);
    a.iter()
        .zip(&b)
        .filter(|((_, x), (_, y))| x != y)
        .map(|((k, x), (_, y))| format!("{k} (set: {x}, expected: {y})"))
        .collect()
}

/// Verifies the certificate set in `dir` (see the module documentation) for whatever
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
        let hash = config_hash(want);
        if hash != manifest.config_sha256 {
            let diff = config_differences(&cfg, want);
            let shown: Vec<&str> = diff.iter().take(6).map(String::as_str).collect();
            return Err(bad(
                "index.json config",
                format!(
                    "the set was made for config sha256 {}, not the expected configuration (sha256 {hash}): {}{}",
                    manifest.config_sha256,
                    shown.join(", "),
                    if diff.len() > 6 { format!(" and {} more keys differ", diff.len() - 6) } else { String::new() }
                ),
            ));
        }
    }
    let cfg_params = config_params(&cfg)?;
    // The directory holds exactly index.json and the listed files.
    let listed: BTreeSet<&str> = manifest.certificates.iter().map(|e| e.file.as_str()).collect();
    if listed.len() != manifest.certificates.len() {
        return Err(bad(INDEX, "a file is listed twice"));
    }
    let entries = std::fs::read_dir(dir).map_err(|e| CertifyError::Io { path: dir.to_path_buf(), source: e })?;
    for entry in entries {
        let entry = entry.map_err(|e| CertifyError::Io { path: dir.to_path_buf(), source: e })?;
        let name = entry.file_name().to_string_lossy().to_string();
        if name != INDEX && !listed.contains(name.as_str()) {
            return Err(bad(&name, "not listed in index.json (a set holds only the files its manifest lists)"));
        }
    }
    // Pass 1, no arithmetic beyond bounded parsing: names, hashes, ids, roles, the set's
    // config and one discretisation across the set.
    let mut parsed: Vec<(&'static Role, CertificateFile, &str)> = Vec::new();
    let mut enclosure: Option<(&'static Role, Omega1Certificate, &str)> = None;
    for e in &manifest.certificates {
        let role = role(&e.id).ok_or_else(|| bad(&e.file, format!("unknown certificate id {:?}", e.id)))?;
        if e.file != format!("{}.json", e.id) {
            return Err(bad(&e.file, format!("file name does not match id {:?}", e.id)));
        }
        let bytes = read_bounded(&dir.join(&e.file))?;
        let hash = sha256_hex(&bytes);
        if hash != e.sha256 {
            return Err(bad(&e.file, format!("content hashes to {hash}, index.json lists {}", e.sha256)));
        }
        let text = std::str::from_utf8(&bytes).map_err(|_| bad(&e.file, "not UTF-8"))?;
        if role.fact == FactKind::Omega1Enclosure {
            let file = Omega1Certificate::parse(text).map_err(|err| err.in_file(&e.file))?;
            if file.id != e.id {
                return Err(bad(&e.file, format!("id {:?} inside, {:?} in index.json", file.id, e.id)));
            }
            let wing = file.exact_wing().map_err(|err| err.in_file(&e.file))?;
            same_wing(&e.file, &wing, &cfg_params.wing)?;
            enclosure = Some((role, file, e.file.as_str()));
            continue;
        }
        let file = CertificateFile::parse(text).map_err(|err| err.in_file(&e.file))?;
        if file.id != e.id {
            return Err(bad(&e.file, format!("id {:?} inside, {:?} in index.json", file.id, e.id)));
        }
        if file.fact != role.fact {
            return Err(bad(
                &e.file,
                format!("fact {} but role {} needs {}", file.fact.as_str(), role.id, role.fact.as_str()),
            ));
        }
        let params = file.exact_params().map_err(|err| err.in_file(&e.file))?;
        same_wing(&e.file, &params.wing, &cfg_params.wing)?;
        match role.weights {
            WeightsRule::Config if params.weights != cfg_params.weights => {
                return Err(bad(
                    &e.file,
                    format!(
                        "weights a = {}, b = {} but the set's config has a = {}, b = {}",
                        show(&params.weights[0]),
                        show(&params.weights[1]),
                        show(&cfg_params.weights[0]),
                        show(&cfg_params.weights[1])
                    ),
                ))
            }
            WeightsRule::Ratio if !params.weights[1].is_one() => {
                return Err(bad(
                    &e.file,
                    format!("a ratio certificate needs b = 1, has b = {}", show(&params.weights[1])),
                ))
            }
            _ => {}
        }
        parsed.push((role, file, e.file.as_str()));
    }
    // The bounds (statements about one Galerkin space) share one discretisation; a negative
    // direction is a state of the PDE whatever its space, so it may come from a finer one.
    let mut sizes = Vec::new();
    for (role, file, name) in &parsed {
        if file.fact != FactKind::Mu3Infeasible {
            let n = file.require_elements().map_err(|err| err.in_file(name))?;
            if file.fact != FactKind::WNegativeDirection {
                sizes.push((role.id, n));
            }
        }
    }
    if let Some(&(first_id, n)) = sizes.first() {
        if let Some(&(id, m)) = sizes.iter().find(|&&(_, m)| m != n) {
            return Err(bad(
                id,
                format!("elements = {m}, but {first_id} uses {n}: one discretisation across the set's bounds"),
            ));
        }
    }
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
    let conclusions = conclusions(&manifest, &cfg_params, &certs, omega1.as_ref())?;
    Ok(VerifiedSet { config: cfg, config_sha256: manifest.config_sha256, certs, conclusions, omega1 })
}

/// A certificate's wing decimals must be the set's config's, exactly.
fn same_wing(file: &str, have: &[BigRational; 7], want: &[BigRational; 7]) -> Result<(), CertifyError> {
    for (k, (have, want)) in have.iter().zip(want).enumerate() {
        if have != want {
            return Err(bad(
                file,
                format!(
                    "wing.{} = {} but the set's config has {}",
                    super::facts::WING_FIELDS[k],
                    show(have),
                    show(want)
                ),
            ));
        }
    }
    Ok(())
}

fn find<'a>(certs: &'a [VerifiedCert], id: &str) -> Option<&'a CheckedFact> {
    certs.iter().find(|c| c.role.id == id).map(|c| &c.fact)
}

/// The ids the verifier requires for each claim, given the facts present and the config.
pub fn required(cfg_params: &ExactParams, lower_lambda: Option<&BigRational>) -> Vec<(ClaimId, Vec<&'static str>)> {
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

fn conclusions(
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
    let mut used = BTreeSet::new();
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
    for (claim, ids) in required(cfg_params, lower.as_ref()) {
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
    Ok(out)
}

/// What the enclosure decides at the set's a/b, for the continuous model (W ≻ 0 iff a/b < ω₁,
/// docs/model.md "W ≻ 0 iff a/b < ω₁").
fn enclosure_conclusion(e: &Omega1Enclosure, p: &ExactParams) -> String {
    let [a, b] = &p.weights;
    let ratio = a / b;
    let head = format!(
        "{} ≤ ω₁ ≤ {} rad/s for the continuous wing, so ",
        omega1::exact_decimal(&e.lower),
        omega1::exact_decimal(&e.upper)
    );
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
