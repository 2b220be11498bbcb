//! The `exponential` time scheme in the closed loop's own eigenbasis: the same exact transition
//! of the semi-discrete loop with held inputs as [`super::exact`], O(N) work per step instead of
//! a dense N×N product.
//!
//! With z = (p, ζ, w) (p_i = ω_i η_i) and the held inputs u = (ḡ1 − ĝ1, ḡ2 − ĝ2, φ̄, ĝ1, ĝ2),
//! ż = A z + B u. Diagonalise A = VΛV⁻¹ once per run (complex, the conjugate pairs stored
//! once) and carry x̂ = V⁻¹z. Over a step with u held, z relaxes to z*(u) = −A⁻¹Bu, so
//! x̂(h) = μ ⊙ x̂ + (1 − μ) ⊙ ŝ with μ_i = e^{λ_i h} and ŝ = V⁻¹z*(u): O(N).
//!
//! τ_c = c_cᵀz + d_cᵀu = c_cᵀe + τ*_c with e = z − z*(u), ė = Ae. Its square integral over a
//! step is split by the Lyapunov solution P_c = ∫_0^∞ e^{Aᵀs}c_c c_cᵀe^{As} ds (closed form in
//! the eigenbasis, P_ij = −c̄̃_i c̃_j/(λ̄_i + λ_j), c̃ = Vᵀc):
//!
//! ∫_0^h τ² = e₀ᵀPe₀ − e_hᵀPe_h + 2τ* ∫_0^h c̃ᵀe^{Λs}ẽ₀ ds + hτ*².
//!
//! The first two terms telescope over consecutive steps except where u jumps (at every step
//! start): the jump of eᵀPe is −2Δz*ᵀPe + Δz*ᵀPΔz*. Its part in the inputs is a 3 × 3 form;
//! its part in the state, −2Δz*ᵀPVx̂ = −2Σ_k Δu_k (Z_kᵀPV)·x̂, is linear in x̂, so the steps sum
//! Σ Δu_k x̂ (three O(N) sums) and the checkpoint takes the six products once. So each step
//! returns its jump's input part, linear and constant terms, and [`DiagonalStep::checkpoint`]
//! adds the jumps' state part and the boundary terms eᵀPe at the previous and the current
//! checkpoint (every output sample; one O(N²) reconstruction of z and an O(N r) quadratic form
//! with P's low-rank factor).
//! The sum over every interval between two checkpoints is then the exact ∫τ² over it;
//! the single steps' shares are not.
//!
//! The solver's eigendecomposition gets one Newton refinement ([`super::refine`]) before use.
//! Refused (the caller falls back to the dense [`super::exact::ExactStep`]) where the
//! eigenbasis would lose accuracy: a round-off estimate above [`MAX_ROUNDOFF`] (stiff
//! Kelvin–Voigt modes against slow ones; a mode so slowly decaying that the telescoped terms
//! dwarf a step's integral), a nearly defective A (condition of V above [`MAX_CONDITION`]), an
//! eigendecomposition residual above its tolerance, or an eigenvalue not strictly in the left
//! half-plane.

use faer::{c64, Mat};

use super::closed_loop::{closed_loop, LoopCoefficients, INPUTS};
use super::gemv::RowMajor;
use super::layout::{stack, Half, Layout};
use super::loop_eigen::{within, LoopEigen, Refused};
use super::lyapunov::{pivoted_cholesky, real_forms};
use super::woodbury::dot;
use super::{ModalBasis, ModalState};

