//! Line / point charts of a [`PlotData`] (linear or logarithmic axes).

use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::coord::Shift;
use plotters::prelude::*;
use wingcheck_claims::PlotData;

use crate::ChartError;
use crate::{padded_range, tick_linear, PALETTE, SIZE};

/// Render `pd` as an SVG document (log axes and point markers as the data asks).
pub fn line_svg(pd: &PlotData) -> Result<String, ChartError> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        let err = |e: String| ChartError { name: pd.name.clone(), detail: e };
        root.fill(&WHITE).map_err(|e| err(e.to_string()))?;
        let xs = padded_range(pd.lines.iter().flat_map(|l| l.x.iter().copied()), pd.log_x);
        let ys = padded_range(
            pd.lines.iter().flat_map(|l| l.x.iter().zip(&l.y).filter(|(x, _)| !pd.log_x || **x > 0.0).map(|(_, y)| *y)),
            pd.log_y,
        );
        let x_lin = xs.0..xs.1;
        let y_lin = ys.0..ys.1;
        // Spans for the round-off snapping of linear tick labels (0: log axis, no snapping).
        let spans = (if pd.log_x { 0.0 } else { xs.1 - xs.0 }, if pd.log_y { 0.0 } else { ys.1 - ys.0 });
        let r = match (pd.log_x, pd.log_y) {
            (false, false) => draw(&root, pd, x_lin, y_lin, spans),
            (true, false) => draw(&root, pd, x_lin.log_scale(), y_lin, spans),
            (false, true) => draw(&root, pd, x_lin, y_lin.log_scale(), spans),
            (true, true) => draw(&root, pd, x_lin.log_scale(), y_lin.log_scale(), spans),
        };
        r.map_err(err)?;
        root.present().map_err(|e| err(e.to_string()))?;
    }
    Ok(svg)
}

fn draw<X, Y>(root: &DrawingArea<SVGBackend, Shift>, pd: &PlotData, x: X, y: Y, spans: (f64, f64)) -> Result<(), String>
where
    X: AsRangedCoord<Value = f64>,
    Y: AsRangedCoord<Value = f64>,
    X::CoordDescType: ValueFormatter<f64>,
    Y::CoordDescType: ValueFormatter<f64>,
{
    let mut chart = ChartBuilder::on(root)
        .margin(12)
        .x_label_area_size(44)
        .y_label_area_size(72)
        .build_cartesian_2d(x, y)
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .x_desc(pd.x_label.as_str())
        .y_desc(pd.y_label.as_str())
        .x_label_formatter(&|v| tick_linear(*v, spans.0))
        .y_label_formatter(&|v| tick_linear(*v, spans.1))
        .label_style(("sans-serif", 14))
        .axis_desc_style(("sans-serif", 15))
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(|e| e.to_string())?;
    // A labelled line takes the next colour; an unlabelled one (e.g. the markers of the
    // previous line) reuses the last.
    let mut next = 0usize;
    for line in &pd.lines {
        if !line.label.is_empty() || next == 0 {
            next += 1;
        }
        let color = PALETTE[(next - 1) % PALETTE.len()];
        // The first line is drawn wider so that it stays visible under later ones it overlaps.
        let width = if next == 1 { 3 } else { 2 };
        let keep =
            |(x, y): &(f64, f64)| x.is_finite() && y.is_finite() && (!pd.log_x || *x > 0.0) && (!pd.log_y || *y > 0.0);
        let pts: Vec<(f64, f64)> = line.x.iter().copied().zip(line.y.iter().copied()).collect();
        let series = if line.points {
            let pts: Vec<(f64, f64)> = pts.into_iter().filter(keep).collect();
            chart.draw_series(pts.into_iter().map(|p| Circle::new(p, 4, color.filled()))).map_err(|e| e.to_string())?
        } else {
            // Break the polyline where a value cannot be drawn (e.g. 0 on a log axis).
            let mut segments: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
            for p in pts {
                if keep(&p) {
                    segments.last_mut().expect("non-empty").push(p);
                } else if !segments.last().expect("non-empty").is_empty() {
                    segments.push(Vec::new());
                }
            }
            chart
                .draw_series(
                    segments
                        .into_iter()
                        .filter(|s| !s.is_empty())
                        .map(|s| PathElement::new(s, color.stroke_width(width))),
                )
                .map_err(|e| e.to_string())?
        };
        if !line.label.is_empty() {
            series
                .label(line.label.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(3)));
        }
    }
    if pd.lines.iter().any(|l| !l.label.is_empty()) {
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK.mix(0.4))
            .label_font(("sans-serif", 14))
            .draw()
            .map_err(|e| e.to_string())?;
    }
    Ok(())
}
