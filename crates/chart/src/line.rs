//! Line / point / step charts of a [`PlotData`](crate::PlotData) (linear or logarithmic axes), with the legend
//! in a panel beside the plot (never over the data), optional zoomed x range, vertical
//! markers (e.g. a reaching time t_f), horizontal reference levels (a threshold) and dashed
//! reference lines (e.g. an O(h²) slope).

use plotters::coord::combinators::LogCoord;
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;

use crate::line_chart::{colours, vline_style, BandStyle, LineChart, LineStyle, MARK};
use crate::symlog::{SymLog, SymLogCoord};
use crate::{
    decade_label, linear_ticks, log_labels, log_ticks, padded_range, px, scaled_svg_header, tick, tick_linear, Ticked,
    CANVAS,
};
use crate::{ChartError, DrawError};

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
