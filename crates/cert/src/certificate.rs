//! Versioned JSON certificate envelope, canonical hashing and atomic writes.
//!
//! On disk a certificate is
//! `{"format": "wingcheck-certificate", "version": 1, "id", "claim",
//! "statement", "kind", "payload", "sha256"}` with every rational written as a
//! `"p/q"` string. `sha256` is the lowercase hex SHA-256 of the **canonical
//! serialisation** of the whole object without the `sha256` key: compact JSON,
//! object keys sorted by bytes (recursively), strings escaped as `serde_json`
//! does, integers in decimal. Whitespace and key order in the file therefore
//! do not matter, but any change of a value does. The hash only detects
//! accidental/naive edits; soundness comes from re-checking the mathematics.

use std::path::{Path, PathBuf};

use num_rational::BigRational;
use serde::{Deserialize, Serialize};
use serde_json::Value;
use sha2::{Digest, Sha256};

use crate::exact::{parse_rational, to_fraction_string, ExactError};
use crate::lp::{FarkasCertificate, LinearSystem, LpError};
use crate::matrix::RationalMatrix;
use crate::psd::PsdError;
use crate::recipe::RecipeRef;

/// Value of the `"format"` field.
pub const FORMAT: &str = "wingcheck-certificate";
/// The only envelope version this crate reads and writes.
pub const VERSION: u64 = 1;

/// Everything that can go wrong reading, writing or verifying a certificate.
#[derive(Debug, thiserror::Error)]
pub enum CertError {
    /// The file could not be read.
    #[error("unreadable file {path}: {source}")]
    Io {
        /// File or directory.
        path: PathBuf,
        /// Underlying error.
        source: std::io::Error,
    },
    /// Writing the certificate failed.
    #[error("cannot write {path}: {source}")]
    Write {
        /// Destination.
        path: PathBuf,
        /// Underlying error.
        source: std::io::Error,
    },
    /// The JSON text ends early.
    #[error("truncated JSON: unexpected end of input at line {line}, column {column}")]
    Truncated {
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
    },
    /// The text is not valid JSON.
    #[error("malformed JSON at line {line}, column {column}: {message}")]
    Malformed {
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// serde_json's description.
        message: String,
    },
    /// Valid JSON, but the envelope is wrong (not an object, missing or
    /// unexpected fields, wrong types).
    #[error("malformed certificate envelope: {0}")]
    Envelope(String),
    /// `"format"` is not `"wingcheck-certificate"`.
    #[error("wrong format {0:?} (expected \"wingcheck-certificate\")")]
    WrongFormat(String),
    /// `"version"` is not 1.
    #[error("unsupported certificate version {0} (this verifier reads version 1)")]
    UnsupportedVersion(String),
    /// Stored hash differs from the hash of the contents.
    #[error("tampered: sha256 mismatch (file records {stored}, contents hash to {computed})")]
    Tampered {
        /// `sha256` field in the file.
        stored: String,
        /// Hash of the canonical contents.
        computed: String,
    },
    /// `"kind"` is not one of the known kinds.
    #[error("unknown certificate kind {0:?}")]
    UnknownKind(String),
    /// The payload does not match its kind's schema.
    #[error("malformed {kind} payload: {message}")]
    Payload {
        /// Certificate kind.
        kind: &'static str,
        /// What is wrong.
        message: String,
    },
    /// A number field is not an exact rational.
    #[error("bad number in {field}: {source}")]
    Number {
        /// JSON path of the field, e.g. `payload.y[3]`.
        field: String,
        /// Parse error.
        source: ExactError,
    },
    /// A matrix/vector field has inconsistent dimensions.
    #[error("bad shape of {field}: {message}")]
    Shape {
        /// JSON path of the field.
        field: String,
        /// What is wrong.
        message: String,
    },
    /// No recipe with this name is registered.
    #[error("unknown matrix recipe {0:?}")]
    UnknownRecipe(String),
    /// A second recipe with an existing name was registered.
    #[error("recipe {0:?} is already registered")]
    DuplicateRecipe(String),
    /// The recipe could not rebuild the matrix.
    #[error("recipe {name:?} failed: {message}")]
    Recipe {
        /// Recipe name.
        name: String,
        /// Its error message.
        message: String,
    },
    /// The (semi)definiteness claim does not hold.
    #[error("claim refuted: {0}")]
    Psd(#[from] PsdError),
    /// The Farkas certificate or feasible point is wrong.
    #[error("claim refuted: {0}")]
    Lp(#[from] LpError),
}

/// The mathematical kind of a certificate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum CertKind {
    /// A recipe-built symmetric matrix is positive definite.
    PositiveDefinite,
    /// A recipe-built matrix equals the stored `L D Lᵀ` with `D ≥ 0` (PSD).
    PsdLdlt,
    /// A linear system is infeasible (Farkas multipliers).
    FarkasInfeasible,
    /// A linear system is feasible (explicit point).
    FeasiblePoint,
}

impl CertKind {
    /// The string written in the `"kind"` field.
    pub fn as_str(self) -> &'static str {
        match self {
            CertKind::PositiveDefinite => "positive-definite",
            CertKind::PsdLdlt => "psd-ldlt",
            CertKind::FarkasInfeasible => "farkas-infeasible",
            CertKind::FeasiblePoint => "feasible-point",
        }
    }

