//! A certified enclosure ω̲₁ ≤ ω₁ ≤ ω̄₁ of the fundamental frequency of the *continuous*
//! cantilever wing (undamped, free tip), checked in exact rational arithmetic.
//!
//! The eigenproblem: find (q, θ) ≠ 0 in V = {q ∈ H², q(0) = q'(0) = 0} × {θ ∈ H¹, θ(0) = 0}
//! with a((q,θ), v) = ω² m((q,θ), v) for all v ∈ V, where
//! a = ∫ EI q''² + GJ θ'² dz (stiffness) and m = ∫ ρq² − 2ρx_c qθ + I_pθ² dz (kinetic mass,
//! the model's M = [[ρ, −ρx_c], [−ρx_c, I_p]] ≻ 0). Its eigenvalues ω₁² ≤ ω₂² ≤ … are the
//! squared natural frequencies (rad/s).
//!
//! * **Upper bound** (Rayleigh–Ritz): for any admissible v ≠ 0, ω₁² ≤ R(v) = a(v,v)/m(v,v).
//!   v is a rational nodal vector of the space V_N below, so R(v) is an exact rational
//!   ([`rayleigh_quotient`]); ω̄₁ is a rational with ω̄₁² ≥ R(v).
//! * **Lower bound** (trace of the compliance operator, [`crate::green`]):
//!   Σᵢ ωᵢ⁻⁴ = tr(G²), so ω₁⁻⁴ ≤ tr(G²) − Σ_{i=2}^{k} Λᵢ⁻² whenever Λᵢ ≥ ωᵢ². Each Λᵢ is
//!   certified by an exact inertia count ([`shift_inertia`]): if K_N − Λᵢ M_N has at least i
//!   negative eigenvalues, the i-th Galerkin eigenvalue is < Λᵢ, and the Galerkin eigenvalues
//!   of a conforming space bound the continuous ones from above (min–max), so ωᵢ² < Λᵢ.
//!   ω̲₁ is a rational with ω̲₁⁴ · (tr(G²) − Σ Λᵢ⁻²) ≤ 1.
//!
//! The Galerkin space V_N ([`pencil`]): N uniform elements on [0, s], C¹ cubic Hermite for
//! both q and θ (nodal values and slopes), clamped by q(0) = q'(0) = θ(0) = 0 only — the slope
//! θ'(0) stays free, as in V. C¹ cubics lie in H² ⊂ H¹, so V_N ⊂ V is conforming for both
//! fields. (The simulator's linear torsion elements are conforming too, but their O(h²)
//! eigenvalue error would need ~200 elements for a 1e-8 enclosure at the paper's wing; cubic θ
//! has O(h⁶), and 24 elements suffice. See docs/model.md.)

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use rayon::prelude::*;

use crate::banded::{inertia, Inertia, SymBand, ZeroLeadingMinor};
use crate::exact::{denominator_lcm, from_f64_exact, int, to_f64};
use crate::fe::{gram, hermite_basis};
use crate::green::trace_g2;
use crate::matrix::RationalMatrix;
use crate::poly::Poly;

/// Errors of checking an enclosure.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EnclosureError {
    /// An input is outside its allowed range (checked before any arithmetic on it).
    #[error("{field}: {message}")]
    Invalid {
        /// Which input.
        field: String,
        /// What is wrong and what is allowed.
        message: String,
    },
    /// The exact check failed: the data do not prove the bound they were made for.
    #[error("refuted: {0}")]
    Refuted(String),
    /// Shift Λ_mode has fewer than `mode` negative pivots: it does not bound ω_mode².
    #[error(
        "refuted: Λ{mode} = {lambda:.10e}: K_N − Λ{mode} M_N has only {negative} negative pivots \
         (at least {mode} are needed to bound ω{mode}²)"
    )]
    ShiftTooLow {
        /// The mode i of Λᵢ (2 … k).
        mode: usize,
        /// Negative pivots found.
        negative: usize,
        /// Λᵢ, for display.
        lambda: f64,
    },
    /// K_N − Λ_mode M_N has an exactly singular leading minor: no inertia count at this shift.
    #[error("refuted: Λ{mode} = {lambda:.10e}: {source}; no inertia count at this shift")]
    SingularShift {
        /// The mode i of Λᵢ.
        mode: usize,
        /// Λᵢ, for display.
        lambda: f64,
        /// Which minor vanished.
        source: ZeroLeadingMinor,
    },
}

