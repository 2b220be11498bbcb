//! The closed loop's eigendecomposition for [`super::diagonal`]: faer's real eigen-solve, one
//! Newton refinement ([`super::refine`]) and the checks that do not depend on the step or the
//! horizon, kept for the next run of the same loop ([`super::memo`]).

use std::convert::Infallible;
use std::sync::Arc;

use faer::linalg::solvers::DenseSolveCore;
use faer::Mat;

use super::closed_loop::LoopCoefficients;
use super::eigen_solve::real_eigen;
use super::memo::{Key, Memo};
use super::refine::RealEigen;
use super::ModalBasis;

/// Tolerance of the relative residual ‖AV − VΛ‖_F/(‖A‖_F‖V‖_F) of the eigendecomposition.
pub(crate) const RESIDUAL_TOLERANCE: f64 = 1e-10;

/// Why a loop is not stepped in its eigenbasis (the dense scheme is used instead).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Refused(pub(crate) String);

/// x ≤ limit, false for NaN (a refusal).
pub(crate) fn within(x: f64, limit: f64) -> bool {
    x <= limit
}

/// The closed loop's eigendecomposition after one Newton refinement, with the checks that do
/// not depend on the step or the horizon: the part of a [`DiagonalStep`] that runs of one loop
/// share ([`super::memo`]; 0.2 s at 288 unknowns, 1.4 s at 576, O(N³)).
#[derive(Debug)]
pub(crate) struct LoopEigen {
    /// (column of the solver's eigenvalue, weight 1 for a real one or 2 for a pair) per
    /// representative.
    pub(crate) reps: Vec<(usize, f64)>,
    /// The first column of each representative in V_r.
    pub(crate) first_col: Vec<usize>,
    /// The refined decomposition.
    pub(crate) eig: RealEigen,
    /// min |Re λ| (1/s).
    pub(crate) slowest: f64,
    /// ‖A‖_F.
    pub(crate) a_norm: f64,
}

/// The eigendecompositions kept for the next run of the same loop, refusals included.
static EIGEN: Memo<Result<LoopEigen, Refused>> = Memo::new();

impl LoopEigen {
    /// The decomposition of A (m × m), the loop's matrix on `basis` with `co`: the one kept
    /// from an earlier run of this loop, or a new one.
    pub(crate) fn shared(basis: &ModalBasis, co: &LoopCoefficients, a: &Mat<f64>) -> Arc<Result<LoopEigen, Refused>> {
        let kept = EIGEN.get_or_try(Key::of(basis, co, None), || Ok::<_, Infallible>(LoopEigen::new(a)));
        match kept {
            Ok(kept) => kept,
            Err(never) => match never {},
        }
    }

    /// Decompose A (m × m), refine once and check.
    fn new(a: &Mat<f64>) -> Result<LoopEigen, Refused> {
        let m = a.nrows();
        let evd = match real_eigen(a) {
            Ok(e) => e,
            Err(e) => return Err(Refused(format!("eigen-solve failed: {e:?}"))),
        };
        let lambda = evd.values;
        // representatives: faer puts a conjugate pair in adjacent columns, +Im first
        let mut reps: Vec<(usize, f64)> = Vec::with_capacity(m);
        let mut j = 0;
        while j < m {
            if lambda[j].im == 0.0 {
                reps.push((j, 1.0));
                j += 1;
            } else {
                if j + 1 >= m || lambda[j + 1] != lambda[j].conj() {
                    return Err(Refused("eigenvalues not in conjugate pairs".into()));
                }
                reps.push((j, 2.0));
                j += 2;
            }
        }
        if !lambda.iter().all(|l| l.re.is_finite() && l.im.is_finite() && l.re < 0.0) {
            return Err(Refused("an eigenvalue with Re λ ≥ 0".into()));
        }
        let slowest = lambda.iter().map(|l| -l.re).fold(f64::INFINITY, f64::min);
        // V_r: the representatives' (Re v) and, for pairs, (Im v) columns, from column
        // first_col[rep] on; z = Re(V x̂) = V_re x̂_re − V_im x̂_im with the weighted columns below.
        let first_col: Vec<usize> =
            reps.iter().scan(0, |col, &(_, w)| Some(std::mem::replace(col, *col + w as usize))).collect();
        // faer's real form is V_r itself: a pair's (Re v, Im v) in its two columns (the solver's
        // columns are the representatives' first_col)
        let vr = evd.vectors;
        // one Newton step on the decomposition, and the next step's size as its error
        let solved = RealEigen {
            vr_inv: vr.partial_piv_lu().inverse(),
            vr,
            lambda: reps.iter().map(|&(j, _)| lambda[j]).collect(),
            blocks: reps.iter().zip(&first_col).map(|(&(_, w), &c)| (c, w as usize)).collect(),
        };
        let step = solved.correction(a);
        if !within(step.residual, RESIDUAL_TOLERANCE) {
            return Err(Refused(format!("eigendecomposition residual {:.1e}", step.residual)));
        }
        let eig = solved.refined(&step);
        if !eig.lambda.iter().all(|l| l.re.is_finite() && l.im.is_finite() && l.re < 0.0) {
            return Err(Refused("an eigenvalue with Re λ ≥ 0 after refinement".into()));
        }
        let after = eig.residual(a);
        if !within(after, RESIDUAL_TOLERANCE) {
            return Err(Refused(format!("eigendecomposition residual {after:.1e} after refinement")));
        }
        Ok(LoopEigen { reps, first_col, eig, slowest, a_norm: a.norm_l2() })
    }
}
