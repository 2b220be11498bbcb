//! The Lyapunov function W of (22)–(23) and the energy-like norm κ of (25) as exact quadratic
//! forms on a Galerkin space, for the W-bounds row and its certificates.
//!
//! State: displacements q ∈ cubic Hermite (clamped), θ ∈ linear (clamped) on N uniform
//! elements; velocities q̇, θ̇ ∈ discontinuous piecewise cubics. The velocity space contains
//! every pointwise linear combination of the displacement fields, and W, κ involve velocities
//! only through L² products, so for each displacement the infimum/supremum over velocities in
//! L² is attained inside this space: the discrete extremal ratios are exact for the
//! displacement space V_N, and decrease (inf) / increase (sup) monotonically to the
//! continuum values as N doubles (nested spaces).
//!
//! Unknown ordering: [q: 2N Hermite | θ: N linear | q̇: 4N DG | θ̇: 4N DG] (dimension 11N).
//! All matrices are assembled in exact rational arithmetic (wingcheck-cert) from the decimal
//! parameters, so a certificate's verifier can rebuild exactly the same matrix.

use num_rational::BigRational;
use num_traits::{One, Zero};
use serde::{Deserialize, Serialize};
use serde_json::Value;
use wingcheck_cert::exact::{parse_rational, to_f64};
use wingcheck_cert::fe::{ClampedMesh, Space};
use wingcheck_cert::RationalMatrix;
use wingcheck_model::Config;

use crate::numerics::{FormsError, PencilError};

/// Which cross term −c ∫q̇θ̇ the function carries: the paper prints b·x_c (x_c = ρx_c/ρ);
/// the kinetic energy and the bound (27) have b·ρx_c.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Coupling {
    /// −b x_c ∫q̇θ̇ as printed in (23), x_c = ρx_c/ρ.
    Printed,
    /// −b ρx_c ∫q̇θ̇, so that W_a + that term is b × the kinetic + potential energy.
    Corrected,
}

/// The exact parameters W and κ depend on (rationals parsed from the config's decimals).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct LyapunovParams {
    /// ρ, ρx_c, EI, GJ, I_p, s as decimal strings.
    pub rho: String,
    /// ρx_c.
    pub rho_xc: String,
    /// EI.
    pub ei: String,
    /// GJ.
    pub gj: String,
    /// I_p.
    pub ip: String,
    /// s.
    pub span: String,
    /// Weight a of (15)/(23).
    pub a: String,
    /// Weight b.
    pub b: String,
    /// Cross-term variant.
    pub coupling: Coupling,
    /// Elements N.
    pub elements: usize,
}

/// Shortest decimal text of an f64 (what the user typed for config values like 0.35).
pub fn decimal(x: f64) -> String {
    format!("{x}")
}

impl LyapunovParams {
    /// From a configuration, with a chosen coupling variant and element count.
    pub fn from_config(cfg: &Config, coupling: Coupling, elements: usize) -> Self {
        let w = &cfg.wing;
        LyapunovParams {
            rho: decimal(w.rho),
            rho_xc: decimal(w.rho_xc),
            ei: decimal(w.ei),
            gj: decimal(w.gj),
            ip: decimal(w.ip),
            span: decimal(w.span),
            a: decimal(cfg.control.a),
            b: decimal(cfg.control.b),
            coupling,
            elements,
        }
    }

    /// The same with other weights.
    pub fn with_weights(&self, a: &str, b: &str) -> Self {
        LyapunovParams { a: a.into(), b: b.into(), ..self.clone() }
    }

    fn q(&self, field: &'static str, s: &str) -> Result<BigRational, FormsError> {
        parse_rational(s).map_err(|cause| FormsError::Rational { field, cause })
    }
}

/// W and κ as exact symmetric matrices of dimension 11N.
#[derive(Debug, Clone)]
pub struct ExactForms {
    /// W of (22)–(23).
    pub w: RationalMatrix,
    /// κ of (25).
    pub kappa: RationalMatrix,
}

fn place(target: &mut RationalMatrix, block: &RationalMatrix, r0: usize, c0: usize, coef: &BigRational, sym: bool) {
    if coef.is_zero() {
        return;
    }
    for i in 0..block.rows() {
        for j in 0..block.cols() {
            let v = block.get(i, j);
            if v.is_zero() {
                continue;
            }
            let x = v * coef;
            target.add_to(r0 + i, c0 + j, &x);
            if sym {
                target.add_to(c0 + j, r0 + i, &x);
            }
        }
    }
}

