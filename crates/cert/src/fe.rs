//! Exact finite-element matrices from exactly integrated shape functions.
//!
//! Every element matrix here is a Gram matrix `∫_0^h a_i(x) b_j(x) dx` of
//! polynomial shape functions on one element `[0, h]` (`x` and `h` in metres,
//! or whatever length unit the caller uses consistently), integrated exactly
//! with [`Poly::integrate`] — no quadrature, no floats. Physical coefficients
//! (mass per length, EI, GJ, …) are *not* included; the caller scales.
//!
//! Spaces on a uniform mesh of `N` elements over `[0, s]`, clamped at `x = 0`:
//! * [`Space::Hermite`]: cubic Hermite, local DOFs `(w(0), w'(0), w(h), w'(h))`;
//!   global DOFs `[w_1, w'_1, w_2, w'_2, …, w_N, w'_N]` (node 0 removed by the
//!   clamp `w(0) = w'(0) = 0`), dimension `2N`.
//! * [`Space::Linear`]: continuous piecewise linear, local DOFs `(θ(0), θ(h))`;
//!   global DOFs `[θ_1, …, θ_N]` (clamp `θ(0) = 0`), dimension `N`.
//! * [`Space::DgCubic`]: discontinuous piecewise cubic in the **shifted
//!   Legendre** basis `P_k(2x/h − 1)`, `k = 0..3`, on each element; global
//!   DOFs `[e0k0, e0k1, e0k2, e0k3, e1k0, …]`, dimension `4N`, no clamp.
//!   Its element mass is `diag(h, h/3, h/5, h/7)`.

use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

use crate::exact::int;
use crate::matrix::RationalMatrix;
use crate::poly::Poly;

/// A finite-element space on a uniform clamped mesh (see the module docs for
/// the DOF ordering).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Space {
    /// C¹ cubic Hermite (beam bending deflection `w`).
    Hermite,
    /// C⁰ piecewise linear (shaft twist `θ`).
    Linear,
    /// Discontinuous piecewise cubic, shifted-Legendre basis per element.
    DgCubic,
}

impl Space {
    /// Element shape functions on `[0, h]`, in local DOF order.
    pub fn basis(self, h: &BigRational) -> Vec<Poly> {
        match self {
            Space::Hermite => hermite_basis(h),
            Space::Linear => linear_basis(h),
            Space::DgCubic => dg_cubic_basis(h),
        }
    }

    /// Number of local DOFs per element.
    pub fn local_dim(self) -> usize {
        match self {
            Space::Hermite | Space::DgCubic => 4,
            Space::Linear => 2,
        }
    }

    /// Number of global DOFs on `n_elements` elements after the clamp.
    pub fn global_dim(self, n_elements: usize) -> usize {
        match self {
            Space::Hermite => 2 * n_elements,
            Space::Linear => n_elements,
            Space::DgCubic => 4 * n_elements,
        }
    }

    /// Global index of local DOF `local` of element `elem`, or `None` if the
    /// clamp at `x = 0` removes it.
    pub fn global_index(self, elem: usize, local: usize) -> Option<usize> {
        match self {
            Space::Hermite => (2 * elem + local).checked_sub(2),
            Space::Linear => (elem + local).checked_sub(1),
            Space::DgCubic => Some(4 * elem + local),
        }
    }
}

fn poly(coeffs: &[BigRational]) -> Poly {
    Poly::new(coeffs.to_vec())
}

/// Cubic Hermite shape functions on `[0, h]` in DOF order `w(0), w'(0), w(h), w'(h)`:
/// `N1 = 1 − 3ξ² + 2ξ³`, `N2 = h(ξ − 2ξ² + ξ³)`, `N3 = 3ξ² − 2ξ³`,
/// `N4 = h(ξ³ − ξ²)` with `ξ = x/h`.
pub fn hermite_basis(h: &BigRational) -> Vec<Poly> {
    let z = BigRational::zero;
    let h2 = h * h;
    let h3 = &h2 * h;
    vec![
        poly(&[int(1), z(), int(-3) / &h2, int(2) / &h3]),
        poly(&[z(), int(1), int(-2) / h, int(1) / &h2]),
        poly(&[z(), z(), int(3) / &h2, int(-2) / &h3]),
        poly(&[z(), z(), int(-1) / h, int(1) / &h2]),
    ]
}

/// Linear Lagrange shape functions on `[0, h]`: `1 − x/h`, `x/h`.
pub fn linear_basis(h: &BigRational) -> Vec<Poly> {
    vec![poly(&[int(1), -BigRational::one() / h]), poly(&[BigRational::zero(), BigRational::one() / h])]
}

/// Shifted Legendre polynomials `P_k(2x/h − 1)`, `k = 0..3`, on `[0, h]`:
/// `1`, `2ξ − 1`, `6ξ² − 6ξ + 1`, `20ξ³ − 30ξ² + 12ξ − 1` with `ξ = x/h`.
pub fn dg_cubic_basis(h: &BigRational) -> Vec<Poly> {
    let xi = Poly::x().scale(&(BigRational::one() / h));
    let p = |c: [i64; 4]| poly(&c.map(int)).compose(&xi);
    vec![p([1, 0, 0, 0]), p([-1, 2, 0, 0]), p([1, -6, 6, 0]), p([-1, 12, -30, 20])]
}

