//! Small statistics over sampled series, used for the numbers printed in captions.
//! Windows are closed intervals [t0, t1] of the sample times.

/// max |v| over samples with t ∈ [t0, t1] (NaN if none).
pub fn max_abs(t: &[f64], v: &[f64], t0: f64, t1: f64) -> f64 {
    window(t, v, t0, t1).map(f64::abs).fold(f64::NAN, f64::max)
}

/// Root mean square of v over samples with t ∈ [t0, t1] (NaN if none).
pub fn rms(t: &[f64], v: &[f64], t0: f64, t1: f64) -> f64 {
    let (n, s) = window(t, v, t0, t1).fold((0usize, 0.0), |(n, s), x| (n + 1, s + x * x));
    if n == 0 {
        f64::NAN
    } else {
        (s / n as f64).sqrt()
    }
}

fn window<'a>(t: &'a [f64], v: &'a [f64], t0: f64, t1: f64) -> impl Iterator<Item = f64> + 'a {
    t.iter().zip(v).filter(move |(t, _)| **t >= t0 && **t <= t1).map(|(_, v)| *v)
}

/// Elementwise a − b.
pub fn diff(a: &[f64], b: &[f64]) -> Vec<f64> {
    a.iter().zip(b).map(|(x, y)| x - y).collect()
}

/// Least-squares slope of log(y) against log(x) (pairs with x, y > 0 only; NaN if < 2).
pub fn loglog_slope(x: &[f64], y: &[f64]) -> f64 {
    let pts: Vec<(f64, f64)> =
        x.iter().zip(y).filter(|(a, b)| **a > 0.0 && **b > 0.0).map(|(a, b)| (a.ln(), b.ln())).collect();
    let n = pts.len() as f64;
    if pts.len() < 2 {
        return f64::NAN;
    }
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    sxy / sxx
}

/// A number with 4 significant digits, fixed notation for 1e-3 ≤ |v| < 1e4, else scientific.
/// Deterministic, and parses back with `str::parse::<f64>`.
pub fn fmt_num(v: f64) -> String {
    if !v.is_finite() {
        return format!("{v}");
    }
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    if (1e-3..1e4).contains(&a) {
        let decimals = (3 - a.log10().floor() as i32).max(0) as usize;
        format!("{v:.decimals$}")
    } else {
        format!("{v:.3e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_and_windows() {
        assert_eq!(fmt_num(0.012345), "0.01235");
        assert_eq!(fmt_num(123.456), "123.5");
        assert_eq!(fmt_num(1.5e-5), "1.500e-5");
        let t = [0.0, 1.0, 2.0, 3.0];
        let v = [5.0, -2.0, 0.5, 0.1];
        assert_eq!(max_abs(&t, &v, 1.0, 3.0), 2.0);
        // y = x^-2 exactly.
        assert!((loglog_slope(&[1.0, 2.0, 4.0], &[1.0, 0.25, 0.0625]) + 2.0).abs() < 1e-12);
    }
}
