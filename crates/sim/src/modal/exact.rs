//! The `exponential` time scheme: the semi-discrete closed loop advanced *exactly* over each
//! integrator step with its inputs held (ĝ_k exactly, ḡ and φ̄ as their step means, as the other
//! schemes hold them), and the exact ∫τ² dt of both channels over the step.
//!
//! Between two steps' ends the loop is linear time-invariant: in the state
//! X = (p, ζ, w, u) with p_i = ω_i η_i (energy coordinates, so the uncontrolled part is a
//! contraction), the tip boundary states w (ξ S ẇ = s(τ + g) − S w) and the held inputs
//! u = (ḡ1 − ĝ1, ḡ2 − ĝ2, φ̄, ĝ1, ĝ2) (u̇ = 0), Ẋ = A X, so X(t + h) = e^{Ah} X(t) and
//! ∫_0^h τ_c² = Xᵀ Q_c X with the Gramian Q_c = ∫_0^h e^{Aᵀs} c_c c_cᵀ e^{As} ds of the output
//! row τ_c = c_cᵀ X. Both come from one scaling-and-squaring chain: at s₀ = h/2^m with
//! ‖A s₀‖₁ ≤ ¼, e^{As₀} by its Taylor series and Q_c(s₀) by the series of e^{Aᵀs}c integrated
//! term by term; then m doublings E(2s) = E(s)², carried as F = E − I (F ← 2F + F²), and
//! Q(2s) = Q(s) + E(s)ᵀQ(s)E(s). (Van Loan's
//! block exponential would need e^{−Aᵀh}, which overflows: the stiff Kelvin–Voigt modes decay
//! at ξω² ≫ 1/h.) Q_c is carried through the doublings as an eigenvalue-truncated factor L
//! (Q = LLᵀ, L(2s) = [L, EᵀL] compressed to rank r_c), and applied as ∫τ² = Σ_j (f_jᵀX)² with
//! the columns f_j of L.
//!
//! Work: O(N³ log(‖A‖h)) once per run for E (one N×N product per doubling; the Gramians add
//! O(N² r_c) each), N = 2n + 2 + 5 (2n + 5 with ξ = 0: no tip states), then one dense
//! (2n + 2 + r1 + r2)×N product per step ([`super::gemv`]; r_c ≈ 23 each on the default
//! grid). `wingcheck bench` prints its cost against TR-BDF2's in the same run. What it buys: τ
//! statistics that do not depend on dt at a fixed observer period, however the held estimate
//! jumps (the explicit FTDO alternates at the sample rate, which one TR-BDF2 step per sample
//! resolves only to 1–2 % in RMS τ).

use std::sync::Arc;

use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, Par, Side};

use crate::{NumericalError, SimError};

use super::closed_loop::{closed_loop, LoopCoefficients, INPUTS};
use super::gemv::RowMajor;
use super::memo::{Key, Memo};
use super::probe::{ProbeBuilder, ProbedStep, SubStepProbe, TauRows, PROBED};
use super::{ModalBasis, ModalState};

/// Taylor degree of e^{As₀} and of e^{Aᵀs}c on [0, s₀] with ‖As₀‖₁ ≤ ¼: the remainder is below
/// (¼)^{19}/19! ≈ 2e-29 relative.
const TAYLOR_DEGREE: usize = 18;
/// ‖A s₀‖₁ bound of the Taylor start.
const START_NORM: f64 = 0.25;
/// Gramian eigenvalues below this fraction of the largest are dropped from its factor, at the
/// Taylor start and at every doubling ([`compress`]); a dropped part δQ reaches the final Q as
/// E(s)ᵀδQ E(s) through the later doublings, so the truncations together stay of the same order
/// (‖E(s)‖ ≤ e^{‖A‖s}, and ‖A s‖ ≤ ¼ at the start). The computed Q carries an absolute round-off of order ε‖Q‖ in every entry anyway, so the quadratic
/// form XᵀQX has an error of order ε‖Q‖·|X|² with or without the truncation, which adds at most
/// N·1e-15·‖Q‖·|X|² (in the state's own coordinates: energy coordinates for the modes, the tip
/// states and the held inputs in their units). Measured: rank 23 of 151 on the default grid, 38
/// on an SI-scale wing; the runs' RMS τ agree with TR-BDF2's dt → 0 limit (tests/exponential.rs).
const GRAMIAN_CUTOFF: f64 = 1e-15;

