//! The data behind one line chart, independent of how it is drawn: lines of (x, y) with a
//! title and axis labels, exportable as CSV. The claims crate fills it, the report draws it.

use serde::{Deserialize, Serialize};

/// Significant digits of a plot line's values in JSON (`ledger.json`, `check --json`) and in its
/// CSV: at most 5e-6 relative, below the errors the tool states for the drawn quantities (2e-4
/// absolute on the tips at the default grid) and far below a pixel. A plot line is drawing
/// data; the evidence numbers beside it keep full precision.
pub const PLOT_DIGITS: usize = 6;

/// `v` rounded to [`PLOT_DIGITS`] significant digits (finite values; others unchanged).
pub fn drawing_value(v: f64) -> f64 {
    if v == 0.0 || !v.is_finite() {
        return v;
    }
    format!("{v:.*e}", PLOT_DIGITS - 1).parse().unwrap_or(v)
}

fn drawing_digits<S: serde::Serializer>(values: &[f64], s: S) -> Result<S::Ok, S::Error> {
    use serde::ser::SerializeSeq;
    let mut seq = s.serialize_seq(Some(values.len()))?;
    for v in values {
        seq.serialize_element(&drawing_value(*v))?;
    }
    seq.end()
}

/// Drawing data (a figure's data file and the series it draws, a row's plot in `ledger.json`)
/// hold at most this many samples per series; longer series are thinned ([`stride`]), so a
/// report's folder does not grow with the horizon.
pub const MAX_DRAWN_SAMPLES: usize = 2001;

/// The stride that thins `n` samples to at most [`MAX_DRAWN_SAMPLES`]: every k-th sample, k =
/// ⌈(n − 1)/(MAX_DRAWN_SAMPLES − 1)⌉ (1 for n ≤ MAX_DRAWN_SAMPLES).
pub fn stride(n: usize) -> usize {
    n.saturating_sub(1).div_ceil(MAX_DRAWN_SAMPLES - 1).max(1)
}

/// The samples kept of `n` at stride `k`: 0, k, 2k, … and always the last.
pub fn kept(n: usize, k: usize) -> Vec<usize> {
    let mut v: Vec<usize> = (0..n).step_by(k.max(1)).collect();
    if n > 0 && v.last() != Some(&(n - 1)) {
        v.push(n - 1);
    }
    v
}

/// `v` at the kept samples.
pub fn thin<T: Copy>(v: &[T], kept: &[usize]) -> Vec<T> {
    kept.iter().filter_map(|&i| v.get(i).copied()).collect()
}

/// A band of per-interval extremes (`lo[i]`, `hi[i]` over the interval ending at sample i)
/// thinned to `kept`: each kept sample's interval is the union of the intervals since the
/// previous kept one (the minimum of the minima, the maximum of the maxima), so no extreme is
/// lost.
pub fn thin_band(lo: &[f64], hi: &[f64], kept: &[usize]) -> (Vec<f64>, Vec<f64>) {
    let mut start = 0;
    let (mut l, mut h) = (Vec::with_capacity(kept.len()), Vec::with_capacity(kept.len()));
    for &i in kept {
        let (a, b) = (start.min(i), i);
        l.push(lo[a..=b.min(lo.len() - 1)].iter().copied().fold(f64::INFINITY, f64::min));
        h.push(hi[a..=b.min(hi.len() - 1)].iter().copied().fold(f64::NEG_INFINITY, f64::max));
        start = i + 1;
    }
    (l, h)
}

/// One line of a plot: y against x.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Line {
    /// Legend label.
    pub label: String,
    /// Abscissae (serialised to [`PLOT_DIGITS`] significant digits).
    #[serde(serialize_with = "drawing_digits")]
    pub x: Vec<f64>,
    /// Ordinates (same length as x; serialised to [`PLOT_DIGITS`] significant digits).
    #[serde(serialize_with = "drawing_digits")]
    pub y: Vec<f64>,
    /// Draw as points instead of a polyline.
    #[serde(default)]
    pub points: bool,
}

/// The data behind one evidence figure, ready to plot or export as CSV.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct PlotData {
    /// File-name-safe identifier, unique within the ledger (e.g. `finite-time-sigma1`).
    pub name: String,
    /// Title / caption (numbers in it come from the run).
    pub title: String,
    /// x-axis label with units.
    pub x_label: String,
    /// y-axis label with units.
    pub y_label: String,
    /// Logarithmic x axis.
    #[serde(default)]
    pub log_x: bool,
    /// Logarithmic y axis.
    #[serde(default)]
    pub log_y: bool,
    /// The lines.
    pub lines: Vec<Line>,
}

impl PlotData {
    /// The data as CSV in long form, `series,x,y` (one row per point, the line's legend label
    /// in `series`); x and y are in the units of the axis labels [`Self::x_label`] and
    /// [`Self::y_label`], which the report's `provenance.json` lists for every figure file.
    pub fn to_csv(&self) -> String {
        let rows = self.lines.iter().flat_map(|l| {
            l.x.iter().zip(&l.y).map(|(x, y)| {
                [l.label.clone(), wingcheck_io::number(drawing_value(*x)), wingcheck_io::number(drawing_value(*y))]
            })
        });
        wingcheck_io::csv_text(["series", "x", "y"], rows)
    }

    /// The plot with every polyline of the longest length thinned to at most
    /// [`MAX_DRAWN_SAMPLES`] points ([`stride`]; marker lines and shorter lines unchanged).
    pub fn thinned(mut self) -> PlotData {
        let n = self.lines.iter().filter(|l| !l.points).map(|l| l.x.len()).max().unwrap_or(0);
        let k = stride(n);
        if k > 1 {
            let keep = kept(n, k);
            for l in self.lines.iter_mut().filter(|l| !l.points && l.x.len() == n && l.y.len() == n) {
                l.x = thin(&l.x, &keep);
                l.y = thin(&l.y, &keep);
            }
        }
        self
    }

    /// What the CSV holds, for the provenance record: the axes' labels with their units.
    pub fn csv_contents(&self) -> String {
        format!("{}: series = line label, x = {}, y = {}", self.title, self.x_label, self.y_label)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thinning_keeps_the_ends_and_every_extreme() {
        // 2001 samples (t_end = 20 s at 0.01 s): unchanged; 4001 (40 s): every 2nd; 10001: 5th.
        assert_eq!((stride(2001), stride(4001), stride(10001), stride(1)), (1, 2, 5, 1));
        let keep = kept(7, 3);
        assert_eq!(keep, vec![0, 3, 6]);
        assert_eq!(kept(8, 3), vec![0, 3, 6, 7]);
        // per-interval extremes: the kept sample's band covers every merged interval
        let lo = [0.0, -1.0, -5.0, -2.0, -3.0, -1.0, -4.0];
        let hi = [0.0, 1.0, 2.0, 9.0, 3.0, 1.0, 4.0];
        assert_eq!(thin_band(&lo, &hi, &keep), (vec![0.0, -5.0, -4.0], vec![0.0, 9.0, 4.0]));
    }

    #[test]
    fn drawing_values_keep_six_significant_digits() {
        // references: the decimal expansions written out by hand
        assert_eq!(drawing_value(0.35000000000000003), 0.35);
        assert_eq!(drawing_value(-1.234567891e-7), -1.23457e-7);
        assert_eq!(drawing_value(0.0), 0.0);
        for v in [1.0000049, 9.999995e3, 2.718281e-3, 2.0e-300] {
            assert!(((drawing_value(v) - v) / v).abs() <= 5e-6, "{v}");
        }
    }
}