    /// Parses the `"kind"` field.
    pub fn parse(s: &str) -> Option<Self> {
        [CertKind::PositiveDefinite, CertKind::PsdLdlt, CertKind::FarkasInfeasible, CertKind::FeasiblePoint]
            .into_iter()
            .find(|k| k.as_str() == s)
    }
}

/// A linear system as stored in JSON (rationals as strings).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SystemJson {
    /// Number of variables (needed when a block has no rows).
    pub n_vars: usize,
    /// Rows of `A`.
    pub a: Vec<Vec<String>>,
    /// `b`.
    pub b: Vec<String>,
    /// Rows of `A_eq`.
    pub a_eq: Vec<Vec<String>>,
    /// `b_eq`.
    pub b_eq: Vec<String>,
}

impl SystemJson {
    /// Serialises a [`LinearSystem`].
    pub fn from_system(sys: &LinearSystem) -> Self {
        Self {
            n_vars: sys.n_vars(),
            a: matrix_to_json(&sys.a),
            b: vector_to_json(&sys.b),
            a_eq: matrix_to_json(&sys.a_eq),
            b_eq: vector_to_json(&sys.b_eq),
        }
    }

    /// Parses back into a [`LinearSystem`] (`field` prefixes error paths).
    pub fn to_system(&self, field: &str) -> Result<LinearSystem, CertError> {
        let block = |name: &str, rows: &[Vec<String>]| {
            let path = format!("{field}.{name}");
            let m = matrix_from_json(&path, rows)?;
            if rows.is_empty() {
                return Ok(RationalMatrix::zeros(0, self.n_vars));
            }
            if m.cols() != self.n_vars {
                return Err(CertError::Shape {
                    field: path,
                    message: format!("{} columns, n_vars is {}", m.cols(), self.n_vars),
                });
            }
            Ok(m)
        };
        Ok(LinearSystem {
            a: block("a", &self.a)?,
            b: vector_from_json(&format!("{field}.b"), &self.b)?,
            a_eq: block("a_eq", &self.a_eq)?,
            b_eq: vector_from_json(&format!("{field}.b_eq"), &self.b_eq)?,
        })
    }
}

/// Payload of a `positive-definite` certificate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PositiveDefinitePayload {
    /// How the verifier rebuilds the matrix.
    pub recipe: RecipeRef,
}

/// Payload of a `psd-ldlt` certificate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PsdLdltPayload {
    /// How the verifier rebuilds the matrix `A`.
    pub recipe: RecipeRef,
    /// Rows of the unit lower-triangular `L`.
    pub l: Vec<Vec<String>>,
    /// Diagonal of `D` (all `≥ 0`).
    pub d: Vec<String>,
}

/// Payload of a `farkas-infeasible` certificate.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FarkasPayload {
    /// The system claimed infeasible.
    pub system: SystemJson,
    /// Inequality multipliers (`≥ 0`).
    pub y: Vec<String>,
    /// Equality multipliers (free).
    pub w: Vec<String>,
}

/// Payload of a `feasible-point` certificate.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FeasiblePointPayload {
    /// The system claimed feasible.
    pub system: SystemJson,
    /// The point.
    pub x: Vec<String>,
}

/// A typed payload; its variant determines `"kind"`.
#[derive(Debug, Clone, PartialEq)]
pub enum Payload {
    /// `positive-definite`.
    PositiveDefinite(PositiveDefinitePayload),
    /// `psd-ldlt`.
    PsdLdlt(PsdLdltPayload),
    /// `farkas-infeasible`.
    FarkasInfeasible(FarkasPayload),
    /// `feasible-point`.
    FeasiblePoint(FeasiblePointPayload),
}

impl Payload {
    /// Positive-definiteness of the matrix built by `recipe`.
    pub fn positive_definite(recipe: RecipeRef) -> Self {
        Payload::PositiveDefinite(PositiveDefinitePayload { recipe })
    }