/// Gram matrix `G[i][j] = ∫_0^h a_i(x) b_j(x) dx`, exactly.
pub fn gram(a: &[Poly], b: &[Poly], h: &BigRational) -> RationalMatrix {
    let zero = BigRational::zero();
    RationalMatrix::from_fn(a.len(), b.len(), |i, j| (&a[i] * &b[j]).integrate(&zero, h))
}

fn derivs(basis: &[Poly], order: usize) -> Vec<Poly> {
    basis.iter().map(|p| (0..order).fold(p.clone(), |q, _| q.derivative())).collect()
}

/// Hermite element mass `∫ N_i N_j` (4 × 4, units of h).
pub fn hermite_mass(h: &BigRational) -> RationalMatrix {
    let b = hermite_basis(h);
    gram(&b, &b, h)
}

/// Hermite element bending stiffness `∫ N_i'' N_j''` (4 × 4, multiply by EI).
pub fn hermite_stiffness(h: &BigRational) -> RationalMatrix {
    let b = derivs(&hermite_basis(h), 2);
    gram(&b, &b, h)
}

/// Linear element mass `∫ L_i L_j` (2 × 2).
pub fn linear_mass(h: &BigRational) -> RationalMatrix {
    let b = linear_basis(h);
    gram(&b, &b, h)
}

/// Linear element stiffness `∫ L_i' L_j'` (2 × 2, multiply by GJ).
pub fn linear_stiffness(h: &BigRational) -> RationalMatrix {
    let b = derivs(&linear_basis(h), 1);
    gram(&b, &b, h)
}

/// Cross mass `∫ N_i L_j`: rows Hermite (4), columns linear (2).
pub fn hermite_linear_cross_mass(h: &BigRational) -> RationalMatrix {
    gram(&hermite_basis(h), &linear_basis(h), h)
}

/// DG-cubic element mass `∫ P_i P_j` = `diag(h, h/3, h/5, h/7)`.
pub fn dg_cubic_mass(h: &BigRational) -> RationalMatrix {
    let b = dg_cubic_basis(h);
    gram(&b, &b, h)
}

/// Cross mass `∫ N_i P_j`: rows Hermite (4), columns DG cubic (4).
pub fn hermite_dg_cross_mass(h: &BigRational) -> RationalMatrix {
    gram(&hermite_basis(h), &dg_cubic_basis(h), h)
}

/// Cross mass `∫ L_i P_j`: rows linear (2), columns DG cubic (4).
pub fn linear_dg_cross_mass(h: &BigRational) -> RationalMatrix {
    gram(&linear_basis(h), &dg_cubic_basis(h), h)
}

/// A uniform mesh of `elements` elements on `[0, length]`, clamped at 0.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ClampedMesh {
    length: BigRational,
    elements: usize,
}

impl ClampedMesh {
    /// A mesh on `[0, length]` (`length` > 0, e.g. the semi-span in metres)
    /// with `elements` ≥ 1 equal elements.
    ///
    /// # Panics
    /// If `elements == 0` or `length ≤ 0`.
    pub fn new(length: BigRational, elements: usize) -> Self {
        assert!(elements > 0, "mesh needs at least one element");
        assert!(length.is_positive(), "mesh length must be positive");
        Self { length, elements }
    }

    /// Total length `s`.
    pub fn length(&self) -> &BigRational {
        &self.length
    }

    /// Number of elements `N`.
    pub fn elements(&self) -> usize {
        self.elements
    }

    /// Element length `h = s / N`.
    pub fn h(&self) -> BigRational {
        &self.length / int(self.elements as i64)
    }

    /// Scatters the same element matrix (rows in `row` space, columns in
    /// `col` space) into the global clamped matrix, dropping clamped DOFs.
    ///
    /// # Panics
    /// If `element` is not `row.local_dim() × col.local_dim()`.
    pub fn assemble(&self, row: Space, col: Space, element: &RationalMatrix) -> RationalMatrix {
        assert_eq!(
            (element.rows(), element.cols()),
            (row.local_dim(), col.local_dim()),
            "element matrix shape does not match the spaces"
        );
        let n = self.elements;
        let mut global = RationalMatrix::zeros(row.global_dim(n), col.global_dim(n));
        for e in 0..n {
            for a in 0..row.local_dim() {
                let Some(gi) = row.global_index(e, a) else {
                    continue;
                };
                for b in 0..col.local_dim() {
                    let Some(gj) = col.global_index(e, b) else {
                        continue;
                    };
                    let v = element.get(a, b);
                    if !v.is_zero() {
                        global.add_to(gi, gj, v);
                    }
                }
            }
        }
        global
    }

    /// Global mass/cross-mass `∫ φ_i ψ_j` over `[0, s]` with `φ` from `row`
    /// and `ψ` from `col` (symmetric when `row == col`).
    pub fn mass(&self, row: Space, col: Space) -> RationalMatrix {
        let h = self.h();
        let el = gram(&row.basis(&h), &col.basis(&h), &h);
        self.assemble(row, col, &el)
    }

    /// Global Hermite bending stiffness `∫ w_i'' w_j''` (2N × 2N, times EI).
    pub fn hermite_stiffness(&self) -> RationalMatrix {
        self.assemble(Space::Hermite, Space::Hermite, &hermite_stiffness(&self.h()))
    }

    /// Global linear torsion stiffness `∫ θ_i' θ_j'` (N × N, times GJ).
    pub fn linear_stiffness(&self) -> RationalMatrix {
        self.assemble(Space::Linear, Space::Linear, &linear_stiffness(&self.h()))
    }
}
