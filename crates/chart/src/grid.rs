//! Heatmaps of a value over a 2-D grid of parameters (the searches, the report's (a, b) region
//! map): sequential colour map with a labelled colour bar, cells without a value in grey with
//! a legend entry, and marks over the cells (boundary segments and lines, dots, circles, a
//! cross at an operating point, shaded regions) listed in a legend below the plot.
//!
//! The cells and the colour bar are one PNG raster each (one pixel per displayed pixel, so an
//! SVG holds two images rather than a rectangle per cell); axes, ticks, labels and marks are
//! vector, drawn on a [`SCALE`]-times canvas like the line charts.

use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;

use crate::clip::{clip_segment, hatch, HATCH_STEP};
use crate::{
    decade_label, linear_ticks, log_labels, log_ticks, px, tick, ChartError, DrawError, Ticked, CANVAS, SCALE, SIZE,
};

/// Colour of cells without a value.
pub const MISSING: RGBColor = RGBColor(190, 190, 190);

/// Displayed height (px) of the plot part of a grid heatmap (the legend rows come below).
const PLOT_H: u32 = 560;
/// Displayed height of one legend row.
const ROW_H: u32 = 26;
/// Displayed width of the colour-bar panel.
const BAR_W: u32 = 150;

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

    /// Tick positions (plot coordinates) and their labels, in one format per axis: the words
    /// of a list axis; on a log axis the decades (10ᵏ, or [`tick`]'s format when all lie in
    /// [0.01, 1000]) or 1-2-5 within a short range; on a linear axis 1-2-5 steps.
    fn ticks(&self) -> (Vec<f64>, Vec<String>) {
        let e = self.edges();
        let (lo, hi) = (e[0], e[e.len() - 1]);
        if let Some(words) = &self.words {
            return ((0..words.len()).map(|i| i as f64).collect(), words.clone());
        }
        if self.log {
            let values = log_ticks(10f64.powf(lo), 10f64.powf(hi), &[]);
            let decades = log_labels(&values);
            let labels = values.iter().map(|v| if decades { decade_label(*v) } else { tick(*v) }).collect();
            (values.iter().map(|v| v.log10()).collect(), labels)
        } else {
            let values = linear_ticks(lo, hi, 6);
            let labels = values.iter().map(|v| crate::tick_linear(*v, hi - lo)).collect();
            (values, labels)
        }
    }

    /// Index of the cell containing plot coordinate `x`.
    fn cell_at(edges: &[f64], x: f64) -> usize {
        edges.partition_point(|e| *e <= x).clamp(1, edges.len() - 1) - 1
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
    /// One solid polyline through the points (e.g. a closed-form boundary).
    Line,
    /// One dashed polyline through the points.
    DashedLine,
    /// An open square around each point (e.g. the configured operating point), outside the
    /// circles and dots of the point's cell, so its own verdict marks stay visible.
    Cross,
    /// A hatched region: the convex polygon through the points, hatched with thin diagonal lines
    /// (the cell colours stay readable), drawn under the other marks.
    Hatch,
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
    /// Title (readable: quantity, window, what the marks are); empty: none (e.g. a report
    /// figure whose title is in the page).
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

/// A contrasting outline for a mark of colour `c` (dark for light colours, light for dark), so
/// marks read on every cell colour and on the white legend.
fn halo(c: RGBColor) -> RGBAColor {
    let luminance = 0.299 * c.0 as f64 + 0.587 * c.1 as f64 + 0.114 * c.2 as f64;
    if luminance > 140.0 {
        BLACK.mix(0.75)
    } else {
        WHITE.mix(0.9)
    }
}

/// An RGB PNG of `w × h` pixels, colour of pixel (column, row) from `colour`.
fn rgb_png(w: usize, h: usize, colour: impl Fn(usize, usize) -> RGBColor) -> Result<Vec<u8>, DrawError> {
    let mut data = Vec::with_capacity(w * h * 3);
    for r in 0..h {
        for c in 0..w {
            let col = colour(c, r);
            data.extend_from_slice(&[col.0, col.1, col.2]);
        }
    }
    let mut png = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut png, w as u32, h as u32);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut wr = enc.write_header()?;
        wr.write_image_data(&data)?;
    }
    Ok(png)
}

/// Displayed size of a grid heatmap with `rows` legend rows.
fn size(rows: usize) -> (u32, u32) {
    (SIZE.0, PLOT_H + 16 + ROW_H * rows as u32)
}