/// The closed loop's transition over one step and its τ Gramians, built once per run.
#[derive(Debug)]
pub(crate) struct ExactStep {
    n: usize,
    /// 2 if ξ > 0 (w is a state), 0 if ξ = 0 (w algebraic).
    tip_states: usize,
    /// ω_i (1/s).
    omega: Vec<f64>,
    /// One operator applied per step: rows 0..2n + tip_states of e^{Ah}, then the rows f_j of
    /// the τ1 Gramian's factor, then those of τ2's (∫_0^h τ_c² = Σ_j (f_j · X)²); padded
    /// row-major ([`RowMajor`]).
    operator: RowMajor,
    /// Ranks of the two Gramian factors.
    ranks: [usize; 2],
    /// The exact outputs inside a step ([`super::probe`]), from the same chain.
    probe: SubStepProbe,
}

/// A factor of Q = LLᵀ with at most rank(L) columns and Q's eigenvalues below
/// [`GRAMIAN_CUTOFF`] × its largest dropped: the columns L v_i = √μ_i u_i of LV for the
/// eigenpairs (μ_i, v_i) of LᵀL above the cutoff (Q's nonzero eigenvalues are those of LᵀL,
/// with eigenvectors u_i = Lv_i/√μ_i). Work O(N k²) for k columns, instead of the O(N³) of
/// forming and decomposing Q.
fn compress(l: &Mat<f64>) -> Result<Mat<f64>, SimError> {
    let k = l.ncols();
    let gram = l.transpose() * l;
    let gram = Mat::from_fn(k, k, |i, j| 0.5 * (gram[(i, j)] + gram[(j, i)]));
    let evd = gram
        .self_adjoint_eigen(Side::Lower)
        .map_err(|_| NumericalError::Decomposition { what: "exponential scheme: the Gramian eigenproblem" })?;
    let top = (0..k).map(|i| evd.S()[i]).fold(0.0, f64::max);
    let keep: Vec<usize> = (0..k).filter(|&i| evd.S()[i] > GRAMIAN_CUTOFF * top).collect();
    let v = Mat::from_fn(k, keep.len(), |r, c| evd.U()[(r, keep[c])]);
    Ok(l * &v)
}

/// Powers of X in each block of [`expm1_taylor`]'s Horner scheme.
const BLOCK: usize = 4;

/// e^X − I = Σ_{k=1}^{K} X^k/k! (K = [`TAYLOR_DEGREE`]) by Paterson–Stockmeyer: X², X³,
/// Y = X⁴, then Horner's scheme in Y over blocks B_j = Σ_{r<4} X^r/(4j + r)! (no identity
/// term: the small F of a slow mode is never formed as a difference). 7 products of N × N
/// matrices where Horner's scheme in X takes K = 18; the same truncation.
fn expm1_taylor(x: &Mat<f64>) -> Mat<f64> {
    let n = x.nrows();
    let product = |a: &Mat<f64>, b: &Mat<f64>| {
        let mut c = Mat::<f64>::zeros(n, n);
        matmul(c.as_mut(), Accum::Replace, a.as_ref(), b.as_ref(), 1.0, Par::Seq);
        c
    };
    let x2 = product(x, x);
    let x3 = product(&x2, x);
    let y = product(&x2, &x2);
    // 1/k! for k ≤ K (k! is exact in f64 up to 18!), 0 for k = 0 and beyond K
    let coefficient = |k: usize| {
        if k == 0 || k > TAYLOR_DEGREE {
            0.0
        } else {
            1.0 / (1..=k).map(|i| i as f64).product::<f64>()
        }
    };
    let block = |j: usize| {
        let c = [0, 1, 2, 3].map(|r| coefficient(BLOCK * j + r));
        Mat::from_fn(n, n, |r, q| {
            let identity = if r == q { c[0] } else { 0.0 };
            identity + c[1] * x[(r, q)] + c[2] * x2[(r, q)] + c[3] * x3[(r, q)]
        })
    };
    let top = TAYLOR_DEGREE / BLOCK;
    let mut sum = block(top);
    for j in (0..top).rev() {
        sum = product(&y, &sum);
        let b = block(j);
        for q in 0..n {
            for r in 0..n {
                sum[(r, q)] += b[(r, q)];
            }
        }
    }
    sum
}