fn invalid(field: &str, message: impl Into<String>) -> EnclosureError {
    EnclosureError::Invalid { field: field.into(), message: message.into() }
}

/// The constants the undamped spectrum depends on, exactly (config units: m, kg/m, kg, N m²,
/// N m², kg m).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct WingConstants {
    /// Span s (m).
    pub span: BigRational,
    /// ρ (kg/m).
    pub rho: BigRational,
    /// ρx_c (kg); the kinetic mass has −ρx_c off the diagonal.
    pub rho_xc: BigRational,
    /// EI (N m²).
    pub ei: BigRational,
    /// GJ (N m²).
    pub gj: BigRational,
    /// I_p (kg m).
    pub ip: BigRational,
}

impl WingConstants {
    /// s, ρ, EI, GJ, I_p > 0 and ρ I_p > (ρx_c)² (M ≻ 0).
    ///
    /// # Errors
    /// [`EnclosureError::Invalid`] naming the constant.
    pub fn validate(&self) -> Result<(), EnclosureError> {
        for (name, v) in
            [("span", &self.span), ("rho", &self.rho), ("ei", &self.ei), ("gj", &self.gj), ("ip", &self.ip)]
        {
            if !v.is_positive() {
                return Err(invalid(&format!("wing.{name}"), "must be > 0"));
            }
        }
        if &self.rho * &self.ip <= &self.rho_xc * &self.rho_xc {
            return Err(invalid("wing.rho_xc", "the kinetic mass matrix needs ρ I_p > (ρx_c)²"));
        }
        Ok(())
    }

    /// tr(G²) = Σ ωᵢ⁻⁴ (s⁴), [`crate::green::trace_g2`].
    pub fn trace_g2(&self) -> BigRational {
        trace_g2(&self.span, &self.rho, &self.rho_xc, &self.ei, &self.gj, &self.ip)
    }
}

/// Nodal fields of V_N, in the order they are stored per node.
pub const FIELDS: [&str; 4] = ["q", "q'", "θ", "θ'"];

/// Upper bandwidth of the pencil in the unknown ordering of [`unknown_index`].
pub const BANDWIDTH: usize = 7;

/// Number of unknowns of V_N on `elements` elements: 4 per node, minus the clamp's three.
pub fn unknowns(elements: usize) -> usize {
    4 * elements + 1
}

/// Unknown index of nodal field `field` (0 … 3, see [`FIELDS`]) at node `node` (0 … N), or
/// `None` for the clamped q(0), q'(0), θ(0). Node 0 keeps θ'(0) as unknown 0; node j ≥ 1 has
/// unknowns 4j − 3 … 4j.
pub fn unknown_index(node: usize, field: usize) -> Option<usize> {
    match node {
        0 => (field == 3).then_some(0),
        _ => Some(4 * node - 3 + field),
    }
}

/// Reference element matrices of the cubic Hermite basis on [0, 1] in the DOFs
/// (u(0), u'(0), u(1), u'(1)): ∫N''N'', ∫N'N', ∫N N. On an element of length h with the
/// scaled DOFs (u₀, h u₀', u₁, h u₁') they become K_b/h³, K_t/h and h·M.
struct Reference {
    kb: RationalMatrix,
    kt: RationalMatrix,
    m: RationalMatrix,
}