/// Render a grid heatmap as an SVG document.
pub fn grid_heatmap_svg(h: &GridHeatmap) -> Result<String, ChartError> {
    let err = |cause: DrawError| ChartError { name: h.name.clone(), cause };
    let (nx, ny) = (h.x.centres.len(), h.y.centres.len());
    if nx == 0 || ny == 0 || h.values.len() != nx * ny {
        return Err(err(DrawError::GridShape { values: h.values.len(), nx, ny }));
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
    let missing = vals.iter().filter(|v| v.is_none()).count();
    let mut entries: Vec<(String, RGBColor, Option<MarkShape>)> =
        h.marks.iter().filter(|m| !m.label.is_empty()).map(|m| (m.label.clone(), m.colour, Some(m.shape))).collect();
    if missing > 0 {
        entries.push((format!("{} ({missing} cells)", h.missing_label), MISSING, None));
    }
    let (width, height) = size(entries.len().div_ceil(2));
    let canvas = (width * SCALE, height * SCALE);
    let (xe, ye) = (h.x.edges(), h.y.edges());
    let mut svg = String::new();
    let (plot_px, bar_px);
    {
        let root = SVGBackend::with_string(&mut svg, canvas).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(e.into()))?;
        let (top, legend_area) = root.split_vertically(px(PLOT_H));
        let (main, bar) = top.split_horizontally(CANVAS.0 - px(BAR_W));
        plot_px = draw_cells_frame(&main, h, &xe, &ye).map_err(err)?;
        bar_px = draw_colour_bar(&bar, h, vmin, vmax).map_err(err)?;
        draw_legend(&legend_area, &entries).map_err(err)?;
        root.present().map_err(|e| err(e.into()))?;
    }
    // The cells, nearest cell per displayed pixel; the colour bar, one row per pixel.
    let (cx, cy) = (&xe, &ye);
    let raster = |r: &(std::ops::Range<i32>, std::ops::Range<i32>)| {
        (((r.0.end - r.0.start) as u32 / SCALE).max(2) as usize, ((r.1.end - r.1.start) as u32 / SCALE).max(2) as usize)
    };
    let (w, hgt) = raster(&plot_px);
    let (x0, x1, y0, y1) = (cx[0], cx[nx], cy[0], cy[ny]);
    let cells = rgb_png(w, hgt, |c, r| {
        let x = x0 + (x1 - x0) * (c as f64 + 0.5) / w as f64;
        let y = y1 - (y1 - y0) * (r as f64 + 0.5) / hgt as f64;
        let (i, j) = (GridAxis::cell_at(cx, x), GridAxis::cell_at(cy, y));
        vals[i * ny + j].map_or(MISSING, |v| viridis((v - vmin) / (vmax - vmin)))
    })
    .map_err(err)?;
    let (bw, bh) = raster(&bar_px);
    let bar = rgb_png(bw, bh, |_, r| viridis(1.0 - (r as f64 + 0.5) / bh as f64)).map_err(err)?;
    crate::embed_raster(&mut svg, &bar_px, &bar).map_err(err)?;
    crate::embed_raster(&mut svg, &plot_px, &cells).map_err(err)?;
    let svg = svg.replacen(
        &format!("<svg width=\"{}\" height=\"{}\"", canvas.0, canvas.1),
        &format!("<svg width=\"{width}\" height=\"{height}\""),
        1,
    );
    Ok(svg)
}

type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;
type PixelRange = (std::ops::Range<i32>, std::ops::Range<i32>);

