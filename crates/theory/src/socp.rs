//! A small builder for the second-order-cone programs of the μ-conditions, solved by clarabel.

use std::sync::Arc;

use clarabel::algebra::CscMatrix;
use clarabel::solver::{DefaultSettingsBuilder, DefaultSolver, IPSolver, SolverStatus, SupportedConeT};

use crate::numerics::PencilError;

/// min cᵀx s.t. linear inequalities `row·x ≤ rhs` and rotated cones u·η ≥ k (u, η ≥ 0).
#[derive(Debug, Clone, Default)]
pub struct Socp {
    /// Number of variables.
    pub n: usize,
    /// Objective coefficients (length n).
    pub cost: Vec<f64>,
    /// Inequalities: sparse row, right-hand side.
    pub le: Vec<(Vec<(usize, f64)>, f64)>,
    /// Rotated cones (u, η, k): u·η ≥ k with u, η ≥ 0.
    pub hyperbolic: Vec<(usize, usize, f64)>,
}

/// Outcome of a solve; infeasibility is an answer.
#[derive(Debug, Clone, PartialEq)]
pub struct SocpOutcome {
    /// Clarabel's status.
    pub status: SolverStatus,
    /// Primal solution (meaningful when solved).
    pub x: Vec<f64>,
    /// Optimal objective.
    pub objective: f64,
    /// Solve time (s).
    pub seconds: f64,
}

impl SocpOutcome {
    /// Clarabel found a primal infeasibility certificate.
    pub fn infeasible(&self) -> bool {
        matches!(self.status, SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible)
    }
}

impl Socp {
    /// A problem in n variables with zero cost.
    pub fn new(n: usize) -> Self {
        Socp { n, cost: vec![0.0; n], ..Default::default() }
    }

    /// Add `row·x ≤ rhs`.
    pub fn le(&mut self, row: Vec<(usize, f64)>, rhs: f64) -> &mut Self {
        self.le.push((row, rhs));
        self
    }

    /// Add u·η ≥ k with u, η ≥ 0.
    pub fn hyperbolic(&mut self, u: usize, eta: usize, k: f64) -> &mut Self {
        self.hyperbolic.push((u, eta, k));
        self
    }

    /// Solve with clarabel (quiet, default tolerances).
    pub fn solve(&self) -> Result<SocpOutcome, PencilError> {
        let (mut ri, mut ci, mut vals, mut rhs) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let mut row = 0;
        for (r, b) in &self.le {
            for &(c, v) in r {
                ri.push(row);
                ci.push(c);
                vals.push(v);
            }
            rhs.push(*b);
            row += 1;
        }
        let mut cones = vec![SupportedConeT::NonnegativeConeT(self.le.len())];
        // u·η ≥ k ⟺ ‖(2√k, u − η)‖ ≤ u + η; slack s = rhs − A x = (u + η, 2√k, u − η).
        for &(u, eta, k) in &self.hyperbolic {
            for (c, v) in [(u, -1.0), (eta, -1.0)] {
                ri.push(row);
                ci.push(c);
                vals.push(v);
            }
            rhs.push(0.0);
            rhs.push(2.0 * k.sqrt());
            for (c, v) in [(u, -1.0), (eta, 1.0)] {
                ri.push(row + 2);
                ci.push(c);
                vals.push(v);
            }
            rhs.push(0.0);
            row += 3;
            cones.push(SupportedConeT::SecondOrderConeT(3));
        }
        let a = CscMatrix::new_from_triplets(row, self.n, ri, ci, vals);
        let p = CscMatrix::zeros((self.n, self.n));
        let settings = DefaultSettingsBuilder::default()
            .verbose(false)
            .build()
            .map_err(|e| PencilError::SolverSettings(Arc::new(e)))?;
        let mut solver = DefaultSolver::new(&p, &self.cost, &a, &rhs, &cones, settings)
            .map_err(|e| PencilError::SolverSetup(Arc::new(e)))?;
        solver.solve();
        let s = &solver.solution;
        Ok(SocpOutcome { status: s.status, x: s.x.clone(), objective: s.obj_val, seconds: s.solve_time })
    }
}
