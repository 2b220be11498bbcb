//! The data behind one line chart, independent of how it is drawn: lines of (x, y) with a
//! title and axis labels, exportable as CSV. The claims crate fills it, the report draws it.

use serde::{Deserialize, Serialize};

/// One line of a plot: y against x.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Line {
    /// Legend label.
    pub label: String,
    /// Abscissae.
    pub x: Vec<f64>,
    /// Ordinates (same length as x).
    pub y: Vec<f64>,
    /// Draw as points instead of a polyline.
    #[serde(default)]
    pub points: bool,
}

/// The data behind one evidence figure, ready to plot or export as CSV.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
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
    /// The data as CSV: one block per line (`label,x,y`).
    pub fn to_csv(&self) -> String {
        let mut out = format!("line,{},{}\n", csv_field(&self.x_label), csv_field(&self.y_label));
        for l in &self.lines {
            for (x, y) in l.x.iter().zip(&l.y) {
                out.push_str(&format!("{},{x},{y}\n", csv_field(&l.label)));
            }
        }
        out
    }
}

pub(crate) fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}