/// Axes, ticks and marks of the cell plot; returns the plotting area (canvas pixels).
fn draw_cells_frame(main: &Area, h: &GridHeatmap, xe: &[f64], ye: &[f64]) -> Result<PixelRange, DrawError> {
    let (xt, xl) = h.x.ticks();
    let (yt, yl) = h.y.ticks();
    let label_of = |ticks: &[f64], labels: &[String], v: f64| {
        ticks.iter().position(|t| (t - v).abs() < 1e-9).map_or(String::new(), |i| labels[i].clone())
    };
    let mut builder = ChartBuilder::on(main);
    builder.margin(px(14)).x_label_area_size(px(48)).y_label_area_size(px(76));
    if !h.title.is_empty() {
        builder.caption(h.title.as_str(), ("sans-serif", px(17)));
    }
    let mut chart = builder.build_cartesian_2d(
        Ticked::<RangedCoordf64>::new(xe[0]..xe[xe.len() - 1], xt.clone()),
        Ticked::<RangedCoordf64>::new(ye[0]..ye[ye.len() - 1], yt.clone()),
    )?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(h.x.label.as_str())
        .y_desc(h.y.label.as_str())
        .x_label_formatter(&|v| label_of(&xt, &xl, *v))
        .y_label_formatter(&|v| label_of(&yt, &yl, *v))
        .label_style(("sans-serif", px(17)))
        .axis_desc_style(("sans-serif", px(17)))
        .axis_style(BLACK.stroke_width(px(1)))
        .set_all_tick_mark_size(px(5))
        .draw()?;
    let at = |(x, y): (f64, f64)| (h.x.coord(x), h.y.coord(y));
    // Hatched regions first, so the other marks lie over them.
    let mut marks: Vec<&Mark> = h.marks.iter().collect();
    marks.sort_by_key(|m| m.shape != MarkShape::Hatch);
    // plotters pins coordinates outside the plot to its frame, which would bend a line that
    // leaves the plot: lines are clipped here, markers outside the plot dropped.
    let bounds = ((xe[0], xe[xe.len() - 1]), (ye[0], ye[ye.len() - 1]));
    let inside =
        |p: &(f64, f64)| (bounds.0 .0..=bounds.0 .1).contains(&p.0) && (bounds.1 .0..=bounds.1 .1).contains(&p.1);
    for m in marks {
        let mut pts: Vec<(f64, f64)> = m.points.iter().map(|&p| at(p)).collect();
        match m.shape {
            MarkShape::Segments => {
                pts = pts
                    .chunks_exact(2)
                    .filter_map(|s| clip_segment(s[0], s[1], bounds))
                    .flat_map(|(a, b)| [a, b])
                    .collect();
            }
            MarkShape::Line | MarkShape::DashedLine => {
                // Only straight lines through two points are clipped exactly; longer polylines
                // keep their vertices inside the plot.
                pts = match pts[..] {
                    [a, b] => clip_segment(a, b, bounds).map_or(Vec::new(), |(a, b)| vec![a, b]),
                    _ => pts.into_iter().filter(inside).collect(),
                };
            }
            MarkShape::Dots | MarkShape::Circles | MarkShape::Cross => pts.retain(inside),
            MarkShape::Hatch => {}
        }
        if pts.is_empty() {
            continue;
        }
        let (c, o) = (m.colour, halo(m.colour));
        let series = |chart: &mut ChartContext<SVGBackend, _>, w: u32, style: ShapeStyle, dashed: bool| {
            if dashed {
                chart.draw_series(DashedLineSeries::new(pts.clone(), px(10), px(6), style)).map(|_| ())
            } else {
                chart.draw_series(std::iter::once(PathElement::new(pts.clone(), style.stroke_width(w)))).map(|_| ())
            }
        };
        match m.shape {
            MarkShape::Hatch => {
                let corners: Vec<(f64, f64)> =
                    pts.iter().map(|p| chart.backend_coord(p)).map(|(x, y)| (f64::from(x), f64::from(y))).collect();
                let (area, frame) = (chart.plotting_area().get_pixel_range(), f64::from(px(HATCH_STEP)));
                for s in hatch(&corners, frame, (area.0.start, area.0.end)) {
                    main.draw(&PathElement::new(s.to_vec(), c.mix(0.55).stroke_width(px(1))))?;
                }
            }
            MarkShape::Segments => {
                for (style, w) in [(o.stroke_width(px(5)), px(5)), (c.stroke_width(px(3)), px(3))] {
                    chart.draw_series(
                        pts.chunks_exact(2).map(|p| PathElement::new(p.to_vec(), style.stroke_width(w))),
                    )?;
                }
            }
            MarkShape::Line | MarkShape::DashedLine => {
                let dashed = m.shape == MarkShape::DashedLine;
                series(&mut chart, px(5), o.stroke_width(px(5)), dashed)?;
                series(&mut chart, px(3), c.stroke_width(px(3)), dashed)?;
            }
            MarkShape::Dots => {
                chart.draw_series(pts.iter().map(|&p| Circle::new(p, px(4), o.filled())))?;
                chart.draw_series(pts.iter().map(|&p| Circle::new(p, px(3), c.filled())))?;
            }
            MarkShape::Circles => {
                chart.draw_series(pts.iter().map(|&p| Circle::new(p, px(7), o.stroke_width(px(4)))))?;
                chart.draw_series(pts.iter().map(|&p| Circle::new(p, px(7), c.stroke_width(px(2)))))?;
            }
            MarkShape::Cross => {
                for &p in &pts {
                    let (x, y) = chart.backend_coord(&p);
                    let d = px(13) as i32;
                    let square = vec![(x - d, y - d), (x + d, y - d), (x + d, y + d), (x - d, y + d), (x - d, y - d)];
                    for (style, w) in [(o, px(6)), (c.to_rgba(), px(3))] {
                        main.draw(&PathElement::new(square.clone(), style.stroke_width(w)))?;
                    }
                }
            }
        }
    }
    Ok(chart.plotting_area().get_pixel_range())
}

