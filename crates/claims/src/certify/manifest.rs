//! The certificate set: `index.json` and the verifier's own table of roles.
//!
//! `index.json` names the configuration the set was made for (the whole config and its
//! SHA-256), the claims and the facts each needs, and every certificate file with the SHA-256
//! of its bytes. [`verify_set`](super::verify_set) accepts a directory only if
//! * it holds exactly `index.json` and the files it lists (nothing missing, nothing extra);
//! * every file is `<id>.json`, its `id` is the listed one and its bytes hash to the listed hash;
//! * every certificate was made for the manifest's configuration (its wing parameters, and the
//!   weights a, b where the role says so, equal the config's exactly);
//! * each claim lists at least the facts the verifier's own [`ROLES`](crate::spec::ROLES) table requires, and every
//!   certificate re-derives (see [`super::facts`]).

use std::collections::BTreeSet;
use std::path::Path;

use num_rational::BigRational;
use num_traits::One;
use serde::{Deserialize, Serialize};
use wingcheck_model::Config;

use super::facts::{show, CertificateFile, CheckedFact, ExactParams, FactKind, MAX_FILE_BYTES};
use super::omega1::Omega1Certificate;
use super::CertifyError;
use crate::spec::{role, ClaimId, Role, WeightsRule};

/// File name of the manifest.
pub const INDEX: &str = "index.json";
/// Value of the manifest's `"format"` field.
pub const INDEX_FORMAT: &str = "wingcheck-proofs";
/// Version of the manifest.
pub const INDEX_VERSION: u64 = 1;

/// A claim and the certificate ids it needs.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ClaimEntry {
    /// The claim (one of the claims with certificate roles, `spec::ROLES`), by its id (`W-bounds`).
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

/// Reads at most [`MAX_FILE_BYTES`] of a regular file ([`wingcheck_io::read_regular`]: the type
/// is checked before the file is opened — opening a FIFO for reading blocks until a writer
/// appears — and again on the file opened non-blocking).
pub fn read_bounded(path: &Path) -> Result<Vec<u8>, CertifyError> {
    wingcheck_io::read_regular(path, MAX_FILE_BYTES).map_err(|e| match e {
        wingcheck_io::ReadError::Io(source) => CertifyError::Io { path: path.to_path_buf(), source },
        wingcheck_io::ReadError::NotRegular(kind) => CertifyError::Invalid {
            field: path.display().to_string(),
            message: format!("{kind}, not a regular file (a certificate set holds only regular files)"),
        },
        wingcheck_io::ReadError::TooLarge(max) => {
            CertifyError::Invalid { field: path.display().to_string(), message: format!("larger than {max} bytes") }
        }
    })
}

/// One verified certificate.
#[derive(Debug, Clone, PartialEq)]
pub struct VerifiedCert {
    /// Its role.
    pub role: &'static Role,
    /// What was checked.
    pub fact: CheckedFact,
}

pub(super) fn bad(field: &str, message: impl Into<String>) -> CertifyError {
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

/// A pinned verify: the set must have been made for exactly `want` (its hash), else refused
/// naming the keys that differ.
pub(super) fn check_pinned(manifest: &Manifest, cfg: &Config, want: &Config) -> Result<(), CertifyError> {
    let hash = config_hash(want);
    if hash != manifest.config_sha256 {
        let diff = config_differences(cfg, want);
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
    Ok(())
}

/// The directory holds exactly index.json and the listed files, each listed once.
pub(super) fn check_listing(dir: &Path, manifest: &Manifest) -> Result<(), CertifyError> {
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
    Ok(())
}

/// A listed certificate parsed and matched to its role, not yet checked.
pub(super) type Parsed<'a, F> = (&'static Role, F, &'a str);

/// Pass 1, no arithmetic beyond bounded parsing: names, hashes, ids, roles, the set's wing and
/// the weights each role asks for. The ω₁ enclosure is returned apart (its own file format).
#[allow(clippy::type_complexity)]
pub(super) fn parse_certificates<'a>(
    dir: &Path,
    manifest: &'a Manifest,
    cfg_params: &ExactParams,
) -> Result<(Vec<Parsed<'a, CertificateFile>>, Option<Parsed<'a, Omega1Certificate>>), CertifyError> {
    let mut parsed: Vec<Parsed<'a, CertificateFile>> = Vec::new();
    let mut enclosure: Option<Parsed<'a, Omega1Certificate>> = None;
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
    Ok((parsed, enclosure))
}

/// The bounds (statements about one Galerkin space) share one discretisation; a negative
/// direction is a state of the PDE whatever its space, so it may come from a finer one.
pub(super) fn check_one_discretisation(parsed: &[Parsed<'_, CertificateFile>]) -> Result<(), CertifyError> {
    let mut sizes = Vec::new();
    for (role, file, name) in parsed {
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
    Ok(())
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
