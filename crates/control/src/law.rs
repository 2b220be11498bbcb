//! The boundary control law (15), written once: τ1 = −k1 (a q(s,t) + b q̇(s,t)) − ĝ1 (N) and
//! τ2 = −k2 (a θ(s,t) + b θ̇(s,t)) − ĝ2 (N m). Without a controller both gains are 0 and ĝ is
//! not applied (the simulator holds ĝ = 0 then).

use wingcheck_model::bounds::bound;
use wingcheck_model::{Config, ControllerKind};

use crate::ControlError;

/// The gains and weights of (15).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoundaryLaw {
    /// k1 (N/m) and k2 (N m/rad); both 0 without a controller.
    pub gains: [f64; 2],
    /// Weight a of the tip displacement (dimensionless).
    pub a: f64,
    /// Weight b of the tip rate (s).
    pub b: f64,
}

impl BoundaryLaw {
    /// The law of `cfg` (`control.kind = none` gives zero gains).
    pub fn of(cfg: &Config) -> BoundaryLaw {
        let gains = match cfg.control.kind {
            ControllerKind::None => [0.0, 0.0],
            _ => [cfg.control.k1, cfg.control.k2],
        };
        BoundaryLaw { gains, a: cfg.control.a, b: cfg.control.b }
    }

    /// τ of channel `c` (0: bending, N; 1: torsion, N m) at the tip displacement `x`, tip rate
    /// `v` and held estimate `g_hat`.
    pub fn tau(&self, c: usize, x: f64, v: f64, g_hat: f64) -> f64 {
        -self.gains[c] * (self.a * x + self.b * v) - g_hat
    }

    /// Refuse a law outside the configuration's ranges of control.k1, control.k2, control.a and
    /// control.b (for a law a controller supplies rather than one read from a validated
    /// configuration), naming the value and the range.
    pub fn check(&self) -> Result<(), ControlError> {
        let values = [("k1", self.gains[0]), ("k2", self.gains[1]), ("a", self.a), ("b", self.b)];
        for (name, v) in values {
            let range = bound(&format!("control.{name}"));
            if !range.admits(v) {
                return Err(ControlError::Continuous { reason: format!("{name} = {v} is not {}", range.allowed()) });
            }
        }
        Ok(())
    }

    /// k·a of channel `c`: the displacement part of (15), a tip stiffness.
    pub fn stiffness(&self, c: usize) -> f64 {
        self.gains[c] * self.a
    }

    /// k·b of channel `c`: the rate part of (15), a tip damper.
    pub fn damping(&self, c: usize) -> f64 {
        self.gains[c] * self.b
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_law_is_15_and_none_has_no_gain() {
        let mut cfg = Config::paper();
        let law = BoundaryLaw::of(&cfg);
        // paper: k1 = 2, a = b = 1: τ1 = −2(0.25 + 0.5) − 0.125 = −1.625 (exact in binary)
        assert_eq!(law.tau(0, 0.25, 0.5, 0.125), -1.625);
        assert_eq!(law.stiffness(1), 1.0);
        cfg.control.kind = ControllerKind::None;
        assert_eq!(BoundaryLaw::of(&cfg).tau(0, 0.25, 0.5, 0.0), 0.0);
    }

    #[test]
    fn a_supplied_law_is_checked_against_the_configurations_ranges() {
        // Reference: the validator's table (control.b ∈ [0, 1e12]).
        assert!(BoundaryLaw::of(&Config::paper()).check().is_ok());
        let bad = BoundaryLaw { gains: [1.0, 1.0], a: 1.0, b: -2.0 };
        let msg = bad.check().unwrap_err().to_string();
        assert!(msg.starts_with("controller.continuous: b = -2 is not in [0, "), "{msg}");
        assert!(BoundaryLaw { gains: [f64::NAN, 0.0], a: 0.0, b: 0.0 }.check().is_err());
    }
}
