//! Certificates for the definiteness and infeasibility facts behind the W-bounds and
//! mu-conditions rows, and the enclosure of the continuous wing's ω₁ ([`omega1`]), written by
//! `wingcheck certify` and re-derived by `wingcheck verify` in exact rational arithmetic
//! (wingcheck-cert), independent of clarabel and faer.
//!
//! A certificate is a *recipe*: parameters (the configuration's decimals, the Galerkin element
//! count, λ as a rational) and a witness. The verifier rebuilds W and κ ((22)–(25), via
//! [`crate::lyapunov::assemble`]) or the μ3 system of (32) from the parameters, checks the
//! witness and writes the statement itself ([`facts`]). The set is bound to one configuration
//! by `index.json` ([`manifest`]). A passing verify proves that the printed facts follow from
//! the printed parameters; it says nothing about who made the files.

pub mod facts;
pub mod manifest;
pub mod omega1;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use num_rational::BigRational;
use wingcheck_cert::exact::{parse_rational_bounded, to_f64, NumberLimits};
use wingcheck_model::Config;

use crate::lyapunov::{self, Coupling, LyapunovParams};
use facts::{CertificateFile, FactKind, WeightsText, WingText, FORMAT, VERSION};
use manifest::{ClaimEntry, FileEntry, Manifest, INDEX, INDEX_FORMAT, INDEX_VERSION};

pub use manifest::{verify_set, VerifiedSet};

/// Elements of the Galerkin space used in certificates (dimension 11·N).
pub const CERT_ELEMENTS: usize = 4;

/// Errors of writing and verifying certificate sets.
#[derive(Debug, thiserror::Error)]
pub enum CertifyError {
    /// Reading a file or directory failed.
    #[error("cannot read {path}: {source}")]
    Io {
        /// The path.
        path: PathBuf,
        /// The OS error.
        source: std::io::Error,
    },
    /// Writing the set failed (the previous set, if any, is unchanged).
    #[error(transparent)]
    Write(#[from] wingcheck_io::IoError),
    /// A field of a certificate or the manifest is malformed, out of its bounds or
    /// inconsistent with the set.
    #[error("{field}: {message}")]
    Invalid {
        /// File and/or field.
        field: String,
        /// What is wrong.
        message: String,
    },
    /// The exact check failed: the claimed fact does not follow from the parameters.
    #[error("refuted: {0}")]
    Refuted(String),
    /// The float computation that finds a witness failed (certify only).
    #[error("numerical failure while computing {what}: {detail}")]
    Numerical {
        /// Which quantity.
        what: String,
        /// The solver's message.
        detail: String,
    },
}

impl CertifyError {
    /// Prefixes the error with the file it occurred in.
    pub fn in_file(self, file: &str) -> Self {
        match self {
            CertifyError::Invalid { field, message } => {
                CertifyError::Invalid { field: format!("{file}: {field}"), message }
            }
            CertifyError::Refuted(m) => CertifyError::Refuted(format!("{file}: {m}")),
            other => other,
        }
    }
}

/// Exact decimal text of a config value ([`wingcheck_model::format_number`]: the shortest
/// round-trip decimal, `0.35`, `10`, `1e-12`).
pub fn format_decimal(x: f64) -> String {
    wingcheck_model::format_number(x)
}

fn numerical(what: &str) -> impl FnOnce(String) -> CertifyError + '_ {
    move |detail| CertifyError::Numerical { what: what.into(), detail }
}

/// Rational close to x with denominator 10⁶, rounded down (`down`) or up.
fn round_rational(x: f64, down: bool) -> BigRational {
    let scaled = x * 1e6;
    let k = if down { scaled.floor() } else { scaled.ceil() };
    BigRational::new((k as i64).into(), 1_000_000.into())
}

fn fraction(r: &BigRational) -> String {
    wingcheck_cert::exact::to_fraction_string(r)
}

struct Maker {
    wing: WingText,
    params: LyapunovParams,
}

impl Maker {
    fn file(&self, id: &str, fact: FactKind, a: &str, b: &str) -> CertificateFile {
        CertificateFile {
            format: FORMAT.into(),
            version: VERSION,
            id: id.into(),
            fact,
            wing: self.wing.clone(),
            weights: WeightsText { a: a.into(), b: b.into() },
            elements: None,
            lambda: None,
            witness: None,
        }
    }

