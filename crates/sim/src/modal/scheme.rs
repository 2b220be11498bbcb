//! The two schemes of [`crate::Stepper`] in the modal basis: one step of the
//! trapezoidal rule or of TR-BDF2, each solve with the step matrix as diagonal plus rank 2
//! (Woodbury), O(n) per step.

use std::sync::Arc;

use wingcheck_control::{BoundaryLaw, TipChannel};
use wingcheck_model::{Config, TimeScheme};

use crate::{Sample, SimError};

use super::closed_loop::LoopCoefficients;
use super::diagonal::{DiagonalState, DiagonalStep, Timing};
use super::exact::ExactStep;
use super::trbdf2_pass::{StateSums, TipStages, Trbdf2Pass};
use super::woodbury::{dot, padded_len, total, StepSolve, LANES};
use super::{ModalBasis, SampleInput, StepQuadrature};

/// [u0·η, u1·η, u0·ζ, u1·ζ] over the modes of u (u: the tip rows), each exactly as [`dot`]
/// sums it, in one pass over the state instead of four.
fn tip_dots(u: &[Vec<f64>; 2], eta: &[f64], zeta: &[f64]) -> [f64; 4] {
    let n = u[0].len().min(u[1].len()).min(eta.len()).min(zeta.len());
    let (u0, u1, eta, zeta) = (&u[0][..n], &u[1][..n], &eta[..n], &zeta[..n]);
    let mut s = [[0.0; LANES]; 4];
    for i in (0..n - n % LANES).step_by(LANES) {
        for l in 0..LANES {
            let j = i + l;
            s[0][l] += u0[j] * eta[j];
            s[1][l] += u1[j] * eta[j];
            s[2][l] += u0[j] * zeta[j];
            s[3][l] += u1[j] * zeta[j];
        }
    }
    let tail = n - n % LANES;
    let finish =
        |k: usize, a: &[f64], b: &[f64]| a[tail..].iter().zip(&b[tail..]).fold(total(&s[k]), |acc, (x, y)| acc + x * y);
    [finish(0, u0, eta), finish(1, u1, eta), finish(2, u0, zeta), finish(3, u1, zeta)]
}

/// The modal state of the closed loop: x = Φη, v = Φζ, with the tip values and tip boundary
/// states carried alongside.
///
/// `repr(C)` with w between x_tip and v_tip: τ = −k(a x + b v) − ĝ, read right after a step
/// wrote x_tip and v_tip, was compiled to one 16-byte load of the adjacent x_tip[1], v_tip[0],
/// which spans both of the step's 16-byte stores and so waits for them to reach the cache (no
/// store-to-load forwarding); apart, the two are read as single values. A search point was 3 %
/// faster (1-thread 32×32 search, paired runs), with the same output.
#[derive(Debug)]
#[repr(C)]
pub struct ModalState {
    /// Modal displacements η (x = Φη).
    pub eta: Vec<f64>,
    /// Modal velocities ζ (v = Φζ).
    pub zeta: Vec<f64>,
    /// Work buffer: D⁻¹ r of the current solve.
    pub y: Vec<f64>,
    /// q(s), θ(s) (m, rad) = Uᵀη.
    pub x_tip: [f64; 2],
    /// Tip boundary states q'''(s) (1/m²), θ'(s) (1/m).
    pub w: [f64; 2],
    /// q̇(s), θ̇(s) (m/s, rad/s) = Uᵀζ.
    pub v_tip: [f64; 2],
    /// Work buffers of the exponential scheme (empty for the others).
    pub(crate) exact_x: Vec<f64>,
    /// See `exact_x`.
    pub(crate) exact_y: Vec<f64>,
    /// The exponential scheme's state in the closed loop's eigenbasis (its diagonal form only;
    /// η, ζ and w are then brought up to date at every checkpoint, [`ModalLoop::checkpoint`]).
    pub(crate) diagonal: Option<DiagonalState>,
    /// TR-BDF2's tip sums of η, ζ for the next step ([`Trbdf2Pass`]), formed by the pass that
    /// made them: a state is stepped by the loop that made it.
    pub(crate) sums: StateSums,
}

