//! Heatmaps of a value over a 2-D grid of parameters (the searches): sequential colour map
//! with a labelled colour bar, cells without a value in grey with a legend entry, and marks
//! (boundary segments, dots, circles) listed in a legend.

use plotters::prelude::*;

use crate::{tick, ChartError};

/// Width and height (px) of a grid heatmap.
pub const GRID_SIZE: (u32, u32) = (940, 720);

/// Colour of cells without a value.
pub const MISSING: RGBColor = RGBColor(190, 190, 190);

/// One axis of the grid.
#[derive(Debug, Clone)]
pub struct GridAxis {
    /// Axis title with unit, e.g. "control.a (weight of tip displacement in (15), m⁻¹)".
    pub label: String,
    /// Values at the cell centres (increasing); for a list axis of words, 0, 1, 2, ….
    pub centres: Vec<f64>,
    /// Logarithmic axis (centres > 0).
    pub log: bool,
    /// Labels of the centres for a list axis of words (None: numeric ticks).
    pub words: Option<Vec<String>>,
}

impl GridAxis {
    fn coord(&self, v: f64) -> f64 {
        if self.log {
            v.log10()
        } else {
            v
        }
    }

    /// Cell edges in plot coordinates (midpoints; the ends extend by half a spacing).
    fn edges(&self) -> Vec<f64> {
        let c: Vec<f64> = self.centres.iter().map(|&v| self.coord(v)).collect();
        let n = c.len();
        let half = if n > 1 { 0.5 * (c[1] - c[0]) } else { 0.5 };
        let half_end = if n > 1 { 0.5 * (c[n - 1] - c[n - 2]) } else { 0.5 };
        let mut e = Vec::with_capacity(n + 1);
        e.push(c[0] - half);
        for i in 1..n {
            e.push(0.5 * (c[i - 1] + c[i]));
        }
        e.push(c[n - 1] + half_end);
        e
    }

    fn label_at(&self, v: f64) -> String {
        match &self.words {
            Some(words) => {
                let i = v.round();
                if (v - i).abs() < 1e-6 && i >= 0.0 && (i as usize) < words.len() {
                    words[i as usize].clone()
                } else {
                    String::new()
                }
            }
            None if self.log => decade_tick(v, self.decades()),
            None => tick(v),
        }
    }

    /// Decades spanned (log axes).
    fn decades(&self) -> f64 {
        let e = self.edges();
        e[e.len() - 1] - e[0]
    }
}

/// Label of log10 coordinate `v` on a log axis spanning `decades`: only whole decades are
/// labelled when the axis spans at least one (so every label has the same form), in [`tick`]'s
/// format.
fn decade_tick(v: f64, decades: f64) -> String {
    if decades >= 1.0 && (v - v.round()).abs() > 1e-9 {
        String::new()
    } else {
        tick(10f64.powf(if decades >= 1.0 { v.round() } else { v }))
    }
}

/// Shape of a mark.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MarkShape {
    /// Line segments (pairs of points).
    Segments,
    /// Filled dots.
    Dots,
    /// Open circles.
    Circles,
}

/// A set of marks drawn over the cells, with a legend entry.
#[derive(Debug, Clone)]
pub struct Mark {
    /// Legend text.
    pub label: String,
    /// Colour.
    pub colour: RGBColor,
    /// Shape.
    pub shape: MarkShape,
    /// Points in axis values (not plot coordinates); segments take them in pairs.
    pub points: Vec<(f64, f64)>,
}

/// A value over a grid: `values[i·ny + j]` at (x.centres[i], y.centres[j]).
#[derive(Debug, Clone)]
pub struct GridHeatmap {
    /// File stem.
    pub name: String,
    /// Title (readable: quantity, window, what the marks are).
    pub title: String,
    /// First axis (x).
    pub x: GridAxis,
    /// Second axis (y).
    pub y: GridAxis,
    /// Values (None: no value).
    pub values: Vec<Option<f64>>,
    /// Colour scale logarithmic in the value (values ≤ 0 count as missing).
    pub log_values: bool,
    /// Colour-bar label: quantity and unit.
    pub value_label: String,
    /// Legend text for cells without a value (why they have none).
    pub missing_label: String,
    /// Marks over the cells.
    pub marks: Vec<Mark>,
}

