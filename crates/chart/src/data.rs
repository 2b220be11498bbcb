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

    /// What the CSV holds, for the provenance record: the axes' labels with their units.
    pub fn csv_contents(&self) -> String {
        format!("{}: series = line label, x = {}, y = {}", self.title, self.x_label, self.y_label)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
