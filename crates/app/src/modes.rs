//! `modes`: the arguments' checks and the document of the converged natural frequencies of the
//! undamped, uncontrolled wing (`modes --json`), each with its error estimate, beside the
//! analytic uncoupled ones.

use serde::Serialize;
use wingcheck_model::{Config, Method};
use wingcheck_sim::modes;

use crate::{AppError, Front, WorkPolicy};

/// The arguments of `modes`.
#[derive(Debug, Clone, Copy)]
pub struct ModesRequest {
    /// Number of frequencies (1..=50).
    pub count: usize,
    /// Spatial discretisation; none: the configuration's.
    pub method: Option<Method>,
    /// Relative tolerance on every frequency's error estimate (≥ 1e-13).
    pub tol: f64,
}

impl Default for ModesRequest {
    fn default() -> Self {
        ModesRequest { count: 5, method: None, tol: modes::DEFAULT_MODE_TOLERANCE }
    }
}

/// The `modes --json` document (keys in this order; docs/schema/modes.schema.json).
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct ModesDocument {
    /// Layout version ([`wingcheck_io::SCHEMA_VERSION`]).
    pub schema_version: u32,
    /// Tool build and the configuration's SHA-256 (no files: the document is the output).
    pub provenance: wingcheck_io::Provenance,
    /// `fd` or `fe`.
    pub method: String,
    /// The uniform meshes extrapolated over (elements or intervals).
    pub meshes: Vec<usize>,
    /// The relative tolerance asked for.
    pub tolerance: f64,
    /// Whether every estimate met it.
    pub converged: bool,
    /// Coupled ω_n (rad/s), Romberg-extrapolated.
    pub coupled_rad_s: Vec<f64>,
    /// Bound on |ω_n − ω_exact| (rad/s).
    pub coupled_error_rad_s: Vec<f64>,
    /// Observed convergence order per frequency; none: at round-off (`"round-off"` in JSON).
    #[serde(serialize_with = "orders")]
    #[schemars(schema_with = "orders_schema")]
    pub coupled_observed_order: Vec<Option<f64>>,
    /// Uncoupled analytic ω_n (rad/s) (ρx_c = 0: the bending and torsion frequencies merged).
    pub uncoupled_analytic_rad_s: Vec<f64>,
    /// Cantilever bending ω_n (rad/s), roots of 1 + cos βs cosh βs = 0.
    pub bending_analytic_rad_s: Vec<f64>,
    /// Torsion ω_n = (2n−1)π/(2s)·√(GJ/I_p) (rad/s).
    pub torsion_analytic_rad_s: Vec<f64>,
    /// How the numbers are made.
    pub note: &'static str,
}

/// Each entry a number or the text `round-off`.
fn orders_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
    schemars::json_schema!({
        "type": "array",
        "items": {"anyOf": [{"type": "number"}, {"const": "round-off"}]}
    })
}

fn orders<S: serde::Serializer>(v: &[Option<f64>], s: S) -> Result<S::Ok, S::Error> {
    use serde::ser::SerializeSeq;
    let mut seq = s.serialize_seq(Some(v.len()))?;
    for o in v {
        match o {
            Some(p) => seq.serialize_element(p)?,
            None => seq.serialize_element("round-off")?,
        }
    }
    seq.end()
}

const NOTE: &str = "coupled: K φ = ω² M φ of the undamped, uncontrolled wing on uniform meshes (sparse shift-invert through the strain factorisation K = GᵀDG), Romberg-extrapolated in h²; coupled_error_rad_s[i] bounds |ω − ω_exact| (the larger of the last two Romberg corrections plus the eigen-solver bound); analytic: ρx_c = 0, exact (cantilever roots of 1 + cos βs cosh βs = 0 and (2n−1)π/(2s)·√(GJ/I_p))";

impl ModesRequest {
    /// Check the arguments (the messages name them as `front` spells them).
    pub fn validate(&self, front: Front) -> Result<(), AppError> {
        if !(1..=50).contains(&self.count) {
            return Err(AppError::Argument {
                name: "count",
                message: format!("{} {}: use an integer in [1, 50]", front.arg("count"), self.count),
            });
        }
        if !(self.tol.is_finite() && self.tol >= 1e-13) {
            return Err(AppError::Argument {
                name: "tol",
                message: format!("{} {}: use a relative tolerance >= 1e-13", front.arg("tol"), self.tol),
            });
        }
        Ok(())
    }

    /// The converged frequencies of `cfg` and the analytic ones, refused before any work above
    /// `policy`'s limits (the worst case: every mesh at the iteration limit,
    /// `wingcheck_model::work::WorkEstimate::modes`).
    pub fn run(&self, cfg: &Config, policy: WorkPolicy) -> Result<ModesDocument, AppError> {
        let method = self.method.unwrap_or(cfg.discretisation.method);
        self.validate(policy.front)?;
        policy.guard(&wingcheck_model::work::WorkEstimate::modes(cfg, method, self.count))?;
        let conv = modes::converged_frequencies(cfg, method, self.count, self.tol)?;
        let w = &cfg.wing;
        Ok(ModesDocument {
            schema_version: wingcheck_io::SCHEMA_VERSION,
            provenance: wingcheck_io::Provenance::new(&cfg.sha256(), Vec::new()),
            method: method.name().into(),
            meshes: conv.meshes,
            tolerance: self.tol,
            converged: conv.converged,
            coupled_rad_s: conv.modes.iter().map(|m| m.omega).collect(),
            coupled_error_rad_s: conv.modes.iter().map(|m| m.error).collect(),
            coupled_observed_order: conv.modes.iter().map(|m| m.observed_order).collect(),
            uncoupled_analytic_rad_s: modes::uncoupled_frequencies(w.span, w.ei, w.rho, w.gj, w.ip, self.count),
            bending_analytic_rad_s: modes::bending_frequencies(w.span, w.ei, w.rho, self.count),
            torsion_analytic_rad_s: modes::torsion_frequencies(w.span, w.gj, w.ip, self.count),
            note: NOTE,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arguments_outside_their_ranges_are_refused_naming_them() {
        let bad = ModesRequest { count: 0, ..Default::default() };
        assert_eq!(bad.validate(Front::Cli).unwrap_err().to_string(), "--count 0: use an integer in [1, 50]");
        let bad = ModesRequest { tol: 1e-14, ..Default::default() };
        assert_eq!(
            bad.validate(Front::Python).unwrap_err().to_string(),
            "tol 0.00000000000001: use a relative tolerance >= 1e-13"
        );
    }
}
