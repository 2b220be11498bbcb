//! The configuration structs. Units are SI as in the paper's Section 4 (m, kg, N, s, rad).

use serde::{Deserialize, Serialize};

use crate::{ConfigError, Disturbance, StepBasis, TimeScheme, UnknownName};

/// The whole run configuration.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Config {
    /// Structural parameters of the wing (paper Section 4).
    pub wing: Wing,
    /// Boundary control law (15) and the controller kind.
    pub control: Control,
    /// Finite-time disturbance observer (16)–(21); also used for DOBC's sampling.
    pub observer: Observer,
    /// Disturbances (56).
    pub disturbance: Disturbance,
    /// Initial condition.
    pub initial: Initial,
    /// Spatial and temporal discretisation.
    pub discretisation: Discretisation,
    /// Simulated horizon and output sampling.
    pub horizon: Horizon,
}

/// Wing parameters (paper Section 4, notation of `docs/model.md`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Wing {
    /// Span s (m).
    pub span: f64,
    /// Mass per unit length ρ (kg/m).
    pub rho: f64,
    /// Mass–elastic-axis coupling ρx_c (kg): the paper's ρ x_c c with x_c c = 0.35 m.
    pub rho_xc: f64,
    /// Bending rigidity EI (N m²) (paper: EI_b).
    pub ei: f64,
    /// Torsion rigidity GJ (N m²).
    pub gj: f64,
    /// Polar moment of inertia per unit length I_p (kg m).
    pub ip: f64,
    /// Aerodynamic-centre offset x_ac (m) (paper: x_a c).
    pub x_ac: f64,
    /// Kelvin–Voigt damping coefficient ξ (s).
    pub xi: f64,
}

/// Which boundary controller acts at the tip.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum ControllerKind {
    /// τ1 = τ2 = 0 (paper Figs 3–4).
    None,
    /// τ from (15) without the disturbance estimate (ĝ = 0).
    Pd,
    /// τ from (15) with the finite-time disturbance observer (16)–(21).
    Ftdo,
    /// τ from (15) with the linear disturbance observer of (57), corrected.
    Dobc,
}

impl ControllerKind {
    /// Name as used on the command line and in outputs.
    pub fn name(self) -> &'static str {
        match self {
            ControllerKind::None => "none",
            ControllerKind::Pd => "pd",
            ControllerKind::Ftdo => "ftdo",
            ControllerKind::Dobc => "dobc",
        }
    }
}

impl std::str::FromStr for ControllerKind {
    type Err = UnknownName;
    fn from_str(s: &str) -> Result<Self, UnknownName> {
        match s {
            "none" => Ok(Self::None),
            "pd" => Ok(Self::Pd),
            "ftdo" => Ok(Self::Ftdo),
            "dobc" => Ok(Self::Dobc),
            _ => Err(UnknownName { what: "controller", given: s.into(), allowed: "none, pd, ftdo, dobc" }),
        }
    }
}

/// Boundary control law (15): τ1 = −k1(a q(s) + b q̇(s)) − ĝ1, τ2 = −k2(a θ(s) + b θ̇(s)) − ĝ2.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Control {
    /// Controller kind.
    pub kind: ControllerKind,
    /// Bending boundary gain k1 (N/m per unit of a q + b q̇).
    pub k1: f64,
    /// Torsion boundary gain k2.
    pub k2: f64,
    /// Weight a on the tip displacement in (15) (1; the paper does not give it).
    pub a: f64,
    /// Weight b on the tip velocity in (15) (s; the paper does not give it).
    pub b: f64,
}

/// How the digital observer evaluates the discontinuous ĝ(σ) at a sample.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum ObserverRule {
    /// Set-valued implicit (Acary–Brogliato) step: solve σ̃ + T ĝ(σ̃) ∋ σ_k, ĝ_k = (σ_k − σ̃)/T.
    Implicit,
    /// Explicit sampling ĝ_k = ĝ(σ_k); chatters.
    Explicit,
}

impl ObserverRule {
    /// Name as used on the command line and in outputs.
    pub fn name(self) -> &'static str {
        match self {
            ObserverRule::Implicit => "implicit",
            ObserverRule::Explicit => "explicit",
        }
    }
}

impl std::str::FromStr for ObserverRule {
    type Err = UnknownName;
    fn from_str(s: &str) -> Result<Self, UnknownName> {
        match s {
            "implicit" => Ok(Self::Implicit),
            "explicit" => Ok(Self::Explicit),
            _ => Err(UnknownName { what: "observer rule", given: s.into(), allowed: "implicit, explicit" }),
        }
    }
}