/// Held inputs that move the state: ḡ1 − ĝ1, ḡ2 − ĝ2, φ̄ (ĝ enters τ only).
const DRIVING: usize = 3;
/// Largest accepted ‖V‖_F‖V⁻¹‖_F (unit eigenvectors): the state is read through V and V⁻¹,
/// so its round-off is of order this × ε relative (≤ 2e-10 here).
pub(crate) const MAX_CONDITION: f64 = 1e6;
/// Largest accepted round-off estimate, relative: ε(‖A‖_F·min(T, 1/s) + cond V + 1/(s h))
/// with T the run's horizon, s the loop's slowest decay rate min|Re λ| and h the step. A dense eigen-solve
/// is backward stable: the eigenpairs are exact for A + E with ‖E‖ of order ε‖A‖, so the
/// stepped trajectory is the exact one of that perturbed loop, and to first order its error is
/// ∫₀ᵗ e^{A(t−τ)} E z(τ) dτ, at most ‖E‖·min(t, 1/s)·sup‖z‖ where the loop contracts at rate s
/// (‖e^{Aτ}‖ ≤ e^{−sτ}, taken in the modal energy norm); the Kelvin–Voigt modes make
/// ‖A‖ ≈ ξω_max² large. The held inputs' equilibrium, reached after 1/s, carries the t → ∞
/// limit ε‖A‖/s of the same bound; reading the state through V and V⁻¹ adds ε·cond V. The
/// ∫τ² terms that telescope (eᵀPe, P_ij = −ḡ_i g_j/(λ̄_i + λ_j)) are up to 1/(s h) times a
/// step's integral, so their round-off adds ε/(s h) relative to it (measured: 0.4–0.5 × that
/// at s = 3.8e-6 and 2.7e-5 1/s, h = 1 ms, where it is 5.9e-8 and 8.2e-9).
/// This is the estimate of the solver's decomposition; the step uses it after one Newton
/// refinement ([`super::refine`]), which the estimate does not credit. Measured against the
/// dense scheme over whole 20-s horizons (unit test in `eigenbasis_tests.rs`, eleven wings): at most
/// 0.4 × this estimate with the refinement, 1e-5–1e-4 × it on the slow loops whose unrefined
/// drift reached 1.2 × it.
pub(crate) const MAX_ROUNDOFF: f64 = 1e-6;

/// e^{z} − 1 for complex z without cancellation at small |z|.
fn expm1(z: c64) -> c64 {
    let (s, c) = z.im.sin_cos();
    let half = (0.5 * z.im).sin();
    c64::new(z.re.exp_m1() * c - 2.0 * half * half, z.re.exp() * s)
}

/// The state of a run in the eigenbasis, kept in [`ModalState`].
#[derive(Debug, Clone)]
pub(crate) struct DiagonalState {
    /// x̂ = V⁻¹z over the representatives in the [`Layout`] (N reals), padded with zeros for
    /// [`RowMajor`].
    x: Vec<f64>,
    /// The inputs of the latest step (0 before the first).
    inputs: [f64; INPUTS],
    /// e_cᵀP_c e_c at the latest checkpoint (e = z − z*(inputs)).
    boundary: [f64; 2],
    /// Work buffers: z, ŝ and ê = x̂ − ŝ in the layout.
    z: Vec<f64>,
    relaxed: Vec<f64>,
    e: Vec<f64>,
    /// The [`DiagonalStep`]'s `rows` at the current x̂: the tip values, then the next step's
    /// start-of-step values ([`START`] on).
    rows: Vec<f64>,
    /// Σ Δu_k x̂ over the steps since the checkpoint that last added the jumps' state part, one
    /// sum per driving input k (x̂ at each step's start): the jumps' −2Δz*ᵀP_c V x̂ summed is
    /// −2 Σ_k (Z_kᵀP_c V) · jump_sums[k], formed at that checkpoint.
    jump_sums: [Vec<f64>; DRIVING],
}

/// Where the start-of-step values begin in the rows: after the four tip rows.
const START: usize = 4;

/// The times a [`DiagonalStep`] is built for (s): the step h and the run's horizon T.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Timing {
    pub(crate) h: f64,
    pub(crate) horizon: f64,
}

