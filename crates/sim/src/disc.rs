//! A spatial discretisation of the coupled wing: sparse symmetric mass and stiffness
//! matrices, the distributed-load vector, the tip degrees of freedom, the initial state and
//! the interpolation onto an output grid. Built by [`crate::fd`] or [`crate::fe`]
//! from the shared pieces of [`crate::assembly`].

use wingcheck_model::{Config, Method};

pub use crate::assembly::{Interpolation, Parts};
use crate::sparse::SymMatrix;
use crate::strain::StrainForm;

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
