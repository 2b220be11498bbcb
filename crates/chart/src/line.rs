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
use crate::ChartError;
use crate::{
    decade_label, linear_ticks, log_labels, log_ticks, padded_range, px, scaled_svg_header, tick, tick_linear, Ticked,
    CANVAS, PALETTE,
};

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
}

impl From<PlotData> for LineChart {
    fn from(data: PlotData) -> Self {
        LineChart { data, styles: Vec::new(), x_range: None, vlines: Vec::new(), hlines: Vec::new(), symlog_y: None }
    }
}

impl LineChart {
    fn style(&self, i: usize) -> LineStyle {
        self.styles.get(i).copied().unwrap_or_default()
    }

    /// The symmetric-log transform of the y axis, if it has one.
    fn symlog(&self) -> Option<SymLog> {
        self.symlog_y.filter(|_| !self.data.log_y)
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
const LEGEND_W: u32 = 230;

/// Render the chart as an SVG document.
pub fn line_svg(c: &LineChart) -> Result<String, ChartError> {
    let pd = &c.data;
    let err = |e: String| ChartError { name: pd.name.clone(), detail: e };
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, CANVAS).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(e.to_string()))?;
        let labelled = pd.lines.iter().any(|l| !l.label.is_empty())
            || !c.vlines.is_empty()
            || !c.hlines.is_empty()
            || c.symlog().is_some();
        let (plot, legend) = if labelled {
            let (a, b) = root.split_horizontally(CANVAS.0 - px(LEGEND_W));
            (a, Some(b))
        } else {
            (root.clone(), None)
        };
        let in_x = |x: f64| c.x_range.is_none_or(|(a, b)| x >= a && x <= b);
        let xs = match c.x_range {
            Some((a, b)) if b > a => (a, b),
            _ => padded_range(pd.lines.iter().flat_map(|l| l.x.iter().copied()), pd.log_x),
        };
        let y_values = pd
            .lines
            .iter()
            .flat_map(|l| l.x.iter().zip(&l.y).filter(|(x, _)| (!pd.log_x || **x > 0.0) && in_x(**x)).map(|(_, y)| *y))
            .chain(c.hlines.iter().map(|h| h.0));
        let ys = match c.symlog() {
            Some(s) => s.padded_range(y_values),
            None => padded_range(y_values, pd.log_y),
        };
        let data_x: Vec<f64> = pd.lines.iter().flat_map(|l| l.x.iter().copied()).collect();
        let xt = if pd.log_x { log_ticks(xs.0, xs.1, &data_x) } else { linear_ticks(xs.0, xs.1, 8) };
        let yt = match c.symlog() {
            Some(s) => s.ticks(ys.0, ys.1),
            None if pd.log_y => log_ticks(ys.0, ys.1, &[]),
            None => linear_ticks(ys.0, ys.1, 6),
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
            draw_legend(&area, c).map_err(err)?;
        }
        root.present().map_err(|e| err(e.to_string()))?;
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
fn colours(pd: &PlotData) -> Vec<RGBColor> {
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
const MARK: RGBColor = RGBColor(90, 90, 90);

fn draw<X, Y>(
    root: &DrawingArea<SVGBackend, Shift>,
    c: &LineChart,
    x: X,
    y: Y,
    labels: (Labels, Labels),
) -> Result<(), String>
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
        .build_cartesian_2d(x, y)
        .map_err(|e| e.to_string())?;
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
        .draw()
        .map_err(|e| e.to_string())?;
    let x_range = chart.x_range();
    let y_range = chart.y_range();
    let colours = colours(pd);
    // Points outside a zoomed x range are dropped (plotters would pin them to the frame).
    let (xa, xb) = c.x_range.unwrap_or((f64::NEG_INFINITY, f64::INFINITY));
    let keep = |(x, y): &(f64, f64)| {
        x.is_finite() && y.is_finite() && (!log_x || *x > 0.0) && (!log_y || *y > 0.0) && *x >= xa && *x <= xb
    };
    for (i, line) in pd.lines.iter().enumerate() {
        let color = colours[i];
        let width = px(if i == 0 { 3 } else { 2 });
        let mut pts: Vec<(f64, f64)> = line.x.iter().copied().zip(line.y.iter().copied()).collect();
        if line.points {
            let pts: Vec<(f64, f64)> = pts.into_iter().filter(keep).collect();
            chart
                .draw_series(pts.into_iter().map(|p| Circle::new(p, px(4), color.filled())))
                .map_err(|e| e.to_string())?;
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
            if c.style(i) == LineStyle::Dashed {
                chart
                    .draw_series(DashedLineSeries::new(s, px(8), px(5), color.stroke_width(width)))
                    .map_err(|e| e.to_string())?;
            } else {
                chart
                    .draw_series(std::iter::once(PathElement::new(s, color.stroke_width(width))))
                    .map_err(|e| e.to_string())?;
            }
        }
    }
    for (x, _) in &c.vlines {
        let s = vec![(*x, y_range.start), (*x, y_range.end)];
        chart
            .draw_series(DashedLineSeries::new(s, px(6), px(4), MARK.stroke_width(px(2))))
            .map_err(|e| e.to_string())?;
    }
    for (y, _) in &c.hlines {
        let s = vec![(x_range.start, *y), (x_range.end, *y)];
        chart
            .draw_series(DashedLineSeries::new(s, px(3), px(4), MARK.stroke_width(px(2))))
            .map_err(|e| e.to_string())?;
    }
    Ok(())
}

/// The legend panel: one entry per labelled line (swatch as drawn: line, dashes or marker),
/// then the markers and levels.
fn draw_legend(area: &DrawingArea<SVGBackend, Shift>, c: &LineChart) -> Result<(), String> {
    let pd = &c.data;
    let colours = colours(pd);
    let font = ("sans-serif", px(17)).into_font().color(&BLACK);
    let mut y = px(24) as i32;
    let x0 = px(10) as i32;
    let step = px(26) as i32;
    let e = |e: DrawingAreaErrorKind<std::io::Error>| e.to_string();
    for (i, line) in pd.lines.iter().enumerate() {
        if line.label.is_empty() {
            continue;
        }
        let color = colours[i];
        // A line followed by an unlabelled marker series of the same colour gets both.
        let marked = line.points || pd.lines.get(i + 1).is_some_and(|n| n.label.is_empty() && n.points);
        if !line.points {
            let w = px(3);
            let seg = vec![(x0, y), (x0 + px(28) as i32, y)];
            if c.style(i) == LineStyle::Dashed {
                area.draw(&PathElement::new(vec![(x0, y), (x0 + px(10) as i32, y)], color.stroke_width(w)))
                    .map_err(e)?;
                area.draw(&PathElement::new(
                    vec![(x0 + px(16) as i32, y), (x0 + px(28) as i32, y)],
                    color.stroke_width(w),
                ))
                .map_err(e)?;
            } else {
                area.draw(&PathElement::new(seg, color.stroke_width(w))).map_err(e)?;
            }
        }
        if marked {
            area.draw(&Circle::new((x0 + px(14) as i32, y), px(4), color.filled())).map_err(e)?;
        }
        area.draw(&Text::new(line.label.clone(), (x0 + px(36) as i32, y - px(9) as i32), font.clone())).map_err(e)?;
        y += step;
    }
    for (_, label) in c.vlines.iter().chain(&c.hlines) {
        area.draw(&PathElement::new(vec![(x0, y), (x0 + px(10) as i32, y)], MARK.stroke_width(px(2)))).map_err(e)?;
        area.draw(&PathElement::new(vec![(x0 + px(16) as i32, y), (x0 + px(28) as i32, y)], MARK.stroke_width(px(2))))
            .map_err(e)?;
        area.draw(&Text::new(label.clone(), (x0 + px(36) as i32, y - px(9) as i32), font.clone())).map_err(e)?;
        y += step;
    }
    if let Some(s) = c.symlog() {
        y += step / 2;
        for line in s.note() {
            area.draw(&Text::new(line, (x0, y - px(9) as i32), font.clone())).map_err(e)?;
            y += step;
        }
    }
    Ok(())
}