/// The closed loop's transition in its eigenbasis, built once per run.
#[derive(Debug)]
pub(crate) struct DiagonalStep {
    n: usize,
    tip_states: usize,
    h: f64,
    omega: Vec<f64>,
    /// Where the representatives sit in the real vectors the step carries ([`Layout`]).
    layout: Layout,
    /// e^{λh} and 1 − e^{λh} in that layout: the real eigenvalues' values, then the pairs'
    /// real parts, then the pairs' imaginary parts.
    mu: Vec<f64>,
    one_minus_mu: Vec<f64>,
    /// ∫_0^h c̃ᵀe^{Λs}ẽ ds = Re(lin · x̂) − lin_input · u (lin in `rows`).
    lin_input: [[f64; DRIVING]; 2],
    /// τ*_c = tau_star_c · u.
    tau_star: [[f64; INPUTS]; 2],
    /// Zᵀ P_c Z, Z = the columns of z*(u) (the rows Z_kᵀ P_c V are in `rows`).
    jump_input: [[[f64; DRIVING]; DRIVING]; 2],
    /// z = Re(V x̂) = [V_re, −V_im](x̂_re, x̂_im) (weighted columns).
    v: RowMajor,
    /// The rows read at every step's end, over x̂ in the layout: the four tip rows, then those
    /// the next step reads at its start, lin[0], lin[1] — one product per step for both.
    rows: RowMajor,
    /// The rows Z_kᵀP_cV over x̂ in the layout, jump[0][0..3], jump[1][0..3]: read at the
    /// checkpoints against the state's [`DiagonalState::jump_sums`] (three O(N) sums a step
    /// instead of six products).
    jump_rows: RowMajor,
    /// The columns of S in the layout.
    s_flat: [Vec<f64>; DRIVING],
    /// Rows of P_c's factor over ê in the layout: e_cᵀP_c e_c = Σ_j (f_j · ê)².
    factor: [RowMajor; 2],
    /// Rows of V⁻¹ giving x̂ in the layout from z (N × N).
    v_inv: RowMajor,
    /// The relative round-off estimate of the state ([`MAX_ROUNDOFF`]).
    pub(crate) roundoff: f64,
    /// ½‖V₁‖²_F, V₁ = the rows of `v` giving (p, ζ): the mechanical energy ½‖(p, ζ)‖² is at
    /// most this × ‖x̂‖² ([`DiagonalStep::energy_bound`]).
    half_energy_norm2: f64,
    /// Run the per-step update compiled for AVX ([`DiagonalStep::relax_avx`]; the CPU has it).
    avx: bool,
}