/// Finite-time disturbance observer (16)–(21), sampled with period `sample_period`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Observer {
    /// Evaluation rule of the digital observer.
    pub rule: ObserverRule,
    /// Sample (hold) period T of the digital observer (s); a multiple of `discretisation.dt`.
    pub sample_period: f64,
    /// κ1: linear gain of ĝ1.
    pub kappa1: f64,
    /// κ2: switching gain of ĝ1 (Theorem 3 needs κ2 ≥ ζ1).
    pub kappa2: f64,
    /// κ3: fractional-power gain of ĝ1.
    pub kappa3: f64,
    /// κ4: linear gain of ĝ2.
    pub kappa4: f64,
    /// κ5: switching gain of ĝ2 (Theorem 4 needs κ5 ≥ ζ2).
    pub kappa5: f64,
    /// κ6: fractional-power gain of ĝ2.
    pub kappa6: f64,
    /// Odd integer a1 with a1 < a2 < 2 a1; exponent r1 = (2a1 − a2)/a2.
    pub a1: u32,
    /// Odd integer a2.
    pub a2: u32,
    /// Odd integer b1 with b1 < b2 < 2 b1; exponent r2 = (2b1 − b2)/b2.
    pub b1: u32,
    /// Odd integer b2.
    pub b2: u32,
    /// Initial observer state ν1(0) (N).
    pub nu1_0: f64,
    /// Initial observer state ν2(0) (N m).
    pub nu2_0: f64,
}

impl Observer {
    /// Exponent r1 = (2a1 − a2)/a2 of sig^r(σ1) in (17)/(20).
    pub fn r1(&self) -> f64 {
        (2.0 * self.a1 as f64 - self.a2 as f64) / self.a2 as f64
    }
    /// Exponent r2 = (2b1 − b2)/b2 of sig^r(σ2) in (19)/(21).
    pub fn r2(&self) -> f64 {
        (2.0 * self.b1 as f64 - self.b2 as f64) / self.b2 as f64
    }
}

/// Shape of the initial displacement.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum InitialShape {
    /// The paper's q(z,0) = q_tip z/s, θ(z,0) = θ_tip z/s, with the clamp imposed at the root
    /// (root rotation 0); violates q'(0) = 0, so a kink at the root decays over a few ξ.
    Linear,
    /// Clamp-consistent static tip-load shape q(z,0) = q_tip z²(3s − z)/(2s³); θ as in `Linear`.
    Cantilever,
}

/// Initial condition; velocities are zero (paper Section 4).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Initial {
    /// Shape of q(z,0).
    pub shape: InitialShape,
    /// Tip bending displacement q(s,0) (m) (paper: 1).
    pub q_tip: f64,
    /// Tip twist θ(s,0) (rad) (paper: π/2).
    pub theta_tip: f64,
}

/// Spatial discretisation method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// The paper's finite differences with ghost points, lumped mass, tip loads as point loads.
    Fd,
    /// Finite elements: cubic Hermite for q, linear for θ, consistent coupled mass.
    Fe,
}

impl Method {
    /// Name as used on the command line and in outputs.
    pub fn name(self) -> &'static str {
        match self {
            Method::Fd => "fd",
            Method::Fe => "fe",
        }
    }
}

impl std::str::FromStr for Method {
    type Err = UnknownName;
    fn from_str(s: &str) -> Result<Self, UnknownName> {
        match s {
            "fd" => Ok(Self::Fd),
            "fe" => Ok(Self::Fe),
            _ => Err(UnknownName { what: "method", given: s.into(), allowed: "fd, fe" }),
        }
    }
}

/// Discretisation settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Discretisation {
    /// FD or FE.
    pub method: Method,
    /// Number of finite elements along the span (method `fe`; paper default 24, graded 0.7:
    /// tip error ≤ 2e-4 over the whole horizon).
    pub elements: usize,
    /// Number of finite-difference grid intervals along the span (method `fd`; default 96:
    /// tip error ≤ 2e-4 over the whole horizon; the FD grid is uniform).
    #[serde(default = "default_fd_points")]
    pub fd_points: usize,
    /// Integrator time step (s); must divide `observer.sample_period`.
    pub dt: f64,
    /// FE mesh grading in [0, 0.9]: node z_i = s·(u − grading·sin(2πu)/(2π)), u = i/N, so the
    /// root and tip elements are (1 − grading) × the uniform size. FE only: with method `fd` a
    /// nonzero grading is refused (the FD grid is uniform).
    #[serde(default)]
    pub grading: f64,
    /// Time integrator (default `auto`, see [`TimeScheme::Auto`]).
    #[serde(default)]
    pub stepper: TimeScheme,
    /// Basis the closed loop is stepped in (default `auto`: modal where
    /// [`Config::expected_modal`] finds it cheaper); it changes the cost, not the result beyond
    /// round-off.
    #[serde(default)]
    pub basis: StepBasis,
}

fn default_fd_points() -> usize {
    96
}

