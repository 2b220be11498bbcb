//! A report figure: its chart data, its caption (text with numbers computed from the runs,
//! each tagged with a stable key) and its file names.

use serde::Serialize;
use wingcheck_claims::{Line, PlotData};

use crate::chart::{heatmap_svg, line_svg, surface_svg, Heatmap, LineChart};
use crate::stats::fmt_num;
use crate::ReportError;

/// One piece of a caption: plain text, or a number computed from a run (`key` set).
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Part {
    /// The text (for a number: its formatted value).
    pub text: String,
    /// Stable key of a computed number (e.g. `fig9.max_abs_late`); `None` for plain text.
    pub key: Option<String>,
}

/// Caption builder.
#[derive(Debug, Clone, Default)]
pub struct Caption(pub Vec<Part>);

impl Caption {
    /// Append text.
    pub fn t(mut self, s: impl Into<String>) -> Self {
        self.0.push(Part { text: s.into(), key: None });
        self
    }
    /// Append a computed count with its key.
    pub fn count(mut self, key: impl Into<String>, v: usize) -> Self {
        self.0.push(Part { text: v.to_string(), key: Some(key.into()) });
        self
    }
    /// Append a computed number (4 significant digits) with its key.
    pub fn n(mut self, key: impl Into<String>, v: f64) -> Self {
        self.0.push(Part { text: fmt_num(v), key: Some(key.into()) });
        self
    }
}

/// What is drawn.
#[derive(Debug, Clone)]
pub enum Chart {
    /// Lines / points / steps.
    Line(LineChart),
    /// A field over (t, z).
    Heat(Heatmap),
    /// A field over (t, z) as a 3-D surface.
    Surface(Heatmap),
    /// A grid heatmap with marks (the (a, b) region map) and the CSV of its data.
    Grid {
        /// The chart.
        map: Box<crate::chart::GridHeatmap>,
        /// The data behind it.
        csv: String,
    },
}

/// A figure of the report.
#[derive(Debug, Clone)]
pub struct Figure {
    /// File stem of the SVG and CSV (file-name safe, unique in the report).
    pub file: String,
    /// Label, e.g. `Figure 9` or `Evidence E1`.
    pub label: String,
    /// Short title.
    pub title: String,
    /// Caption parts.
    pub caption: Vec<Part>,
    /// The data.
    pub chart: Chart,
}

/// Rendered files of a figure.
pub struct Rendered {
    /// SVG document.
    pub svg: String,
    /// CSV of the data behind it.
    pub csv: String,
    /// What the CSV's columns hold, with units (the report's provenance.json lists it).
    pub contents: String,
}

impl Figure {
    /// Draw the SVG and write the CSV.
    pub fn render(&self) -> Result<Rendered, ReportError> {
        Ok(match &self.chart {
            Chart::Line(c) => Rendered { svg: line_svg(c)?, csv: c.data.to_csv(), contents: c.data.csv_contents() },
            Chart::Heat(h) => Rendered { svg: heatmap_svg(h)?, csv: h.to_csv(), contents: h.csv_contents() },
            Chart::Surface(s) => Rendered { svg: surface_svg(s)?, csv: s.to_csv(), contents: s.csv_contents() },
            Chart::Grid { map, csv } => Rendered {
                svg: crate::chart::grid_heatmap_svg(map)?,
                csv: csv.clone(),
                contents: "the (a, b) region map: one row per cell (docs/outputs.md, region map)".into(),
            },
        })
    }
}

/// Make a string file-name safe (`[A-Za-z0-9_-]`, others become `-`).
pub fn safe_name(s: &str) -> String {
    let s: String =
        s.chars().map(|c| if c.is_ascii_alphanumeric() || c == '_' || c == '-' { c } else { '-' }).collect();
    if s.is_empty() {
        "plot".into()
    } else {
        s
    }
}

/// A one-line plot: y(t).
pub fn line_plot(name: &str, title: &str, y_label: &str, lines: Vec<(String, &[f64], Vec<f64>)>) -> PlotData {
    PlotData {
        name: name.into(),
        title: title.into(),
        x_label: "t (s)".into(),
        y_label: y_label.into(),
        log_x: false,
        log_y: false,
        lines: lines.into_iter().map(|(label, x, y)| Line { label, x: x.to_vec(), y, points: false }).collect(),
    }
}
