//! cos ωt and sin ωt along times that advance one step h at a time, by rotation: the
//! disturbances (56) are sinusoids evaluated at every integrator step, and the trigonometric
//! calls were ≈ 14 % of a default `simulate` run.
//!
//! Each value is either exact (the standard library's `sin` and `cos` at t, an *anchor*) or the
//! previous value rotated by ωh, where t is the previous time plus h (to round-off) and fewer
//! than [`ANCHOR_EVERY`] rotations have been made since the last anchor. A rotation is four
//! products and two sums: its value is the previous one's to ≈ 2ε (on a unit circle), and the
//! time it stands for is the anchor's plus m·h instead of the float t; both errors stay
//! within [`Oscillator::error_bound`] (tested against the exact values over 20-s runs).

/// Rotations between two exact evaluations.
pub const ANCHOR_EVERY: u32 = 16;

/// cos ωt and sin ωt at a sequence of times ([`Oscillator::at`]).
#[derive(Debug, Clone)]
pub struct Oscillator {
    /// ω (rad/s).
    omega: f64,
    /// The step h (s).
    h: f64,
    /// (cos ωh, sin ωh).
    rotation: (f64, f64),
    /// The previous time and its (cos, sin).
    last: Option<(f64, f64, f64)>,
    /// Rotations since the last exact evaluation.
    rotations: u32,
}

impl Oscillator {
    /// An oscillator of angular frequency ω (rad/s) for times a step h (s) apart.
    pub fn new(omega: f64, h: f64) -> Oscillator {
        let step = omega * h;
        Oscillator { omega, h, rotation: (step.cos(), step.sin()), last: None, rotations: 0 }
    }

    /// (cos ωt, sin ωt): the previous value again at the same t, the previous value rotated by
    /// ωh where t is one step after it (|t − t_prev − h| ≤ 4ε max(|t|, h)) and fewer than
    /// [`ANCHOR_EVERY`] rotations were made since the last exact value, else exact.
    #[inline]
    pub fn at(&mut self, t: f64) -> (f64, f64) {
        if let Some((previous, c, s)) = self.last {
            if t == previous {
                return (c, s);
            }
            if self.rotations + 1 < ANCHOR_EVERY
                && (t - previous - self.h).abs() <= 4.0 * f64::EPSILON * t.abs().max(self.h)
            {
                let (ch, sh) = self.rotation;
                let (c, s) = (c * ch - s * sh, s * ch + c * sh);
                self.last = Some((t, c, s));
                self.rotations += 1;
                return (c, s);
            }
        }
        let angle = self.omega * t;
        let (c, s) = (angle.cos(), angle.sin());
        self.last = Some((t, c, s));
        self.rotations = 0;
        (c, s)
    }

    /// A bound on |cos ωt − c| and |sin ωt − s| for a value (c, s) of [`Oscillator::at`] at
    /// times up to `t_max` (s), against the exact values at the same float t: the rotations'
    /// round-off (≤ 3ε each, [`ANCHOR_EVERY`] − 1 of them), the angle ω(t_a + m h − t) they
    /// stand for instead of ωt (≤ (4m + 1)ε·max(t_max, h)·|ω|, the test of a step), and the
    /// round-off of cos ωh, sin ωh carried m times.
    pub fn error_bound(&self, t_max: f64) -> f64 {
        let m = f64::from(ANCHOR_EVERY - 1);
        let angle = (4.0 * m + 1.0) * f64::EPSILON * t_max.max(self.h) * self.omega.abs();
        m * 3.0 * f64::EPSILON + angle + m * 2.0 * f64::EPSILON * (1.0 + (self.omega * self.h).abs())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Over a 20-s run of 1-ms steps (the step midpoints t_n = n·h + h/2, as the runs form
    /// them), every value is within the bound of the exact one, the bound is small (≤ 1e-10
    /// for ω ≤ 100 rad/s; it allows every step to deviate from h by the most the step test
    /// accepts, so it is loose: measured 3e-15 against 2.9e-13 at ω = 1), and an anchor is
    /// exact (the standard library's bits).
    #[test]
    fn rotated_values_stay_within_the_bound_of_the_exact_ones() {
        for omega in [0.0, 1.0, 3.0 * std::f64::consts::PI, 9.42477796076938, 100.0, -7.0] {
            let h = 1e-3;
            let mut osc = Oscillator::new(omega, h);
            let bound = osc.error_bound(20.0);
            assert!(bound <= 1e-10, "ω = {omega}: bound {bound:e}");
            let mut worst = 0.0f64;
            for n in 0..20_000 {
                let t = n as f64 * h + 0.5 * h;
                let (c, s) = osc.at(t);
                let (ce, se) = ((omega * t).cos(), (omega * t).sin());
                worst = worst.max((c - ce).abs()).max((s - se).abs());
                if n % ANCHOR_EVERY as usize == 0 {
                    assert_eq!((c.to_bits(), s.to_bits()), (ce.to_bits(), se.to_bits()), "anchor at n = {n}");
                }
            }
            assert!(worst <= bound, "ω = {omega}: {worst:e} > {bound:e}");
            println!("ω = {omega}: worst {worst:.1e}, bound {bound:.1e}");
        }
    }

    /// Times that do not advance by one step are evaluated exactly; the same time twice gives
    /// the same value.
    #[test]
    fn irregular_times_are_exact() {
        let mut osc = Oscillator::new(2.5, 1e-3);
        for t in [0.0, 0.0137, 0.0137, 0.5, 0.5005, 0.2, 3.0] {
            let (c, s) = osc.at(t);
            assert_eq!((c.to_bits(), s.to_bits()), ((2.5 * t).cos().to_bits(), (2.5 * t).sin().to_bits()), "t = {t}");
        }
    }
}