/// e ← I + f.
fn identity_plus(f: &Mat<f64>, e: &mut Mat<f64>) {
    for j in 0..f.ncols() {
        for i in 0..f.nrows() {
            e[(i, j)] = f[(i, j)] + if i == j { 1.0 } else { 0.0 };
        }
    }
}

/// The dense set-ups kept for the next run of the same loop and step.
static SETUPS: Memo<ExactStep> = Memo::new();

impl ExactStep {
    /// [`ExactStep::new`], or the same set-up kept from an earlier run of this loop and step
    /// ([`super::memo`]: the same bits).
    pub(crate) fn shared(basis: &ModalBasis, co: &LoopCoefficients, h: f64) -> Result<Arc<ExactStep>, SimError> {
        SETUPS.get_or_try(Key::of(basis, co, Some(h)), || ExactStep::new(basis, co, h))
    }

    /// e^{Ah} and the Gramians for step h (s) of the loop on `basis`.
    pub(crate) fn new(basis: &ModalBasis, co: &LoopCoefficients, h: f64) -> Result<ExactStep, SimError> {
        let n = basis.len();
        if basis.omega2.iter().any(|w| !(w.is_finite() && *w > 0.0)) {
            return Err(NumericalError::NonPositiveMode.into());
        }
        let omega: Vec<f64> = basis.omega2.iter().map(|w| w.sqrt()).collect();
        let tip_states = if co.xi > 0.0 { 2 } else { 0 };
        let len = 2 * n + tip_states + INPUTS;
        let (a, outputs) = closed_loop(basis, co, &omega, tip_states);
        let norm = (0..len).map(|j| (0..len).map(|i| a[(i, j)].abs()).sum::<f64>()).fold(0.0, f64::max);
        if !(norm.is_finite() && h.is_finite() && h > 0.0) {
            return Err(NumericalError::StepNorm { norm, h }.into());
        }
        let doublings = ((norm * h / START_NORM).log2().ceil().max(0.0)) as u32;
        if doublings > 200 {
            return Err(NumericalError::StepNormRange { norm_h: norm * h }.into());
        }
        let s0 = h / 2f64.powi(doublings as i32);
        let a_s0 = Mat::from_fn(len, len, |i, j| a[(i, j)] * s0);
        // F = e^{As₀} − I, carried as such through the doublings (F ← 2F + F², E = I + F): the
        // slow modes' motion over s₀ is in the small F, which I + F would round away, and the
        // rounding error of E would grow as 2^m over the squarings.
        let mut f = expm1_taylor(&a_s0);
        let mut next = Mat::<f64>::zeros(len, len);
        let mut e = Mat::<f64>::zeros(len, len);
        // Q_c(s₀) = s₀ Σ_jk d_j d_kᵀ/(j + k + 1) = D H Dᵀ with d_j = (s₀Aᵀ)^j c/j! the columns
        // of D and H_jk = s₀/(j + k + 1), carried as a factor L (Q = LLᵀ): L = D W Λ^½ from
        // H = WΛWᵀ, then L(2s) = [L(s), E(s)ᵀL(s)] at every doubling, compressed ([`compress`]).
        let terms = TAYLOR_DEGREE + 1;
        let hilbert = Mat::from_fn(terms, terms, |j, k| s0 / (j + k + 1) as f64);
        let hilbert_root = {
            let evd = hilbert.self_adjoint_eigen(Side::Lower).map_err(|_| NumericalError::Decomposition {
                what: "exponential scheme: the Taylor Gramian's eigenproblem",
            })?;
            let top = (0..terms).map(|i| evd.S()[i]).fold(0.0, f64::max);
            let keep: Vec<usize> = (0..terms).filter(|&i| evd.S()[i] > GRAMIAN_CUTOFF * top).collect();
            Mat::from_fn(terms, keep.len(), |r, c| evd.U()[(r, keep[c])] * evd.S()[keep[c]].sqrt())
        };
        let mut factors = Vec::with_capacity(2);
        for c in &outputs {
            let mut d = Mat::<f64>::zeros(len, terms);
            for (r, v) in c.iter().enumerate() {
                d[(r, 0)] = *v;
            }
            for j in 1..terms {
                let (prev, rest) = d.as_mut().split_at_col_mut(j);
                matmul(
                    rest.col_mut(0).as_mat_mut(),
                    Accum::Replace,
                    a_s0.transpose(),
                    prev.col(j - 1).as_mat(),
                    1.0 / j as f64,
                    Par::Seq,
                );
            }
            factors.push(compress(&(&d * &hilbert_root))?);
        }
        // the probe's rows: q(s) = Σ U_0j p_j/ω_j, θ(s) likewise, q̇(s) = Σ U_0j ζ_j, θ̇(s)
        // likewise; τ_c = −k_c(a x_c + b v_c) − ĝ_c from them (the output rows c_c are exactly
        // this combination, [`closed_loop`])
        let tip_row = |c: usize| {
            let mut row = vec![0.0; len];
            for j in 0..n {
                row[j] = basis.tip[c][j] / omega[j];
            }
            row
        };
        let rate_row = |c: usize| {
            let mut row = vec![0.0; len];
            row[n..2 * n].copy_from_slice(&basis.tip[c][..n]);
            row
        };
        let rows = [tip_row(0), tip_row(1), rate_row(0), rate_row(1)];
        let tau = TauRows {
            gain_x: [0, 1].map(|c| -co.gain[c] * co.a),
            gain_v: [0, 1].map(|c| -co.gain[c] * co.b),
            g_hat_at: [0, 1].map(|c| 2 * n + tip_states + 3 + c),
        };
        let mut probe = ProbeBuilder::new(rows, tau, s0, doublings);
        for level in 0..doublings {
            identity_plus(&f, &mut e);
            probe.level(level, &e);
            for l in factors.iter_mut() {
                // Q ← Q + EᵀQE: L ← [L, EᵀL]
                let k = l.ncols();
                let mut wide = Mat::<f64>::zeros(len, 2 * k);
                wide.as_mut().submatrix_mut(0, 0, len, k).copy_from(l.as_ref());
                matmul(
                    wide.as_mut().submatrix_mut(0, k, len, k),
                    Accum::Replace,
                    e.transpose(),
                    l.as_ref(),
                    1.0,
                    Par::Seq,
                );
                *l = compress(&wide)?;
            }
            // F ← 2F + F²
            matmul(next.as_mut(), Accum::Replace, f.as_ref(), f.as_ref(), 1.0, Par::Seq);
            for j in 0..len {
                for i in 0..len {
                    f[(i, j)] = 2.0 * f[(i, j)] + next[(i, j)];
                }
            }
        }
        identity_plus(&f, &mut e);
        let rows = 2 * n + tip_states;
        let ranks = [factors[0].ncols(), factors[1].ncols()];
        let factor_rows: Vec<Vec<f64>> =
            factors.iter().flat_map(|l| (0..l.ncols()).map(move |k| (0..len).map(|r| l[(r, k)]).collect())).collect();
        let operator =
            Mat::from_fn(
                rows + factor_rows.len(),
                len,
                |i, j| {
                    if i < rows {
                        e[(i, j)]
                    } else {
                        factor_rows[i - rows][j]
                    }
                },
            );
        let operator = RowMajor::new(&operator);
        if !operator.is_finite() {
            return Err(NumericalError::NotFinite { what: "exponential scheme: e^{Ah} or a τ Gramian" }.into());
        }
        let probe = probe.finish(h, &e);
        Ok(ExactStep { n, tip_states, omega, operator, ranks, probe })
    }