fn reference() -> Reference {
    let one = BigRational::one();
    let b = hermite_basis(&one);
    let d1: Vec<Poly> = b.iter().map(Poly::derivative).collect();
    let d2: Vec<Poly> = d1.iter().map(Poly::derivative).collect();
    Reference { kb: gram(&d2, &d2, &one), kt: gram(&d1, &d1, &one), m: gram(&b, &b, &one) }
}

/// The Galerkin pencil (K_N, M_N) of V_N in the scaled unknowns (q_j, h q'_j, θ_j, h θ'_j)
/// ordered by [`unknown_index`] — a positive diagonal congruence of the pencil in the nodal
/// values, so the same eigenvalues ω² (rad²/s²) and the same inertia of K − ΛM.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Pencil {
    /// Stiffness ∫ EI q''² + GJ θ'² (units of the scaled unknowns).
    pub stiffness: SymBand,
    /// Kinetic mass ∫ ρq² − 2ρx_c qθ + I_pθ².
    pub mass: SymBand,
}

/// Assembles the pencil of V_N on `elements` ≥ 1 uniform elements.
pub fn pencil(w: &WingConstants, elements: usize) -> Pencil {
    let r = reference();
    let h = &w.span / int(elements as i64);
    let h3 = &h * &h * &h;
    let (cb, ct) = (&w.ei / &h3, &w.gj / &h);
    let (mqq, mqt, mtt) = (&w.rho * &h, -(&w.rho_xc * &h), &w.ip * &h);
    let n = unknowns(elements);
    let mut k = SymBand::zeros(n, BANDWIDTH);
    let mut m = SymBand::zeros(n, BANDWIDTH);
    // local DOF a of an element: node e + a/2, slope if a is odd; bending fields 0/1, torsion 2/3
    let idx = |e: usize, a: usize, torsion: bool| unknown_index(e + a / 2, a % 2 + if torsion { 2 } else { 0 });
    for e in 0..elements {
        for a in 0..4 {
            for b in 0..4 {
                let (qa, qb, ta, tb) = (idx(e, a, false), idx(e, b, false), idx(e, a, true), idx(e, b, true));
                let (kb, kt, mr) = (r.kb.get(a, b), r.kt.get(a, b), r.m.get(a, b));
                if let (Some(i), Some(j)) = (qa, qb) {
                    if i <= j {
                        k.add_to(i, j, &(&cb * kb));
                        m.add_to(i, j, &(&mqq * mr));
                    }
                }
                if let (Some(i), Some(j)) = (ta, tb) {
                    if i <= j {
                        k.add_to(i, j, &(&ct * kt));
                        m.add_to(i, j, &(&mtt * mr));
                    }
                }
                // cross mass −ρx_c ∫ q θ: entry (q-DOF a, θ-DOF b), once per unordered pair
                if let (Some(i), Some(j)) = (qa, tb) {
                    m.add_to(i, j, &(&mqt * mr));
                }
            }
        }
    }
    Pencil { stiffness: k, mass: m }
}

/// Exact inertia of K_N − Λ M_N: the number of negative eigenvalues is the number of Galerkin
/// eigenvalues below Λ (rad²/s²).
///
/// # Errors
/// [`ZeroLeadingMinor`] if the elimination meets an exactly singular leading minor (choose a
/// slightly different Λ).
pub fn shift_inertia(p: &Pencil, lambda: &BigRational) -> Result<Inertia, ZeroLeadingMinor> {
    inertia(&p.stiffness.add_scaled(&-lambda, &p.mass))
}

