//! Symmetric-logarithmic ("symlog") axes: linear within ±c of zero, logarithmic beyond, for a
//! quantity whose values span decades on both sides of zero (e.g. sup λ3 ≈ 3e-5 on one side of
//! a boundary and −40 on the other, which a linear axis shows as 0).
//!
//! The transform, with linear threshold c > 0, is
//! f(y) = y / c for |y| ≤ c and f(y) = sign(y) · (1 + log10(|y| / c)) beyond:
//! continuous, strictly increasing, odd, one unit of axis per decade outside ±c and one unit for
//! the linear part on each side. Ticks at 0 and ±c · 10ᵏ.

use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint, Ranged};
use plotters::coord::types::RangedCoordf64;

/// A symmetric-log transform with linear threshold `c` (same unit as the data).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SymLog {
    /// Linear threshold c > 0: the axis is linear for |y| ≤ c.
    pub threshold: f64,
}

/// At most this many decades between the threshold and the largest |y|.
const MAX_DECADES: f64 = 8.0;

impl SymLog {
    /// The transform with threshold `c` (> 0, finite; otherwise 1).
    pub fn new(c: f64) -> Self {
        SymLog { threshold: if c.is_finite() && c > 0.0 { c } else { 1.0 } }
    }

    /// f(y) (axis units).
    pub fn forward(&self, y: f64) -> f64 {
        let a = y.abs() / self.threshold;
        if a <= 1.0 {
            y / self.threshold
        } else {
            y.signum() * (1.0 + a.log10())
        }
    }

    /// f⁻¹(u) (data units).
    pub fn inverse(&self, u: f64) -> f64 {
        if u.abs() <= 1.0 {
            u * self.threshold
        } else {
            u.signum() * self.threshold * 10f64.powf(u.abs() - 1.0)
        }
    }

    /// Whether values `ys` (the plotted ordinates) need a symmetric-log axis, and its threshold.
    ///
    /// Rule: on a linear axis the smallest values read as 0 when a tenth of the nonzero values
    /// lie below 10⁻³ × max |y|, or when the values of one sign all lie below 10⁻² × max |y| of
    /// the other. Then c = the power of ten at or below the 10th percentile of the nonzero |y|,
    /// but at most [`MAX_DECADES`] decades below max |y|. None: a linear axis shows the data.
    pub fn for_values(ys: impl Iterator<Item = f64>) -> Option<SymLog> {
        let ys: Vec<f64> = ys.filter(|y| y.is_finite()).collect();
        let mut mags: Vec<f64> = ys.iter().map(|y| y.abs()).filter(|a| *a > 0.0).collect();
        if mags.len() < 2 {
            return None;
        }
        mags.sort_by(f64::total_cmp);
        let max = mags[mags.len() - 1];
        let p10 = mags[(mags.len() - 1) / 10];
        let side =
            |pos: bool| ys.iter().filter(|y| (**y > 0.0) == pos && **y != 0.0).fold(0.0_f64, |m, y| m.max(y.abs()));
        let (pos, neg) = (side(true), side(false));
        let one_side_hidden = pos > 0.0 && neg > 0.0 && pos.min(neg) < 1e-2 * pos.max(neg);
        if !(p10 < 1e-3 * max || one_side_hidden) {
            return None;
        }
        let floor = max * 10f64.powf(-MAX_DECADES);
        Some(SymLog::new(10f64.powf(p10.max(floor).log10().floor())))
    }

    /// The axis range covering `ys` padded by 5 % of its extent in axis units (so the padding
    /// looks the same on the linear and the logarithmic parts).
    pub fn padded_range(&self, ys: impl Iterator<Item = f64>) -> (f64, f64) {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for u in ys.filter(|y| y.is_finite()).map(|y| self.forward(y)) {
            lo = lo.min(u);
            hi = hi.max(u);
        }
        if !lo.is_finite() {
            return (self.inverse(-1.0), self.inverse(1.0));
        }
        // Always show the linear part on the side of zero the data reach, and zero itself.
        let (lo, hi) = (lo.min(0.0), hi.max(0.0));
        let pad = 0.05 * (hi - lo).max(1.0);
        (self.inverse(lo - pad), self.inverse(hi + pad))
    }

    /// Ticks in [lo, hi]: 0 and ±c·10ᵏ (every k-th decade when there are more than 11 ticks).
    pub fn ticks(&self, lo: f64, hi: f64) -> Vec<f64> {
        let (ulo, uhi) = (self.forward(lo), self.forward(hi));
        let decades = ulo.abs().max(uhi.abs()).ceil().max(1.0) as i32;
        for every in 1..=decades {
            let mut out = Vec::new();
            for k in (0..decades).rev().filter(|k| k % every == 0) {
                out.push(-self.threshold * 10f64.powi(k));
            }
            out.push(0.0);
            for k in (0..decades).filter(|k| k % every == 0) {
                out.push(self.threshold * 10f64.powi(k));
            }
            out.retain(|v| *v >= lo && *v <= hi);
            if out.len() <= 11 {
                return out;
            }
        }
        vec![0.0]
    }

