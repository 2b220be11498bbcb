//! Digital observers: the gain function φ, its explicit and implicit sampling, and the
//! integrator state ν of (17)/(19).

use wingcheck_model::{Config, ControllerKind, ObserverRule};

/// sig^r(x) = sign(x)·|x|^r, with sign(0) = 0 (paper's σ^{(2a1−a2)/a2} for odd a1, a2).
pub fn sig(x: f64, r: f64) -> f64 {
    if x == 0.0 {
        0.0
    } else {
        x.signum() * x.abs().powf(r)
    }
}

/// sign(x) with sign(0) = 0.
pub fn sign(x: f64) -> f64 {
    if x == 0.0 {
        0.0
    } else {
        x.signum()
    }
}

/// Observer gain φ(σ) = linear·σ + switching·sign(σ) + fractional·sig^exponent(σ)
/// (eq. (20) with (κ1, κ2, κ3, r1), (21) with (κ4, κ5, κ6, r2); DOBC: (1, 0, 0)). Units of
/// ĝ: N for bending, N m for torsion; σ has the same units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ObserverGain {
    /// κ1 or κ4 (1/s).
    pub linear: f64,
    /// κ2 or κ5 (same units as ĝ).
    pub switching: f64,
    /// κ3 or κ6.
    pub fractional: f64,
    /// r = (2a1 − a2)/a2 ∈ (0, 1).
    pub exponent: f64,
}

impl ObserverGain {
    /// The DOBC of (57): ĝ = σ.
    pub const DOBC: ObserverGain = ObserverGain { linear: 1.0, switching: 0.0, fractional: 0.0, exponent: 1.0 };

    /// φ(σ), single-valued with sign(0) = 0.
    pub fn phi(&self, sigma: f64) -> f64 {
        self.linear * sigma + self.switching * sign(sigma) + self.fractional * sig(sigma, self.exponent)
    }

    /// Explicit sampling: ĝ_k = φ(σ_k).
    pub fn explicit(&self, sigma: f64) -> f64 {
        self.phi(sigma)
    }

    /// Implicit (Acary–Brogliato) sampling with hold period `period` (s): find σ̃ with
    /// σ̃ + T·Φ(σ̃) ∋ σ_k, where Φ is φ with sign replaced by the set-valued Sgn, and return
    /// ĝ_k = (σ_k − σ̃)/T ∈ Φ(σ̃). For |σ_k| ≤ T·switching the answer is σ̃ = 0, ĝ_k = σ_k/T.
    /// Otherwise |σ̃| = x > 0 solves (1 + T·linear)·x + T·fractional·x^r = |σ_k| − T·switching,
    /// solved by Newton's method in y = x^r (convex and increasing, so Newton from the right
    /// converges monotonically) to the last bit.
    pub fn implicit(&self, sigma: f64, period: f64) -> f64 {
        let rest = sigma.abs() - period * self.switching;
        if rest <= 0.0 {
            return sigma / period;
        }
        let a = 1.0 + period * self.linear;
        let c = period * self.fractional;
        let x = if c == 0.0 {
            rest / a
        } else {
            let r = self.exponent;
            let inv = 1.0 / r;
            // f(y) = a·y^{1/r} + c·y − rest, increasing and convex for y > 0.
            let f = |y: f64| a * y.powf(inv) + c * y - rest;
            let mut y = (rest / a).powf(r).min(rest / c);
            for _ in 0..200 {
                let fy = f(y);
                if fy <= 0.0 {
                    break;
                }
                let df = a * inv * y.powf(inv - 1.0) + c;
                let next = y - fy / df;
                if next.partial_cmp(&y) != Some(std::cmp::Ordering::Less) || next <= 0.0 {
                    break;
                }
                y = next;
            }
            y.powf(inv)
        };
        let tilde = sigma.signum() * x;
        (sigma - tilde) / period
    }

    /// Sampled estimate by the chosen rule.
    pub fn sample(&self, rule: ObserverRule, sigma: f64, period: f64) -> f64 {
        match rule {
            ObserverRule::Explicit => self.explicit(sigma),
            ObserverRule::Implicit => self.implicit(sigma, period),
        }
    }
}

/// Which tip quantity a channel acts on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TipChannel {
    /// Bending: tip force τ1 + g1 (N), tip shear state q'''(s) (1/m²).
    Bending,
    /// Torsion: tip moment τ2 + g2 (N m), tip slope state θ'(s) (1/m).
    Torsion,
}

impl TipChannel {
    /// Sign s in the tip boundary condition ξ S ẇ = s(τ + g) − S w, with w = q'''(s), S = EI, s = −1
    /// (bending) or w = θ'(s), S = GJ, s = +1 (torsion) (corrected (10)).
    pub fn bc_sign(self) -> f64 {
        match self {
            TipChannel::Bending => -1.0,
            TipChannel::Torsion => 1.0,
        }
    }
}

