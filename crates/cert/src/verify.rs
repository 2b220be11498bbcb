//! Re-checking certificates: parse, check the hash, rebuild, re-prove.

use std::path::{Path, PathBuf};

use crate::certificate::{matrix_from_json, vector_from_json, CertError, CertKind, Certificate, Payload};
use crate::exact::to_f64;
use crate::lp::{check_farkas, check_feasible_point, FarkasCertificate};
use crate::psd::{check_positive_definite, check_psd_with_witness};
use crate::recipe::RecipeRegistry;

/// A certificate whose claim was re-proved in exact arithmetic.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Verified {
    /// Certificate id.
    pub id: String,
    /// The paper's claim it supports.
    pub claim: String,
    /// The human statement that is now proved.
    pub statement: String,
    /// Kind of proof.
    pub kind: CertKind,
    /// One-line summary of what was checked (sizes, smallest pivot, …).
    pub detail: String,
}

/// Re-proves the mathematics of an already parsed certificate, rebuilding
/// matrices through `registry`.
pub fn verify_certificate(cert: &Certificate, registry: &RecipeRegistry) -> Result<Verified, CertError> {
    let detail = match &cert.payload {
        Payload::PositiveDefinite(p) => {
            let a = registry.build(&p.recipe)?;
            let report = check_positive_definite(&a)?;
            let min = report.min_pivot().map_or_else(|| "none".to_string(), |m| format!("{:e}", to_f64(m)));
            format!(
                "{n}×{n} matrix from recipe {:?} is positive definite (all {n} LDLᵀ pivots > 0, smallest ≈ {min})",
                p.recipe.name,
                n = a.rows()
            )
        }
        Payload::PsdLdlt(p) => {
            let a = registry.build(&p.recipe)?;
            let l = matrix_from_json("payload.l", &p.l)?;
            let d = vector_from_json("payload.d", &p.d)?;
            check_psd_with_witness(&a, &l, &d)?;
            let zeros = d.iter().filter(|v| num_traits::Zero::is_zero(*v)).count();
            format!(
                "{n}×{n} matrix from recipe {:?} equals L·D·Lᵀ with D ≥ 0 ({zeros} zero pivots): PSD",
                p.recipe.name,
                n = a.rows()
            )
        }
        Payload::FarkasInfeasible(p) => {
            let sys = p.system.to_system("payload.system")?;
            let cert =
                FarkasCertificate { y: vector_from_json("payload.y", &p.y)?, w: vector_from_json("payload.w", &p.w)? };
            let value = check_farkas(&sys, &cert)?;
            format!(
                "system with {} inequalities, {} equalities in {} variables is infeasible (yᵀb + wᵀb_eq = {value})",
                sys.a.rows(),
                sys.a_eq.rows(),
                sys.n_vars()
            )
        }
        Payload::FeasiblePoint(p) => {
            let sys = p.system.to_system("payload.system")?;
            let x = vector_from_json("payload.x", &p.x)?;
            check_feasible_point(&sys, &x)?;
            format!(
                "point satisfies all {} inequalities and {} equalities in {} variables",
                sys.a.rows(),
                sys.a_eq.rows(),
                sys.n_vars()
            )
        }
    };
    Ok(Verified {
        id: cert.id.clone(),
        claim: cert.claim.clone(),
        statement: cert.statement.clone(),
        kind: cert.payload.kind(),
        detail,
    })
}

/// Reads, parses and re-proves one certificate file using `registry`.
pub fn verify_file_with(path: &Path, registry: &RecipeRegistry) -> Result<Verified, CertError> {
    let text = std::fs::read_to_string(path).map_err(|source| CertError::Io { path: path.to_path_buf(), source })?;
    let cert = Certificate::from_json(&text)?;
    verify_certificate(&cert, registry)
}

/// [`verify_file_with`] using only the built-in recipes.
pub fn verify_file(path: &Path) -> Result<Verified, CertError> {
    verify_file_with(path, &RecipeRegistry::new())
}

/// Verifies every `*.json` file directly inside `dir` (sorted by name),
/// reporting each separately. If `dir` itself cannot be listed, the result
/// is a single entry for `dir` carrying the I/O error.
pub fn verify_dir_with(dir: &Path, registry: &RecipeRegistry) -> Vec<(PathBuf, Result<Verified, CertError>)> {
    let entries = match std::fs::read_dir(dir) {
        Ok(e) => e,
        Err(source) => return vec![(dir.to_path_buf(), Err(CertError::Io { path: dir.to_path_buf(), source }))],
    };
    let mut paths: Vec<PathBuf> = entries
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.is_file() && p.extension().is_some_and(|x| x == "json"))
        .collect();
    paths.sort();
    paths
        .into_iter()
        .map(|p| {
            let r = verify_file_with(&p, registry);
            (p, r)
        })
        .collect()
}

/// [`verify_dir_with`] using only the built-in recipes.
pub fn verify_dir(dir: &Path) -> Vec<(PathBuf, Result<Verified, CertError>)> {
    verify_dir_with(dir, &RecipeRegistry::new())
}