/// Sequential colour map (viridis, 5 stops, linear in between); u ∈ [0, 1].
pub fn viridis(u: f64) -> RGBColor {
    const STOPS: [[f64; 3]; 5] =
        [[68.0, 1.0, 84.0], [59.0, 82.0, 139.0], [33.0, 145.0, 140.0], [94.0, 201.0, 98.0], [253.0, 231.0, 37.0]];
    let x = if u.is_finite() { u.clamp(0.0, 1.0) } else { 0.0 } * 4.0;
    let i = (x.floor() as usize).min(3);
    let w = x - i as f64;
    let c = |k: usize| (STOPS[i][k] + w * (STOPS[i + 1][k] - STOPS[i][k])).round() as u8;
    RGBColor(c(0), c(1), c(2))
}

/// Render a grid heatmap as an SVG document.
pub fn grid_heatmap_svg(h: &GridHeatmap) -> Result<String, ChartError> {
    let err = |e: String| ChartError { name: h.name.clone(), detail: e };
    let (nx, ny) = (h.x.centres.len(), h.y.centres.len());
    if nx == 0 || ny == 0 || h.values.len() != nx * ny {
        return Err(err(format!("{} values for a {nx} × {ny} grid", h.values.len())));
    }
    let scaled = |v: f64| if h.log_values { (v > 0.0).then(|| v.log10()) } else { Some(v) };
    let vals: Vec<Option<f64>> = h.values.iter().map(|v| v.and_then(scaled).filter(|v| v.is_finite())).collect();
    let (mut vmin, mut vmax) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in vals.iter().flatten() {
        vmin = vmin.min(*v);
        vmax = vmax.max(*v);
    }
    if !vmin.is_finite() {
        (vmin, vmax) = (0.0, 1.0);
    }
    if vmax - vmin <= 1e-12 * vmax.abs().max(1.0) {
        (vmin, vmax) = (vmin - 0.5, vmax + 0.5);
    }
    let (xe, ye) = (h.x.edges(), h.y.edges());
    let (xr, yr) = (xe[0]..xe[nx], ye[0]..ye[ny]);
    let missing = vals.iter().filter(|v| v.is_none()).count();
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, GRID_SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(e.to_string()))?;
        let (top, legend_area) = root.split_vertically(GRID_SIZE.1 - 90);
        let (main, bar) = top.split_horizontally(GRID_SIZE.0 - 150);
        let mut chart = ChartBuilder::on(&main)
            .margin(14)
            .caption(h.title.as_str(), ("sans-serif", 15))
            .x_label_area_size(48)
            .y_label_area_size(72)
            .build_cartesian_2d(xr, yr)
            .map_err(|e| err(e.to_string()))?;
        let mut cells = Vec::with_capacity(nx * ny);
        for i in 0..nx {
            for j in 0..ny {
                let colour = vals[i * ny + j].map_or(MISSING, |v| viridis((v - vmin) / (vmax - vmin)));
                cells.push(Rectangle::new([(xe[i], ye[j]), (xe[i + 1], ye[j + 1])], colour.filled()));
            }
        }
        chart.draw_series(cells).map_err(|e| err(e.to_string()))?;
        let at = |(x, y): (f64, f64)| (h.x.coord(x), h.y.coord(y));
        for m in &h.marks {
            let style = m.colour.stroke_width(3);
            match m.shape {
                MarkShape::Segments => chart
                    .draw_series(m.points.chunks_exact(2).map(|p| PathElement::new(vec![at(p[0]), at(p[1])], style)))
                    .map(|_| ()),
                MarkShape::Dots => {
                    chart.draw_series(m.points.iter().map(|&p| Circle::new(at(p), 2, m.colour.filled()))).map(|_| ())
                }
                MarkShape::Circles => chart
                    .draw_series(m.points.iter().map(|&p| Circle::new(at(p), 4, m.colour.stroke_width(2))))
                    .map(|_| ()),
            }
            .map_err(|e| err(e.to_string()))?;
        }
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(h.x.label.as_str())
            .y_desc(h.y.label.as_str())
            .x_label_formatter(&|v| h.x.label_at(*v))
            .y_label_formatter(&|v| h.y.label_at(*v))
            .label_style(("sans-serif", 13))
            .axis_desc_style(("sans-serif", 14))
            .draw()
            .map_err(|e| err(e.to_string()))?;

        // colour bar, labelled with values (not their logarithms) and the quantity
        let mut cb = ChartBuilder::on(&bar)
            .margin_top(40)
            .margin_bottom(60)
            .margin_left(8)
            .margin_right(4)
            .right_y_label_area_size(64)
            .caption(h.value_label.as_str(), ("sans-serif", 13))
            .build_cartesian_2d(0.0..1.0, vmin..vmax)
            .map_err(|e| err(e.to_string()))?;
        let steps = 64;
        cb.draw_series((0..steps).map(|k| {
            let a = vmin + (vmax - vmin) * k as f64 / steps as f64;
            let b = vmin + (vmax - vmin) * (k + 1) as f64 / steps as f64;
            Rectangle::new([(0.0, a), (1.0, b)], viridis((k as f64 + 0.5) / steps as f64).filled())
        }))
        .map_err(|e| err(e.to_string()))?;
        let (log, span) = (h.log_values, vmax - vmin);
        cb.configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .y_labels(if log && span >= 1.0 { (span.ceil() as usize + 1).min(12) } else { 7 })
            .y_label_formatter(&|v| if log { decade_tick(*v, span) } else { tick(*v) })
            .label_style(("sans-serif", 12))
            .draw()
            .map_err(|e| err(e.to_string()))?;

        // legend: the marks, and the grey cells
        let font = ("sans-serif", 13).into_font();
        let mut entries: Vec<(String, RGBColor, MarkShape)> =
            h.marks.iter().map(|m| (m.label.clone(), m.colour, m.shape)).collect();
        entries.push((format!("{} ({missing} cells)", h.missing_label), MISSING, MarkShape::Dots));
        for (k, (label, colour, shape)) in entries.iter().enumerate() {
            let (col, row) = ((k % 2) as i32, (k / 2) as i32);
            let (x0, y0) = (20 + col * 460, 10 + row * 24);
            let e = match (shape, k + 1 == entries.len()) {
                (_, true) => legend_area.draw(&Rectangle::new([(x0, y0), (x0 + 18, y0 + 14)], colour.filled())),
                (MarkShape::Segments, _) => {
                    legend_area.draw(&PathElement::new(vec![(x0, y0 + 7), (x0 + 18, y0 + 7)], colour.stroke_width(3)))
                }
                (MarkShape::Dots, _) => legend_area.draw(&Circle::new((x0 + 9, y0 + 7), 3, colour.filled())),
                (MarkShape::Circles, _) => legend_area.draw(&Circle::new((x0 + 9, y0 + 7), 5, colour.stroke_width(2))),
            };
            e.map_err(|e| err(e.to_string()))?;
            legend_area.draw(&Text::new(label.clone(), (x0 + 26, y0), font.clone())).map_err(|e| err(e.to_string()))?;
        }
        root.present().map_err(|e| err(e.to_string()))?;
    }
    Ok(svg)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colour_map_ends() {
        // the first and last stops of the table
        assert_eq!(viridis(0.0), RGBColor(68, 1, 84));
        assert_eq!(viridis(1.0), RGBColor(253, 231, 37));
    }

    #[test]
    fn log_axis_edges_are_geometric_midpoints() {
        // centres 1, 10, 100 → log10 coordinates 0, 1, 2; edges −0.5, 0.5, 1.5, 2.5
        let a = GridAxis { label: "a".into(), centres: vec![1.0, 10.0, 100.0], log: true, words: None };
        assert_eq!(a.edges(), vec![-0.5, 0.5, 1.5, 2.5]);
        assert_eq!(a.label_at(1.0), "10");
    }
}