/// a(v, v), m(v, v) and R(v) = a/m (rad²/s²) of the nodal vector `nodal` on V_N:
/// 4(N + 1) values (q_j, q'_j, θ_j, θ'_j) for nodes j = 0 … N, in SI units.
///
/// # Errors
/// [`EnclosureError::Invalid`] for a wrong length, [`EnclosureError::Refuted`] if v violates
/// the clamp q(0) = q'(0) = θ(0) = 0 (then it is not admissible) or m(v, v) = 0.
pub fn rayleigh_quotient(
    w: &WingConstants,
    elements: usize,
    nodal: &[BigRational],
) -> Result<(BigRational, BigRational, BigRational), EnclosureError> {
    if nodal.len() != 4 * (elements + 1) {
        return Err(invalid(
            "vector",
            format!(
                "{} entries, {} required (q, q', θ, θ' at {} nodes)",
                nodal.len(),
                4 * (elements + 1),
                elements + 1
            ),
        ));
    }
    for (f, v) in nodal.iter().take(3).enumerate() {
        if !v.is_zero() {
            return Err(EnclosureError::Refuted(format!(
                "the test vector violates the clamp: {}(0) = {} ≠ 0, so it is not an admissible state",
                FIELDS[f],
                to_f64(v)
            )));
        }
    }
    let h = &w.span / int(elements as i64);
    // Scaled nodal values (slopes times h), then one integer vector c·v.
    let scaled: Vec<BigRational> =
        nodal.iter().enumerate().map(|(i, v)| if i % 2 == 1 { v * &h } else { v.clone() }).collect();
    let c = denominator_lcm(scaled.iter());
    let x: Vec<BigInt> = scaled.iter().map(|v| v.numer() * (&c / v.denom())).collect();
    let r = reference();
    let ints = |m: &RationalMatrix, scale: i64| -> Vec<Vec<BigInt>> {
        let entry = |a: usize, b: usize| {
            let v = m.get(a, b) * int(scale);
            assert!(v.is_integer(), "reference element matrices times 1, 30, 420 are integer");
            v.to_integer()
        };
        (0..4).map(|a| (0..4).map(|b| entry(a, b)).collect()).collect()
    };
    // Reference matrices as integers: K_b (×1), 30 K_t, 420 M.
    let (kb, kt, mm) = (ints(&r.kb, 1), ints(&r.kt, 30), ints(&r.m, 420));
    let form = |m: &[Vec<BigInt>], u: &[&BigInt; 4], v: &[&BigInt; 4]| -> BigInt {
        let mut s = BigInt::zero();
        for a in 0..4 {
            let row: BigInt = (0..4).map(|b| &m[a][b] * v[b]).sum();
            s += u[a] * row;
        }
        s
    };
    let (mut sb, mut st, mut sqq, mut sqt, mut stt) =
        (BigInt::zero(), BigInt::zero(), BigInt::zero(), BigInt::zero(), BigInt::zero());
    for e in 0..elements {
        let q = [&x[4 * e], &x[4 * e + 1], &x[4 * e + 4], &x[4 * e + 5]];
        let t = [&x[4 * e + 2], &x[4 * e + 3], &x[4 * e + 6], &x[4 * e + 7]];
        sb += form(&kb, &q, &q);
        st += form(&kt, &t, &t);
        sqq += form(&mm, &q, &q);
        sqt += form(&mm, &q, &t);
        stt += form(&mm, &t, &t);
    }
    let q = |i: BigInt| BigRational::from_integer(i);
    let stiffness = &w.ei * q(sb) / (&h * &h * &h) + &w.gj * q(st) / (int(30) * &h);
    let mass = &h / int(420) * (&w.rho * q(sqq) - int(2) * &w.rho_xc * q(sqt) + &w.ip * q(stt));
    if !mass.is_positive() {
        return Err(EnclosureError::Refuted("the test vector has m(v, v) = 0 (it is the zero state)".into()));
    }
    let cc = BigRational::from_integer(&c * &c);
    let (stiffness, mass) = (stiffness / &cc, mass / &cc);
    let quotient = &stiffness / &mass;
    Ok((stiffness, mass, quotient))
}

/// Work limits of [`check`] (inputs beyond them are refused before any arithmetic).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// Most modes k (shifts Λ₂ … Λ_k).
    pub max_modes: usize,
    /// Most elements of the inertia mesh.
    pub max_inertia_elements: usize,
    /// Most elements of the Rayleigh mesh.
    pub max_rayleigh_elements: usize,
}

