//! Charts as standalone SVG files, drawn with plotters' SVG backend, shared by the report
//! (line charts, field heatmaps) and the searches (grid heatmaps): one tick format, one set of
//! colour maps.
//!
//! Text: with plotters' default features off no font crate is compiled in; the SVG backend
//! writes labels as SVG `<text>` elements (font chosen by the viewer) and plotters only
//! *estimates* their width, so no system font is ever read.

mod field;
mod grid;
mod line;

pub use field::{heatmap_svg, Heatmap};
pub use grid::{grid_heatmap_svg, GridAxis, GridHeatmap, Mark, MarkShape};
pub use line::line_svg;
pub use plotters::style::RGBColor;

/// A chart could not be drawn.
#[derive(Debug, thiserror::Error)]
#[error("chart {name}: {detail}")]
pub struct ChartError {
    /// The chart's file stem.
    pub name: String,
    /// What failed.
    pub detail: String,
}

/// Width and height (px) of every chart.
pub const SIZE: (u32, u32) = (980, 440);

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

/// Tick label: short, deterministic.
pub fn tick(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    if (1e-3..1e4).contains(&a) {
        let s = format!("{v:.4}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        if s == "-0" {
            "0".into()
        } else {
            s.to_string()
        }
    } else {
        let s = format!("{v:.2e}");
        // 1.00e-3 → 1e-3
        match s.split_once('e') {
            Some((m, e)) => format!("{}e{e}", m.trim_end_matches('0').trim_end_matches('.')),
            None => s,
        }
    }
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
        assert_eq!(tick(1e-5), "1e-5");
        assert_eq!(tick(-0.00001), "-1e-5");
    }
}