impl ModalState {
    /// Recompute the tip values from the modal state (x_tip = Uᵀη, v_tip = Uᵀζ): the steps
    /// carry them alongside η, ζ and the two drift apart by round-off; the runs call this at
    /// every output sample, so the recorded tip equals the field at the tip and no drift
    /// accumulates.
    pub fn sync_tip(&mut self, basis: &ModalBasis) {
        let [x0, x1, v0, v1] = tip_dots(&basis.tip, &self.eta, &self.zeta);
        (self.x_tip, self.v_tip) = ([x0, x1], [v0, v1]);
    }
}

/// The inputs of one integrator step: φ̄, ḡ − ĝ and ĝ per channel.
#[derive(Debug, Clone, Copy)]
pub struct StepInput {
    /// φ̄: the step mean of the distributed load's time factor.
    pub phi: f64,
    /// ḡ − ĝ over the step: N (bending), N m (torsion).
    pub tip_input: [f64; 2],
    /// The held estimate ĝ: N, N m.
    pub g_hat: [f64; 2],
}

/// The scheme of a loop ([`Config::time_scheme`] in the modal basis) with what its steps use:
/// the Woodbury step solve of the implicit schemes, the exact transition of the exponential one.
#[derive(Debug)]
enum Stepping {
    Trapezoid(StepSolve),
    Trbdf2(Trbdf2Pass),
    /// The dense exact transition, shared with the other runs of the same loop and step
    /// ([`super::memo`]).
    Exponential(Arc<ExactStep>),
    /// The exponential scheme in the closed loop's eigenbasis ([`DiagonalStep`]): the same
    /// exact transition, O(N) per step; used where the loop is built by
    /// [`ModalLoop::with_eigenbasis`] (the search) and its checks pass.
    Diagonal(Box<DiagonalStep>),
}

/// Everything a step reads that is fixed over a run.
#[derive(Debug)]
pub struct ModalLoop<'a> {
    u: &'a [Vec<f64>; 2],
    stepping: Stepping,
    /// Why [`DiagonalStep::new`] refused where the eigenbasis was asked for.
    eigenbasis_refused: Option<String>,
    h: f64,
    /// α of the implicit scheme's step matrix (s): h/2 (trapezoid), γh/2 (TR-BDF2).
    alpha: f64,
    /// The control law (15).
    law: BoundaryLaw,
    xi: f64,
    /// EI (N m²), GJ (N m²).
    stiff: [f64; 2],
    sign: [f64; 2],
    /// The TR-BDF2 tip-state stages' fixed factors per channel ([`TipStages`]).
    tip_stages: [TipStages; 2],
}