/// The data of an enclosure: everything a verifier needs, nothing it derives.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct EnclosureData {
    /// The wing.
    pub wing: WingConstants,
    /// Elements of the mesh on which the shifts are certified.
    pub inertia_elements: usize,
    /// Λ₂ … Λ_k (rad²/s²): Λᵢ is claimed to exceed the i-th Galerkin eigenvalue; k = len + 1.
    pub shifts: Vec<BigRational>,
    /// Elements of the test vector's mesh.
    pub rayleigh_elements: usize,
    /// The test vector: nodal values (q, q', θ, θ') at nodes 0 … N of the Rayleigh mesh.
    pub vector: Vec<BigRational>,
}

/// What [`check`] established, with the exact numbers.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CheckedEnclosure {
    /// ω̲₁ (rad/s): a rational with ω̲₁⁴ · `inverse_fourth_bound` ≤ 1.
    pub lower: BigRational,
    /// ω̄₁ (rad/s): a rational with ω̄₁² ≥ `rayleigh`.
    pub upper: BigRational,
    /// tr(G²) = Σ ωᵢ⁻⁴ (s⁴).
    pub trace: BigRational,
    /// tr(G²) − Σ Λᵢ⁻² ≥ ω₁⁻⁴ (s⁴).
    pub inverse_fourth_bound: BigRational,
    /// R(v) ≥ ω₁² (rad²/s²).
    pub rayleigh: BigRational,
    /// Negative eigenvalues of K_N − Λᵢ M_N for i = 2 … k.
    pub counts: Vec<usize>,
}

/// Significant decimal digits of ω̲₁, ω̄₁ (their rounding costs ≤ 1e-15 relative).
const DIGITS: i32 = 16;

/// The rational 10^e (any sign of e).
fn ten_pow(e: i32) -> BigRational {
    let p = num_traits::pow(BigInt::from(10), e.unsigned_abs() as usize);
    if e >= 0 {
        BigRational::from_integer(p)
    } else {
        BigRational::new(BigInt::one(), p)
    }
}

/// The best decimal with [`DIGITS`] significant digits on one side of a threshold: the largest
/// r with `ok(r)` if `down` (ok holds below the threshold), else the smallest. Canonical: the
/// float guess `x` only says where to start looking, so the result does not depend on how
/// the guess was rounded.
fn decimal_bound(x: f64, down: bool, ok: impl Fn(&BigRational) -> bool) -> Result<BigRational, EnclosureError> {
    let fail = |what: &str| EnclosureError::Refuted(format!("could not round the bound to a decimal: {what}"));
    if !(x.is_finite() && x > 0.0) {
        return Err(fail(&format!("float guess {x:e} is not a positive number")));
    }
    let (lo, hi) = (ten_pow(DIGITS - 1).to_integer(), ten_pow(DIGITS).to_integer());
    let mut e = DIGITS - 1 - x.log10().floor() as i32;
    for _ in 0..4 {
        let unit = ten_pow(-e);
        let at = |m: &BigInt| ok(&(BigRational::from_integer(m.clone()) * &unit));
        let guess = from_f64_exact(x).expect("finite") * ten_pow(e);
        let mut m = if down { guess.floor() } else { guess.ceil() }.to_integer();
        // Walk to the last grid point on the ok side (the guess is within a few units).
        let (inward, outward) = if down { (-1, 1) } else { (1, -1) };
        let mut steps = 0;
        if at(&m) {
            while at(&(&m + outward)) && steps < 64 {
                m += outward;
                steps += 1;
            }
        } else {
            while !at(&m) && steps < 64 {
                m += inward;
                steps += 1;
            }
        }
        if steps >= 64 {
            return Err(fail("float guess too far off"));
        }
        if m >= hi {
            e -= 1;
        } else if m < lo {
            e += 1;
        } else {
            return Ok(BigRational::from_integer(m) * unit);
        }
    }
    Err(fail("no digit count fits"))
}