/// The colour bar's frame and value ticks (the gradient is a raster placed in the returned
/// area), labelled with values (not their logarithms) and the quantity.
fn draw_colour_bar(bar: &Area, h: &GridHeatmap, vmin: f64, vmax: f64) -> Result<PixelRange, DrawError> {
    // The scale's ends are labelled too (the top of the region map's is the unsuppressed
    // deflection), unless a tick is within 6 % of the bar's height of them.
    let (ticks, labels): (Vec<f64>, Vec<String>) = if h.log_values {
        let t = log_ticks(10f64.powf(vmin), 10f64.powf(vmax), &[]);
        let decades = log_labels(&t);
        let logs: Vec<f64> = t.iter().map(|v| v.log10()).collect();
        let all = crate::with_ends(&logs, vmin, vmax, 0.06);
        let label = |l: f64| {
            let v = 10f64.powf(l);
            if t.iter().any(|x| (x.log10() - l).abs() < 1e-9) && decades {
                decade_label(v)
            } else {
                tick(v)
            }
        };
        (all.clone(), all.iter().map(|l| label(*l)).collect())
    } else {
        let t = crate::with_ends(&linear_ticks(vmin, vmax, 6), vmin, vmax, 0.06);
        let f = 10f64.powi(common_exponent(&t).unwrap_or(0));
        (t.clone(), t.iter().map(|v| crate::tick_linear(*v / f, (vmax - vmin) / f)).collect())
    };
    // Room for the longest label (≈ 9 px a character at 16 px, the tick and a gap; a narrow
    // range's ticks read `2.935×10⁻⁶` and were clipped at 76 px), taken from the bar's width.
    let longest = labels.iter().map(|l| l.chars().count()).max().unwrap_or(0) as u32;
    let label_w = (9 * longest + 12).clamp(76, 110);
    let mut cb = ChartBuilder::on(bar)
        .margin_top(px(44))
        .margin_bottom(px(62))
        .margin_left(px(10))
        .margin_right(px(4))
        .right_y_label_area_size(px(label_w))
        .build_cartesian_2d(0.0..1.0, Ticked::<RangedCoordf64>::new(vmin..vmax, ticks.clone()))?;
    cb.configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_label_formatter(&|v| {
            ticks.iter().position(|t| (t - v).abs() < 1e-9).map_or(String::new(), |i| labels[i].clone())
        })
        .label_style(("sans-serif", px(16)))
        .axis_style(BLACK.stroke_width(px(1)))
        .set_all_tick_mark_size(px(4))
        .draw()?;
    let title = match (h.log_values, common_exponent(&ticks)) {
        (false, Some(k)) => scaled_label(&h.value_label, k),
        _ => h.value_label.clone(),
    };
    bar.draw(&Text::new(title, (px(4) as i32, px(14) as i32), ("sans-serif", px(16)).into_font().color(&BLACK)))?;
    Ok(cb.plotting_area().get_pixel_range())
}

/// The decimal exponent k shared by every nonzero value of a linear scale whose labels would
/// all need ×10ᵏ (|v| outside [10⁻³, 10⁵), [`crate::tick`]): a narrow range (the Goland
/// region map's RMS spans 2.90–2.94×10⁻⁶ m) then reads as mantissas with 10ᵏ in the title.
fn common_exponent(values: &[f64]) -> Option<i32> {
    let exps: Vec<i32> = values.iter().filter(|v| **v != 0.0).map(|v| v.abs().log10().floor() as i32).collect();
    let k = *exps.first()?;
    (exps.iter().all(|e| *e == k) && !(-3..5).contains(&k)).then_some(k)
}

/// A scale's title with its values in units of 10ᵏ: `RMS |q| (m)` → `RMS |q| (10⁻⁶ m)`.
fn scaled_label(label: &str, k: i32) -> String {
    let p = format!("10{}", wingcheck_io::prose::superscript(k));
    match label.strip_suffix(')').and_then(|l| l.rsplit_once('(')) {
        Some((head, unit)) => format!("{head}({p} {unit})"),
        None => format!("{label} (×{p})"),
    }
}