impl Discretisation {
    /// Grid size of the configured method: `elements` (FE) or `fd_points` (FD).
    pub fn grid_size(&self) -> usize {
        match self.method {
            Method::Fe => self.elements,
            Method::Fd => self.fd_points,
        }
    }
}

/// Horizon and output sampling.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Horizon {
    /// Final time T (s) (paper: 20).
    pub t_end: f64,
    /// Output sampling interval (s): a whole multiple of `observer.sample_period` (outputs are
    /// taken at observer samples; other values are refused, naming the nearest allowed ones).
    pub sample_every: f64,
    /// Number of points of the coarse output grid for q(z,t), θ(z,t) (≥ 2).
    pub field_points: usize,
}

impl Config {
    /// The paper's configuration, embedded from `configs/paper.json`.
    pub fn paper() -> Config {
        Self::parse_complete(crate::PAPER_JSON).expect("embedded configs/paper.json is valid")
    }

    /// Parse and validate a JSON document of at most [`MAX_CONFIG_BYTES`]: a complete
    /// configuration or only some of its keys, merged over the embedded default
    /// ([`Config::paper`]; objects merged key by key, a value replacing the default's). Unknown
    /// keys, a key given twice and anything after the document (other than whitespace) are
    /// rejected, naming the key. A top-level `"$schema"` string (an editor's pointer to the
    /// JSON Schema, [`crate::config_schema`]) is ignored.
    pub fn from_json_str(text: &str) -> Result<Config, ConfigError> {
        let mut partial = Self::read_document(text)?;
        // an editor's pointer to the schema (docs/schema/config.schema.json): not a parameter
        if let Some(pointer) = partial.as_object_mut().and_then(|m| m.remove("$schema")) {
            if !pointer.is_string() {
                return Err(ConfigError::Parse(format!(
                    "$schema: must be a string (the URI or path of the configuration's JSON Schema), got {pointer}"
                )));
            }
        }
        let mut merged = serde_json::to_value(Self::paper()).expect("config serialises");
        merge(&mut merged, partial);
        Self::from_json_value(merged)
    }

    /// The embedded default, parsed strictly (every key present).
    fn parse_complete(text: &str) -> Result<Config, ConfigError> {
        let value = Self::read_document(text)?;
        let cfg: Config = serde_path_to_error::deserialize(value).map_err(|e| ConfigError::Parse(describe(&e)))?;
        let cfg = cfg.normalised();
        cfg.validate()?;
        Ok(cfg)
    }

    /// One JSON object of sections, checked before any merging: size, trailing data, arrays,
    /// underflowing numbers, duplicate keys.
    fn read_document(text: &str) -> Result<serde_json::Value, ConfigError> {
        use serde::Deserialize as _;
        if text.len() as u64 > MAX_CONFIG_BYTES {
            return Err(ConfigError::Parse(format!("{} bytes, at most {MAX_CONFIG_BYTES} allowed", text.len())));
        }
        if let Some(n) = crate::json::unrepresentable_number(text) {
            return Err(n.error());
        }
        let de = &mut serde_json::Deserializer::from_str(text);
        let value = serde_json::Value::deserialize(&mut *de).map_err(|e| ConfigError::Parse(e.to_string()))?;
        de.end().map_err(|e| ConfigError::Parse(format!("trailing data after the JSON document: {e}")))?;
        // one object of sections, never positional (serde would fill the structs from arrays)
        crate::json::reject_positional(&value)?;
        if let Some(key) = crate::json::duplicate_key(text.as_bytes()) {
            return Err(ConfigError::Parse(format!("{key}: the key occurs twice (each key once)")));
        }
        Ok(value)
    }

    /// SHA-256 (hex) of the configuration's compact JSON (struct field order, so stable): the
    /// one configuration hash of every output, study cache and certificate set.
    pub fn sha256(&self) -> String {
        wingcheck_io::sha256_hex(serde_json::to_string(self).expect("config serialises").as_bytes())
    }

    /// Every key whose value differs between `self` and `other`, in the config's key order:
    /// (`section.key`, value here, value there) — what `wingcheck config --diff` prints.
    pub fn diff(&self, other: &Config) -> Vec<(String, serde_json::Value, serde_json::Value)> {
        let (a, b) = (
            serde_json::to_value(self).expect("config serialises"),
            serde_json::to_value(other).expect("config serialises"),
        );
        let mut out = Vec::new();
        diff_values("", &a, &b, &mut out);
        out
    }

    /// The same configuration with every −0 replaced by 0, so that equal parameters give equal
    /// text and hashes.
    fn normalised(self) -> Config {
        let mut v = serde_json::to_value(&self).expect("config serialises");
        crate::json::normalise_zeros(&mut v);
        serde_json::from_value(v).unwrap_or(self)
    }