/// Checks an enclosure exactly: inputs against `limits` first, then the test vector's
/// admissibility and R(v), tr(G²), every shift's inertia and the lower bound's positivity.
///
/// # Errors
/// [`EnclosureError::Invalid`] for inputs out of range, [`EnclosureError::Refuted`] when a
/// shift has too few negative pivots (it does not bound its eigenvalue), tr(G²) − Σ Λᵢ⁻² ≤ 0,
/// or the test vector is not admissible.
pub fn check(d: &EnclosureData, limits: &Limits) -> Result<CheckedEnclosure, EnclosureError> {
    let k = d.shifts.len() + 1;
    if k > limits.max_modes {
        return Err(invalid("shifts", format!("k = {k} modes, at most {} allowed", limits.max_modes)));
    }
    if !(1..=limits.max_inertia_elements).contains(&d.inertia_elements) {
        return Err(invalid(
            "inertia_elements",
            format!("{} outside [1, {}]", d.inertia_elements, limits.max_inertia_elements),
        ));
    }
    if !(1..=limits.max_rayleigh_elements).contains(&d.rayleigh_elements) {
        return Err(invalid(
            "rayleigh_elements",
            format!("{} outside [1, {}]", d.rayleigh_elements, limits.max_rayleigh_elements),
        ));
    }
    if d.vector.len() != 4 * (d.rayleigh_elements + 1) {
        return Err(invalid(
            "vector",
            format!(
                "{} entries, {} required for {} elements",
                d.vector.len(),
                4 * (d.rayleigh_elements + 1),
                d.rayleigh_elements
            ),
        ));
    }
    d.wing.validate()?;
    if let Some(i) = d.shifts.iter().position(|l| !l.is_positive()) {
        return Err(invalid(&format!("shifts[{i}]"), "Λ must be > 0"));
    }
    // The cheap parts first: the test vector's admissibility and R(v), then tr(G²).
    let (_, _, rayleigh) = rayleigh_quotient(&d.wing, d.rayleigh_elements, &d.vector)?;
    let trace = d.wing.trace_g2();
    let p = pencil(&d.wing, d.inertia_elements);
    // The k − 1 inertia counts are independent: in parallel, collected in order.
    let results: Vec<Result<Inertia, ZeroLeadingMinor>> =
        d.shifts.par_iter().map(|lambda| shift_inertia(&p, lambda)).collect();
    let mut counts = Vec::with_capacity(d.shifts.len());
    let mut bound = trace.clone();
    for (j, (lambda, r)) in d.shifts.iter().zip(results).enumerate() {
        let i = j + 2;
        let c = r.map_err(|source| EnclosureError::SingularShift { mode: i, lambda: to_f64(lambda), source })?;
        if c.negative < i {
            return Err(EnclosureError::ShiftTooLow { mode: i, negative: c.negative, lambda: to_f64(lambda) });
        }
        counts.push(c.negative);
        bound -= BigRational::one() / (lambda * lambda);
    }
    if !bound.is_positive() {
        return Err(EnclosureError::Refuted(format!(
            "tr(G²) − Σ Λᵢ⁻² = {:.6e} ≤ 0 gives no lower bound",
            to_f64(&bound)
        )));
    }
    let lower = decimal_bound(to_f64(&bound).powf(-0.25), true, |r| {
        let r2 = r * r;
        r.is_positive() && &r2 * &r2 * &bound <= BigRational::one()
    })?;
    let upper = decimal_bound(to_f64(&rayleigh).sqrt(), false, |r| r * r >= rayleigh)?;
    if lower > upper {
        return Err(EnclosureError::Refuted(format!(
            "inconsistent: lower bound {:.16e} > upper bound {:.16e}",
            to_f64(&lower),
            to_f64(&upper)
        )));
    }
    Ok(CheckedEnclosure { lower, upper, trace, inverse_fourth_bound: bound, rayleigh, counts })
}