    fn bound(&self, id: &str, fact: FactKind, a: &str, b: &str, lambda: &BigRational) -> CertificateFile {
        CertificateFile {
            elements: Some(self.params.elements),
            lambda: Some(fraction(lambda)),
            ..self.file(id, fact, a, b)
        }
    }

    fn negative(&self, id: &str, a: &str, b: &str, argmin: &[f64]) -> CertificateFile {
        let x = lyapunov::round_vector(argmin).iter().map(fraction).collect();
        CertificateFile {
            elements: Some(self.params.elements),
            witness: Some(x),
            ..self.file(id, FactKind::WNegativeDirection, a, b)
        }
    }
}

/// All certificate files for `cfg` (in memory, in manifest order).
pub fn certificates(cfg: &Config) -> Result<Vec<CertificateFile>, CertifyError> {
    let exact = manifest::config_params(cfg)?; // refuses values that cannot be certified
    let n = CERT_ELEMENTS;
    let w = &cfg.wing;
    let d = format_decimal;
    let wing = WingText {
        span: d(w.span),
        rho: d(w.rho),
        rho_xc: d(w.rho_xc),
        ei: d(w.ei),
        gj: d(w.gj),
        ip: d(w.ip),
        xi: d(w.xi),
    };
    let params = LyapunovParams {
        rho: wing.rho.clone(),
        rho_xc: wing.rho_xc.clone(),
        ei: wing.ei.clone(),
        gj: wing.gj.clone(),
        ip: wing.ip.clone(),
        span: wing.span.clone(),
        a: d(cfg.control.a),
        b: d(cfg.control.b),
        coupling: Coupling::Corrected,
        elements: n,
    };
    let maker = Maker { wing, params: params.clone() };
    let forms = lyapunov::assemble(&params).map_err(numerical("the exact forms W, κ"))?;
    let tight = lyapunov::tight_constants(&forms).map_err(numerical("the tight constants of W/κ"))?;
    let (a, b) = (params.a.as_str(), params.b.as_str());
    let mut out = Vec::new();
    let l2 = if tight.lambda2 > 0.0 {
        round_rational(tight.lambda2 * (1.0 - 1e-3), true)
    } else {
        round_rational(tight.lambda2 - 1e-4 * tight.lambda2.abs().max(1.0), true)
    };
    out.push(maker.bound("w-bounds-lower", FactKind::WLowerBound, a, b, &l2));
    let l1 = round_rational(tight.lambda1 + 1e-4 * tight.lambda1.abs().max(1.0), false);
    out.push(maker.bound("w-bounds-upper", FactKind::WUpperBound, a, b, &l1));
    if to_f64(&l2) <= 0.0 {
        if tight.lambda2 >= 0.0 {
            return Err(CertifyError::Numerical {
                what: "the lower bound of W/κ".into(),
                detail: format!("min W/κ = {:.3e} is too close to 0 to certify either sign", tight.lambda2),
            });
        }
        out.push(maker.negative("w-bounds-indefinite", a, b, &tight.argmin));
    }
    // a/b_max = ω₁: above ω₁·1.05 a negative direction exists; below ω₁·0.95 W ≻ 0 on V_N.
    let ratio = crate::wbounds::a_over_b_max(cfg, Coupling::Corrected, n)
        .map_err(|e| numerical("the largest a/b with W positive definite")(e.to_string()))?;
    let above = decimal_of(&round_rational(ratio * 1.05, false));
    let p = params.with_weights(&above, "1");
    let t = lyapunov::tight_constants(&lyapunov::assemble(&p).map_err(numerical("W at a/b above ω₁"))?)
        .map_err(numerical("W at a/b above ω₁"))?;
    out.push(maker.negative("w-bounds-ratio-above", &above, "1", &t.argmin));
    let below = decimal_of(&round_rational(ratio * 0.95, true));
    let p = params.with_weights(&below, "1");
    let t = lyapunov::tight_constants(&lyapunov::assemble(&p).map_err(numerical("W at a/b below ω₁"))?)
        .map_err(numerical("W at a/b below ω₁"))?;
    let lam = round_rational(t.lambda2 * 0.99, true);
    out.push(maker.bound("w-bounds-ratio-below", FactKind::WLowerBound, &below, "1", &lam));
    let (_, c3) = facts::mu3_system(&exact);
    if c3 < BigRational::from_integer(0.into()) {
        // Farkas multipliers for rows (b, 2aρx_c) ≤ C3, −η1 ≤ 0, −η5 ≤ 0: y = (1, b, 2aρx_c).
        let [_, _, rho_xc, ..] = &exact.wing;
        let [ea, eb] = &exact.weights;
        let two = BigRational::from_integer(2.into());
        let y = vec!["1/1".to_string(), fraction(eb), fraction(&(&two * ea * rho_xc))];
        out.push(CertificateFile {
            witness: Some(y),
            ..maker.file("mu-conditions-infeasible", FactKind::Mu3Infeasible, a, b)
        });
    }
    Ok(out)
}

