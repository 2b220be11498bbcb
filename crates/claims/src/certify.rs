//! Certificates for the definiteness and infeasibility facts behind the W-bounds and
//! mu-conditions rows, and the enclosure of the continuous wing's ω₁ ([`omega1`]), written by
//! `wingcheck certify` and re-derived by `wingcheck verify` in exact rational arithmetic
//! (wingcheck-cert), independent of clarabel and faer.
//!
//! A certificate is a *recipe*: parameters (the configuration's decimals, the Galerkin element
//! count, λ as a rational) and a witness. The verifier rebuilds W and κ ((22)–(25), via
//! [`wingcheck_theory::lyapunov::assemble`]) or the μ3 system of (32) from the parameters, checks the
//! witness and writes the statement itself ([`facts`]). The set is bound to one configuration
//! by `index.json` ([`manifest`]). A passing verify proves that the printed facts follow from
//! the printed parameters; it says nothing about who made the files.

mod conclude;
pub mod facts;
pub mod manifest;
pub mod omega1;
mod verify;

use crate::numerics::NumericsError;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use num_rational::BigRational;
use wingcheck_cert::exact::{to_f64, NumberLimits};
use wingcheck_model::Config;

use facts::{CertificateFile, FactKind, WeightsText, WingText, FORMAT, VERSION};
use manifest::{ClaimEntry, FileEntry, Manifest, INDEX, INDEX_FORMAT, INDEX_VERSION};
use wingcheck_theory::lyapunov::{self, Coupling, LyapunovParams};