impl DiagonalStep {
    /// The eigenbasis step for step h (s) of the loop on `basis` over a run of `horizon` (s)
    /// (checkpoints at any steps), accepted where its round-off estimate is at
    /// most `max_roundoff` ([`MAX_ROUNDOFF`] for the search); [`Refused`] with the reason where
    /// the dense scheme must be used.
    pub(crate) fn new(
        basis: &ModalBasis,
        co: &LoopCoefficients,
        step: Timing,
        max_roundoff: f64,
    ) -> Result<DiagonalStep, Refused> {
        let Timing { h, horizon } = step;
        let refuse = |s: String| Err(Refused(s));
        let n = basis.len();
        let omega: Vec<f64> = basis.omega2.iter().map(|w| w.sqrt()).collect();
        let tip_states = if co.xi > 0.0 { 2 } else { 0 };
        let m = 2 * n + tip_states;
        let (a_full, outputs) = closed_loop(basis, co, &omega, tip_states);
        let a = a_full.as_ref().submatrix(0, 0, m, m).to_owned();
        let kept = LoopEigen::shared(basis, co, &a);
        let LoopEigen { reps, first_col, eig, slowest, a_norm } = match &*kept {
            Ok(found) => found,
            Err(why) => return Err(why.clone()),
        };
        let (slowest, k) = (*slowest, reps.len());
        let (vr, vr_inv) = (&eig.vr, &eig.vr_inv);
        let vc = |r: usize, rep: usize| {
            let col = first_col[rep];
            c64::new(vr[(r, col)], if reps[rep].1 == 2.0 { vr[(r, col + 1)] } else { 0.0 })
        };
        let condition = vr.norm_l2() * vr_inv.norm_l2();
        let reach = horizon.min(1.0 / slowest);
        let telescope = 1.0 / (slowest * h);
        let roundoff = f64::EPSILON * (a_norm * reach + condition + telescope);
        if !within(roundoff, max_roundoff) {
            return refuse(format!(
                "eigenbasis round-off {roundoff:.1e} relative (ε‖A‖·{reach:.3e} s, the smaller of the horizon and \
                 1/(slowest decay rate {slowest:.3e} 1/s), + ε·cond V + ε·{telescope:.1e} for ∫τ²'s telescoped \
                 terms; limit {max_roundoff:.0e})"
            ));
        }
        if !within(condition, MAX_CONDITION) {
            return refuse(format!("eigenvector condition {condition:.1e} (limit {MAX_CONDITION:.0e})"));
        }
        // x̂ = V⁻¹z over the representatives from ρ = V_r⁻¹z: x̂ = ρ (real), ρ_a + iρ_b (pair;
        // z = Σ v ρ for a real eigenvalue, Σ 2Re(v x̂) = v_re ρ_a' + … with ρ_a = x̂_re, ρ_b = −x̂_im
        // after the weight 2 is put in the columns below)
        let to_half: Vec<[Option<(usize, f64)>; 2]> = reps
            .iter()
            .zip(first_col)
            .map(
                |(&(_, w), &col)| {
                    if w == 2.0 {
                        [Some((col, 0.5)), Some((col + 1, -0.5))]
                    } else {
                        [Some((col, 1.0)), None]
                    }
                },
            )
            .collect();
        let half_of_real = |rho: &dyn Fn(usize) -> f64| -> Half {
            let part = |p: usize| to_half.iter().map(|t| t[p].map_or(0.0, |(c, f)| f * rho(c))).collect();
            Half { re: part(0), im: part(1) }
        };
        let v_inv = Mat::from_fn(2 * k, m, |row, q| {
            let (rep, p) = (row % k, row / k);
            to_half[rep][p].map_or(0.0, |(c, f)| f * vr_inv[(c, q)])
        });
        let v = Mat::from_fn(
            m,
            2 * k,
            |r, c| if c < k { vc(r, c).re * reps[c].1 } else { -vc(r, c - k).im * reps[c - k].1 },
        );
        let lam: Vec<c64> = eig.lambda.clone();
        // ŝ = V⁻¹ z*(u), z* = −A⁻¹Bu: S_ik = −(V⁻¹B)_ik/λ_i
        let s = [0, 1, 2].map(|kk| {
            let b: Vec<f64> = (0..m).map(|i| a_full[(i, m + kk)]).collect();
            let rho: Vec<f64> = (0..m).map(|c| (0..m).map(|q| vr_inv[(c, q)] * b[q]).sum()).collect();
            let x = half_of_real(&|c| rho[c]);
            Half::from_fn(k, |r| -c64::new(x.re[r], x.im[r]) / lam[r])
        });
        // t·V over the representatives, weighted (Re(row · x̂) = t·z)
        let row_times_v = |t: &[f64]| -> Half {
            Half::from_fn(k, |c| (0..m).fold(c64::new(0.0, 0.0), |acc, r| acc + vc(r, c) * t[r]) * reps[c].1)
        };
        let u = &basis.tip;
        let tip_row = |c: usize, vel: bool| -> Vec<f64> {
            let mut row = vec![0.0; m];
            for j in 0..n {
                if vel {
                    row[n + j] = u[c][j];
                } else {
                    row[j] = u[c][j] / omega[j];
                }
            }
            row
        };
        let tip = [(0, false), (1, false), (0, true), (1, true)].map(|(c, vel)| row_times_v(&tip_row(c, vel)));
        let em1: Vec<c64> = lam.iter().map(|l| expm1(*l * h)).collect();
        let mu = Half::from_fn(k, |r| em1[r] + c64::new(1.0, 0.0));
        let one_minus_mu = Half::from_fn(k, |r| -em1[r]);
        // φ_i = (e^{λh} − 1)/λ = ∫_0^h e^{λs} ds
        let phi: Vec<c64> = em1.iter().zip(&lam).map(|(e, l)| e / l).collect();
        // S's columns as (re, im): the vector the rows over ξ = (x̂_re, x̂_im) act on
        let layout = Layout::new(reps);
        let slots = layout.len();
        // S's columns in the layout: the vector the rows over x̂ act on
        let s_flat = [0, 1, 2].map(|kk| layout.vector(&[s[kk].re.as_slice(), s[kk].im.as_slice()].concat()));
        let mut lin = [Half::zeros(k), Half::zeros(k)];
        let mut lin_input = [[0.0; DRIVING]; 2];
        let mut tau_star = [[0.0; INPUTS]; 2];
        // the rows Z_kᵀ P_c over x̂ in the layout, channel by channel
        let mut jump: [Vec<Vec<f64>>; 2] = [Vec::new(), Vec::new()];
        let mut jump_input = [[[0.0; DRIVING]; DRIVING]; 2];
        let mut factors: Vec<Mat<f64>> = Vec::with_capacity(2);
        // g = c·V weighted per channel; unweighted g_i for P
        let gw = [0, 1].map(|c| row_times_v(&outputs[c][..m]));
        let g =
            [0, 1].map(|c| -> Vec<c64> { (0..k).map(|r| c64::new(gw[c].re[r], gw[c].im[r]) / reps[r].1).collect() });
        // Φ = êᴴPê over all N eigenvalues, P_ij = −ḡ_i g_j/(λ̄_i + λ_j), as a real quadratic
        // form ξᵀP_rξ in the layout's real coordinates ξ of x̂: a pair contributes
        // ê_i = ξ_re + iξ_im and its conjugate.
        let p_rs = real_forms([&g[0], &g[1]], &lam, reps, &layout);
        for (c, p_r) in p_rs.iter().enumerate() {
            lin[c] = Half::from_fn(k, |r| c64::new(gw[c].re[r], gw[c].im[r]) * phi[r]);
            for kk in 0..DRIVING {
                lin_input[c][kk] = lin[c].re_dot(&s[kk]);
            }
            for kk in 0..INPUTS {
                let through_state = if kk < DRIVING { gw[c].re_dot(&s[kk]) } else { 0.0 };
                tau_star[c][kk] = through_state + outputs[c][m + kk];
            }
            for kk in 0..DRIVING {
                let row: Vec<f64> = (0..slots).map(|a| (0..slots).map(|b| p_r[(a, b)] * s_flat[kk][b]).sum()).collect();
                for ll in 0..DRIVING {
                    jump_input[c][kk][ll] = row.iter().zip(&s_flat[ll]).map(|(a, b)| a * b).sum();
                }
                jump[c].push(row);
            }
            factors.push(pivoted_cholesky(p_r));
        }
        // the rows read at every step: the tips, then lin[0], lin[1]; the jump rows apart
        let lin_rows = layout.columns(&stack(&lin));
        let tip_rows = layout.columns(&stack(&tip));
        let rows =
            Mat::from_fn(START + 2, slots, |i, j| if i < START { tip_rows[(i, j)] } else { lin_rows[(i - START, j)] });
        let jump_rows = Mat::from_fn(2 * DRIVING, slots, |i, j| jump[i / DRIVING][i % DRIVING][j]);
        let flat = |h: &Half| layout.vector(&[h.re.as_slice(), h.im.as_slice()].concat());
        let v = RowMajor::new(&layout.columns(&v));
        let half_energy_norm2 = 0.5 * (0..2 * n).map(|i| v.row(i).iter().map(|x| x * x).sum::<f64>()).sum::<f64>();
        let step = DiagonalStep {
            n,
            tip_states,
            h,
            omega,
            mu: flat(&mu),
            one_minus_mu: flat(&one_minus_mu),
            lin_input,
            tau_star,
            jump_input,
            v,
            rows: RowMajor::new(&rows),
            jump_rows: RowMajor::new(&jump_rows),
            s_flat,
            factor: [RowMajor::new(&factors[0]), RowMajor::new(&factors[1])],
            v_inv: RowMajor::new(&layout.rows(&v_inv)),
            layout,
            roundoff,
            half_energy_norm2,
            #[cfg(target_arch = "x86_64")]
            avx: std::arch::is_x86_feature_detected!("avx"),
            #[cfg(not(target_arch = "x86_64"))]
            avx: false,
        };
        if !(step.v.is_finite()
            && step.rows.is_finite()
            && step.jump_rows.is_finite()
            && step.v_inv.is_finite()
            && step.factor.iter().all(RowMajor::is_finite)
            && step.s_flat.iter().flatten().all(|x| x.is_finite())
            && step.mu.iter().chain(&step.one_minus_mu).all(|x| x.is_finite()))
        {
            return refuse("a coefficient is not finite".into());
        }
        Ok(step)
    }

