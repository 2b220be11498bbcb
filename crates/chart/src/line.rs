//! Line / point / step charts of a [`PlotData`] (linear or logarithmic axes), with the legend
//! in a panel beside the plot (never over the data), optional zoomed x range, vertical
//! markers (e.g. a reaching time t_f), horizontal reference levels (a threshold) and dashed
//! reference lines (e.g. an O(h²) slope).

use crate::PlotData;
use plotters::coord::combinators::LogCoord;
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;

use crate::symlog::{SymLog, SymLogCoord};
use crate::{
    decade_label, linear_ticks, log_labels, log_ticks, padded_range, px, scaled_svg_header, tick, tick_linear, Ticked,
    CANVAS, PALETTE,
};
use crate::{ChartError, DrawError};

/// How a line is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LineStyle {
    /// Polyline through the samples (or markers when the line asks for points).
    #[default]
    Solid,
    /// Zero-order hold: the value is held until the next sample (sampled signals).
    Step,
    /// Dashed polyline (reference lines, bounds).
    Dashed,
    /// A thin, light polyline: a secondary line under a band that is the main one (the output
    /// samples of a chattering signal, which alias it).
    Faint,
}

/// A band around a line: the signal's range between its samples (e.g. the full-rate min/max of
/// τ over each output interval, which the samples alone alias). Drawn as a translucent fill in
/// the line's colour, held over each interval (x_{k−1}, x_k] like the data it bounds; written to
/// the CSV as two columns beside the line's values.
#[derive(Debug, Clone, PartialEq)]
pub struct Band {
    /// Index of the line whose x the band uses (and whose colour).
    pub line: usize,
    /// Lower edge per sample of that line (over the interval ending there).
    pub lo: Vec<f64>,
    /// Upper edge per sample.
    pub hi: Vec<f64>,
    /// Legend text (e.g. `full-rate min … max per 10-ms output interval`).
    pub label: String,
    /// How it is drawn.
    pub style: BandStyle,
}

/// How a [`Band`] is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BandStyle {
    /// A translucent fill around its line.
    #[default]
    Shade,
    /// The fill with its edges as solid lines in the line's colour: the band is the main curve
    /// (a signal that chatters between its samples), not a shading around one.
    Edges,
    /// Not drawn and not in the legend (thinner than a line at the chart's scale), but written
    /// to the data file.
    Hidden,
}

/// A chart: the data and how to show it.
#[derive(Debug, Clone)]
pub struct LineChart {
    /// The data (labels with units, lines).
    pub data: PlotData,
    /// Style per line (missing entries: [`LineStyle::Solid`]).
    pub styles: Vec<LineStyle>,
    /// Show only this x range (the data outside is still in the CSV).
    pub x_range: Option<(f64, f64)>,
    /// Vertical markers at x with a label (e.g. `t_f = 0.054 s`).
    pub vlines: Vec<(f64, String)>,
    /// Horizontal levels at y with a label (e.g. the |g̃| threshold).
    pub hlines: Vec<(f64, String)>,
    /// A symmetric-log y axis with this transform (ignored when `data.log_y`); the legend panel
    /// states its linear threshold.
    pub symlog_y: Option<SymLog>,
    /// Show this y range instead of the data's padded range (a pair of figures on common axes).
    pub y_range: Option<(f64, f64)>,
    /// Bands around lines (full-rate ranges between samples).
    pub bands: Vec<Band>,
}

impl From<PlotData> for LineChart {
    fn from(data: PlotData) -> Self {
        LineChart {
            data,
            styles: Vec::new(),
            x_range: None,
            vlines: Vec::new(),
            hlines: Vec::new(),
            symlog_y: None,
            y_range: None,
            bands: Vec::new(),
        }
    }
}

impl LineChart {
    pub(crate) fn style(&self, i: usize) -> LineStyle {
        self.styles.get(i).copied().unwrap_or_default()
    }

    /// The symmetric-log transform of the y axis, if it has one.
    pub(crate) fn symlog(&self) -> Option<SymLog> {
        self.symlog_y.filter(|_| !self.data.log_y)
    }

