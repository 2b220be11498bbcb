//! The data behind one line chart, independent of how it is drawn: lines of (x, y) with a
//! title and axis labels, exportable as CSV. The claims crate fills it, the report draws it.

use serde::{Deserialize, Serialize};

/// One line of a plot: y against x.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
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
            l.x.iter().zip(&l.y).map(|(x, y)| [l.label.clone(), wingcheck_io::number(*x), wingcheck_io::number(*y)])
        });
        wingcheck_io::csv_text(["series", "x", "y"], rows)
    }

    /// What the CSV holds, for the provenance record: the axes' labels with their units.
    pub fn csv_contents(&self) -> String {
        format!("{}: series = line label, x = {}, y = {}", self.title, self.x_label, self.y_label)
    }
}
