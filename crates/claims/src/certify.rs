//! Certificates for the definiteness and infeasibility facts behind the W-bounds and
//! mu-conditions rows, written by `wingcheck certify` and re-checked by `wingcheck verify`
//! in exact rational arithmetic (wingcheck-cert), independent of clarabel and faer: the
//! verifier rebuilds every matrix from the decimal parameters with [`crate::lyapunov`].

use std::path::{Path, PathBuf};

use num_rational::BigRational;
use serde_json::{json, Value};
use wingcheck_cert::exact::{parse_rational, to_fraction_string};
use wingcheck_cert::lp::{FarkasCertificate, LinearSystem};
use wingcheck_cert::{write_certificate, Certificate, FnRecipe, Payload, RationalMatrix, RecipeRef, RecipeRegistry};
use wingcheck_model::Config;

use crate::lyapunov::{self, decimal, Coupling, LyapunovParams};
use crate::ClaimsError;

/// Elements of the Galerkin space used in certificates (dimension 11·N).
pub const CERT_ELEMENTS: usize = 4;

/// The registry with the wing Lyapunov recipe.
pub fn registry() -> RecipeRegistry {
    let mut r = RecipeRegistry::new();
    r.register(Box::new(FnRecipe { name: lyapunov::RECIPE, build: lyapunov::recipe_build }))
        .expect("recipe name is unique");
    r
}

fn cert_err(e: impl std::fmt::Display) -> ClaimsError {
    ClaimsError::Numerical { what: "certificate".into(), detail: e.to_string() }
}

fn recipe(params: &LyapunovParams, form: &str, lambda: &BigRational, x: Option<&[BigRational]>) -> RecipeRef {
    let mut p = json!({ "forms": params, "form": form, "lambda": to_fraction_string(lambda) });
    if let Some(x) = x {
        p["x"] = Value::from(x.iter().map(to_fraction_string).collect::<Vec<_>>());
    }
    RecipeRef { name: lyapunov::RECIPE.into(), params: p }
}

/// Rational close to x with denominator 10⁶, rounded down (`down`) or up.
fn round_rational(x: f64, down: bool) -> BigRational {
    let scaled = x * 1e6;
    let k = if down { scaled.floor() } else { scaled.ceil() };
    BigRational::new((k as i64).into(), 1_000_000.into())
}

/// Produce all certificates for `cfg` (in memory).
pub fn certificates(cfg: &Config) -> Result<Vec<(String, Certificate)>, ClaimsError> {
    let n = CERT_ELEMENTS;
    let params = LyapunovParams::from_config(cfg, Coupling::Corrected, n);
    let forms = lyapunov::assemble(&params).map_err(cert_err)?;
    let tight = lyapunov::tight_constants(&forms).map_err(cert_err)?;
    let (a, b) = (cfg.control.a, cfg.control.b);
    let space = format!("cubic Hermite q, linear θ and discontinuous cubic velocities on {n} uniform elements");
    let mut out = Vec::new();
    // Lower and upper bounds on the Galerkin space (discrete statements).
    let l2 = round_rational(tight.lambda2 - 1e-4 * tight.lambda2.abs().max(1.0), true);
    out.push((
        "w-bounds-lower.json".to_string(),
        Certificate {
            id: "w-bounds-lower".into(),
            claim: "W-bounds (Theorem 1)".into(),
            statement: format!(
                "With a = {a}, b = {b}, W − λκ is positive definite for λ = {} on the space of {space}: inf W/κ > {:.6} there (an upper estimate of the continuum infimum).",
                to_fraction_string(&l2),
                wingcheck_cert::exact::to_f64(&l2)
            ),
            payload: Payload::positive_definite(recipe(&params, "w-minus-lambda-kappa", &l2, None)),
        },
    ));
    let l1 = round_rational(tight.lambda1 + 1e-4 * tight.lambda1.abs().max(1.0), false);
    out.push((
        "w-bounds-upper.json".to_string(),
        Certificate {
            id: "w-bounds-upper".into(),
            claim: "W-bounds (Theorem 1)".into(),
            statement: format!(
                "With a = {a}, b = {b}, λκ − W is positive definite for λ = {} on the space of {space}: sup W/κ < {:.6} there.",
                to_fraction_string(&l1),
                wingcheck_cert::exact::to_f64(&l1)
            ),
            payload: Payload::positive_definite(recipe(&params, "lambda-kappa-minus-w", &l1, None)),
        },
    ));
    // Indefiniteness at the configured weights (a statement about the PDE).
    let zero = BigRational::from_integer(0.into());
    if tight.lambda2 < 0.0 {
        let x = lyapunov::round_vector(&tight.argmin);
        out.push((
            "w-bounds-indefinite.json".to_string(),
            Certificate {
                id: "w-bounds-indefinite".into(),
                claim: "W-bounds (Theorem 1)".into(),
                statement: format!(
                    "With a = {a}, b = {b}, the state x given (coefficients in the space of {space}, a genuine state of the PDE) has W(x) < 0: \
                     W is not positive definite, so no λ2 > 0 satisfies λ2 κ ≤ W."
                ),
                payload: Payload::positive_definite(recipe(&params, "negative-direction", &zero, Some(&x))),
            },
        ));
    }
    // a/b_max: above ω₁·1.05 a negative direction exists (PDE statement); below ω₁·0.95 W ≻ 0 on V_N.
    let ratio = crate::wbounds::a_over_b_max(cfg, Coupling::Corrected, n)?;
    for (tag, r, form) in
        [("above", ratio * 1.05, "negative-direction"), ("below", ratio * 0.95, "w-minus-lambda-kappa")]
    {
        let rq = round_rational(r, tag == "below");
        let p = params.with_weights(&to_decimal(&rq), "1");
        let f = lyapunov::assemble(&p).map_err(cert_err)?;
        let t = lyapunov::tight_constants(&f).map_err(cert_err)?;
        let (payload, statement) = if form == "negative-direction" {
            let x = lyapunov::round_vector(&t.argmin);
            (
                Payload::positive_definite(recipe(&p, form, &zero, Some(&x))),
                format!("With a/b = {} (b = 1), the state x given has W(x) < 0: the largest a/b with W positive definite is below this value (PDE statement).", to_fraction_string(&rq)),
            )
        } else {
            let lam = round_rational(t.lambda2 * 0.99, true);
            (
                Payload::positive_definite(recipe(&p, form, &lam, None)),
                format!(
                    "With a/b = {} (b = 1), W − λκ ≻ 0 for λ = {} > 0 on the space of {space}.",
                    to_fraction_string(&rq),
                    to_fraction_string(&lam)
                ),
            )
        };
        out.push((
            format!("w-bounds-ratio-{tag}.json"),
            Certificate {
                id: format!("w-bounds-ratio-{tag}"),
                claim: "W-bounds (Theorem 1)".into(),
                statement,
                payload,
            },
        ));
    }
    if let Some(c) = mu_farkas(cfg)? {
        out.push(("mu-conditions-infeasible.json".into(), c));
    }
    Ok(out)
}

