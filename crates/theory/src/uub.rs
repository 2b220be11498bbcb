//! Theorem 2's uniform ultimate bound (37) on the deflection and the twist, from λ2, λ = λ3/λ1
//! and ε of (29)–(32).

use crate::BestPoint;

/// Theorem 2's bound (37): |q(z,t)| ≤ √(s³/λ2 · (W(0)e^{−λt} + ε/λ)) (m) and
/// |θ(z,t)| ≤ √(s/λ2 · (W(0)e^{−λt} + ε/λ)) (rad), for λ2 > 0, λ > 0. The one definition, used
/// by the UUB row and the search.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UubBound {
    /// Span s (m).
    pub span: f64,
    /// λ2 > 0 (J s per SI unit of κ).
    pub lambda2: f64,
    /// λ = λ3/λ1 > 0 (1/s).
    pub lambda: f64,
    /// ε of (32) (J).
    pub epsilon: f64,
    /// W(0) (J s; 0 for the ultimate bound).
    pub w0: f64,
}

impl UubBound {
    /// The bound (35) on W(t): W(0)e^{−λt} + ε/λ (J s).
    pub fn lyapunov(&self, t: f64) -> f64 {
        self.w0 * (-self.lambda * t).exp() + self.epsilon / self.lambda
    }

    /// The bound on |q| at time t (m).
    pub fn q(&self, t: f64) -> f64 {
        (self.span.powi(3) / self.lambda2 * self.lyapunov(t)).sqrt()
    }

    /// The bound on |θ| at time t (rad).
    pub fn theta(&self, t: f64) -> f64 {
        (self.span / self.lambda2 * self.lyapunov(t)).sqrt()
    }

    /// The ultimate bound √(s³/λ2 · ε/λ) on |q| (m), the limit t → ∞.
    pub fn ultimate_q(&self) -> f64 {
        (self.span.powi(3) / self.lambda2 * self.epsilon / self.lambda).sqrt()
    }
}

/// Theorem 2's ultimate bound √(s³/λ2 · ε/λ) on |q| (m) at the best point, for λ2 > 0.
pub fn ultimate_bound_q(span: f64, lambda2: f64, best: &BestPoint) -> Option<f64> {
    (lambda2 > 0.0)
        .then(|| UubBound { span, lambda2, lambda: best.lambda, epsilon: best.epsilon, w0: 0.0 }.ultimate_q())
}