impl<'a> ModalLoop<'a> {
    /// The loop of `cfg` on `basis` (built from the same wing and grid), with the scheme
    /// `cfg.discretisation.stepper` selects.
    pub fn new(cfg: &Config, basis: &'a ModalBasis) -> Result<ModalLoop<'a>, SimError> {
        Self::build(cfg, basis, BoundaryLaw::of(cfg), None)
    }

    /// The loop of `cfg` as [`ModalLoop::new`] with the continuous part `law` in place of
    /// `cfg`'s law (15): a controller's own ([`wingcheck_control::Controller::continuous`]).
    pub fn with_law(cfg: &Config, basis: &'a ModalBasis, law: BoundaryLaw) -> Result<ModalLoop<'a>, SimError> {
        Self::build(cfg, basis, law, None)
    }

    /// The loop of `cfg` as [`ModalLoop::new`], except that the exponential scheme steps in the
    /// closed loop's eigenbasis ([`super::diagonal`], O(N) per step) wherever its checks pass:
    /// the same exact transition as the dense form within its round-off estimate (≤ 1e-6
    /// relative of the state by construction; [`ModalLoop::eigenbasis_roundoff`]). The search
    /// steps this way; `simulate` keeps the dense form.
    pub fn with_eigenbasis(cfg: &Config, basis: &'a ModalBasis) -> Result<ModalLoop<'a>, SimError> {
        Self::build(cfg, basis, BoundaryLaw::of(cfg), Some(super::diagonal::MAX_ROUNDOFF))
    }

    /// [`ModalLoop::with_eigenbasis`] with another limit on the eigenbasis's round-off estimate
    /// (relative of the state): for runs whose quantities carry errors far above it
    /// (`simulate`'s [`crate::RunOptions::eigenbasis`]).
    pub fn with_eigenbasis_within(
        cfg: &Config,
        basis: &'a ModalBasis,
        max_roundoff: f64,
    ) -> Result<ModalLoop<'a>, SimError> {
        Self::build(cfg, basis, BoundaryLaw::of(cfg), Some(max_roundoff))
    }

    /// The relative round-off estimate of the state where the loop steps in the eigenbasis,
    /// `None` where it steps otherwise.
    pub fn eigenbasis_roundoff(&self) -> Option<f64> {
        match &self.stepping {
            Stepping::Diagonal(d) => Some(d.roundoff),
            _ => None,
        }
    }

    /// Why the eigenbasis was refused where [`ModalLoop::with_eigenbasis`] asked for it and the
    /// dense exponential scheme steps instead; `None` otherwise.
    pub fn eigenbasis_refusal(&self) -> Option<&str> {
        self.eigenbasis_refused.as_deref()
    }

    /// `law`: the continuous part; `eigenbasis`: the round-off limit of the eigenbasis form,
    /// `None` for the dense one.
    fn build(
        cfg: &Config,
        basis: &'a ModalBasis,
        law: BoundaryLaw,
        eigenbasis: Option<f64>,
    ) -> Result<ModalLoop<'a>, SimError> {
        let h = cfg.discretisation.dt;
        let (a, b, xi, gain) = (law.a, law.b, cfg.wing.xi, law.gains);
        let scheme = cfg.time_scheme(true);
        let alpha = match scheme {
            TimeScheme::Trapezoid => 0.5 * h,
            _ => crate::trbdf2::ALPHA * h,
        };
        let stiff = [cfg.wing.ei, cfg.wing.gj];
        let sign = [TipChannel::Bending.bc_sign(), TipChannel::Torsion.bc_sign()];
        let solve = || StepSolve::new(basis, alpha, xi, b + alpha * a, gain);
        let mut eigenbasis_refused = None;
        let stepping = match scheme {
            TimeScheme::Trapezoid => Stepping::Trapezoid(solve()?),
            TimeScheme::Exponential => {
                let co = LoopCoefficients { gain, a, b, xi, stiff, sign };
                let timing = Timing { h, horizon: cfg.horizon.t_end };
                match eigenbasis.map(|limit| DiagonalStep::new(basis, &co, timing, limit)) {
                    Some(Ok(diagonal)) => Stepping::Diagonal(Box::new(diagonal)),
                    other => {
                        eigenbasis_refused = other.and_then(Result::err).map(|why| why.0);
                        Stepping::Exponential(ExactStep::shared(basis, &co, h)?)
                    }
                }
            }
            _ => Stepping::Trbdf2(Trbdf2Pass::new(solve()?, alpha)),
        };
        let tip_stages = [0, 1].map(|ch| TipStages::new(xi, alpha, stiff[ch], sign[ch]));
        Ok(ModalLoop { u: &basis.tip, stepping, eigenbasis_refused, h, alpha, law, xi, stiff, sign, tip_stages })
    }

    /// The work buffer of [`ModalLoop::probe_last_step`] (empty where the scheme has no probe).
    pub fn probe_buffer(&self) -> Vec<f64> {
        match &self.stepping {
            Stepping::Exponential(exact) => exact.probe_buffer(),
            _ => Vec::new(),
        }
    }

    /// The exact q(s), θ(s), q̇(s), θ̇(s), τ1, τ2 inside the step just made on `st` where they may exceed
    /// `running` (their running peaks), and whether one was still rising at the step's end
    /// ([`super::ProbedStep`]), for the dense exponential scheme ([`super::probe`];
    /// `exhaustive`: the whole fine grid, no screen); `None` for the schemes without one
    /// (TR-BDF2, the trapezoidal rule, the eigenbasis form).
    pub fn probe_last_step(
        &self,
        st: &ModalState,
        running: [f64; super::PROBED],
        buf: &mut [f64],
        exhaustive: bool,
    ) -> Option<super::ProbedStep> {
        match &self.stepping {
            Stepping::Exponential(exact) => Some(exact.probe_last_step(st, running, buf, exhaustive)),
            _ => None,
        }
    }

    /// Points of the sub-step probe's fine grid per step (0 where the scheme has none).
    pub fn probe_points(&self) -> usize {
        match &self.stepping {
            Stepping::Exponential(exact) => exact.probe_points(),
            _ => 0,
        }
    }

    /// The scheme this loop steps with (`auto` resolved).
    pub fn scheme(&self) -> TimeScheme {
        match self.stepping {
            Stepping::Trapezoid(_) => TimeScheme::Trapezoid,
            Stepping::Trbdf2(_) => TimeScheme::Trbdf2,
            Stepping::Exponential(_) | Stepping::Diagonal(_) => TimeScheme::Exponential,
        }
    }

    /// The initial state: η(0), ζ = 0, and the tip boundary states of the initial shape as the
    /// nodal stepper sets them (q'''(s,0) = −3 q_tip/s³ for the cantilever shape, 0 for the
    /// linear one; θ'(s,0) = θ_tip/s).
    pub fn initial_state(&self, cfg: &Config, basis: &ModalBasis) -> ModalState {
        let mut st = ModalState {
            x_tip: [dot(&basis.tip[0], &basis.eta0), dot(&basis.tip[1], &basis.eta0)],
            eta: padded(&basis.eta0),
            zeta: vec![0.0; padded_len(basis.len())],
            y: vec![0.0; padded_len(basis.len())],
            v_tip: [0.0, 0.0],
            w: crate::stepper::initial_tip_states(cfg),
            exact_x: Vec::new(),
            exact_y: Vec::new(),
            diagonal: None,
            sums: StateSums::default(),
        };
        match &self.stepping {
            Stepping::Exponential(exact) => (st.exact_x, st.exact_y) = exact.buffers(),
            Stepping::Diagonal(diagonal) => st.diagonal = Some(diagonal.start(&st)),
            Stepping::Trbdf2(pass) => st.sums = pass.sums_of(&st.zeta, &st.eta),
            _ => {}
        }
        st
    }

    /// The state as a [`Sample`] at time t with the observer's output `obs` (energy from the
    /// modal state, τ with the held estimate).
    pub fn sample(&self, basis: &ModalBasis, st: &ModalState, t: f64, obs: &SampleInput) -> Sample {
        Sample {
            t,
            q_tip: st.x_tip[0],
            theta_tip: st.x_tip[1],
            q_tip_rate: st.v_tip[0],
            theta_tip_rate: st.v_tip[1],
            tau1: self.tau(0, st.x_tip[0], st.v_tip[0], obs.g_hat[0]),
            tau2: self.tau(1, st.x_tip[1], st.v_tip[1], obs.g_hat[1]),
            g1: obs.g[0],
            g2: obs.g[1],
            g1_hat: obs.g_hat[0],
            g2_hat: obs.g_hat[1],
            sigma1: obs.sigma[0],
            sigma2: obs.sigma[1],
            energy: basis.energy(&st.eta, &st.zeta),
            // ⟨x, Mv⟩ = ηᵀΦᵀMΦζ = η·ζ (ΦᵀMΦ = I)
            displacement_momentum: dot(&st.eta, &st.zeta),
            q_tip_shear: st.w[0],
            theta_tip_slope: st.w[1],
        }
    }

    /// One integrator step of the configured scheme; returns the exact ∫τ_c² dt over the step
    /// (N² s, N² m² s) for the exponential scheme, `None` for the others (whose τ is known at
    /// the step's ends only).
    #[inline]
    pub fn step(&self, st: &mut ModalState, input: &StepInput) -> Option<[f64; 2]> {
        self.step_with(st, input, true)
    }

    /// [`ModalLoop::step`]; with `tip_states` false, TR-BDF2 leaves the tip boundary states w
    /// as they are instead of advancing them (they do not feed back: every other value is the
    /// same bits), for a run that never reads them (the search, [`super::Reads`]'s
    /// `tip_states`). The other schemes advance them either way.
    #[inline]
    pub fn step_with(&self, st: &mut ModalState, input: &StepInput, tip_states: bool) -> Option<[f64; 2]> {
        self.step_quadrature(st, input, tip_states).0
    }

    /// [`ModalLoop::step_with`], with the step's quadrature of τ and of the tip states w
    /// ([`StepQuadrature`]; with `tip_states` false, TR-BDF2's w part is not formed).
    #[inline(always)]
    pub fn step_quadrature(
        &self,
        st: &mut ModalState,
        input: &StepInput,
        tip_states: bool,
    ) -> (Option<[f64; 2]>, StepQuadrature) {
        match &self.stepping {
            Stepping::Exponential(exact) => {
                let start = self.ends(st, input);
                let square = self.exponential_step(exact, st, input);
                (Some(square), start.mean_with(self.ends(st, input)))
            }
            Stepping::Diagonal(diagonal) => {
                let start = self.ends(st, input);
                let square = self.diagonal_step(diagonal, st, input);
                (Some(square), start.mean_with(self.ends(st, input)))
            }
            Stepping::Trapezoid(solve) => (None, self.trapezoid_step(solve, st, input)),
            Stepping::Trbdf2(pass) => (None, self.trbdf2_step(pass, st, input, tip_states)),
        }
    }

    /// τ and w of `st` now, with the step's held estimate (an end of an exponential step).
    #[inline(always)]
    fn ends(&self, st: &ModalState, input: &StepInput) -> StepQuadrature {
        StepQuadrature { tau: [0, 1].map(|c| self.tau(c, st.x_tip[c], st.v_tip[c], input.g_hat[c])), w: st.w }
    }

    /// Step with the baseline instructions even where AVX is available (the results are the
    /// same bits: see [`super::woodbury`]).
    #[cfg(test)]
    pub(crate) fn without_avx(mut self) -> Self {
        match &mut self.stepping {
            Stepping::Trapezoid(s) => s.avx = false,
            Stepping::Trbdf2(p) => p.solve.avx = false,
            _ => {}
        }
        self
    }

    /// One exact step ([`ExactStep`]); the tip values are recomputed from the modal state, and
    /// with ξ = 0 the tip states from the end-of-step force (w = s(τ + ḡ)/S).
    fn exponential_step(&self, exact: &ExactStep, st: &mut ModalState, input: &StepInput) -> [f64; 2] {
        let u = input.tip_input;
        let square = exact.advance(st, [u[0], u[1], input.phi, input.g_hat[0], input.g_hat[1]]);
        st.x_tip = [dot(&self.u[0], &st.eta), dot(&self.u[1], &st.eta)];
        st.v_tip = [dot(&self.u[0], &st.zeta), dot(&self.u[1], &st.zeta)];
        self.algebraic_tip_states(st, input);
        square
    }

    /// One exact step in the eigenbasis ([`DiagonalStep`]); its ∫τ² is this step's share,
    /// exact summed between checkpoints ([`ModalLoop::checkpoint`]).
    fn diagonal_step(&self, diagonal: &DiagonalStep, st: &mut ModalState, input: &StepInput) -> [f64; 2] {
        let u = input.tip_input;
        let ds = st.diagonal.as_mut().expect("a diagonal loop's state has its eigenbasis part");
        let (square, tips) = diagonal.advance(ds, [u[0], u[1], input.phi, input.g_hat[0], input.g_hat[1]]);
        (st.x_tip, st.v_tip) = ([tips[0], tips[1]], [tips[2], tips[3]]);
        self.algebraic_tip_states(st, input);
        square
    }

    /// With ξ = 0 the tip states from the end-of-step force (w = s(τ + ḡ)/S).
    fn algebraic_tip_states(&self, st: &mut ModalState, input: &StepInput) {
        if self.xi <= 0.0 {
            let u = input.tip_input;
            for ch in 0..2 {
                let force = self.tau(ch, st.x_tip[ch], st.v_tip[ch], input.g_hat[ch]) + u[ch] + input.g_hat[ch];
                st.w[ch] = self.sign[ch] * force / self.stiff[ch];
            }
        }
    }

    /// Bring the modal state η, ζ (and w) of `st` up to date where the scheme carries it in
    /// another form (the eigenbasis), and return what the steps' ∫τ² since the previous
    /// checkpoint still lack (N² s, N² m² s; `None` for the schemes whose steps' values are
    /// complete). The driver calls it at every output sample, before the output is recorded.
    /// `squares`: add the deferred part here; where false it is carried to the next checkpoint
    /// that adds it (the parts telescope, so their sum over the checkpoints is unchanged) and
    /// [0, 0] is returned.
    pub fn checkpoint(&self, st: &mut ModalState, squares: bool) -> Option<[f64; 2]> {
        match &self.stepping {
            Stepping::Diagonal(diagonal) => {
                let ModalState { diagonal: ds, eta, zeta, w, .. } = st;
                let ds = ds.as_mut().expect("a diagonal loop's state has its eigenbasis part");
                Some(diagonal.checkpoint(ds, eta, zeta, w, squares))
            }
            _ => None,
        }
    }

    /// The deferred ∫τ² terms of the output interval just ended where the scheme carries the
    /// state in the eigenbasis, without the O(N²) reconstruction of η, ζ, w that
    /// [`ModalLoop::checkpoint`] makes (`None` for the other schemes, which defer nothing).
    pub fn interval_squares(&self, st: &mut ModalState) -> Option<[f64; 2]> {
        match (&self.stepping, st.diagonal.as_mut()) {
            (Stepping::Diagonal(diagonal), Some(ds)) => Some(diagonal.interval_squares(ds)),
            _ => None,
        }
    }

    /// An upper bound of the mechanical energy (J) of `st`'s current state for the scheme that
    /// carries it in the eigenbasis (O(N), without the O(N²) reconstruction a
    /// [`ModalLoop::checkpoint`] does; `None` for the other schemes): ½‖V₁‖²_F‖x̂‖², V₁ the
    /// rows of V that give (ω_iη_i, ζ_i). Not finite where the state is not.
    pub fn energy_bound(&self, st: &ModalState) -> Option<f64> {
        match (&self.stepping, &st.diagonal) {
            (Stepping::Diagonal(diagonal), Some(ds)) => Some(diagonal.energy_bound(ds)),
            _ => None,
        }
    }

    /// Tip forces of the right-hand side: ḡ − ĝ − k a x_tip (the displacement part of the
    /// control law is in K_c).
    #[inline(always)]
    fn tip_forces(&self, input: &StepInput, x_tip: [f64; 2]) -> [f64; 2] {
        [0, 1].map(|c| input.tip_input[c] - self.law.stiffness(c) * x_tip[c])
    }

    /// τ of (15) at the tip values (x, v) of channel c ([`BoundaryLaw::tau`]).
    pub fn tau(&self, c: usize, x: f64, v: f64, g_hat: f64) -> f64 {
        self.law.tau(c, x, v, g_hat)
    }

    /// One trapezoidal step (α = h/2): S v̄ = (2/h)ζ − Ω²η + f̄, η += h v̄, ζ = 2v̄ − ζ; the
    /// tip states as `crate::Stepper`'s trapezoidal step.
    #[inline(always)]
    fn trapezoid_step(&self, solve: &StepSolve, st: &mut ModalState, input: &StepInput) -> StepQuadrature {
        let h = self.h;
        let mut quad = StepQuadrature::default();
        let f = self.tip_forces(input, st.x_tip);
        let t = solve.rhs(&st.zeta, &st.eta, input.phi, f, &mut st.y);
        let (c, vbar) = solve.correct(t);
        solve.trapezoid_update(&st.y, c, h, &mut st.zeta, &mut st.eta);
        let xi = self.xi;
        for ch in 0..2 {
            let xbar = st.x_tip[ch] + 0.5 * h * vbar[ch];
            let tau = self.tau(ch, xbar, vbar[ch], input.g_hat[ch]);
            let force = tau + input.tip_input[ch] + input.g_hat[ch];
            let (s, w) = (self.stiff[ch], st.w[ch]);
            st.w[ch] = if xi > 0.0 {
                (xi * s * w + h * self.sign[ch] * force - 0.5 * h * s * w) / (xi * s + 0.5 * h * s)
            } else {
                self.sign[ch] * force / s
            };
            // the nodal stepper's quadrature: τ at the midpoint state, w̄ = (w_n + w_{n+1})/2
            quad.tau[ch] = tau;
            quad.w[ch] = if xi > 0.0 { 0.5 * (w + st.w[ch]) } else { st.w[ch] };
            st.x_tip[ch] += h * vbar[ch];
            st.v_tip[ch] = 2.0 * vbar[ch] - st.v_tip[ch];
        }
        quad
    }

    /// One TR-BDF2 step (α = γh/2), as `crate::Stepper`'s. Stage 1 (trapezoid to
    /// t + γh): S u = ζ/α − Ω²η + f̄, (η_γ, ζ_γ) = (η + 2αu, 2u − ζ). Stage 2 (BDF2 to t + h):
    /// (η̂, ζ̂) = A(η_γ, ζ_γ) − B(η, ζ), S ζ₁ = ζ̂/α − Ω²η̂ + f̄, η₁ = η̂ + αζ₁. Both solves'
    /// tip sums come from the sums the previous pass carried, so the modes are visited once
    /// ([`Trbdf2Pass`]); the tip values by the Woodbury identity Uᵀu = t − Q c, the tip states
    /// by the same stages where `tip_states` ([`ModalLoop::step_with`]).
    #[inline(always)]
    fn trbdf2_step(
        &self,
        pass: &Trbdf2Pass,
        st: &mut ModalState,
        input: &StepInput,
        tip_states: bool,
    ) -> StepQuadrature {
        use crate::trbdf2::{A, B};
        let (alpha, sv) = (self.alpha, &pass.solve);
        let (xn, vn) = (st.x_tip, st.v_tip);
        // Stage 1.
        let f = self.tip_forces(input, xn);
        let (c, u_tip) = sv.correct(pass.stage1_sum(&st.sums, input.phi, f));
        let xg = [0, 1].map(|ch| xn[ch] + 2.0 * alpha * u_tip[ch]);
        let vg = [0, 1].map(|ch| 2.0 * u_tip[ch] - vn[ch]);
        let x_hat = [0, 1].map(|ch| A * xg[ch] - B * xn[ch]);
        // Stage 2.
        let e = [f[0] - c[0], f[1] - c[1]];
        let f2 = self.tip_forces(input, x_hat);
        let (c2, v1) = sv.correct(pass.stage2_sum(&st.sums, input.phi, e, f2));
        let e2 = [f2[0] - c2[0], f2[1] - c2[1]];
        st.sums = pass.pass(input.phi, e, e2, &mut st.zeta, &mut st.eta);
        let x1 = [0, 1].map(|ch| x_hat[ch] + alpha * v1[ch]);
        let quad = if tip_states {
            self.trbdf2_tip_states(st, input, [xn, xg, x1], [vn, vg, v1])
        } else {
            StepQuadrature::default()
        };
        st.x_tip = x1;
        st.v_tip = v1;
        quad
    }

    /// The tip boundary states ξ S ẇ = s(τ + g) − S w over a TR-BDF2 step by its two stages,
    /// from the tip values at the step's start, stage 1's end and the step's end; returns the
    /// step's quadrature of τ and w with the scheme's weights (`crate::trbdf2::WEIGHTS`, as the
    /// nodal stepper hands its controller).
    #[inline(always)]
    fn trbdf2_tip_states(
        &self,
        st: &mut ModalState,
        input: &StepInput,
        x: [[f64; 2]; 3],
        v: [[f64; 2]; 3],
    ) -> StepQuadrature {
        use crate::trbdf2::{A, B, WEIGHTS};
        let alpha = self.alpha;
        let mut quad = StepQuadrature::default();
        for ch in 0..2 {
            let g_mean = input.tip_input[ch] + input.g_hat[ch];
            let tau = |k: usize| self.tau(ch, x[k][ch], v[k][ch], input.g_hat[ch]);
            let (fn_, fg, f1) = (tau(0) + g_mean, tau(1) + g_mean, tau(2) + g_mean);
            let (s, sg, w) = (self.stiff[ch], self.sign[ch], st.w[ch]);
            let (w_n, wg, w1) = if self.xi > 0.0 {
                let k = &self.tip_stages[ch];
                let wg = (k.xi_stiff * w + alpha * (sg * (fn_ + fg) - s * w)) * k.trapezoid_scale;
                (w, wg, (A * wg - B * w + k.bdf2_force * f1) * k.bdf2_scale)
            } else {
                (sg * fn_ / s, sg * fg / s, sg * f1 / s)
            };
            st.w[ch] = w1;
            let [q0, q1, q2] = WEIGHTS;
            quad.tau[ch] = q0 * tau(0) + q1 * tau(1) + q2 * tau(2);
            quad.w[ch] = q0 * w_n + q1 * wg + q2 * w1;
        }
        quad
    }
}

/// `v` with zeros appended to the state length ([`padded_len`]).
fn padded(v: &[f64]) -> Vec<f64> {
    let mut p = v.to_vec();
    p.resize(padded_len(v.len()), 0.0);
    p
}

#[cfg(test)]
#[path = "scheme_tests.rs"]
mod tests;