    /// Every y value the chart shows (lines and bands inside the x range), for axis ranges.
    pub fn y_values(&self) -> Vec<f64> {
        let pd = &self.data;
        let in_x = |x: f64| (!pd.log_x || x > 0.0) && self.x_range.is_none_or(|(a, b)| x >= a && x <= b);
        let mut v: Vec<f64> =
            pd.lines.iter().flat_map(|l| l.x.iter().zip(&l.y).filter(|(x, _)| in_x(**x)).map(|(_, y)| *y)).collect();
        for b in &self.bands {
            if let Some(l) = pd.lines.get(b.line) {
                for (k, _) in l.x.iter().enumerate().filter(|(_, x)| in_x(**x)) {
                    v.extend(b.lo.get(k).copied().into_iter().chain(b.hi.get(k).copied()));
                }
            }
        }
        // the horizontal levels drawn (a threshold) are inside the axis too
        v.extend(self.hlines.iter().map(|(y, _)| *y).filter(|y| !pd.log_y || *y > 0.0));
        v.retain(|y| y.is_finite());
        v
    }

    /// The data as CSV: the lines as [`PlotData::to_csv`] writes them; with bands, two more
    /// columns (the band's lower and upper edge) on the rows of each line a band belongs to.
    pub fn to_csv(&self) -> String {
        self.to_csv_with(wingcheck_io::number)
    }

    /// [`LineChart::to_csv`] with the y values and band edges written by `value` (e.g. to the
    /// digits of their error); x in the shortest round-trip form. Long form `series,x,y`
    /// ([`PlotData::to_csv`]); with bands, `y_min,y_max` (the band's edges, empty on rows of a
    /// line without one).
    pub fn to_csv_with(&self, value: impl Fn(f64) -> String) -> String {
        let pd = &self.data;
        let banded = !self.bands.is_empty();
        let header: &[&str] = if banded { &["series", "x", "y", "y_min", "y_max"] } else { &["series", "x", "y"] };
        let rows = pd.lines.iter().enumerate().flat_map(|(i, l)| {
            let band = self.bands.iter().find(|b| b.line == i);
            let value = &value;
            l.x.iter().zip(&l.y).enumerate().map(move |(k, (x, y))| {
                let mut row = vec![l.label.clone(), wingcheck_io::number(*x), value(*y)];
                if banded {
                    let edges = band.and_then(|b| Some((b.lo.get(k)?, b.hi.get(k)?)));
                    let (lo, hi) = edges.map_or((String::new(), String::new()), |(a, b)| (value(*a), value(*b)));
                    row.extend([lo, hi]);
                }
                row
            })
        });
        wingcheck_io::csv_text(header.iter().copied(), rows)
    }

    /// The chart with its longest polylines thinned to at most [`crate::MAX_DRAWN_SAMPLES`]
    /// points (every k-th sample, [`crate::stride`]) and their bands merged over the k intervals
    /// (no extreme lost, [`crate::thin_band`]); marker lines and shorter lines unchanged. The
    /// stride k is returned too (1: unchanged).
    pub fn thinned(&self) -> (LineChart, usize) {
        let n = self.data.lines.iter().filter(|l| !l.points).map(|l| l.x.len()).max().unwrap_or(0);
        let k = crate::stride(n);
        if k == 1 {
            return (self.clone(), 1);
        }
        let keep = crate::kept(n, k);
        let mut c = self.clone();
        let full: Vec<bool> = c.data.lines.iter().map(|l| !l.points && l.x.len() == n && l.y.len() == n).collect();
        for (l, _) in c.data.lines.iter_mut().zip(&full).filter(|(_, f)| **f) {
            l.x = crate::thin(&l.x, &keep);
            l.y = crate::thin(&l.y, &keep);
        }
        for b in c.bands.iter_mut().filter(|b| full.get(b.line) == Some(&true) && b.lo.len() == n && b.hi.len() == n) {
            (b.lo, b.hi) = crate::thin_band(&b.lo, &b.hi, &keep);
        }
        (c, k)
    }

    /// What the CSV holds, for the provenance record.
    pub fn csv_contents(&self) -> String {
        let bands = if self.bands.is_empty() {
            String::new()
        } else {
            format!("; y_min, y_max = the band ({}) per output interval", self.bands[0].label)
        };
        format!("{}{bands}", self.data.csv_contents())
    }
}

/// How the tick labels of an axis are written.
#[derive(Clone, Copy)]
enum Labels {
    /// Linear axis spanning this much (round-off snapping to 0).
    Linear(f64),
    /// Log axis; 10ᵏ labels when true.
    Log(bool),
    /// Symmetric-log axis.
    SymLog(SymLog),
}

