//! The cantilever Green's functions and the Hilbert–Schmidt norm of the compliance operator.
//!
//! With the stiffness operator K = diag(EI ∂⁴, −GJ ∂²) under the cantilever conditions
//! (q(0) = q'(0) = θ(0) = 0, q''(s) = q'''(s) = θ'(s) = 0) and the constant kinetic mass matrix
//! M = [[ρ, m], [m, I_p]] (the model has m = −ρx_c), the compliance operator G = K⁻¹M is
//! self-adjoint and positive in the M-inner product, with eigenvalues 1/ωᵢ². K⁻¹ is the integral
//! operator with the diagonal kernel diag(g_b, g_t),
//!
//! ```text
//! g_b(z, ζ) = min(z,ζ)² (3 max(z,ζ) − min(z,ζ)) / (6 EI),   g_t(z, ζ) = min(z,ζ) / GJ,
//! ```
//!
//! so G is similar (by the constant M^{1/2}) to the operator with kernel M^{1/2} g M^{1/2}, and
//!
//! ```text
//! tr(G²) = Σᵢ ωᵢ⁻⁴ = ∫₀ˢ∫₀ˢ tr(g M g M) dζ dz = ∫₀ˢ∫₀ˢ [ρ² g_b² + 2 m² g_b g_t + I_p² g_t²] dζ dz.
//! ```
//!
//! The coupling enters only as m², so the sign convention of the cross mass does not matter
//! (θ → −θ maps one convention to the other and leaves K and every boundary condition alone).
//! The kernels are polynomials on each triangle ζ < z, ζ > z, so tr(G²) is integrated exactly
//! ([`trace_g2`]); its closed form 11ρ²s⁸/(1680 EI²) + 11m²s⁶/(180 EI GJ) + I_p²s⁴/(6 GJ²) is a
//! test of it. Units: s⁴ (tr(G²) = Σ ω⁻⁴ with ω in rad/s).

use num_rational::BigRational;
use num_traits::{One, Zero};

use crate::exact::int;

/// A polynomial Σ c[i][j] zⁱ ζʲ in two variables with exact rational coefficients.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Bivariate {
    coeffs: Vec<Vec<BigRational>>,
}

impl Bivariate {
    /// The monomial c · zⁱ ζʲ.
    pub fn monomial(c: BigRational, i: usize, j: usize) -> Self {
        let mut coeffs = vec![vec![BigRational::zero(); j + 1]; i + 1];
        coeffs[i][j] = c;
        Bivariate { coeffs }
    }

    /// Sum of two polynomials.
    pub fn add(&self, other: &Self) -> Self {
        let rows = self.coeffs.len().max(other.coeffs.len());
        let coeffs = (0..rows)
            .map(|i| {
                let (a, b) = (self.coeffs.get(i), other.coeffs.get(i));
                let cols = a.map_or(0, Vec::len).max(b.map_or(0, Vec::len));
                (0..cols)
                    .map(|j| {
                        let x = a.and_then(|r| r.get(j)).cloned().unwrap_or_else(BigRational::zero);
                        x + b.and_then(|r| r.get(j)).cloned().unwrap_or_else(BigRational::zero)
                    })
                    .collect()
            })
            .collect();
        Bivariate { coeffs }
    }

    /// Product of two polynomials.
    pub fn mul(&self, other: &Self) -> Self {
        let rows = (self.coeffs.len() + other.coeffs.len()).saturating_sub(1);
        let cols =
            self.coeffs.iter().map(Vec::len).max().unwrap_or(0) + other.coeffs.iter().map(Vec::len).max().unwrap_or(0);
        let mut coeffs = vec![vec![BigRational::zero(); cols.saturating_sub(1)]; rows];
        for (i, ra) in self.coeffs.iter().enumerate() {
            for (j, a) in ra.iter().enumerate().filter(|(_, a)| !a.is_zero()) {
                for (k, rb) in other.coeffs.iter().enumerate() {
                    for (l, b) in rb.iter().enumerate().filter(|(_, b)| !b.is_zero()) {
                        coeffs[i + k][j + l] += a * b;
                    }
                }
            }
        }
        Bivariate { coeffs }
    }

    /// c · self.
    pub fn scale(&self, c: &BigRational) -> Self {
        Bivariate { coeffs: self.coeffs.iter().map(|r| r.iter().map(|x| x * c).collect()).collect() }
    }

    /// ∫₀ˢ ∫₀^z p(z, ζ) dζ dz, exactly (the triangle ζ < z of the square [0, s]²).
    pub fn integrate_lower_triangle(&self, s: &BigRational) -> BigRational {
        // ∫₀^z zⁱ ζʲ dζ = z^{i+j+1}/(j+1); ∫₀ˢ z^p dz = s^{p+1}/(p+1).
        let mut total = BigRational::zero();
        for (i, row) in self.coeffs.iter().enumerate() {
            for (j, c) in row.iter().enumerate().filter(|(_, c)| !c.is_zero()) {
                let p = i + j + 1;
                let s_pow = (0..=p).fold(BigRational::one(), |acc, _| acc * s);
                total += c * s_pow / (int((j + 1) as i64) * int((p + 1) as i64));
            }
        }
        total
    }
}

/// g_b on the triangle ζ < z: ζ²(3z − ζ)/(6 EI) (m/N: deflection at z per unit load at ζ).
pub fn bending_green_lower(ei: &BigRational) -> Bivariate {
    let c = BigRational::one() / (int(6) * ei);
    Bivariate::monomial(int(3) * &c, 1, 2).add(&Bivariate::monomial(-c, 0, 3))
}

/// g_t on the triangle ζ < z: ζ/GJ (rad/(N m) per unit distributed torque).
pub fn torsion_green_lower(gj: &BigRational) -> Bivariate {
    Bivariate::monomial(BigRational::one() / gj, 0, 1)
}

/// tr(G²) = Σᵢ ωᵢ⁻⁴ (s⁴) of the cantilever wing with span `s`, mass matrix
/// [[ρ, ±ρx_c], [±ρx_c, I_p]] and rigidities EI, GJ, by exact integration of the squared
/// kernels over the square (twice the lower triangle, the kernels being symmetric).
pub fn trace_g2(
    s: &BigRational,
    rho: &BigRational,
    rho_xc: &BigRational,
    ei: &BigRational,
    gj: &BigRational,
    ip: &BigRational,
) -> BigRational {
    let gb = bending_green_lower(ei);
    let gt = torsion_green_lower(gj);
    let integrand = gb
        .mul(&gb)
        .scale(&(rho * rho))
        .add(&gb.mul(&gt).scale(&(int(2) * rho_xc * rho_xc)))
        .add(&gt.mul(&gt).scale(&(ip * ip)));
    int(2) * integrand.integrate_lower_triangle(s)
}