    fn len(&self) -> usize {
        2 * self.n + self.tip_states
    }

    /// jump_sums[k] += Δu_k x̂, then x̂ ← μ x̂ + (1 − μ) ŝ with ŝ = S u (element by element: the
    /// same bits however wide the vector instructions the compiler picks,
    /// [`DiagonalStep::relax_avx`]).
    #[inline(always)]
    fn relax(&self, inputs: &[f64; INPUTS], du: &[f64; DRIVING], ds: &mut DiagonalState) {
        let [s0, s1, s2] = &mut ds.jump_sums;
        for (i, &x) in ds.x.iter().enumerate().take(self.layout.len()) {
            s0[i] += du[0] * x;
            s1[i] += du[1] * x;
            s2[i] += du[2] * x;
        }
        self.relaxed(inputs, &mut ds.relaxed);
        let (real, pairs) = (self.layout.real, self.layout.pairs);
        let (mu, om, s, x) = (&self.mu, &self.one_minus_mu, &ds.relaxed, &mut ds.x);
        for i in 0..real {
            x[i] = mu[i] * x[i] + om[i] * s[i];
        }
        for p in 0..pairs {
            let (r, i) = (real + p, real + pairs + p);
            let (a, b) = (x[r], x[i]);
            x[r] = mu[r] * a - mu[i] * b + (om[r] * s[r] - om[i] * s[i]);
            x[i] = mu[r] * b + mu[i] * a + (om[r] * s[i] + om[i] * s[r]);
        }
    }

