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

/// A linear axis over [lo, hi] widened to the 1-2-5 ticks just outside it ([`linear_ticks`]'s
/// step), with those ticks: every value of the range lies between two labelled ticks, so no
/// curve runs above the top label or below the bottom one.
pub fn enclosing_linear(lo: f64, hi: f64, target: usize) -> ((f64, f64), Vec<f64>) {
    let t = linear_ticks(lo, hi, target);
    if t.len() < 2 {
        return ((lo, hi), t);
    }
    let step = t[1] - t[0];
    let (first, last) = ((lo / step - 1e-9).floor() as i64, (hi / step + 1e-9).ceil() as i64);
    let ticks: Vec<f64> = (first..=last).map(|k| k as f64 * step).collect();
    ((lo.min(first as f64 * step), hi.max(last as f64 * step)), ticks)
}

/// A logarithmic axis over [lo, hi] (lo > 0) widened to the decades around it (on the grid of
/// every k-th decade when [`log_ticks`] labels every k-th), with its ticks: every value lies
/// between two labelled ticks.
pub fn enclosing_log(lo: f64, hi: f64) -> ((f64, f64), Vec<f64>) {
    if !(lo > 0.0 && hi > lo && hi.is_finite()) {
        return ((lo, hi), log_ticks(lo, hi, &[]));
    }
    let (k0, k1) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    let every = ((k1 - k0 + 1) as f64 / 8.0).ceil().max(1.0) as i32;
    let k1 = k0 + every * ((k1 - k0 + every - 1) / every).max(1);
    let (a, b) = (10f64.powi(k0), 10f64.powi(k1));
    ((a, b), log_ticks(a, b, &[]))
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
    fn enclosing_ticks_bound_every_value() {
        // −4.9 … 3.5 (an explicit-observer τ1): ticks from −5 to 4 (step 1), not −4 to 3
        let ((lo, hi), t) = enclosing_linear(-4.9, 3.5, 6);
        assert_eq!((lo, hi), (-5.0, 4.0));
        assert!(t.first() == Some(&-5.0) && t.last() == Some(&4.0), "{t:?}");
        // 3e-7 … 40 on a log axis: 1e-7 … 1e3 (every second decade labelled), both ends labelled
        let ((lo, hi), t) = enclosing_log(3e-7, 40.0);
        assert_eq!((lo, hi), (1e-7, 1000.0));
        assert!(t.first() == Some(&1e-7) && t.last() == Some(&1000.0), "{t:?}");
        let ((lo, hi), t) = enclosing_log(0.03, 40.0);
        assert_eq!((lo, hi, t.first().copied()), (0.01, 100.0, Some(0.01)));
        // 14 decades: every second one labelled, the top on that grid
        let ((_, hi), t) = enclosing_log(2e-13, 5.0);
        assert!(*t.last().unwrap() >= 5.0 && (hi - t.last().unwrap()).abs() < 1e-9 * hi, "{t:?} {hi}");
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