    /// Reads a config file of at most [`MAX_CONFIG_BYTES`] and parses it with
    /// [`Config::from_json_str`]; only a regular file (or a symlink to one) is read: `/dev/zero`,
    /// `/dev/stdin` or a FIFO is refused without being opened.
    pub fn from_file(path: &std::path::Path) -> Result<Config, ConfigError> {
        let read = |reason: String| ConfigError::Read { path: path.display().to_string(), reason };
        // a FIFO or device is never opened (it could block or never end)
        let bytes = wingcheck_io::read_regular(path, MAX_CONFIG_BYTES).map_err(|e| read(e.to_string()))?;
        let text = String::from_utf8(bytes).map_err(|_| read("not UTF-8 text".into()))?;
        Self::from_json_str(&text)
    }

    /// Parse a JSON value (after overrides) and validate it.
    pub fn from_json_value(mut value: serde_json::Value) -> Result<Config, ConfigError> {
        crate::json::reject_positional(&value)?;
        crate::json::normalise_zeros(&mut value);
        let cfg: Config = serde_path_to_error::deserialize(value).map_err(|e| ConfigError::Parse(describe(&e)))?;
        cfg.validate()?;
        Ok(cfg)
    }

    /// The configuration as pretty JSON (stable key order: struct order).
    pub fn to_json_pretty(&self) -> String {
        serde_json::to_string_pretty(self).expect("config serialises")
    }

    /// Number of integrator steps per observer sample, T/dt (validated to be a whole number).
    pub fn steps_per_sample(&self) -> usize {
        (self.observer.sample_period / self.discretisation.dt).round().max(1.0) as usize
    }

    /// Number of observer samples per output sample.
    pub fn samples_per_output(&self) -> usize {
        (self.horizon.sample_every / self.observer.sample_period).round().max(1.0) as usize
    }

    /// Total number of observer samples in [0, T].
    pub fn total_samples(&self) -> usize {
        (self.horizon.t_end / self.observer.sample_period).round() as usize
    }

    /// Output samples of a run: observer samples k = 0, e, 2e, … (e = [`Self::samples_per_output`])
    /// and the last one, k = K, when K is not a multiple of e. Every runner records exactly
    /// these (and allocates its series at this length).
    pub fn output_samples(&self) -> usize {
        let (every, total) = (self.samples_per_output(), self.total_samples());
        total / every + 1 + usize::from(total % every != 0)
    }
}

/// Largest configuration document accepted (bytes).
pub const MAX_CONFIG_BYTES: u64 = 1 << 20;

/// A number in short form (messages, certificate decimals): the shortest round-trip decimal,
/// positional when it has at most 6 characters (`0.35`, `1000`), otherwise whichever of the
/// positional and the scientific form is shorter (`1e9`, `1e308`, `0.0123`, `1.234567e-9`).
/// Both forms read back to the same `f64`, so the text is exact.
pub fn format_number(x: f64) -> String {
    let plain = format!("{x}");
    if plain.len() <= 6 || !x.is_finite() {
        return plain;
    }
    let sci = format!("{x:e}");
    if sci.len() < plain.len() {
        sci
    } else {
        plain
    }
}

/// "field.path: message" for a deserialisation error (the path is omitted at the top level).
/// Merges `over` into `base`: objects key by key (recursively), anything else replaces.
/// Keys the default does not have are inserted, so deserialising names them as unknown.
fn merge(base: &mut serde_json::Value, over: serde_json::Value) {
    match (base, over) {
        (serde_json::Value::Object(b), serde_json::Value::Object(o)) => {
            for (k, v) in o {
                match b.get_mut(&k) {
                    Some(slot) if slot.is_object() && v.is_object() => merge(slot, v),
                    _ => {
                        b.insert(k, v);
                    }
                }
            }
        }
        (b, o) => *b = o,
    }
}

fn diff_values(
    path: &str,
    a: &serde_json::Value,
    b: &serde_json::Value,
    out: &mut Vec<(String, serde_json::Value, serde_json::Value)>,
) {
    match (a, b) {
        (serde_json::Value::Object(x), serde_json::Value::Object(y)) => {
            for (k, va) in x {
                let p = if path.is_empty() { k.clone() } else { format!("{path}.{k}") };
                match y.get(k) {
                    Some(vb) => diff_values(&p, va, vb, out),
                    None => out.push((p, va.clone(), serde_json::Value::Null)),
                }
            }
        }
        _ if a != b => out.push((path.to_string(), a.clone(), b.clone())),
        _ => {}
    }
}

fn describe(e: &serde_path_to_error::Error<serde_json::Error>) -> String {
    let path = e.path().to_string();
    if path == "." || path.is_empty() {
        e.inner().to_string()
    } else {
        format!("{path}: {}", e.inner())
    }
}