impl Labels {
    fn label(self, v: f64) -> String {
        match self {
            Labels::Linear(span) => tick_linear(v, span),
            Labels::Log(true) => decade_label(v),
            Labels::Log(false) => tick(v),
            Labels::SymLog(s) => s.label(v),
        }
    }
}

/// Width (displayed px) of the legend panel right of the plot.
pub(crate) const LEGEND_W: u32 = 230;

/// Render the chart as an SVG document.
pub fn line_svg(c: &LineChart) -> Result<String, ChartError> {
    let pd = &c.data;
    let err = |cause: DrawError| ChartError { name: pd.name.clone(), cause };
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, CANVAS).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(e.into()))?;
        let labelled = pd.lines.iter().any(|l| !l.label.is_empty())
            || !c.bands.is_empty()
            || !c.vlines.is_empty()
            || !c.hlines.is_empty()
            || c.symlog().is_some();
        let (plot, legend) = if labelled {
            let (a, b) = root.split_horizontally(CANVAS.0 - px(LEGEND_W));
            (a, Some(b))
        } else {
            (root.clone(), None)
        };
        let xs = match c.x_range {
            Some((a, b)) if b > a => (a, b),
            _ => padded_range(pd.lines.iter().flat_map(|l| l.x.iter().copied()), pd.log_x),
        };
        let y_values = c.y_values().into_iter().chain(c.hlines.iter().map(|h| h.0));
        let ys = match (c.y_range, c.symlog()) {
            (Some((a, b)), _) if b > a && (!pd.log_y || a > 0.0) => (a, b),
            (_, Some(s)) => s.padded_range(y_values),
            _ => padded_range(y_values, pd.log_y),
        };
        let data_x: Vec<f64> = pd.lines.iter().flat_map(|l| l.x.iter().copied()).collect();
        let xt = if pd.log_x { log_ticks(xs.0, xs.1, &data_x) } else { linear_ticks(xs.0, xs.1, 8) };
        // the y axis widened to the ticks just outside its range, so every curve lies between
        // two labelled ticks
        let (ys, yt) = match c.symlog() {
            Some(s) => (ys, s.ticks(ys.0, ys.1)),
            None if pd.log_y => crate::ticks::enclosing_log(ys.0, ys.1),
            None => crate::ticks::enclosing_linear(ys.0, ys.1, 6),
        };
        // Tick label style per axis: a linear span (round-off snapping), log (10ᵏ or plain), symlog.
        let labels = (
            if pd.log_x { Labels::Log(log_labels(&xt)) } else { Labels::Linear(xs.1 - xs.0) },
            match c.symlog() {
                Some(s) => Labels::SymLog(s),
                None if pd.log_y => Labels::Log(log_labels(&yt)),
                None => Labels::Linear(ys.1 - ys.0),
            },
        );
        let (xr, yr) = (xs.0..xs.1, ys.0..ys.1);
        let r = match (pd.log_x, c.symlog(), pd.log_y) {
            (false, Some(s), _) => draw(&plot, c, lin(xr, xt), symlog(ys, s, yt), labels),
            (true, Some(s), _) => draw(&plot, c, log(xr, xt), symlog(ys, s, yt), labels),
            (false, None, false) => draw(&plot, c, lin(xr, xt), lin(yr, yt), labels),
            (true, None, false) => draw(&plot, c, log(xr, xt), lin(yr, yt), labels),
            (false, None, true) => draw(&plot, c, lin(xr, xt), log(yr, yt), labels),
            (true, None, true) => draw(&plot, c, log(xr, xt), log(yr, yt), labels),
        };
        r.map_err(err)?;
        if let Some(area) = legend {
            crate::line_legend::draw_legend(&area, c).map_err(err)?;
        }
        root.present().map_err(|e| err(e.into()))?;
    }
    Ok(scaled_svg_header(svg))
}

fn lin(r: std::ops::Range<f64>, ticks: Vec<f64>) -> Ticked<RangedCoordf64> {
    Ticked::new(r, ticks)
}

fn log(r: std::ops::Range<f64>, ticks: Vec<f64>) -> Ticked<LogCoord<f64>> {
    Ticked::new(r.log_scale(), ticks)
}

fn symlog(r: (f64, f64), s: SymLog, ticks: Vec<f64>) -> Ticked<SymLogCoord> {
    Ticked::new(SymLogCoord::new(r.0, r.1, s), ticks)
}

