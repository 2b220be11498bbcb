//! What the two assemblers ([`crate::fd`], [`crate::fe`]) share and return: the
//! unit-coefficient parts of the quadratic forms, the output interpolation, the initial shape
//! and the raw assembly [`crate::disc::Discretisation`] is built from. A leaf: it knows neither
//! assembler nor the discretisation.

use wingcheck_model::{Config, InitialShape};

use crate::sparse::{SymBuilder, SymMatrix};
use crate::strain::StrainRow;

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

/// What an assembler returns (unit-coefficient parts; the wing's coefficients are applied
/// by [`crate::disc::Discretisation::with`]).
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