/// Assemble W and κ exactly.
pub fn assemble(p: &LyapunovParams) -> Result<ExactForms, FormsError> {
    if p.elements == 0 || p.elements > 64 {
        return Err(FormsError::Elements(p.elements));
    }
    let rho = p.q("rho", &p.rho)?;
    let rho_xc = p.q("rho_xc", &p.rho_xc)?;
    let ei = p.q("ei", &p.ei)?;
    let gj = p.q("gj", &p.gj)?;
    let ip = p.q("ip", &p.ip)?;
    let span = p.q("span", &p.span)?;
    let a = p.q("a", &p.a)?;
    let b = p.q("b", &p.b)?;
    if span <= BigRational::zero() || rho <= BigRational::zero() {
        return Err(FormsError::NonPositive);
    }
    let n = p.elements;
    let mesh = ClampedMesh::new(span, n);
    let kh = mesh.hermite_stiffness();
    let kl = mesh.linear_stiffness();
    let md = mesh.mass(Space::DgCubic, Space::DgCubic);
    let c_dh = mesh.mass(Space::DgCubic, Space::Hermite);
    let c_dl = mesh.mass(Space::DgCubic, Space::Linear);
    let (oq, ot, ovq, ovt) = (0, 2 * n, 3 * n, 7 * n);
    let dim = 11 * n;
    let half = BigRational::new(1.into(), 2.into());
    let one = BigRational::one();
    let c = match p.coupling {
        Coupling::Printed => &rho_xc / &rho,
        Coupling::Corrected => rho_xc.clone(),
    };
    let mut w = RationalMatrix::zeros(dim, dim);
    let bh = &b * &half;
    place(&mut w, &kh, oq, oq, &(&bh * &ei), false);
    place(&mut w, &kl, ot, ot, &(&bh * &gj), false);
    place(&mut w, &md, ovq, ovq, &(&bh * &rho), false);
    place(&mut w, &md, ovt, ovt, &(&bh * &ip), false);
    place(&mut w, &md, ovq, ovt, &(-(&bh * &c)), true);
    let ah = &a * &half;
    place(&mut w, &c_dh, ovq, oq, &(&ah * &rho), true);
    place(&mut w, &c_dl, ovq, ot, &(-(&ah * &rho_xc)), true);
    place(&mut w, &c_dh, ovt, oq, &(-(&ah * &rho_xc)), true);
    place(&mut w, &c_dl, ovt, ot, &(&ah * &ip), true);
    let mut kappa = RationalMatrix::zeros(dim, dim);
    place(&mut kappa, &kh, oq, oq, &one, false);
    place(&mut kappa, &kl, ot, ot, &one, false);
    place(&mut kappa, &md, ovq, ovq, &one, false);
    place(&mut kappa, &md, ovt, ovt, &one, false);
    Ok(ExactForms { w, kappa })
}

/// Dense f64 copy (row-major) of an exact matrix.
pub fn to_dense(m: &RationalMatrix) -> faer::Mat<f64> {
    faer::Mat::from_fn(m.rows(), m.cols(), |i, j| to_f64(m.get(i, j)))
}

/// Generalised eigenpairs of (A, B), B ≻ 0: eigenvalues ascending and eigenvectors (columns).
pub fn generalized_eigen(a: &faer::Mat<f64>, b: &faer::Mat<f64>) -> Result<(Vec<f64>, faer::Mat<f64>), PencilError> {
    use faer::Side;
    let n = a.nrows();
    let llt = b.llt(Side::Lower).map_err(|cause| PencilError::NotPositiveDefinite { what: "κ", cause })?;
    let l = llt.L();
    let c = wingcheck_sim::dense::congruence(l, a);
    let eig =
        c.self_adjoint_eigen(Side::Lower).map_err(|cause| PencilError::Eigen { what: "eigen solver failed", cause })?;
    let vals: Vec<f64> = (0..n).map(|i| eig.S()[i]).collect();
    // back-transform: x = L⁻ᵀ y
    let mut vecs = eig.U().to_owned();
    faer::linalg::triangular_solve::solve_upper_triangular_in_place(l.transpose(), vecs.as_mut(), faer::Par::Seq);
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&i, &j| vals[i].total_cmp(&vals[j]));
    let sorted_vals = order.iter().map(|&i| vals[i]).collect();
    let sorted_vecs = faer::Mat::from_fn(n, n, |r, k| vecs[(r, order[k])]);
    Ok((sorted_vals, sorted_vecs))
}

