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
    /// Append a quantity as the ledger prints it: its number with the key, then its error and
    /// unit (`0.0540814241193751` ` ± 9.0×10⁻¹⁵ s`).
    pub fn q(mut self, key: impl Into<String>, q: &wingcheck_model::Quantity) -> Self {
        let shown = q.shown();
        let rest = match q.error() {
            Some(e) if !shown.unresolved => format!(" ± {}{}", wingcheck_model::format::format_error(e), shown.unit),
            _ => shown.unit.clone(),
        };
        self.0.push(Part { text: shown.number, key: Some(key.into()) });
        self.0.push(Part { text: rest, key: None });
        self
    }
}

/// How the values of a data file are written.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Digits {
    /// Shortest round-trip decimal (exact: where small differences matter).
    RoundTrip,
    /// To an absolute resolution: the digits of the values' estimated error
    /// ([`wingcheck_model::quantity::resolution_of`], [`wingcheck_model::quantity::format_resolved`]).
    Resolution(f64),
    /// With this many significant digits: values on a log axis, from their relative error
    /// (two significant digits of it, the rule of [`wingcheck_model::quantity::format_value`]).
    Significant(usize),
}

impl Digits {
    /// The digits of a value with absolute error `error` (round-trip when there is none).
    pub fn absolute(error: f64) -> Digits {
        wingcheck_model::quantity::resolution_of(error).map_or(Digits::RoundTrip, Digits::Resolution)
    }

    /// The significant digits of values with relative error `relative` (round-trip when there
    /// is none), at most 15.
    pub fn relative(relative: f64) -> Digits {
        match wingcheck_model::quantity::resolution_of(relative) {
            Some(r) => Digits::Significant(((-r.log10()).round() as usize + 1).clamp(1, 15)),
            None => Digits::RoundTrip,
        }
    }

    /// `v` as written.
    pub fn format(self, v: f64) -> String {
        match self {
            Digits::RoundTrip => v.to_string(),
            Digits::Resolution(r) => wingcheck_model::quantity::format_resolved(v, r),
            Digits::Significant(n) => {
                // the shorter of the plain and the scientific form of the rounded value
                let sci = format!("{:.*e}", n.saturating_sub(1), v);
                let x: f64 = sci.parse().unwrap_or(v);
                let (plain, sci) = (x.to_string(), format!("{x:e}"));
                if sci.len() < plain.len() {
                    sci
                } else {
                    plain
                }
            }
        }
    }
}

/// What is drawn.
#[derive(Debug, Clone)]
pub enum Chart {
    /// Lines / points / steps; data file with round-trip numbers.
    Line(LineChart),
    /// Lines of measured (simulated) values; data file with the values' digits,
    /// gzip-compressed.
    Measured {
        /// The chart.
        chart: LineChart,
        /// How its values are written.
        digits: Digits,
    },
    /// A ledger row's plot: its data is in `ledger.json` (at `path`), so it writes no file.
    InLedger {
        /// The chart.
        chart: LineChart,
        /// Where in ledger.json (`rows[5].plots[0]`), for tools.
        path: String,
        /// The same in words (`the UUB row's plot 2`), for the link.
        what: String,
    },
    /// A field over (t, z); its data file has the values to `resolution` (the digits of their
    /// estimated error, [`wingcheck_model::quantity::format_resolved`]; None: shortest
    /// round-trip), gzip-compressed.
    Heat {
        /// The field.
        map: Heatmap,
        /// Resolution of the written values.
        resolution: Option<f64>,
    },
    /// A field over (t, z) as a 3-D surface: the same data as its map (figure file stem
    /// `<map>-surface`), so it writes no data file of its own.
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
    /// The data behind it (file bytes), unless another figure's file holds it.
    pub csv: Option<Vec<u8>>,
    /// What the data file's columns hold, with units (the report's provenance.json lists it).
    pub contents: String,
}

/// The deflate level of the report's `.csv.gz` files. miniz_oxide (flate2's Rust backend) at 4
/// wrote the report's data in a fifth of the time it took at 6 (the earlier level), in files of
/// the same size: measured 2026-12-06 on the data at the paper's configuration, at b = 3000 and
/// with the explicit observer, 1.615, 2.002 and 1.616 MB at 4 against 1.614, 2.010 and 1.614 MB at
/// 6, in 0.11 against 0.52 s (one thread). 5 is 0.4 % smaller at the paper's point and 50 %
/// slower; 1–3 are 6–40 % larger, 7–9 larger and slower still.
const GZIP_LEVEL: u32 = 4;

