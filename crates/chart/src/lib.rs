//! Charts as standalone SVG files, drawn with plotters' SVG backend, shared by the report
//! (line charts with linear, log or symmetric-log axes, field heatmaps) and the searches (grid
//! heatmaps): one tick format, one set of colour maps.
//!
//! Text: with plotters' default features off no font crate is compiled in; the SVG backend
//! writes labels as SVG `<text>` elements (font chosen by the viewer) and plotters only
//! *estimates* their width, so no system font is ever read.

#![forbid(unsafe_code)]

//!
//! Resolution: plotters' SVG backend writes integer coordinates, which turns smooth curves
//! into false one-pixel staircases. Line charts and field maps are therefore drawn on a canvas
//! [`SCALE`] times the displayed size and the SVG's `viewBox` maps it back
//! ([`scaled_svg_header`]): curves are placed to 1/[`SCALE`] px. Fields are embedded as PNG
//! rasters with vector axes ([`heatmap_svg`]).

mod clip;
mod data;
mod field;
mod grid;
mod labels;
mod line;
mod line_chart;
mod line_legend;
mod surface;
mod symlog;
mod ticks;

pub use data::{kept, stride, thin, thin_band, Line, PlotData, MAX_DRAWN_SAMPLES};
pub use field::{heatmap_svg, Heatmap};
pub use grid::{grid_heatmap_svg, viridis, GridAxis, GridHeatmap, Mark, MarkShape};
pub use line::line_svg;
pub use line_chart::{Band, BandStyle, LineChart, LineStyle};
pub use plotters::style::RGBColor;
pub use surface::surface_svg;
pub use symlog::{SymLog, SymLogCoord};
pub use ticks::{linear_ticks, log_ticks, with_ends, Ticked};

/// A chart could not be drawn.
#[derive(Debug, thiserror::Error)]
#[error("chart {name}: {cause}")]
pub struct ChartError {
    /// The chart's file stem.
    pub name: String,
    /// What failed.
    #[source]
    pub cause: DrawError,
}

/// What failed while drawing a chart.
#[derive(Debug, thiserror::Error)]
pub enum DrawError {
    /// plotters' SVG backend failed (its error, generic over the backend, kept as its text).
    #[error("{0}")]
    Plot(String),
    /// Encoding a raster as PNG failed.
    #[error(transparent)]
    Png(#[from] png::EncodingError),
    /// The SVG has no background rectangle to insert a raster after.
    #[error("unexpected SVG layout")]
    SvgLayout,
    /// A field (heatmap or surface) has fewer than 2 times or grid points, or its values do
    /// not match them.
    #[error("need at least 2 times and 2 grid points, and one value per (t, z)")]
    FieldShape,
    /// A grid heatmap's values do not match its grid.
    #[error("{values} values for a {nx} × {ny} grid")]
    GridShape {
        /// Values given.
        values: usize,
        /// Cells along x.
        nx: usize,
        /// Cells along y.
        ny: usize,
    },
}

impl From<plotters::drawing::DrawingAreaErrorKind<std::io::Error>> for DrawError {
    fn from(e: plotters::drawing::DrawingAreaErrorKind<std::io::Error>) -> Self {
        DrawError::Plot(e.to_string())
    }
}

/// Displayed width and height (px) of every chart.
pub const SIZE: (u32, u32) = (980, 440);

/// Drawing-canvas pixels per displayed pixel.
pub const SCALE: u32 = 4;

/// `v` displayed pixels in canvas pixels.
pub const fn px(v: u32) -> u32 {
    v * SCALE
}

/// The canvas size.
pub const CANVAS: (u32, u32) = (SIZE.0 * SCALE, SIZE.1 * SCALE);

/// Replace the root element's `width`/`height` (canvas pixels) by the displayed size, keeping
/// the canvas `viewBox`.
pub fn scaled_svg_header(svg: String) -> String {
    let from = format!("<svg width=\"{}\" height=\"{}\"", CANVAS.0, CANVAS.1);
    let to = format!("<svg width=\"{}\" height=\"{}\"", SIZE.0, SIZE.1);
    svg.replacen(&from, &to, 1)
}

/// Insert a PNG raster as an `<image>` covering the plotting area `plot_px` (canvas pixels),
/// right after the SVG's background rectangle, so that the axes drawn afterwards lie over it.
pub fn embed_raster(
    svg: &mut String,
    plot_px: &(std::ops::Range<i32>, std::ops::Range<i32>),
    png: &[u8],
) -> Result<(), DrawError> {
    use base64::Engine;
    let (xr, yr) = plot_px;
    let image = format!(
        "<image x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" preserveAspectRatio=\"none\" href=\"data:image/png;base64,{}\"/>\n",
        xr.start,
        yr.start,
        xr.end - xr.start,
        yr.end - yr.start,
        base64::engine::general_purpose::STANDARD.encode(png)
    );
    let at = svg.find("/>\n").map(|i| i + 3).ok_or(DrawError::SvgLayout)?;
    svg.insert_str(at, &image);
    Ok(())
}

/// Line colours (the "tab10" palette).
pub const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
];