pub use verify::{verify_set, verify_set_for, VerifiedSet};

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
    /// `certify` made a set its own verifier rejects (a number outside the verifier's limits,
    /// a witness that rounding spoiled): nothing was replaced.
    #[error(
        "certify made a set that its own verify rejects, so the previous set is unchanged: {0} (the witnesses \
         and λ's come from float eigen-solves, which lose accuracy when the wing's parameters span many decades)"
    )]
    SelfCheck(String),
    /// The float computation that finds a witness failed (certify only).
    #[error("numerical failure while computing {what}: {cause}")]
    Numerical {
        /// Which quantity.
        what: &'static str,
        /// What failed.
        #[source]
        cause: crate::numerics::NumericsError,
    },
    /// Stopped through the cancel token before the set was moved into place.
    #[error(transparent)]
    Cancelled(#[from] wingcheck_model::Cancelled),
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

fn numerical<E: Into<NumericsError>>(what: &'static str) -> impl FnOnce(E) -> CertifyError {
    move |cause| CertifyError::Numerical { what, cause: cause.into() }
}

/// x rounded down (`down`) or up to a decimal k·10^(−places), exactly (x's exact binary value
/// times a power of ten, then floor or ceiling in big integers: no f64 → i64 cast, which
/// saturated at 1e12 · 1e6). Six places for |x| in [1e-3, 1e13) (the committed set's λ's and
/// ratios), at least four significant digits below and at most nineteen above, so the text stays
/// short for every magnitude a config allows.
fn round_decimal(x: f64, down: bool) -> Decimal {
    let e = if x == 0.0 || !x.is_finite() { 0 } else { x.abs().log10().floor() as i64 };
    let places = if e < -3 {
        3 - e
    } else if e > 12 {
        18 - e
    } else {
        6
    };
    let exact = wingcheck_cert::exact::from_f64_exact(if x.is_finite() { x } else { 0.0 }).expect("finite");
    let ten = BigRational::from_integer(10.into());
    let scale = num_traits::pow(ten, places.unsigned_abs() as usize);
    let scaled = if places >= 0 { exact * &scale } else { exact / &scale };
    let k = if down { scaled.floor() } else { scaled.ceil() }.to_integer();
    Decimal { k, places }
}

/// The exact decimal k·10^(−places).
struct Decimal {
    k: num_bigint::BigInt,
    places: i64,
}

impl Decimal {
    fn value(&self) -> BigRational {
        let ten = BigRational::from_integer(10.into());
        let scale = num_traits::pow(ten, self.places.unsigned_abs() as usize);
        let k = BigRational::from_integer(self.k.clone());
        if self.places >= 0 {
            k / scale
        } else {
            k * scale
        }
    }

    /// As a fraction `p/q` where that fits the verifier's number limits (the committed set's
    /// form), else as `ke−places`.
    fn fraction_text(&self) -> String {
        let f = fraction(&self.value());
        if f.len() <= NumberLimits::CERTIFICATE.max_chars {
            f
        } else {
            self.scientific()
        }
    }

    /// As a plain decimal with `places` digits after the point when 0 ≤ places ≤ 6 (`0.126955`),
    /// else as `ke−places`.
    fn decimal_text(&self) -> String {
        if !(0..=6).contains(&self.places) || self.k.sign() == num_bigint::Sign::Minus {
            return self.scientific();
        }
        let digits = format!("{:0>width$}", self.k, width = self.places as usize + 1);
        let (int, frac) = digits.split_at(digits.len() - self.places as usize);
        if frac.is_empty() {
            int.to_string()
        } else {
            format!("{int}.{frac}")
        }
    }

    fn scientific(&self) -> String {
        format!("{}e{}", self.k, -self.places)
    }
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

    fn bound(&self, id: &str, fact: FactKind, a: &str, b: &str, lambda: &str) -> CertificateFile {
        CertificateFile {
            elements: Some(self.params.elements),
            lambda: Some(lambda.into()),
            ..self.file(id, fact, a, b)
        }
    }

    fn negative(&self, id: &str, a: &str, b: &str, argmin: &[f64], elements: usize) -> CertificateFile {
        let p = LyapunovParams { a: a.into(), b: b.into(), elements, ..self.params.clone() };
        let (x, _) = negative_witness(&p, argmin);
        CertificateFile {
            elements: Some(elements),
            witness: Some(x),
            ..self.file(id, FactKind::WNegativeDirection, a, b)
        }
    }
}

/// Elements of the finer Galerkin spaces tried for a negative direction of W when W ≻ 0 on the
/// [`CERT_ELEMENTS`] space although a/b exceeds the converged ω₁: the Galerkin ω₁ of a space is
/// an upper bound that decreases to ω₁ under refinement, so the negative directions of W for a/b
/// between ω₁ and the coarse space's ω₁ appear only on finer spaces.
pub const NEGATIVE_DIRECTION_ELEMENTS: [usize; 3] = [8, 16, 32];

/// The witness of W(x) < 0 from the float extremal state: rounded to multiples of 2⁻²⁰ after
/// scaling to max-norm 1 (short fractions; the committed set's form), or, where that loses the
/// small components and W(x) < 0 no longer holds exactly, each component to 7 significant digits
/// (`1.234567e-15`). Falls back to the first if neither holds (the self-check then refuses);
/// the flag says whether W(x) < 0 was checked exactly.
fn negative_witness(p: &LyapunovParams, argmin: &[f64]) -> (Vec<String>, bool) {
    let coarse: Vec<BigRational> = lyapunov::round_vector(argmin);
    let texts = |x: &[BigRational]| x.iter().map(fraction).collect::<Vec<String>>();
    let Ok(forms) = lyapunov::assemble(p) else { return (texts(&coarse), false) };
    let zero = BigRational::from_integer(0.into());
    if lyapunov::quadratic_form(&forms.w, &coarse) < zero {
        return (texts(&coarse), true);
    }
    let scale = argmin.iter().fold(0.0f64, |m, v| m.max(v.abs())).max(1e-300);
    let fine: Vec<String> = argmin.iter().map(|v| format!("{:.6e}", v / scale)).collect();
    let exact: Option<Vec<BigRational>> = fine
        .iter()
        .map(|t| wingcheck_cert::exact::parse_rational_bounded(t, &NumberLimits::CERTIFICATE).ok())
        .collect();
    match exact {
        Some(x) if lyapunov::quadratic_form(&forms.w, &x) < zero => (fine, true),
        _ => (texts(&coarse), false),
    }
}

/// All certificate files for `cfg` (in memory, in manifest order).
pub fn certificates(cfg: &Config) -> Result<Vec<CertificateFile>, CertifyError> {
    Ok(certificate_set(cfg)?.0)
}

/// The certificate files for `cfg` and the notes `certify` prints with them (why a fact the
/// claim checker finds is not in the set, e.g. a negative direction of W too close to ω₁).
pub fn certificate_set(cfg: &Config) -> Result<(Vec<CertificateFile>, Vec<String>), CertifyError> {
    let exact = facts::config_params(cfg)?; // refuses values that cannot be certified
    let n = CERT_ELEMENTS;
    let d = format_decimal;
    let wing = wing_text(cfg);
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
    let mut notes = Vec::new();
    let l2 = if tight.lambda2 > 0.0 {
        round_decimal(tight.lambda2 * (1.0 - 1e-3), true)
    } else {
        round_decimal(tight.lambda2 - 1e-4 * tight.lambda2.abs().max(1.0), true)
    };
    out.push(maker.bound("w-bounds-lower", FactKind::WLowerBound, a, b, &l2.fraction_text()));
    let l1 = round_decimal(tight.lambda1 + 1e-4 * tight.lambda1.abs().max(1.0), false);
    out.push(maker.bound("w-bounds-upper", FactKind::WUpperBound, a, b, &l1.fraction_text()));
    if to_f64(&l2.value()) <= 0.0 {
        if tight.lambda2 >= 0.0 {
            return Err(CertifyError::Numerical {
                what: "the lower bound of W/κ",
                cause: NumericsError::NearZero { what: "min W/κ", value: tight.lambda2 },
            });
        }
        out.push(maker.negative("w-bounds-indefinite", a, b, &tight.argmin, n));
    } else {
        match finer_negative_direction(cfg, &params)? {
            Finer::Found(file) => out.push(*file),
            Finer::NotNeeded => {}
            Finer::Why(note) => notes.push(note),
        }
    }
    // a/b_max = ω₁: above ω₁·1.05 a negative direction exists; below ω₁·0.95 W ≻ 0 on V_N.
    let ratio = lyapunov::a_over_b_max(cfg, Coupling::Corrected, n)
        .map_err(numerical("the largest a/b with W positive definite"))?;
    let above = round_decimal(ratio * 1.05, false).decimal_text();
    let p = params.with_weights(&above, "1");
    let t = lyapunov::tight_constants(&lyapunov::assemble(&p).map_err(numerical("W at a/b above ω₁"))?)
        .map_err(numerical("W at a/b above ω₁"))?;
    out.push(maker.negative("w-bounds-ratio-above", &above, "1", &t.argmin, n));
    let below = round_decimal(ratio * 0.95, true).decimal_text();
    let p = params.with_weights(&below, "1");
    let t = lyapunov::tight_constants(&lyapunov::assemble(&p).map_err(numerical("W at a/b below ω₁"))?)
        .map_err(numerical("W at a/b below ω₁"))?;
    let lam = round_decimal(t.lambda2 * 0.99, true);
    out.push(maker.bound("w-bounds-ratio-below", FactKind::WLowerBound, &below, "1", &lam.fraction_text()));
    let (_, c3) = facts::mu3_system(&exact);
    if c3 < BigRational::from_integer(0.into()) {
        // Farkas multipliers for rows (b, 2a|ρx_c|) ≤ C3, −η1 ≤ 0, −η5 ≤ 0: y = (1, b, 2a|ρx_c|).
        let [_, _, rho_xc, ..] = &exact.wing;
        let [ea, eb] = &exact.weights;
        let two = BigRational::from_integer(2.into());
        let y = vec!["1/1".to_string(), fraction(eb), fraction(&(&two * ea * num_traits::Signed::abs(rho_xc)))];
        out.push(CertificateFile {
            witness: Some(y),
            ..maker.file("mu-conditions-infeasible", FactKind::Mu3Infeasible, a, b)
        });
    }
    Ok((out, notes))
}

/// What [`finer_negative_direction`] found.
enum Finer {
    /// a/b is below the converged ω₁ (less its error): W ≻ 0 is what the claim checker finds too.
    NotNeeded,
    /// A negative direction of W at the configured weights on a finer space.
    Found(Box<CertificateFile>),
    /// Why the set cannot carry the negative direction the claim checker finds.
    Why(String),
}

/// When W ≻ 0 on the certificate space: if the configured a/b exceeds the converged ω₁ (so the
/// claim checker finds W indefinite), the first of [`NEGATIVE_DIRECTION_ELEMENTS`] whose rounded
/// extremal state has W(x) < 0 exactly, or why there is none.
fn finer_negative_direction(cfg: &Config, params: &LyapunovParams) -> Result<Finer, CertifyError> {
    let (a, b) = (cfg.control.a, cfg.control.b);
    if b <= 0.0 {
        return Ok(Finer::NotNeeded);
    }
    let omega = wingcheck_theory::w_threshold(cfg).map_err(numerical("ω₁"))?;
    let ratio = a / b;
    if ratio <= omega.value - omega.error {
        return Ok(Finer::NotNeeded);
    }
    let space = format!("W ≻ 0 is certified on the {CERT_ELEMENTS}-element Galerkin space only");
    if ratio <= omega.value + omega.error {
        return Ok(Finer::Why(format!(
            "a/b = {} is within the error of ω₁ = {:.10} ± {:.1e} rad/s, so whether W is positive definite on the \
             PDE's state space is undecided (the claim checker says: at the threshold); {space}",
            format_decimal(ratio),
            omega.value,
            omega.error
        )));
    }
    for &m in &NEGATIVE_DIRECTION_ELEMENTS {
        let p = LyapunovParams { elements: m, ..params.clone() };
        let forms = lyapunov::assemble(&p).map_err(numerical("the exact forms W, κ on a finer space"))?;
        let t = lyapunov::tight_constants(&forms).map_err(numerical("the tight constants on a finer space"))?;
        if t.lambda2 >= 0.0 {
            continue;
        }
        if let (x, true) = negative_witness(&p, &t.argmin) {
            let maker = Maker { wing: wing_text(cfg), params: p.clone() };
            return Ok(Finer::Found(Box::new(CertificateFile {
                elements: Some(m),
                witness: Some(x),
                ..maker.file("w-bounds-indefinite", FactKind::WNegativeDirection, &p.a, &p.b)
            })));
        }
    }
    Ok(Finer::Why(format!(
        "a/b = {} exceeds ω₁ = {:.10} rad/s, so W is indefinite on the PDE's state space, but no negative \
         direction shows exactly on Galerkin spaces of up to {} elements (their ω₁ lies above a/b); {space}",
        format_decimal(ratio),
        omega.value,
        NEGATIVE_DIRECTION_ELEMENTS[NEGATIVE_DIRECTION_ELEMENTS.len() - 1]
    )))
}

fn wing_text(cfg: &Config) -> WingText {
    let (w, d) = (&cfg.wing, format_decimal);
    WingText { span: d(w.span), rho: d(w.rho), rho_xc: d(w.rho_xc), ei: d(w.ei), gj: d(w.gj), ip: d(w.ip), xi: d(w.xi) }
}

/// The manifest and file texts of the set for `cfg`: `(file name, text)` pairs, index last.
pub fn render_set(cfg: &Config) -> Result<Vec<(String, String)>, CertifyError> {
    render_files(cfg, &certificates(cfg)?, &omega1::compute(cfg)?)
}

/// The set a report carries ([`render_deciding_set`]).
#[derive(Debug, Clone)]
pub struct DecidingSet {
    /// `(file name, text)` pairs, index last.
    pub files: Vec<(String, String)>,
    /// Whether its ω₁ enclosure is coarser than the one `certify` writes ([`omega1::PLAN`]'s):
    /// false where nothing coarser decides (b = 0, or a/b within the coarser enclosures).
    pub coarser_enclosure: bool,
}

/// [`render_set`] with the ω₁ enclosure the W-bounds row quotes ([`omega1::deciding`]: the
/// coarsest that decides where the configured a/b lies) instead of the tightest: the set a
/// report carries, so that its `proofs/` proves what its ledger states. The other files are
/// [`render_set`]'s.
pub fn render_deciding_set(cfg: &Config) -> Result<DecidingSet, CertifyError> {
    let enclosure = omega1::deciding(cfg)?;
    let files = render_files(cfg, &certificates(cfg)?, &enclosure)?;
    Ok(DecidingSet { files, coarser_enclosure: enclosure.0.plan() != omega1::PLAN })
}

fn render_files(
    cfg: &Config,
    certs: &[CertificateFile],
    enclosure: &omega1::Computed,
) -> Result<Vec<(String, String)>, CertifyError> {
    let mut files = Vec::new();
    let mut entries = Vec::new();
    for c in certs {
        let text = c.to_text();
        let name = format!("{}.json", c.id);
        entries.push(FileEntry { file: name.clone(), id: c.id.clone(), sha256: manifest::sha256_hex(text.as_bytes()) });
        files.push((name, text));
    }
    // The ω₁ enclosure (its own file format), after the others.
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
        let claim = crate::spec::role(id).expect("certify writes known roles").claim;
        match claims.iter_mut().find(|e| e.claim == claim) {
            Some(e) => e.needs.push(id.into()),
            None => claims.push(ClaimEntry { claim, needs: vec![id.into()] }),
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

/// Writes the whole set for `cfg` into `dir` ([`write_set`]); returns the files written.
pub fn write_all(cfg: &Config, dir: &Path) -> Result<Vec<PathBuf>, CertifyError> {
    Ok(write_set(cfg, dir)?.files)
}

/// What [`write_set`] wrote.
#[derive(Debug, Clone)]
pub struct WrittenSet {
    /// The files written (in `dir`).
    pub files: Vec<PathBuf>,
    /// Why a fact the claim checker finds is not in the set (see [`certificate_set`]).
    pub notes: Vec<String>,
}

/// Writes the whole set for `cfg` into `dir`, replacing an earlier set there atomically (the
/// directory holds the old set or the new one at every instant). The staged set is first
/// verified by [`verify_set`] itself, pinned to `cfg`: a set its own verifier would reject is
/// never swapped in ([`CertifyError::SelfCheck`], the previous set unchanged). An existing `dir`
/// is replaced only if it holds nothing but a certificate set's files (`index.json` and the
/// files it lists); anything else is refused and left untouched.
pub fn write_set(cfg: &Config, dir: &Path) -> Result<WrittenSet, CertifyError> {
    write_set_cancellable(cfg, dir, &wingcheck_model::Cancel::default())
}

/// [`write_set`], stopped through `cancel` ([`CertifyError::Cancelled`]) at any time before
/// the set is moved into place; the move goes through [`wingcheck_model::Cancel::commit`], so
/// once `cancel` is set no set appears.
pub fn write_set_cancellable(
    cfg: &Config,
    dir: &Path,
    cancel: &wingcheck_model::Cancel,
) -> Result<WrittenSet, CertifyError> {
    // the target first, before any arithmetic: its name, its type, and that it holds a set
    wingcheck_io::check_output_dir(dir, true)?;
    if dir.exists() {
        wingcheck_io::only_listed_files(dir, &files_of_set(dir))?;
    }
    let (certs, notes) = certificate_set(cfg)?;
    cancel.check()?;
    let files = render_files(cfg, &certs, &omega1::compute(cfg)?)?;
    let staging = wingcheck_io::StagingDir::new(dir)?;
    for (name, text) in &files {
        staging.write(name, text.as_bytes())?;
    }
    verify_set_for(staging.path(), Some(cfg)).map_err(|e| CertifyError::SelfCheck(e.to_string()))?;
    cancel.commit(|| {
        Ok::<_, CertifyError>(staging.commit(|old| wingcheck_io::only_listed_files(old, &files_of_set(old)))?)
    })?;
    Ok(WrittenSet { files: files.iter().map(|(n, _)| dir.join(n)).collect(), notes })
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