    /// PSD of the matrix built by `recipe`, witnessed by `L`, `D`.
    pub fn psd_ldlt(recipe: RecipeRef, l: &RationalMatrix, d: &[BigRational]) -> Self {
        Payload::PsdLdlt(PsdLdltPayload { recipe, l: matrix_to_json(l), d: vector_to_json(d) })
    }

    /// Infeasibility of `sys`, witnessed by `cert`.
    pub fn farkas(sys: &LinearSystem, cert: &FarkasCertificate) -> Self {
        Payload::FarkasInfeasible(FarkasPayload {
            system: SystemJson::from_system(sys),
            y: vector_to_json(&cert.y),
            w: vector_to_json(&cert.w),
        })
    }

    /// Feasibility of `sys`, witnessed by `x`.
    pub fn feasible_point(sys: &LinearSystem, x: &[BigRational]) -> Self {
        Payload::FeasiblePoint(FeasiblePointPayload { system: SystemJson::from_system(sys), x: vector_to_json(x) })
    }

    /// The kind this payload belongs to.
    pub fn kind(&self) -> CertKind {
        match self {
            Payload::PositiveDefinite(_) => CertKind::PositiveDefinite,
            Payload::PsdLdlt(_) => CertKind::PsdLdlt,
            Payload::FarkasInfeasible(_) => CertKind::FarkasInfeasible,
            Payload::FeasiblePoint(_) => CertKind::FeasiblePoint,
        }
    }

    fn to_value(&self) -> Value {
        let v = match self {
            Payload::PositiveDefinite(p) => serde_json::to_value(p),
            Payload::PsdLdlt(p) => serde_json::to_value(p),
            Payload::FarkasInfeasible(p) => serde_json::to_value(p),
            Payload::FeasiblePoint(p) => serde_json::to_value(p),
        };
        v.expect("payload types serialise infallibly")
    }

    fn from_value(kind: CertKind, v: Value) -> Result<Self, CertError> {
        let err = |e: serde_json::Error| CertError::Payload { kind: kind.as_str(), message: e.to_string() };
        Ok(match kind {
            CertKind::PositiveDefinite => Payload::PositiveDefinite(serde_json::from_value(v).map_err(err)?),
            CertKind::PsdLdlt => Payload::PsdLdlt(serde_json::from_value(v).map_err(err)?),
            CertKind::FarkasInfeasible => Payload::FarkasInfeasible(serde_json::from_value(v).map_err(err)?),
            CertKind::FeasiblePoint => Payload::FeasiblePoint(serde_json::from_value(v).map_err(err)?),
        })
    }
}

/// A certificate: what is claimed, in words and in checkable form.
#[derive(Debug, Clone, PartialEq)]
pub struct Certificate {
    /// Stable identifier, e.g. `"thm1-lyapunov-pd-n60"`.
    pub id: String,
    /// Which claim of the paper this supports, e.g. `"Theorem 1"`.
    pub claim: String,
    /// Human sentence stating exactly what the maths proves.
    pub statement: String,
    /// The checkable content.
    pub payload: Payload,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Envelope {
    format: String,
    version: u64,
    id: String,
    claim: String,
    statement: String,
    kind: String,
    payload: Value,
    sha256: String,
}

/// Canonical compact serialisation with recursively sorted object keys.
pub fn canonical_json(v: &Value) -> String {
    fn go(v: &Value, out: &mut String) {
        match v {
            Value::Array(items) => {
                out.push('[');
                for (i, item) in items.iter().enumerate() {
                    if i > 0 {
                        out.push(',');
                    }
                    go(item, out);
                }
                out.push(']');
            }
            Value::Object(map) => {
                let mut keys: Vec<&String> = map.keys().collect();
                keys.sort();
                out.push('{');
                for (i, k) in keys.into_iter().enumerate() {
                    if i > 0 {
                        out.push(',');
                    }
                    out.push_str(&serde_json::to_string(k).expect("string serialises"));
                    out.push(':');
                    go(&map[k], out);
                }
                out.push('}');
            }
            other => out.push_str(&serde_json::to_string(other).expect("scalar serialises")),
        }
    }
    let mut out = String::new();
    go(v, &mut out);
    out
}

/// Lowercase hex SHA-256 of `canonical_json(v)` with any top-level `sha256` key removed.
pub fn content_hash(v: &Value) -> String {
    let mut v = v.clone();
    if let Value::Object(map) = &mut v {
        map.remove("sha256");
    }
    let digest = Sha256::digest(canonical_json(&v).as_bytes());
    digest.iter().map(|b| format!("{b:02x}")).collect()
}

impl Certificate {
    /// The full JSON object including the computed `sha256`.
    pub fn to_value(&self) -> Value {
        let mut v = serde_json::json!({
            "format": FORMAT,
            "version": VERSION,
            "id": self.id,
            "claim": self.claim,
            "statement": self.statement,
            "kind": self.payload.kind().as_str(),
            "payload": self.payload.to_value(),
        });
        let hash = content_hash(&v);
        v.as_object_mut().expect("object").insert("sha256".into(), Value::String(hash));
        v
    }