/// Exact decimal text of a rational with denominator 10⁶.
fn decimal_of(r: &BigRational) -> String {
    let s = format!("{:.6}", to_f64(r));
    debug_assert_eq!(parse_rational_bounded(&s, &NumberLimits::CERTIFICATE).ok().as_ref(), Some(r));
    s
}

/// The manifest and file texts of the set for `cfg`: `(file name, text)` pairs, index last.
pub fn render_set(cfg: &Config) -> Result<Vec<(String, String)>, CertifyError> {
    let certs = certificates(cfg)?;
    let mut files = Vec::new();
    let mut entries = Vec::new();
    for c in &certs {
        let text = c.to_text();
        let name = format!("{}.json", c.id);
        entries.push(FileEntry { file: name.clone(), id: c.id.clone(), sha256: manifest::sha256_hex(text.as_bytes()) });
        files.push((name, text));
    }
    // The ω₁ enclosure (its own file format), after the others.
    let enclosure = omega1::compute(cfg)?;
    let text = enclosure.0.to_text();
    let name = format!("{}.json", omega1::ID);
    entries.push(FileEntry {
        file: name.clone(),
        id: omega1::ID.into(),
        sha256: manifest::sha256_hex(text.as_bytes()),
    });
    files.push((name, text));
    let ids = certs.iter().map(|c| c.id.as_str()).chain([omega1::ID]);
    let mut claims: Vec<ClaimEntry> = Vec::new();
    for id in ids {
        let claim = manifest::role(id).expect("certify writes known roles").claim;
        match claims.iter_mut().find(|e| e.claim == claim) {
            Some(e) => e.needs.push(id.into()),
            None => claims.push(ClaimEntry { claim: claim.into(), needs: vec![id.into()] }),
        }
    }
    let index = Manifest {
        format: INDEX_FORMAT.into(),
        version: INDEX_VERSION,
        config_sha256: manifest::config_hash(cfg),
        config: serde_json::to_value(cfg).expect("config serialises"),
        claims,
        certificates: entries,
    };
    let mut text = serde_json::to_string_pretty(&index).expect("manifest serialises");
    text.push('\n');
    files.push((INDEX.to_string(), text));
    Ok(files)
}

/// Writes the whole set for `cfg` into `dir`, replacing an earlier set there atomically (the
/// directory holds the old set or the new one at every instant). An existing `dir` is replaced
/// only if it holds nothing but a certificate set's files (`index.json` and the files it
/// lists); anything else is refused and left untouched. Returns the files written.
pub fn write_all(cfg: &Config, dir: &Path) -> Result<Vec<PathBuf>, CertifyError> {
    let files = render_set(cfg)?;
    let staging = wingcheck_io::StagingDir::new(dir)?;
    for (name, text) in &files {
        staging.write(name, text.as_bytes())?;
    }
    staging.commit(|old| wingcheck_io::only_listed_files(old, &files_of_set(old)))?;
    Ok(files.iter().map(|(n, _)| dir.join(n)).collect())
}

/// The files an existing set in `dir` owns: `index.json` and what it lists (empty if there is
/// no readable manifest).
fn files_of_set(dir: &Path) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    let Ok(bytes) = manifest::read_bounded(&dir.join(INDEX)) else { return out };
    let Ok(v) = serde_json::from_slice::<serde_json::Value>(&bytes) else { return out };
    if v["format"] != INDEX_FORMAT {
        return out;
    }
    out.insert(INDEX.to_string());
    for e in v["certificates"].as_array().into_iter().flatten() {
        if let Some(f) = e["file"].as_str().filter(|f| !f.contains(['/', '\\'])) {
            out.insert(f.to_string());
        }
    }
    out
}
