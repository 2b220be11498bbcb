//! A spatial discretisation of the coupled wing: sparse symmetric mass and stiffness
//! matrices, the distributed-load vector, the tip degrees of freedom, the initial state and
//! the interpolation onto an output grid. Built by [`crate::fd`] or [`crate::fe`].

use wingcheck_model::{Config, InitialShape, Method, Wing};

use crate::sparse::{SymBuilder, SymMatrix};
use crate::strain::{StrainForm, StrainRow};

/// Unit-coefficient parts of the discretised quadratic forms, each over the full unknown vector:
/// `mass_qq` ≈ ∫q v, `mass_tt` ≈ ∫θ φ, `mass_qt` ≈ ∫(q φ + θ v) (symmetric cross term),
/// `stiff_qq` ≈ ∫q'' v'', `stiff_tt` ≈ ∫θ' φ'. The wing's matrices are
/// M = ρ·mass_qq + I_p·mass_tt − ρx_c·mass_qt and K = EI·stiff_qq + GJ·stiff_tt.
#[derive(Debug, Clone)]
pub struct Parts {
    /// ∫ q v dz.
    pub mass_qq: SymMatrix,
    /// ∫ θ φ dz.
    pub mass_tt: SymMatrix,
    /// ∫ (q φ + θ v) dz: the symmetric bending–torsion cross mass.
    pub mass_qt: SymMatrix,
    /// ∫ q'' v'' dz.
    pub stiff_qq: SymMatrix,
    /// ∫ θ' φ' dz.
    pub stiff_tt: SymMatrix,
}

/// Sparse rows (index, weight) that evaluate q and θ at the points of an output grid.
#[derive(Debug, Clone)]
pub struct Interpolation {
    /// Grid points z_j (m).
    pub z: Vec<f64>,
    /// Row j evaluates q(z_j).
    pub q_rows: Vec<Vec<(usize, f64)>>,
    /// Row j evaluates θ(z_j).
    pub theta_rows: Vec<Vec<(usize, f64)>>,
}

impl Interpolation {
    /// Evaluate q (or θ) rows on a state vector.
    pub fn eval(rows: &[Vec<(usize, f64)>], x: &[f64]) -> Vec<f64> {
        rows.iter().map(|r| r.iter().map(|&(i, w)| w * x[i]).sum()).collect()
    }
}

/// The semi-discrete wing M ẍ + ξ K ẋ + K x = φ(t) f_h + e_q (τ1 + g1) + e_θ (τ2 + g2)
/// (weak form of the corrected (9)–(10): tip loads enter as point loads at the tip).
#[derive(Debug, Clone)]
pub struct Discretisation {
    /// FD or FE.
    pub method: Method,
    /// Number of elements / grid intervals N.
    pub elements: usize,
    /// Span s (m).
    pub span: f64,
    /// Unit-coefficient parts.
    pub parts: Parts,
    /// Mass matrix M.
    pub mass: SymMatrix,
    /// Stiffness matrix K (elastic energy ½ xᵀKx = ½∫(EI q''² + GJ θ'²)).
    pub stiffness: SymMatrix,
    /// The same stiffness in factored form K = Gᵀ D G (accurate K⁻¹ for the eigen-solve).
    pub strain: StrainForm,
    /// Distributed-load shape f_h = ∫ slope·z·(N_q − x_ac N_θ) dz; the load is φ(t)·f_h.
    pub load: Vec<f64>,
    /// Index of the tip displacement q(s) in the unknown vector.
    pub tip_q: usize,
    /// Index of the tip twist θ(s).
    pub tip_theta: usize,
    /// Initial displacement vector x(0) (velocities are zero).
    pub x0: Vec<f64>,
    /// Output-grid interpolation.
    pub interp: Interpolation,
}

impl Discretisation {
    /// Build the discretisation the configuration asks for.
    pub fn new(cfg: &Config) -> Discretisation {
        Self::with(cfg, cfg.discretisation.method, cfg.discretisation.grid_size())
    }