/// Colour index of each line: a labelled line takes the next colour; an unlabelled one
/// (e.g. the markers of the previous line) reuses the last.
pub(crate) fn colours(pd: &PlotData) -> Vec<RGBColor> {
    let mut next = 0usize;
    pd.lines
        .iter()
        .map(|l| {
            if !l.label.is_empty() || next == 0 {
                next += 1;
            }
            PALETTE[(next - 1) % PALETTE.len()]
        })
        .collect()
}

/// Colour of markers and levels.
pub(crate) const MARK: RGBColor = RGBColor(90, 90, 90);

/// Dash, gap (canvas px) and colour of the `k`-th vertical marker: each marker of a chart drawn
/// differently, so two close ones (a measured time and its bound) stay apart in the legend.
pub(crate) fn vline_style(k: usize) -> (u32, u32, RGBColor) {
    const STYLES: [(u32, u32, RGBColor); 3] = [(6, 4, MARK), (14, 4, RGBColor(0, 0, 0)), (2, 3, RGBColor(140, 60, 0))];
    let (d, g, c) = STYLES[k % STYLES.len()];
    (px(d), px(g), c)
}

fn draw<X, Y>(
    root: &DrawingArea<SVGBackend, Shift>,
    c: &LineChart,
    x: X,
    y: Y,
    labels: (Labels, Labels),
) -> Result<(), DrawError>
where
    X: AsRangedCoord<Value = f64>,
    Y: AsRangedCoord<Value = f64>,
    X::CoordDescType: ValueFormatter<f64>,
    Y::CoordDescType: ValueFormatter<f64>,
{
    let pd = &c.data;
    let mut chart = ChartBuilder::on(root)
        .margin(px(12))
        .x_label_area_size(px(46))
        .y_label_area_size(px(76))
        .build_cartesian_2d(x, y)?;
    let (log_x, log_y) = (pd.log_x, pd.log_y);
    chart
        .configure_mesh()
        .x_desc(pd.x_label.as_str())
        .y_desc(pd.y_label.as_str())
        .x_label_formatter(&|v| labels.0.label(*v))
        .y_label_formatter(&|v| labels.1.label(*v))
        .label_style(("sans-serif", px(18)))
        .axis_desc_style(("sans-serif", px(19)))
        .bold_line_style(BLACK.mix(0.1).stroke_width(px(1)))
        .light_line_style(WHITE.mix(0.0))
        .axis_style(BLACK.stroke_width(px(1)))
        .set_all_tick_mark_size(px(5))
        .draw()?;
    let x_range = chart.x_range();
    let y_range = chart.y_range();
    let colours = colours(pd);
    // Points outside a zoomed x range are dropped (plotters would pin them to the frame).
    let (xa, xb) = c.x_range.unwrap_or((f64::NEG_INFINITY, f64::INFINITY));
    let keep = |(x, y): &(f64, f64)| {
        x.is_finite() && y.is_finite() && (!log_x || *x > 0.0) && (!log_y || *y > 0.0) && *x >= xa && *x <= xb
    };
    for b in c.bands.iter().filter(|b| b.style != BandStyle::Hidden) {
        let Some(line) = pd.lines.get(b.line) else { continue };
        let color = colours[b.line];
        let (y_lo, y_hi) = (y_range.start, y_range.end);
        let clamp = |y: f64| if y.is_finite() { y.clamp(y_lo, y_hi) } else { y_lo };
        let (x_lo, x_hi) = (x_range.start.max(xa), x_range.end.min(xb));
        // Held over each interval (x_{k−1}, x_k], clipped to the plot; intervals narrower than
        // a displayed pixel are merged per pixel column (their min and max), so the drawn
        // region is the same and the path stays short.
        let fx = |x: f64| if log_x { x.log10() } else { x };
        let column = (fx(x_hi) - fx(x_lo)) / f64::from(crate::SIZE.0);
        let (mut upper, mut lower) = (Vec::new(), Vec::new());
        let mut open: Option<(i64, f64, f64, f64, f64)> = None; // (column, x0, x1, lo, hi)
        let flush = |o: Option<(i64, f64, f64, f64, f64)>, upper: &mut Vec<(f64, f64)>, lower: &mut Vec<(f64, f64)>| {
            if let Some((_, x0, x1, lo, hi)) = o {
                upper.extend([(x0, clamp(hi)), (x1, clamp(hi))]);
                lower.extend([(x0, clamp(lo)), (x1, clamp(lo))]);
            }
        };
        for k in 1..line.x.len().min(b.lo.len()).min(b.hi.len()) {
            let (x0, x1) = (line.x[k - 1].max(x_lo), line.x[k].min(x_hi));
            if x1.partial_cmp(&x0) != Some(std::cmp::Ordering::Greater) || (log_x && x0 <= 0.0) {
                continue;
            }
            let (lo, hi) = (b.lo[k].min(b.hi[k]), b.hi[k].max(b.lo[k]));
            let col = if column.is_nan() || column <= 0.0 || fx(x1) - fx(x0) >= column {
                -1 - k as i64
            } else {
                ((fx(x0) - fx(x_lo)) / column).floor() as i64
            };
            match open.as_mut() {
                Some(o) if o.0 == col && col >= 0 => {
                    o.2 = x1;
                    o.3 = o.3.min(lo);
                    o.4 = o.4.max(hi);
                }
                _ => {
                    flush(open.take(), &mut upper, &mut lower);
                    open = Some((col, x0, x1, lo, hi));
                }
            }
        }
        flush(open.take(), &mut upper, &mut lower);
        let edges = (b.style == BandStyle::Edges).then(|| [upper.clone(), lower.clone()]);
        lower.reverse();
        upper.extend(lower);
        if upper.len() >= 3 {
            chart.draw_series(std::iter::once(Polygon::new(upper, color.mix(0.3).filled())))?;
        }
        for edge in edges.into_iter().flatten().filter(|e| e.len() >= 2) {
            chart.draw_series(std::iter::once(PathElement::new(edge, color.stroke_width(px(2)))))?;
        }
    }
    for (i, line) in pd.lines.iter().enumerate() {
        let faint = c.style(i) == LineStyle::Faint;
        let color = if faint { colours[i].mix(0.7) } else { colours[i].mix(1.0) };
        let width = px(if faint {
            1
        } else if i == 0 {
            3
        } else {
            2
        });
        let mut pts: Vec<(f64, f64)> = line.x.iter().copied().zip(line.y.iter().copied()).collect();
        if line.points {
            let pts: Vec<(f64, f64)> = pts.into_iter().filter(keep).collect();
            chart.draw_series(pts.into_iter().map(|p| Circle::new(p, px(4), color.filled())))?;
            continue;
        }
        if c.style(i) == LineStyle::Step {
            let mut held = Vec::with_capacity(2 * pts.len());
            for k in 0..pts.len() {
                held.push(pts[k]);
                if let Some(n) = pts.get(k + 1) {
                    held.push((n.0, pts[k].1));
                }
            }
            pts = held;
        }
        // Break the polyline where a value cannot be drawn (e.g. 0 on a log axis).
        let mut segments: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
        for p in pts {
            if keep(&p) {
                segments.last_mut().expect("non-empty").push(p);
            } else if !segments.last().expect("non-empty").is_empty() {
                segments.push(Vec::new());
            }
        }
        for s in segments.into_iter().filter(|s| !s.is_empty()) {
            // The polyline as drawn: points within a quarter displayed pixel of the line through
            // their kept neighbours add nothing visible (Douglas–Peucker on the canvas).
            let canvas: Vec<(f64, f64)> = s
                .iter()
                .map(|p| {
                    let (x, y) = chart.backend_coord(p);
                    (f64::from(x), f64::from(y))
                })
                .collect();
            let s: Vec<(f64, f64)> =
                crate::clip::simplified(&canvas, f64::from(crate::SCALE) / 4.0).into_iter().map(|k| s[k]).collect();
            if c.style(i) == LineStyle::Dashed {
                chart.draw_series(DashedLineSeries::new(s, px(8), px(5), color.stroke_width(width)))?;
            } else if faint {
                chart.draw_series(DashedLineSeries::new(s, px(3), px(3), color.stroke_width(width)))?;
            } else {
                chart.draw_series(std::iter::once(PathElement::new(s, color.stroke_width(width))))?;
            }
        }
    }
    for (k, (x, _)) in c.vlines.iter().enumerate() {
        let s = vec![(*x, y_range.start), (*x, y_range.end)];
        let (dash, gap, colour) = vline_style(k);
        chart.draw_series(DashedLineSeries::new(s, dash, gap, colour.stroke_width(px(2))))?;
    }
    for (y, _) in &c.hlines {
        let s = vec![(x_range.start, *y), (x_range.end, *y)];
        chart.draw_series(DashedLineSeries::new(s, px(3), px(4), MARK.stroke_width(px(2))))?;
    }
    Ok(())
}