    /// [`DiagonalStep::relax`] compiled for AVX (4 lanes instead of the baseline's 2; no fused
    /// multiply-add, so the same operations and bits).
    ///
    /// # Safety
    /// The CPU must have AVX.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    unsafe fn relax_avx(&self, inputs: &[f64; INPUTS], du: &[f64; DRIVING], ds: &mut DiagonalState) {
        self.relax(inputs, du, ds)
    }

    /// ŝ = S u as (re, im) into `out`.
    #[inline(always)]
    fn relaxed(&self, inputs: &[f64; INPUTS], out: &mut [f64]) {
        let [s0, s1, s2] = &self.s_flat;
        let (u0, u1, u2) = (inputs[0], inputs[1], inputs[2]);
        for (i, o) in out.iter_mut().enumerate().take(s0.len()) {
            *o = s0[i] * u0 + s1[i] * u1 + s2[i] * u2;
        }
    }

    /// The jumps' deferred part −2 Σ_k (Z_kᵀP_cV) · jump_sums[k] per channel since the sums
    /// were last cleared, and clear them.
    fn jump_state_parts(&self, ds: &mut DiagonalState) -> [f64; 2] {
        let mut parts = [0.0; 2];
        for (kk, sums) in ds.jump_sums.iter_mut().enumerate() {
            for (c, part) in parts.iter_mut().enumerate() {
                *part -= 2.0 * dot(self.jump_rows.row(DRIVING * c + kk), sums);
            }
            sums.iter_mut().for_each(|v| *v = 0.0);
        }
        parts
    }

    /// e_cᵀP_c e_c of both channels at x̂ with the inputs `inputs` (e = z − z*(u)).
    fn boundary(&self, ds: &mut DiagonalState) -> [f64; 2] {
        let inputs = ds.inputs;
        self.relaxed(&inputs, &mut ds.relaxed);
        for (i, e) in ds.e.iter_mut().enumerate().take(ds.relaxed.len()) {
            *e = ds.x[i] - ds.relaxed[i];
        }
        [0, 1].map(|c| {
            let mut y = vec![0.0; self.factor[c].rows()];
            self.factor[c].mul_into(&ds.e, &mut y);
            y.iter().map(|f| f * f).sum()
        })
    }

    /// The eigenbasis state of `st` (η, ζ, w as set by the loop's initial state), no inputs yet.
    pub(crate) fn start(&self, st: &ModalState) -> DiagonalState {
        let (n, m) = (self.n, self.len());
        let mut z = vec![0.0; self.v_inv.stride()];
        for i in 0..n {
            z[i] = self.omega[i] * st.eta[i];
            z[n + i] = st.zeta[i];
        }
        z[2 * n..m].copy_from_slice(&st.w[..self.tip_states]);
        let stride = self.rows.stride();
        let mut x = vec![0.0; stride];
        self.v_inv.mul_into(&z, &mut x);
        let mut ds = DiagonalState {
            x,
            inputs: [0.0; INPUTS],
            boundary: [0.0; 2],
            z: vec![0.0; m],
            relaxed: vec![0.0; self.s_flat[0].len()],
            e: vec![0.0; stride],
            rows: vec![0.0; self.rows.rows()],
            jump_sums: std::array::from_fn(|_| vec![0.0; stride]),
        };
        self.rows.mul_into(&ds.x, &mut ds.rows);
        ds.boundary = self.boundary(&mut ds);
        ds
    }

    /// One step with the held inputs u = (ḡ1 − ĝ1, ḡ2 − ĝ2, φ̄, ĝ1, ĝ2): advances x̂ (η, ζ, w
    /// are brought up to date by [`DiagonalStep::checkpoint`]); returns this step's share of
    /// ∫τ_c² (N² s, N² m² s), exact when summed between checkpoints, and the tip values at the
    /// step's end [q, θ, q̇, θ̇] (m, rad, m/s, rad/s).
    pub(crate) fn advance(&self, ds: &mut DiagonalState, inputs: [f64; INPUTS]) -> ([f64; 2], [f64; 4]) {
        let old = ds.inputs;
        let du = [0, 1, 2].map(|kk| inputs[kk] - old[kk]);
        // the start-of-step rows were formed at the previous step's end (or the start)
        let mut square = [0.0; 2];
        for (c, sq) in square.iter_mut().enumerate() {
            // jump of eᵀPe at the step's start: −2Δz*ᵀP(z − z*(old)) + Δz*ᵀPΔz*, its part
            // −2Δz*ᵀP V x̂ deferred to the checkpoint (jump_sums)
            let mut jump = 0.0;
            for kk in 0..DRIVING {
                let pe_input = (0..DRIVING).map(|ll| self.jump_input[c][kk][ll] * old[ll]).sum::<f64>();
                let quad = (0..DRIVING).map(|ll| self.jump_input[c][kk][ll] * du[ll]).sum::<f64>();
                jump += du[kk] * (quad + 2.0 * pe_input);
            }
            let tau_star: f64 = (0..INPUTS).map(|kk| self.tau_star[c][kk] * inputs[kk]).sum();
            let lin = ds.rows[START + c] - (0..DRIVING).map(|kk| self.lin_input[c][kk] * inputs[kk]).sum::<f64>();
            *sq = jump + 2.0 * tau_star * lin + self.h * tau_star * tau_star;
        }
        // the jumps' state part at x̂ (this step's start), then x̂ ← μ x̂ + (1 − μ) ŝ
        #[cfg(target_arch = "x86_64")]
        if self.avx {
            // SAFETY: the CPU has AVX (`avx`).
            unsafe { self.relax_avx(&inputs, &du, ds) };
        } else {
            self.relax(&inputs, &du, ds);
        }
        #[cfg(not(target_arch = "x86_64"))]
        self.relax(&inputs, &du, ds);
        ds.inputs = inputs;
        self.rows.mul_into(&ds.x, &mut ds.rows);
        let tips = [ds.rows[0], ds.rows[1], ds.rows[2], ds.rows[3]];
        (square, tips)
    }

    /// An upper bound of the mechanical energy ½Σ(ω_i²η_i² + ζ_i²) (J) at x̂, O(N) instead of
    /// the O(N²) reconstruction of η, ζ: ½‖V₁x̂‖² ≤ ½‖V₁‖²_F‖x̂‖² (Cauchy–Schwarz per row),
    /// V₁ the rows of V giving (p, ζ). Not finite where x̂ is not.
    pub(crate) fn energy_bound(&self, ds: &DiagonalState) -> f64 {
        self.half_energy_norm2 * ds.x.iter().map(|x| x * x).sum::<f64>()
    }

    /// Bring η, ζ and (ξ > 0) w up to date from x̂ and return the boundary terms
    /// e_aᵀPe_a − e_bᵀPe_b of the interval since the previous checkpoint a that formed them
    /// (N² s, N² m² s); with `squares` false they are not formed ([0, 0], a stays).
    pub(crate) fn checkpoint(
        &self,
        ds: &mut DiagonalState,
        eta: &mut [f64],
        zeta: &mut [f64],
        w: &mut [f64; 2],
        squares: bool,
    ) -> [f64; 2] {
        self.v.mul_into(&ds.x, &mut ds.z);
        let n = self.n;
        for i in 0..n {
            eta[i] = ds.z[i] / self.omega[i];
            zeta[i] = ds.z[n + i];
        }
        w[..self.tip_states].copy_from_slice(&ds.z[2 * n..]);
        if !squares {
            return [0.0; 2];
        }
        self.interval_squares(ds)
    }

    /// The boundary terms e_aᵀPe_a − e_bᵀPe_b of the interval since the previous checkpoint a
    /// (N² s, N² m² s), as [`DiagonalStep::checkpoint`] returns them, without bringing η, ζ, w
    /// up to date: O(N r) instead of the reconstruction's O(N²).
    pub(crate) fn interval_squares(&self, ds: &mut DiagonalState) -> [f64; 2] {
        let now = self.boundary(ds);
        let before = std::mem::replace(&mut ds.boundary, now);
        let jumps = self.jump_state_parts(ds);
        [before[0] - now[0] + jumps[0], before[1] - now[1] + jumps[1]]
    }
}