    /// Tick label: `0`, or ±10ᵏ when c is a power of ten, else the value in [`crate::tick`]'s
    /// format; negative values with a minus sign (−).
    pub fn label(&self, v: f64) -> String {
        if v == 0.0 {
            return "0".into();
        }
        let a = v.abs();
        let s = if crate::is_decade(self.threshold) && crate::is_decade(a) {
            crate::decade_label(a)
        } else {
            crate::tick(a)
        };
        if v < 0.0 {
            format!("−{s}")
        } else {
            s
        }
    }

    /// The statement of the threshold shown beside the chart.
    pub fn note(&self) -> [String; 2] {
        ["y axis: symmetric log,".into(), format!("linear for |y| ≤ {}", self.label(self.threshold))]
    }
}

/// A plotters coordinate over [lo, hi] in data units, mapped through a [`SymLog`] transform.
pub struct SymLogCoord {
    range: (f64, f64),
    transform: SymLog,
    inner: RangedCoordf64,
}

impl SymLogCoord {
    /// The coordinate over [lo, hi].
    pub fn new(lo: f64, hi: f64, transform: SymLog) -> Self {
        let inner = (transform.forward(lo)..transform.forward(hi)).into();
        SymLogCoord { range: (lo, hi), transform, inner }
    }
}

impl Ranged for SymLogCoord {
    type ValueType = f64;
    type FormatOption = DefaultFormatting;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        self.inner.map(&self.transform.forward(*value), limit)
    }

    fn key_points<Hint: KeyPointHint>(&self, _hint: Hint) -> Vec<f64> {
        self.transform.ticks(self.range.0, self.range.1)
    }

    fn range(&self) -> std::ops::Range<f64> {
        self.range.0..self.range.1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn transform_round_trips_and_is_monotone() {
        let s = SymLog::new(1e-6);
        let mut prev = f64::NEG_INFINITY;
        // 2001 values from −10³ to 10³ through the linear part (both sides of ±c and 0).
        for i in -1000_i32..=1000 {
            // y = ±10^(|i|/100 − 7): 10⁻⁷ … 10³ on each side, and 0.
            let y = if i == 0 { 0.0 } else { f64::from(i.signum()) * 10f64.powf(f64::from(i.abs()) / 100.0 - 7.0) };
            let u = s.forward(y);
            assert!(u > prev, "monotone at y = {y}: {u} after {prev}");
            prev = u;
            let back = s.inverse(u);
            assert!((back - y).abs() <= 1e-12 * y.abs().max(1e-6), "round trip {y} → {u} → {back}");
        }
        // Continuity at ±c (both branches give ±1) and one axis unit per decade beyond it.
        assert_eq!(s.forward(1e-6), 1.0);
        assert!((s.forward(-1e-6 * (1.0 + 1e-12)) + 1.0).abs() < 1e-11);
        assert!((s.forward(1e-3) - 4.0).abs() < 1e-12, "10⁻³ is 3 decades above c = 10⁻⁶");
    }

    #[test]
    fn ticks_are_zero_and_signed_decades_of_the_threshold() {
        let s = SymLog::new(1e-3);
        // [−0.5, 2e-2]: decades −10⁻¹, −10⁻², −10⁻³, 0, 10⁻³, 10⁻² (10⁻¹ is above hi).
        assert_eq!(s.ticks(-0.5, 2e-2), vec![-1e-1, -1e-2, -1e-3, 0.0, 1e-3, 1e-2]);
        assert_eq!(s.label(-1e-3), "−10⁻³");
        assert_eq!(s.label(1e-2), "10⁻²");
        assert_eq!(s.label(0.0), "0");
        // 14 decades each side: thinned to at most 11 ticks, 0 and ±c kept.
        let t = SymLog::new(1e-7).ticks(-1e7, 1e7);
        assert!(t.len() <= 11 && t.contains(&0.0) && t.contains(&1e-7) && t.contains(&-1e-7), "{t:?}");
    }

    #[test]
    fn chosen_for_values_hidden_next_to_large_ones_only() {
        // sup λ3/b-like data: 2e-6 … 6e-5 on one side, −7e-4 … −42 on the other.
        let mu = [2.3e-6, 5e-6, 1.1e-5, 2.5e-5, 5.7e-5, -7e-4, -6.8e-3, -0.09, -1.1, -12.0, -42.0];
        let s = SymLog::for_values(mu.into_iter()).expect("the positive side reads as 0 on a linear axis");
        // c: the power of ten at or below the 10th percentile of |y| (the 2nd smallest, 5e-6).
        assert_eq!(s.threshold, 1e-6);
        // A sine over a period: no value hidden, linear.
        let sine = (0..200).map(|k| (k as f64 * 0.0314).sin());
        assert_eq!(SymLog::for_values(sine), None);
        // All of the same magnitude: linear.
        assert_eq!(SymLog::for_values([1.0, -2.0, 3.0].into_iter()), None);
    }

    #[test]
    fn padded_range_contains_the_data_and_zero() {
        let s = SymLog::new(1e-6);
        let (lo, hi) = s.padded_range([-42.0, 5.7e-5].into_iter());
        assert!(lo < -42.0 && hi > 5.7e-5, "{lo} {hi}");
        let (lo, hi) = s.padded_range([3e-3, 5.0].into_iter());
        assert!(lo < 0.0 && hi > 5.0, "zero is shown: {lo} {hi}");
    }
}