/// One channel's digital observer: its gain, rule, hold period and integrator state ν.
///
/// σ = s ξ S w − ν (eq. (16)/(18)); ν̇ = ĝ + τ − s S w (eq. (17)/(19), corrected). The state ν
/// is advanced by [`ChannelObserver::integrate`] with the trapezoidal averages of τ and w
/// over each integrator step, the same quadrature the simulator uses for the boundary-condition
/// ODE of w, so that σ_{n+1} − σ_n = h(ḡ − ĝ) holds to round-off.
#[derive(Debug, Clone, PartialEq)]
pub struct ChannelObserver {
    /// Which channel.
    pub channel: TipChannel,
    /// φ for this channel.
    pub gain: ObserverGain,
    /// Sampling rule.
    pub rule: ObserverRule,
    /// Hold period T (s).
    pub period: f64,
    /// Stiffness S: EI (bending) or GJ (torsion).
    pub stiffness: f64,
    /// Kelvin–Voigt coefficient ξ.
    pub xi: f64,
    /// Integrator state ν.
    pub nu: f64,
    /// Whether the estimate is used at all (false for `none` and `pd`).
    pub active: bool,
    /// The estimate ĝ held since the last sample (0 before the first and when inactive).
    pub held: f64,
}

impl ChannelObserver {
    /// Build the observer of `channel` for the configured controller kind.
    pub fn new(cfg: &Config, channel: TipChannel) -> ChannelObserver {
        let o = &cfg.observer;
        let (gain, stiffness, nu) = match channel {
            TipChannel::Bending => (
                ObserverGain { linear: o.kappa1, switching: o.kappa2, fractional: o.kappa3, exponent: o.r1() },
                cfg.wing.ei,
                o.nu1_0,
            ),
            TipChannel::Torsion => (
                ObserverGain { linear: o.kappa4, switching: o.kappa5, fractional: o.kappa6, exponent: o.r2() },
                cfg.wing.gj,
                o.nu2_0,
            ),
        };
        let (gain, active) = match cfg.control.kind {
            ControllerKind::Ftdo => (gain, true),
            ControllerKind::Dobc => (ObserverGain::DOBC, true),
            ControllerKind::None | ControllerKind::Pd => (gain, false),
        };
        ChannelObserver {
            channel,
            gain,
            rule: o.rule,
            period: o.sample_period,
            stiffness,
            xi: cfg.wing.xi,
            nu,
            active,
            held: 0.0,
        }
    }

    /// Measured σ = s ξ S w − ν for the current tip state w (q'''(s) or θ'(s)).
    pub fn sigma(&self, w: f64) -> f64 {
        self.channel.bc_sign() * self.xi * self.stiffness * w - self.nu
    }

    /// The estimate ĝ_k to hold over the next sample, from the current tip state w.
    pub fn estimate(&self, w: f64) -> f64 {
        if !self.active {
            return 0.0;
        }
        self.gain.sample(self.rule, self.sigma(w), self.period)
    }

    /// Advance ν over one integrator step of length h with the held estimate ĝ and the
    /// trapezoidal averages τ̄ and w̄: ν += h(ĝ + τ̄ − s S w̄).
    pub fn integrate(&mut self, h: f64, g_hat: f64, tau_mean: f64, w_mean: f64) {
        self.nu += h * (g_hat + tau_mean - self.channel.bc_sign() * self.stiffness * w_mean);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const G: ObserverGain = ObserverGain { linear: 0.8, switching: 1.0, fractional: 4.0, exponent: 1.0 / 13.0 };

    #[test]
    fn implicit_solves_the_inclusion() {
        // Reference: the definition σ̃ + T Φ(σ̃) ∋ σ_k, checked by substitution.
        let t = 1e-3;
        for &s in &[1e-9, 5e-4, 1e-3, 2e-3, 0.01, 0.3, -0.7, 5.0, -1e3] {
            let g = G.implicit(s, t);
            let tilde = s - t * g;
            if tilde == 0.0 {
                assert!(g.abs() <= G.switching + 1e-12, "σ={s}");
            } else {
                assert_eq!(tilde.signum(), s.signum());
                let resid = g - G.phi(tilde);
                assert!(resid.abs() <= 1e-9 * (1.0 + g.abs()), "σ={s} resid={resid}");
            }
        }
    }

    #[test]
    fn implicit_inside_the_switching_band_is_deadbeat() {
        // |σ| ≤ T κ2 ⇒ σ̃ = 0 and ĝ = σ/T (the set-valued step removes σ in one sample).
        assert_eq!(G.implicit(4e-4, 1e-3), 4e-4 / 1e-3);
        assert_eq!(G.implicit(0.0, 1e-3), 0.0);
    }

    #[test]
    fn dobc_gain_is_identity() {
        // (57) corrected: ĝ = σ.
        assert_eq!(ObserverGain::DOBC.phi(0.37), 0.37);
        assert!((ObserverGain::DOBC.implicit(0.37, 0.01) - 0.37 / 1.01).abs() < 1e-15);
    }
}