fn to_decimal(r: &BigRational) -> String {
    // denominators here are 10⁶: write as an exact decimal
    let v = wingcheck_cert::exact::to_f64(r);
    let s = format!("{v:.6}");
    debug_assert_eq!(parse_rational(&s).ok().as_ref(), Some(r));
    s
}

/// Farkas certificate that μ3 ≥ 0 is impossible for all η1, η5 ≥ 0 when its constant term
/// bξEI/(2s⁴) − aρ is negative. Variables (η1, η5); rows: bη1 + 2aρx_cη5 ≤ C3, −η1 ≤ 0, −η5 ≤ 0.
pub fn mu_farkas(cfg: &Config) -> Result<Option<Certificate>, ClaimsError> {
    let q = |x: f64| parse_rational(&decimal(x)).map_err(cert_err);
    let w = &cfg.wing;
    let (a, b) = (q(cfg.control.a)?, q(cfg.control.b)?);
    let (xi, ei, s, rho, rxc) = (q(w.xi)?, q(w.ei)?, q(w.span)?, q(w.rho)?, q(w.rho_xc)?);
    let two = BigRational::from_integer(2.into());
    let s4 = &s * &s * &s * &s;
    let c3 = &b * &xi * &ei / (&two * &s4) - &a * &rho;
    if c3 >= BigRational::from_integer(0.into()) {
        return Ok(None);
    }
    let coef5 = &two * &a * &rxc;
    let one = BigRational::from_integer(1.into());
    let zero = BigRational::from_integer(0.into());
    let rows = vec![vec![b.clone(), coef5.clone()], vec![-one.clone(), zero.clone()], vec![zero.clone(), -one.clone()]];
    let sys = LinearSystem {
        a: RationalMatrix::from_rows(rows).expect("rectangular"),
        b: vec![c3.clone(), zero.clone(), zero.clone()],
        a_eq: RationalMatrix::zeros(0, 2),
        b_eq: vec![],
    };
    let cert = FarkasCertificate { y: vec![one, b, coef5], w: vec![] };
    Ok(Some(Certificate {
        id: "mu-conditions-infeasible".into(),
        claim: "mu-conditions (32)".into(),
        statement: format!(
            "With a = {}, b = {}, μ3 = bξEI/(2s⁴) − η1 b − aρ − 2aρx_c η5 ≥ 0 has no solution η1, η5 ≥ 0 (its constant term is {} < 0), so μ1…μ6 > 0 cannot all hold.",
            cfg.control.a,
            cfg.control.b,
            to_fraction_string(&c3)
        ),
        payload: Payload::farkas(&sys, &cert),
    }))
}

/// Write all certificates into `dir` (created if missing), atomically per file.
pub fn write_all(cfg: &Config, dir: &Path) -> Result<Vec<PathBuf>, ClaimsError> {
    std::fs::create_dir_all(dir).map_err(|e| cert_err(format!("cannot create {}: {e}", dir.display())))?;
    let mut written = Vec::new();
    for (name, c) in certificates(cfg)? {
        let path = dir.join(name);
        write_certificate(&path, &c).map_err(cert_err)?;
        written.push(path);
    }
    Ok(written)
}