/// `text` gzip-compressed, deterministically (no file name, time 0, [`GZIP_LEVEL`]).
fn gzip(text: &str) -> Vec<u8> {
    use std::io::Write;
    let mut enc = flate2::GzBuilder::new().mtime(0).write(Vec::new(), flate2::Compression::new(GZIP_LEVEL));
    enc.write_all(text.as_bytes()).expect("writing to memory");
    enc.finish().expect("writing to memory")
}

impl Figure {
    /// Draw the SVG and write the data file.
    pub fn render(&self) -> Result<Rendered, ReportError> {
        Ok(match &self.chart {
            Chart::Line(c) => {
                Rendered { svg: line_svg(c)?, csv: Some(c.to_csv().into_bytes()), contents: c.csv_contents() }
            }
            Chart::Measured { chart, digits } => {
                let (chart, _) = chart.thinned();
                Rendered {
                    svg: line_svg(&chart)?,
                    csv: Some(gzip(&chart.to_csv_with(|v| digits.format(v)))),
                    contents: format!(
                        "{} (digits from the stated error{})",
                        chart.csv_contents(),
                        self.thinning_note()
                    ),
                }
            }
            Chart::InLedger { chart, .. } => Rendered { svg: line_svg(chart)?, csv: None, contents: String::new() },
            Chart::Heat { map, resolution } => {
                let (map, _) = map.thinned();
                let map = &map;
                let csv = match resolution {
                    Some(r) => map.to_csv_with(|v| wingcheck_model::quantity::format_resolved(v, *r)),
                    None => map.to_csv(),
                };
                Rendered {
                    svg: heatmap_svg(map)?,
                    csv: Some(gzip(&csv)),
                    contents: format!("{}{}", map.csv_contents(), self.thinning_note()),
                }
            }
            Chart::Surface(s) => Rendered { svg: surface_svg(s)?, csv: None, contents: String::new() },
            Chart::Grid { map, csv } => Rendered {
                svg: crate::chart::grid_heatmap_svg(map)?,
                csv: Some(csv.clone().into_bytes()),
                contents: "the (a, b) region map: one row per cell (docs/outputs.md, region map)".into(),
            },
        })
    }

    /// The name of the file with the data behind the figure: `<file>.csv`, `<file>.csv.gz` for a
    /// field map, the map's for its 3-D view.
    pub fn data_file(&self) -> String {
        match &self.chart {
            Chart::Heat { .. } | Chart::Measured { .. } => format!("{}.csv.gz", self.file),
            Chart::Surface(_) => format!("{}.csv.gz", self.file.trim_end_matches("-surface")),
            Chart::InLedger { .. } => "ledger.json".into(),
            _ => format!("{}.csv", self.file),
        }
    }

    /// Where in `ledger.json` the data of a row's plot is (`rows[5].plots[0]`), for tools.
    pub fn data_path(&self) -> Option<String> {
        match &self.chart {
            Chart::InLedger { path, .. } => Some(path.clone()),
            _ => None,
        }
    }

    /// The stride its drawing data is thinned at ([`crate::chart::stride`]: 1 up to
    /// [`crate::chart::MAX_DRAWN_SAMPLES`] output samples).
    pub fn thinning(&self) -> usize {
        match &self.chart {
            Chart::Measured { chart, .. } => crate::chart::stride(
                chart.data.lines.iter().filter(|l| !l.points).map(|l| l.x.len()).max().unwrap_or(0),
            ),
            Chart::Heat { map, .. } | Chart::Surface(map) => crate::chart::stride(map.t.len()),
            _ => 1,
        }
    }

    /// `; every k-th output sample, …` when the drawing data is thinned, else "".
    fn thinning_note(&self) -> String {
        match self.thinning() {
            1 => String::new(),
            k => format!(
                "; every {} output sample, at most {} per series, full-rate ranges merged",
                ordinal(k),
                crate::chart::MAX_DRAWN_SAMPLES
            ),
        }
    }

    /// How the data link reads.
    pub fn data_label(&self) -> String {
        let thinned = match self.thinning() {
            1 => String::new(),
            k => format!(", every {} output sample", ordinal(k)),
        };
        match &self.chart {
            Chart::Heat { .. } | Chart::Surface(_) | Chart::Measured { .. } => format!("data (CSV, gzip{thinned})"),
            Chart::InLedger { what, .. } => format!("data: ledger.json, {what}"),
            _ => "data (CSV)".into(),
        }
    }
}

/// `2nd`, `3rd`, `5th`, `11th`, `21st`.
pub fn ordinal(k: usize) -> String {
    let suffix = match (k % 10, k % 100) {
        (_, 11..=13) => "th",
        (1, _) => "st",
        (2, _) => "nd",
        (3, _) => "rd",
        _ => "th",
    };
    format!("{k}{suffix}")
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

/// Anchor of a claim's section.
pub fn claim_anchor(id: &str) -> String {
    format!("claim-{}", safe_name(id))
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