/// Tightest constants on V_N: λ2(N) = min W/κ and λ1(N) = max W/κ, with the extremal states.
#[derive(Debug, Clone)]
pub struct TightConstants {
    /// min W/κ on V_N.
    pub lambda2: f64,
    /// max W/κ on V_N.
    pub lambda1: f64,
    /// State attaining λ2.
    pub argmin: Vec<f64>,
    /// State attaining λ1.
    pub argmax: Vec<f64>,
}

/// Compute the tight constants from exact forms (float generalised eigenvalue problem).
pub fn tight_constants(forms: &ExactForms) -> Result<TightConstants, PencilError> {
    let (vals, vecs) = generalized_eigen(&to_dense(&forms.w), &to_dense(&forms.kappa))?;
    let n = vals.len();
    Ok(TightConstants {
        lambda2: vals[0],
        lambda1: vals[n - 1],
        argmin: (0..n).map(|i| vecs[(i, 0)]).collect(),
        argmax: (0..n).map(|i| vecs[(i, n - 1)]).collect(),
    })
}

/// Largest a/b with W ≻ 0 on V_N: −1/μ_min of the pencil (W(a=1,b=0), W(a=0,b=1)).
pub fn a_over_b_max(cfg: &Config, coupling: Coupling, elements: usize) -> Result<f64, PencilError> {
    let p = LyapunovParams::from_config(cfg, coupling, elements);
    let wa = assemble(&p.with_weights("1", "0"))?;
    let wb = assemble(&p.with_weights("0", "1"))?;
    let (vals, _) = generalized_eigen(&to_dense(&wa.w), &to_dense(&wb.w))?;
    Ok(-1.0 / vals[0])
}

/// xᵀ A x exactly.
pub fn quadratic_form(a: &RationalMatrix, x: &[BigRational]) -> BigRational {
    let ax = a.mul_vec(x).expect("dimensions agree");
    ax.iter().zip(x).fold(BigRational::zero(), |acc, (u, v)| acc + u * v)
}

/// Round a float vector to rationals with denominator 2^20 (after scaling to max-norm 1).
pub fn round_vector(x: &[f64]) -> Vec<BigRational> {
    let scale = x.iter().fold(0.0f64, |m, v| m.max(v.abs())).max(1e-300);
    x.iter().map(|v| BigRational::new(((v / scale * 1048576.0).round() as i64).into(), 1048576.into())).collect()
}

/// Recipe parameters → the certified matrix. `form`: `w-minus-lambda-kappa` (W − λκ),
/// `lambda-kappa-minus-w` (λκ − W) or `negative-direction` (the 1×1 matrix [−xᵀ(W − λκ)x],
/// positive iff W(x) < λ κ(x)), `positive-direction` ([xᵀ(W − λκ)x], positive iff W(x) > λκ(x)).
pub fn recipe_build(params: &Value) -> Result<RationalMatrix, FormsError> {
    let p: LyapunovParams = serde_json::from_value(params.get("forms").cloned().ok_or(FormsError::Missing("forms"))?)
        .map_err(|e| FormsError::Json(std::sync::Arc::new(e)))?;
    let lambda = parse_rational(params.get("lambda").and_then(Value::as_str).ok_or(FormsError::Missing("lambda"))?)
        .map_err(|cause| FormsError::Rational { field: "lambda", cause })?;
    let form = params.get("form").and_then(Value::as_str).ok_or(FormsError::Missing("form"))?;
    let f = assemble(&p)?;
    let lk = f.kappa.scale(&lambda);
    let diff = f.w.sub(&lk).ok_or(FormsError::DimensionMismatch)?;
    match form {
        "w-minus-lambda-kappa" => Ok(diff),
        "lambda-kappa-minus-w" => Ok(lk.sub(&f.w).ok_or(FormsError::DimensionMismatch)?),
        "negative-direction" | "positive-direction" => {
            let xs = params.get("x").and_then(Value::as_array).ok_or(FormsError::Missing("x"))?;
            let x: Result<Vec<BigRational>, FormsError> = xs
                .iter()
                .map(|v| {
                    parse_rational(v.as_str().unwrap_or("")).map_err(|cause| FormsError::Rational { field: "x", cause })
                })
                .collect();
            let x = x?;
            if x.len() != diff.rows() {
                return Err(FormsError::DirectionLength { got: x.len(), dim: diff.rows() });
            }
            let v = quadratic_form(&diff, &x);
            let v = if form == "negative-direction" { -v } else { v };
            Ok(RationalMatrix::from_fn(1, 1, |_, _| v.clone()))
        }
        other => Err(FormsError::UnknownForm(other.into())),
    }
}

/// Name of the recipe in certificates.
pub const RECIPE: &str = "wing-lyapunov-w-kappa";