    /// Work buffers for [`ExactStep::advance`]: X and the operator's output.
    pub(crate) fn buffers(&self) -> (Vec<f64>, Vec<f64>) {
        (vec![0.0; self.operator.stride()], vec![0.0; self.operator.rows()])
    }

    /// The probe's work buffer ([`SubStepProbe::probe`]).
    pub(crate) fn probe_buffer(&self) -> Vec<f64> {
        self.probe.buffer()
    }

    /// Probe the step [`ExactStep::advance`] made last on `st` (its start state X_k is still in
    /// the work buffer) against the running peaks `running` of q, θ, q̇, θ̇, τ1, τ2 ([`super::probe`];
    /// `exhaustive`: the whole fine grid).
    pub(crate) fn probe_last_step(
        &self,
        st: &ModalState,
        running: [f64; PROBED],
        buf: &mut [f64],
        exhaustive: bool,
    ) -> ProbedStep {
        self.probe.probe(&st.exact_x, running, buf, exhaustive)
    }

    /// Points of the probe's fine grid.
    pub(crate) fn probe_points(&self) -> usize {
        self.probe.fine_points()
    }

    /// Advance (η, ζ, w) of `st` by one step with the held inputs
    /// u = (ḡ1 − ĝ1, ḡ2 − ĝ2, φ̄, ĝ1, ĝ2); returns ∫_step τ_c² dt (N² s, N² m² s). With ξ = 0
    /// the tip states are left to the caller (algebraic). One matrix–vector product.
    pub(crate) fn advance(&self, st: &mut ModalState, inputs: [f64; INPUTS]) -> [f64; 2] {
        let n = self.n;
        let (x, y) = (&mut st.exact_x, &mut st.exact_y);
        for i in 0..n {
            x[i] = self.omega[i] * st.eta[i];
            x[n + i] = st.zeta[i];
        }
        x[2 * n..2 * n + self.tip_states].copy_from_slice(&st.w[..self.tip_states]);
        let inputs_at = 2 * n + self.tip_states;
        x[inputs_at..inputs_at + INPUTS].copy_from_slice(&inputs);
        // x's padding past the state stays 0 (set by `buffers`, never written)
        self.operator.mul_into(x, y);
        for i in 0..n {
            st.eta[i] = y[i] / self.omega[i];
            st.zeta[i] = y[n + i];
        }
        let state = 2 * n + self.tip_states;
        st.w[..self.tip_states].copy_from_slice(&y[2 * n..state]);
        let squares = &y[state..];
        let sum = |v: &[f64]| v.iter().map(|f| f * f).sum::<f64>();
        [sum(&squares[..self.ranks[0]]), sum(&squares[self.ranks[0]..])]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// e^X − I of a damped rotation X = s[[−c, w], [−w, −c]] (‖X‖₁ ≤ ¼) against its closed form
    /// e^{−cs}[[cos ws, sin ws], [−sin ws, cos ws]] − I, the diagonal formed without
    /// cancellation: e^{−cs}cos ws − 1 = expm1(−cs)cos ws − 2 sin²(ws/2).
    #[test]
    fn taylor_expm1_is_the_closed_form_of_a_damped_rotation() {
        for (c, w, s) in [(0.3, 2.0, 0.1), (1e-6, 1.0, 1e-3), (2.0, 0.5, 0.05), (0.0, 1e-4, 1e-2)] {
            let x = Mat::from_fn(2, 2, |i, j| s * [[-c, w], [-w, -c]][i][j]);
            let f = expm1_taylor(&x);
            let (sin, cos) = (w * s).sin_cos();
            let half = (0.5 * w * s).sin();
            let decay = (-c * s).exp();
            let diagonal = (-c * s).exp_m1() * cos - 2.0 * half * half;
            let exact = [[diagonal, decay * sin], [-decay * sin, diagonal]];
            for i in 0..2 {
                for j in 0..2 {
                    let scale = exact[i][j].abs().max(1e-300);
                    let rel = (f[(i, j)] - exact[i][j]).abs() / scale;
                    assert!(rel < 1e-14, "c {c} w {w} s {s} ({i},{j}): {} vs {} ({rel:e})", f[(i, j)], exact[i][j]);
                }
            }
        }
    }

    /// Paterson–Stockmeyer against Horner's scheme in X (the form it replaced) on a dense 40 × 40
    /// matrix scaled to ‖X‖₁ = ¼: the same truncated series, so they differ by round-off only.
    #[test]
    fn taylor_expm1_agrees_with_horners_scheme() {
        let n = 40;
        let raw = Mat::from_fn(n, n, |i, j| ((i * 7 + j * 13) % 17) as f64 - 8.0 + if i == j { -20.0 } else { 0.0 });
        let norm = (0..n).map(|j| (0..n).map(|i| raw[(i, j)].abs()).sum::<f64>()).fold(0.0, f64::max);
        let x = Mat::from_fn(n, n, |i, j| raw[(i, j)] * START_NORM / norm);
        let mut p = Mat::<f64>::identity(n, n);
        for k in (2..=TAYLOR_DEGREE).rev() {
            p = &x * &p * (1.0 / k as f64);
            for i in 0..n {
                p[(i, i)] += 1.0;
            }
        }
        let horner = &x * &p;
        let f = expm1_taylor(&x);
        let diff = (0..n).flat_map(|j| (0..n).map(move |i| (i, j))).map(|(i, j)| (f[(i, j)] - horner[(i, j)]).abs());
        let worst = diff.fold(0.0, f64::max);
        assert!(worst < 1e-15, "{worst:e}");
    }
}