    /// Pretty-printed JSON text (what [`write_certificate`] stores), envelope
    /// fields in the documented order `format, version, …, sha256`.
    pub fn to_json(&self) -> String {
        let v = self.to_value();
        let env: Envelope = serde_json::from_value(v).expect("own output is a valid envelope");
        let mut s = serde_json::to_string_pretty(&env).expect("serialisable");
        s.push('\n');
        s
    }

    /// Parses certificate text: JSON syntax, format, version, hash, kind and
    /// payload schema. Does **not** check the mathematics (see
    /// [`crate::verify::verify_certificate`]).
    pub fn from_json(text: &str) -> Result<Self, CertError> {
        let v: Value = serde_json::from_str(text).map_err(|e| {
            let (line, column) = (e.line(), e.column());
            if e.is_eof() {
                CertError::Truncated { line, column }
            } else {
                CertError::Malformed { line, column, message: e.to_string() }
            }
        })?;
        let obj = v.as_object().ok_or_else(|| CertError::Envelope("top level is not a JSON object".into()))?;
        match obj.get("format") {
            Some(Value::String(f)) if f == FORMAT => {}
            Some(other) => return Err(CertError::WrongFormat(other.to_string())),
            None => return Err(CertError::Envelope("missing field `format`".into())),
        }
        match obj.get("version") {
            Some(Value::Number(n)) if n.as_u64() == Some(VERSION) => {}
            Some(other) => return Err(CertError::UnsupportedVersion(other.to_string())),
            None => return Err(CertError::Envelope("missing field `version`".into())),
        }
        let stored = match obj.get("sha256") {
            Some(Value::String(s)) => s.clone(),
            _ => return Err(CertError::Envelope("missing or non-string field `sha256`".into())),
        };
        let computed = content_hash(&v);
        if !stored.eq_ignore_ascii_case(&computed) {
            return Err(CertError::Tampered { stored, computed });
        }
        let env: Envelope = serde_json::from_value(v).map_err(|e| CertError::Envelope(e.to_string()))?;
        let kind = CertKind::parse(&env.kind).ok_or_else(|| CertError::UnknownKind(env.kind.clone()))?;
        Ok(Self {
            id: env.id,
            claim: env.claim,
            statement: env.statement,
            payload: Payload::from_value(kind, env.payload)?,
        })
    }
}

/// Writes `cert` to `path` atomically (wingcheck-io: temp file, `fsync`, rename, mode 0644).
pub fn write_certificate(path: &Path, cert: &Certificate) -> Result<(), CertError> {
    wingcheck_io::write_file_atomic(path, cert.to_json().as_bytes())
        .map_err(|e| CertError::Write { path: path.to_path_buf(), source: std::io::Error::other(e.to_string()) })
}

/// Rationals of a matrix as `"p/q"` strings, row by row.
pub fn matrix_to_json(m: &RationalMatrix) -> Vec<Vec<String>> {
    (0..m.rows()).map(|i| m.row(i).iter().map(to_fraction_string).collect()).collect()
}

/// Rationals of a vector as `"p/q"` strings.
pub fn vector_to_json(v: &[BigRational]) -> Vec<String> {
    v.iter().map(to_fraction_string).collect()
}

/// Parses a vector of exact numbers; errors name `field[i]`.
pub fn vector_from_json(field: &str, v: &[String]) -> Result<Vec<BigRational>, CertError> {
    v.iter()
        .enumerate()
        .map(|(i, s)| parse_rational(s).map_err(|source| CertError::Number { field: format!("{field}[{i}]"), source }))
        .collect()
}

/// Parses a rectangular matrix of exact numbers; errors name `field[i][j]`.
pub fn matrix_from_json(field: &str, rows: &[Vec<String>]) -> Result<RationalMatrix, CertError> {
    let parsed = rows
        .iter()
        .enumerate()
        .map(|(i, r)| vector_from_json(&format!("{field}[{i}]"), r))
        .collect::<Result<Vec<_>, _>>()?;
    let lens: Vec<usize> = parsed.iter().map(Vec::len).collect();
    RationalMatrix::from_rows(parsed).ok_or_else(|| CertError::Shape {
        field: field.to_string(),
        message: format!("rows have different lengths {lens:?}"),
    })
}