/// The legend below the plot, two entries per row: each mark as drawn, then the grey cells.
fn draw_legend(area: &Area, entries: &[(String, RGBColor, Option<MarkShape>)]) -> Result<(), DrawError> {
    let font = ("sans-serif", px(16)).into_font().color(&BLACK);
    for (k, (label, c, shape)) in entries.iter().enumerate() {
        let (col, row) = ((k % 2) as i32, (k / 2) as i32);
        let (x0, y) = (px(24) as i32 + col * px(480) as i32, px(12) as i32 + row * px(ROW_H) as i32);
        let (c, o) = (*c, halo(*c));
        let (xa, xb, xm) = (x0, x0 + px(26) as i32, x0 + px(13) as i32);
        let seg = |style: ShapeStyle| PathElement::new(vec![(xa, y), (xb, y)], style);
        match shape {
            None => area.draw(&Rectangle::new([(xa, y - px(8) as i32), (xb, y + px(8) as i32)], c.filled()))?,
            Some(MarkShape::Hatch) => {
                let (ya, yb) = (f64::from(y - px(9) as i32), f64::from(y + px(9) as i32));
                let corners = [(f64::from(xa), ya), (f64::from(xb), ya), (f64::from(xb), yb), (f64::from(xa), yb)];
                for s in hatch(&corners, f64::from(px(HATCH_STEP) / 2), (xa, xb)) {
                    area.draw(&PathElement::new(s.to_vec(), c.mix(0.8).stroke_width(px(1))))?;
                }
                area.draw(&Rectangle::new([(xa, ya as i32), (xb, yb as i32)], c.mix(0.8).stroke_width(px(1))))?;
            }
            Some(MarkShape::Segments | MarkShape::Line) => {
                area.draw(&seg(o.stroke_width(px(5))))?;
                area.draw(&seg(c.stroke_width(px(3))))?;
            }
            Some(MarkShape::DashedLine) => {
                for (a, b) in [(xa, xa + px(10) as i32), (xa + px(16) as i32, xb)] {
                    area.draw(&PathElement::new(vec![(a, y), (b, y)], o.stroke_width(px(5))))?;
                    area.draw(&PathElement::new(vec![(a, y), (b, y)], c.stroke_width(px(3))))?;
                }
            }
            Some(MarkShape::Dots) => {
                area.draw(&Circle::new((xm, y), px(4), o.filled()))?;
                area.draw(&Circle::new((xm, y), px(3), c.filled()))?;
            }
            Some(MarkShape::Circles) => {
                area.draw(&Circle::new((xm, y), px(7), o.stroke_width(px(4))))?;
                area.draw(&Circle::new((xm, y), px(7), c.stroke_width(px(2))))?;
            }
            Some(MarkShape::Cross) => {
                let d = px(9) as i32;
                let square = vec![(xm - d, y - d), (xm + d, y - d), (xm + d, y + d), (xm - d, y + d), (xm - d, y - d)];
                for (style, w) in [(o, px(6)), (c.to_rgba(), px(3))] {
                    area.draw(&PathElement::new(square.clone(), style.stroke_width(w)))?;
                }
            }
        }
        area.draw(&Text::new(label.clone(), (x0 + px(36) as i32, y - px(9) as i32), font.clone()))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_narrow_scale_reads_as_mantissas_with_its_power_in_the_title() {
        // the Goland region map's colour scale (2.898e-6 … 2.936e-6 m)
        let t = [2.9e-6, 2.91e-6, 2.92e-6, 2.936e-6];
        assert_eq!(super::common_exponent(&t), Some(-6));
        assert_eq!(super::scaled_label("RMS |q(s,t)| (m)", -6), "RMS |q(s,t)| (10⁻⁶ m)");
        // fixed-notation values and mixed decades keep their labels
        assert_eq!(super::common_exponent(&[0.1, 0.2]), None);
        assert_eq!(super::common_exponent(&[9e-7, 1.1e-6]), None);
    }

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
        // ticks at the decades 1, 10, 100 (inside [10^-0.5, 10^2.5]), in one format
        assert_eq!(a.ticks(), (vec![0.0, 1.0, 2.0], vec!["1".to_string(), "10".into(), "100".into()]));
        // the cell containing a coordinate, the ends clamped
        let e = a.edges();
        assert_eq!([-1.0, 0.2, 0.5, 2.4, 9.0].map(|x| GridAxis::cell_at(&e, x)), [0, 0, 1, 2, 2]);
    }
}
