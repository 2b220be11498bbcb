//! Tick positions: 1-2-5 steps on linear axes; decades, or 1-2-5 within decades, or the data's
//! own abscissae (e.g. grid sizes 8, 16, 32, 64) on logarithmic axes.

/// About `target` ticks at multiples of 1, 2 or 5 × 10^k inside [lo, hi].
pub fn linear_ticks(lo: f64, hi: f64, target: usize) -> Vec<f64> {
    if !(lo.is_finite() && hi.is_finite() && hi > lo) {
        return vec![lo];
    }
    let raw = (hi - lo) / target.max(1) as f64;
    let mag = 10f64.powf(raw.log10().floor());
    let count = |step: f64| ((hi / step).floor() - (lo / step).ceil() + 1.0).max(0.0) as usize;
    // The 1-2-5 step whose tick count is closest to the target (ties: more ticks).
    let step = [0.5, 1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .min_by_key(|s| (count(*s).abs_diff(target), usize::MAX - count(*s)))
        .unwrap_or(mag);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    // k·step (not an accumulated sum), so 0 is exactly 0 and labels print cleanly.
    (first..=last).map(|k| k as f64 * step).collect()
}

/// `ticks` with the ends `lo` and `hi` of a colour bar added (each unless a tick lies within
/// `min_gap` · (hi − lo) of it), so the scale's ends are labelled; sorted.
pub fn with_ends(ticks: &[f64], lo: f64, hi: f64, min_gap: f64) -> Vec<f64> {
    let mut out: Vec<f64> = ticks.to_vec();
    for end in [lo, hi] {
        if end.is_finite() && out.iter().all(|t| (t - end).abs() > min_gap * (hi - lo).abs()) {
            out.push(end);
        }
    }
    out.sort_by(f64::total_cmp);
    out
}

/// Ticks of a logarithmic axis over [lo, hi] (lo > 0). `data` are the abscissae of the plotted
/// points: when there are at most 8 distinct ones and the axis spans less than 3 decades,
/// they are the ticks (a grid study at N = 8, 16, 32, 64 is labelled at those N).
/// Otherwise powers of ten (every k-th when there are many), with 2 and 5 added when the
/// axis spans less than 2 decades, so there are always at least two labelled ticks.
pub fn log_ticks(lo: f64, hi: f64, data: &[f64]) -> Vec<f64> {
    if !(lo > 0.0 && hi > lo && hi.is_finite()) {
        return vec![lo.max(f64::MIN_POSITIVE)];
    }
    let decades = (hi / lo).log10();
    let mut distinct: Vec<f64> = data.iter().copied().filter(|x| x.is_finite() && *x >= lo && *x <= hi).collect();
    distinct.sort_by(f64::total_cmp);
    distinct.dedup_by(|a, b| (*a - *b).abs() <= 1e-12 * b.abs());
    if (2..=8).contains(&distinct.len()) && decades < 3.0 {
        return distinct;
    }
    let (k0, k1) = (lo.log10().ceil() as i32, hi.log10().floor() as i32);
    let every = ((k1 - k0 + 1) as f64 / 8.0).ceil().max(1.0) as i32;
    let mut out: Vec<f64> = (k0..=k1).filter(|k| (k - k0) % every == 0).map(|k| 10f64.powi(k)).collect();
    if decades < 2.0 || out.len() < 2 {
        let mut fine = Vec::new();
        for k in (lo.log10().floor() as i32)..=(hi.log10().ceil() as i32) {
            for m in [1.0, 2.0, 5.0] {
                let v = m * 10f64.powi(k);
                if v >= lo && v <= hi {
                    fine.push(v);
                }
            }
        }
        if fine.len() >= 2 {
            out = fine;
        }
    }
    if out.len() < 2 {
        // Narrower than one 1-2-5 step: label the ends.
        out = vec![lo, hi];
    }
    out
}

/// A plotters coordinate with tick positions chosen here ([`linear_ticks`], [`log_ticks`])
/// instead of plotters' own (which give a single tick on short log axes).
pub struct Ticked<R> {
    inner: R,
    ticks: Vec<f64>,
}

impl<R: plotters::coord::ranged1d::Ranged<ValueType = f64>> Ticked<R> {
    /// `inner` with ticks at `ticks`.
    pub fn new(inner: impl Into<R>, ticks: Vec<f64>) -> Self {
        Ticked { inner: inner.into(), ticks }
    }
}

impl<R: plotters::coord::ranged1d::Ranged<ValueType = f64>> plotters::coord::ranged1d::Ranged for Ticked<R> {
    type ValueType = f64;
    type FormatOption = plotters::coord::ranged1d::DefaultFormatting;

    fn range(&self) -> std::ops::Range<f64> {
        self.inner.range()
    }

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        self.inner.map(value, limit)
    }

    fn key_points<Hint: plotters::coord::ranged1d::KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            Vec::new()
        } else {
            self.ticks.clone()
        }
    }

    fn axis_pixel_range(&self, limit: (i32, i32)) -> std::ops::Range<i32> {
        self.inner.axis_pixel_range(limit)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_ticks_are_round() {
        assert_eq!(linear_ticks(0.0, 20.0, 5), vec![0.0, 5.0, 10.0, 15.0, 20.0]);
        assert_eq!(linear_ticks(-0.11, 0.11, 4), vec![-0.1, -0.05, 0.0, 0.05, 0.1]);
    }

    #[test]
    fn log_ticks_use_the_data_or_decades() {
        // A grid study at N = 2, 4, 8, 16: the ticks are those N.
        assert_eq!(log_ticks(1.8, 18.0, &[2.0, 4.0, 8.0, 16.0, 2.0]), vec![2.0, 4.0, 8.0, 16.0]);
        // Many decades: powers of ten.
        assert_eq!(log_ticks(0.5e-3, 2e2, &[]), vec![1e-3, 1e-2, 1e-1, 1.0, 1e1, 1e2]);
        // Less than two decades, no data: 1-2-5.
        assert_eq!(log_ticks(0.9, 30.0, &[]), vec![1.0, 2.0, 5.0, 10.0, 20.0]);
    }
}
