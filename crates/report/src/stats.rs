//! Small statistics over sampled series, used for the numbers printed in captions.
//! Windows are closed intervals [t0, t1] of the sample times.

use wingcheck_sim::metrics::{self, Window};

/// max |v| over samples with t ∈ [t0, t1] ([`wingcheck_sim::metrics::max_abs_in`]); the
/// captions' windows always hold the last sample, 0 for an empty one.
pub fn max_abs(t: &[f64], v: &[f64], t0: f64, t1: f64) -> f64 {
    metrics::max_abs_in(t, v, Window { t0, t1 }).unwrap_or(0.0)
}

/// Root mean square of v over samples with t ∈ [t0, t1] ([`wingcheck_sim::metrics::rms_in`]).
pub fn rms(t: &[f64], v: &[f64], t0: f64, t1: f64) -> f64 {
    metrics::rms_in(t, v, Window { t0, t1 }).unwrap_or(0.0)
}

/// Elementwise a − b.
pub fn diff(a: &[f64], b: &[f64]) -> Vec<f64> {
    a.iter().zip(b).map(|(x, y)| x - y).collect()
}

/// A number with 4 significant digits ([`wingcheck_model::quantity::format_value`], the one
/// number format). Deterministic, and parses back with `str::parse::<f64>`.
pub fn fmt_num(v: f64) -> String {
    wingcheck_model::quantity::format_value(v, None)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_and_windows() {
        assert_eq!(fmt_num(0.012345), "0.01235");
        assert_eq!(fmt_num(123.456), "123.5");
        assert_eq!(fmt_num(1.5e-5), "1.500×10⁻⁵");
        let t = [0.0, 1.0, 2.0, 3.0];
        let v = [5.0, -2.0, 0.5, 0.1];
        assert_eq!(max_abs(&t, &v, 1.0, 3.0), 2.0);
    }
}