    /// Build with an explicit method and element count (for refinement studies).
    pub fn with(cfg: &Config, method: Method, elements: usize) -> Discretisation {
        let raw = match method {
            Method::Fd => crate::fd::assemble(cfg, elements),
            Method::Fe => crate::fe::assemble(cfg, elements),
        };
        let w = &cfg.wing;
        let mass = SymMatrix::combine(&[
            (w.rho, &raw.parts.mass_qq),
            (w.ip, &raw.parts.mass_tt),
            (-w.rho_xc, &raw.parts.mass_qt),
        ]);
        let stiffness = SymMatrix::combine(&[(w.ei, &raw.parts.stiff_qq), (w.gj, &raw.parts.stiff_tt)]);
        let mut strain_rows = StrainForm::scaled(raw.strain_q, w.ei);
        strain_rows.extend(StrainForm::scaled(raw.strain_t, w.gj));
        let strain = StrainForm { rows: strain_rows };
        let load: Vec<f64> = raw
            .load_q
            .iter()
            .zip(&raw.load_t)
            .map(|(q, t)| cfg.disturbance.distributed.slope * (q - w.x_ac * t))
            .collect();
        Discretisation {
            method,
            elements,
            span: w.span,
            parts: raw.parts,
            mass,
            stiffness,
            strain,
            load,
            tip_q: raw.tip_q,
            tip_theta: raw.tip_theta,
            x0: raw.x0,
            interp: raw.interp,
        }
    }

    /// Number of unknowns.
    pub fn dim(&self) -> usize {
        self.mass.dim()
    }

    /// Mechanical energy E = ½ vᵀ M v + ½ xᵀ K x (J): the discrete form of
    /// ½∫(ρq̇² − 2ρx_c q̇θ̇ + I_pθ̇² + EI q''² + GJ θ'²) dz.
    pub fn energy(&self, x: &[f64], v: &[f64]) -> f64 {
        0.5 * self.mass.form(v, v) + 0.5 * self.stiffness.form(x, x)
    }
}

/// What an assembler returns (unit-coefficient parts; the wing's coefficients are applied
/// by [`Discretisation::with`]).
pub(crate) struct RawAssembly {
    pub parts: Parts,
    /// ∫ z N_q dz (unit slope).
    pub load_q: Vec<f64>,
    /// ∫ z N_θ dz (unit slope).
    pub load_t: Vec<f64>,
    pub tip_q: usize,
    pub tip_theta: usize,
    pub x0: Vec<f64>,
    pub interp: Interpolation,
    /// Unit-weight bending strain rows (∫q''² = Σ weight (g·x)²), in substitution order.
    pub strain_q: Vec<StrainRow>,
    /// Unit-weight torsion strain rows (∫θ'² = Σ weight (g·x)²), in substitution order.
    pub strain_t: Vec<StrainRow>,
}

/// Initial bending displacement q(z,0) and slope q'(z,0) for the configured shape.
pub(crate) fn initial_q(cfg: &Config, z: f64) -> (f64, f64) {
    let s = cfg.wing.span;
    let a = cfg.initial.q_tip;
    match cfg.initial.shape {
        // Paper: q(z,0) = z/s. The clamp q'(0) = 0 is imposed at the root node only.
        InitialShape::Linear => (a * z / s, if z == 0.0 { 0.0 } else { a / s }),
        InitialShape::Cantilever => {
            (a * z * z * (3.0 * s - z) / (2.0 * s.powi(3)), a * 3.0 * z * (2.0 * s - z) / (2.0 * s.powi(3)))
        }
    }
}

/// Initial twist θ(z,0) = θ_tip z/s (paper: θ_tip = π/2).
pub(crate) fn initial_theta(cfg: &Config, z: f64) -> f64 {
    cfg.initial.theta_tip * z / cfg.wing.span
}

/// Output grid z_j = j s/(P − 1).
pub(crate) fn output_grid(cfg: &Config) -> Vec<f64> {
    let p = cfg.horizon.field_points;
    (0..p).map(|j| cfg.wing.span * j as f64 / (p - 1) as f64).collect()
}

/// Unit-coefficient builders of dimension n, in the order of [`Parts`].
pub(crate) fn builders(n: usize) -> [SymBuilder; 5] {
    std::array::from_fn(|_| SymBuilder::new(n))
}

/// Turn the five builders into [`Parts`].
pub(crate) fn finish(b: [SymBuilder; 5]) -> Parts {
    let [mqq, mtt, mqt, kqq, ktt] = b;
    Parts {
        mass_qq: mqq.build(),
        mass_tt: mtt.build(),
        mass_qt: mqt.build(),
        stiff_qq: kqq.build(),
        stiff_tt: ktt.build(),
    }
}

/// Mass-matrix determinant condition ρ I_p − (ρx_c)² (> 0 by validation).
pub fn mass_determinant(w: &Wing) -> f64 {
    w.rho * w.ip - w.rho_xc * w.rho_xc
}
