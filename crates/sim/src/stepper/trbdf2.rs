//! One TR-BDF2 step (γ = 2 − √2) of the closed loop.
//!
//! Stage 1, trapezoidal rule over [t, t + γh]: S u = (M/α) v_n − K_c x_n + f̄ with α = γh/2,
//! u = (v_n + v_γ)/2, x_γ = x_n + 2α u. Stage 2, BDF2 over (t, t + γh, t + h):
//! x̂ = A x_γ − B x_n, v̂ = A v_γ − B v_n, S v_{n+1} = (M/α) v̂ − K_c x̂ + f̄,
//! x_{n+1} = x̂ + α v_{n+1}, with A = 1/(γ(2 − γ)), B = (1 − γ)²/(γ(2 − γ)); for this γ both
//! stages have the same step matrix S = M/α + C + αK_c. Inputs are the step means f̄.
//!
//! Eliminating the stages, every linear quantity obeys y_{n+1} − y_n = h(w₀F_n + w₁F_γ + w₂F_{n+1})
//! with w₀ = w₁ = 1/(2(2 − γ)), w₂ = (1 − γ)/(2 − γ): the same quadrature Q is used for the
//! tip-state ODE, the observer integrator ν and the energy ledger, so σ_{n+1} − σ_n = h(ḡ − ĝ)
//! holds to round-off; the energy balance holds up to the scheme's O(h²) numerical dissipation.

use wingcheck_control::Controller;

use super::Stepper;
use crate::SimError;

/// γ = 2 − √2.
pub const GAMMA: f64 = 2.0 - std::f64::consts::SQRT_2;
/// α/h = γ/2 = 1 − 1/√2.
pub const ALPHA: f64 = 1.0 - std::f64::consts::FRAC_1_SQRT_2;
/// BDF2-stage coefficient A = 1/(γ(2 − γ)).
pub const A: f64 = 1.0 / (GAMMA * (2.0 - GAMMA));
/// BDF2-stage coefficient B = (1 − γ)²/(γ(2 − γ)) = A − 1.
pub const B: f64 = (1.0 - GAMMA) * (1.0 - GAMMA) / (GAMMA * (2.0 - GAMMA));
/// Quadrature weights of the step: (w₀, w₁, w₂).
pub const WEIGHTS: [f64; 3] = [0.5 / (2.0 - GAMMA), 0.5 / (2.0 - GAMMA), (1.0 - GAMMA) / (2.0 - GAMMA)];

impl<C: Controller> Stepper<C>
where
    C::Error: Into<SimError>,
{
    /// Right-hand side (M/α) v − K_c x + f̄ into `self.rhs`, solved in place.
    fn stage_solve(&mut self, use_stage: bool, phi_mean: f64, g_mean: [f64; 2]) {
        if use_stage {
            self.rhs_operator.mul_diff_into(&self.v_stage, &self.x_stage, &mut self.rhs);
        } else {
            self.rhs_operator.mul_diff_into(&self.v, &self.x, &mut self.rhs);
        }
        for (r, f) in self.rhs.iter_mut().zip(&self.disc.load) {
            *r += phi_mean * f;
        }
        for (c, g) in self.channels.iter().zip(g_mean) {
            self.rhs[c.dof] += g - c.g_hat;
        }
        self.solver.solve_in_place(&mut self.rhs);
    }

    /// Power of the external forces and Kelvin–Voigt dissipation rate at a stage (x, v).
    fn stage_power(&self, v: &[f64], taus: [f64; 2], phi_mean: f64, g_mean: [f64; 2]) -> (f64, f64) {
        let dist: f64 = phi_mean * self.disc.load.iter().zip(v).map(|(f, v)| f * v).sum::<f64>();
        let tip: f64 = self.channels.iter().zip(taus).zip(g_mean).map(|((c, tau), g)| (tau + g) * v[c.dof]).sum();
        (dist + tip, self.cfg.wing.xi * self.disc.stiffness.form(v, v))
    }

    /// τ of both channels at the state (x, v) with the held estimates.
    fn taus_at(&self, x: &[f64], v: &[f64]) -> [f64; 2] {
        [0, 1].map(|i| {
            let c = &self.channels[i];
            self.law.tau(i, x[c.dof], v[c.dof], c.g_hat)
        })
    }

    /// One TR-BDF2 step of length h starting at time t.
    pub(super) fn substep_trbdf2(&mut self, t: f64) {
        let h = self.h;
        let alpha = self.alpha;
        let (phi_mean, g_mean) = self.means.over_step(t);
        let tau_n = self.taus_at(&self.x, &self.v);
        let power_n = self.track_energy.then(|| self.stage_power(&self.v, tau_n, phi_mean, g_mean));
        // Stage 1: trapezoid to t + γh.
        self.stage_solve(false, phi_mean, g_mean);
        for i in 0..self.x.len() {
            let u = self.rhs[i];
            self.x_stage[i] = self.x[i] + 2.0 * alpha * u;
            self.v_stage[i] = 2.0 * u - self.v[i];
        }
        let tau_g = self.taus_at(&self.x_stage, &self.v_stage);
        let power_g = self.track_energy.then(|| self.stage_power(&self.v_stage, tau_g, phi_mean, g_mean));
        // Stage 2: BDF2 to t + h; the stage buffers become x̂, v̂.
        for i in 0..self.x.len() {
            self.x_stage[i] = A * self.x_stage[i] - B * self.x[i];
            self.v_stage[i] = A * self.v_stage[i] - B * self.v[i];
        }
        self.stage_solve(true, phi_mean, g_mean);
        for i in 0..self.x.len() {
            self.v[i] = self.rhs[i];
            self.x[i] = self.x_stage[i] + alpha * self.rhs[i];
        }
        let tau_1 = self.taus_at(&self.x, &self.v);
        if let (Some(pn), Some(pg)) = (power_n, power_g) {
            let p1 = self.stage_power(&self.v, tau_1, phi_mean, g_mean);
            let [w0, w1, w2] = WEIGHTS;
            self.ledger.work_in += h * (w0 * pn.0 + w1 * pg.0 + w2 * p1.0);
            self.ledger.dissipated += h * (w0 * pn.1 + w1 * pg.1 + w2 * p1.1);
        }
        // Tip states and observers with the same stages and quadrature.
        let xi = self.cfg.wing.xi;
        let [w0, w1, w2] = WEIGHTS;
        let (mut taus, mut ws) = ([0.0; 2], [0.0; 2]);
        for (ci, c) in self.channels.iter_mut().enumerate() {
            let s = c.sign;
            let stiff = c.stiffness;
            let g = g_mean[ci];
            let (fn_, fg, f1) = (tau_n[ci] + g, tau_g[ci] + g, tau_1[ci] + g);
            let (wg, w1_) = if xi > 0.0 {
                let wg = (xi * stiff * c.w + alpha * (s * (fn_ + fg) - stiff * c.w)) / (xi * stiff + alpha * stiff);
                let w1_ = (A * wg - B * c.w + alpha * s * f1 / (xi * stiff)) / (1.0 + alpha / xi);
                (wg, w1_)
            } else {
                (s * fg / stiff, s * f1 / stiff)
            };
            let w_n = if xi > 0.0 { c.w } else { s * fn_ / stiff };
            let tau_q = w0 * tau_n[ci] + w1 * tau_g[ci] + w2 * tau_1[ci];
            let w_q = w0 * w_n + w1 * wg + w2 * w1_;
            (taus[ci], ws[ci]) = (tau_q, w_q);
            c.w = w1_;
        }
        self.control.integrate(h, taus, ws);
    }
}