/// Tick label: at most four significant digits in the one number format
/// ([`wingcheck_io::prose::number`]: real minus sign, ×10ⁿ outside 10⁻³ ≤ |v| < 10⁵).
pub fn tick(v: f64) -> String {
    wingcheck_io::prose::number(v, wingcheck_io::prose::Digits::AtMost(4))
}

/// Whether `v` is an integer power of ten (to rounding).
fn is_decade(v: f64) -> bool {
    v > 0.0 && (v.log10() - v.log10().round()).abs() < 1e-9
}

/// 10^k with a superscript exponent (`10⁻³`).
pub fn decade_label(v: f64) -> String {
    format!("10{}", wingcheck_io::prose::superscript(v.log10().round() as i32))
}

/// Labels of log-axis ticks in one format: all as 10ᵏ when every tick is a power of ten and
/// some lie outside [0.01, 1000], else [`tick`] for all.
pub fn log_labels(ticks: &[f64]) -> bool {
    ticks.iter().all(|t| is_decade(*t)) && ticks.iter().any(|t| !(1e-2..=1e3).contains(t))
}

/// Tick label on a linear axis spanning `span`: values that are round-off away from 0
/// (|v| < 1e-9 · span, e.g. -2.2e-16) print as `0`.
pub fn tick_linear(v: f64, span: f64) -> String {
    if v.abs() < 1e-9 * span.abs() {
        "0".into()
    } else {
        tick(v)
    }
}

/// Padded range of finite values; a degenerate range is widened.
pub fn padded_range(values: impl Iterator<Item = f64>, log: bool) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite() && (!log || *v > 0.0)) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return if log { (1e-3, 1.0) } else { (-1.0, 1.0) };
    }
    if log {
        // At most 12 decades below the largest value: a decay to round-off (1e-200…) would
        // otherwise squeeze everything of interest into the top of the axis.
        lo = lo.max(hi * 1e-12);
        if hi <= lo {
            return (lo / 2.0, hi * 2.0);
        }
        let f = (hi / lo).powf(0.05);
        return (lo / f, hi * f);
    }
    if hi - lo <= 1e-300_f64.max(1e-12 * hi.abs().max(lo.abs())) {
        let w = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
        return (lo - w, hi + w);
    }
    let pad = 0.05 * (hi - lo);
    (lo - pad, hi + pad)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_range_spans_at_most_twelve_decades() {
        // A decay to 1e-211 must not squeeze the data of interest into the top of the axis.
        let (lo, hi) = padded_range([0.2356, 1e-6, 3.7e-211].into_iter(), true);
        // 12 decades below the max, then the 5% log padding (factor (1e12)^0.05 ≈ 4)
        assert!((0.2356e-12 / 5.0..1e-6).contains(&lo), "{lo}");
        assert!(hi > 0.2356);
    }

    #[test]
    fn ticks_are_short() {
        assert_eq!(tick(0.5), "0.5");
        assert_eq!(tick(20.0), "20");
        assert_eq!(tick(1e-5), "1×10⁻⁵");
        assert_eq!(tick(-0.00001), "−1×10⁻⁵");
    }
}
