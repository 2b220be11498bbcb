//! SVG heatmap of a metric over a 2-D search, with the theory boundaries drawn over it.
//!
//! plotters' SVG backend writes text as `<text>` elements and only estimates widths, so no
//! system font is read (plotters is built without its font features).

use plotters::prelude::*;

use crate::point::{metric_index, PointResult};
use crate::refine::BoundaryRow;
use crate::{Axis, Search, SearchError};

const SIZE: (u32, u32) = (900, 700);
const NAN_COLOUR: RGBColor = RGBColor(190, 190, 190);
const W_COLOUR: RGBColor = RGBColor(255, 255, 255);
const MU_COLOUR: RGBColor = RGBColor(230, 30, 40);

/// Sequential colour map (viridis, 5 stops, linear in between); u ∈ [0, 1].
fn viridis(u: f64) -> RGBColor {
    const STOPS: [[f64; 3]; 5] =
        [[68.0, 1.0, 84.0], [59.0, 82.0, 139.0], [33.0, 145.0, 140.0], [94.0, 201.0, 98.0], [253.0, 231.0, 37.0]];
    let x = u.clamp(0.0, 1.0) * 4.0;
    let i = (x.floor() as usize).min(3);
    let w = x - i as f64;
    let c = |k: usize| (STOPS[i][k] + w * (STOPS[i + 1][k] - STOPS[i][k])).round() as u8;
    RGBColor(c(0), c(1), c(2))
}

/// Plot coordinate of value i of an axis: log10 on log axes, the value on lin axes, the
/// position on list axes.
fn coord(a: &Axis, i: usize) -> f64 {
    match a.numeric(i) {
        Some(x) if a.is_log() => x.log10(),
        Some(x) => x,
        None => i as f64,
    }
}

fn value_coord(a: &Axis, x: f64) -> f64 {
    if a.is_log() {
        x.log10()
    } else {
        x
    }
}

/// Cell edges around the centres (midpoints; the ends extend by half a spacing).
fn edges(c: &[f64]) -> Vec<f64> {
    let n = c.len();
    let mut e = Vec::with_capacity(n + 1);
    e.push(c[0] - 0.5 * (c[1] - c[0]));
    for i in 1..n {
        e.push(0.5 * (c[i - 1] + c[i]));
    }
    e.push(c[n - 1] + 0.5 * (c[n - 1] - c[n - 2]));
    e
}

fn tick(v: f64) -> String {
    let a = v.abs();
    if v == 0.0 {
        "0".into()
    } else if (1e-3..1e4).contains(&a) {
        let s = format!("{v:.4}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        let s = format!("{v:.2e}");
        match s.split_once('e') {
            Some((m, e)) => format!("{}e{e}", m.trim_end_matches('0').trim_end_matches('.')),
            None => s,
        }
    }
}

fn label(a: &Axis, v: f64) -> String {
    match a.numeric(0) {
        Some(_) if a.is_log() => tick(10f64.powf(v)),
        Some(_) => tick(v),
        None => {
            let i = v.round();
            if (v - i).abs() < 1e-6 && i >= 0.0 && (i as usize) < a.len() {
                a.text(i as usize)
            } else {
                String::new()
            }
        }
    }
}

/// Render `metric` (log10 of it if `log`) over a 2-D search: x = first axis, y = second.
/// White lines: boundary of W ≻ 0; red lines: boundary of (32) feasibility (between grid
/// cells); black dots: theorem-feasible cells (both hold); circles: refined boundary points.
/// Grey cells: metric not available (diverged or failed points).
pub fn heatmap_svg(
    search: &Search,
    points: &[PointResult],
    metric: &str,
    log: bool,
    boundary: &[BoundaryRow],
) -> Result<String, SearchError> {
    let err = |e: String| SearchError::Io { path: format!("heatmap-{metric}.svg"), detail: e };
    let grid = &search.grid;
    let (ax, ay) = (&grid.axes[0], &grid.axes[1]);
    let (nx, ny) = (grid.dims()[0], grid.dims()[1]);
    let mi = metric_index(metric).ok_or_else(|| err(format!("unknown metric {metric}")))?;
    let value = |p: &PointResult| p.metrics[mi].map(|v| if log { v.log10() } else { v }).filter(|v| v.is_finite());
    let vals: Vec<Option<f64>> = points.iter().map(value).collect();
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
    let xe = edges(&(0..nx).map(|i| coord(ax, i)).collect::<Vec<_>>());
    let ye = edges(&(0..ny).map(|j| coord(ay, j)).collect::<Vec<_>>());
    let (xr, yr) = (xe[0].min(xe[nx])..xe[0].max(xe[nx]), ye[0].min(ye[ny])..ye[0].max(ye[ny]));
    let window = crate::point::window(&search.base, search.options.window);
    let title = format!(
        "{}{metric} (window [{}, {}] s); white: W ≻ 0 boundary, red: (32) boundary, dots: both hold",
        if log { "log10 " } else { "" },
        window.0,
        window.1
    );
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(e.to_string()))?;
        let (main, bar) = root.split_horizontally(SIZE.0 - 110);
        let mut chart = ChartBuilder::on(&main)
            .margin(14)
            .caption(title, ("sans-serif", 14))
            .x_label_area_size(46)
            .y_label_area_size(70)
            .build_cartesian_2d(xr, yr)
            .map_err(|e| err(e.to_string()))?;
        let mut cells = Vec::with_capacity(nx * ny);
        for i in 0..nx {
            for j in 0..ny {
                let p = grid.index(&[i, j]);
                let colour = vals[p].map_or(NAN_COLOUR, |v| viridis((v - vmin) / (vmax - vmin)));
                cells.push(Rectangle::new([(xe[i], ye[j]), (xe[i + 1], ye[j + 1])], colour.filled()));
            }
        }
        chart.draw_series(cells).map_err(|e| err(e.to_string()))?;
        let mut lines = Vec::new();
        for (kind, colour) in [(0usize, W_COLOUR), (1, MU_COLOUR)] {
            let v = |p: usize| if kind == 0 { points[p].w_positive_definite } else { points[p].feasible_32 };
            for i in 0..nx {
                for j in 0..ny {
                    let p = grid.index(&[i, j]);
                    if i + 1 < nx {
                        if let (Some(a), Some(b)) = (v(p), v(grid.index(&[i + 1, j]))) {
                            if a != b {
                                lines.push(PathElement::new(
                                    vec![(xe[i + 1], ye[j]), (xe[i + 1], ye[j + 1])],
                                    colour.stroke_width(3),
                                ));
                            }
                        }
                    }
                    if j + 1 < ny {
                        if let (Some(a), Some(b)) = (v(p), v(grid.index(&[i, j + 1]))) {
                            if a != b {
                                lines.push(PathElement::new(
                                    vec![(xe[i], ye[j + 1]), (xe[i + 1], ye[j + 1])],
                                    colour.stroke_width(3),
                                ));
                            }
                        }
                    }
                }
            }
        }
        chart.draw_series(lines).map_err(|e| err(e.to_string()))?;
        let dots = (0..nx * ny)
            .filter(|&p| points[p].theorem_feasible() == Some(true))
            .map(|p| {
                let m = grid.multi(p);
                Circle::new((coord(ax, m[0]), coord(ay, m[1])), 2, BLACK.filled())
            })
            .collect::<Vec<_>>();
        chart.draw_series(dots).map_err(|e| err(e.to_string()))?;
        let refined = boundary.iter().filter(|r| r.bisections > 0).map(|r| {
            let m = grid.multi(r.point);
            let mut c = [coord(ax, m[0]), coord(ay, m[1])];
            c[r.axis] = value_coord(&grid.axes[r.axis], r.estimate);
            let colour = if r.kind == crate::refine::KINDS[0] { W_COLOUR } else { MU_COLOUR };
            Circle::new((c[0], c[1]), 4, colour.stroke_width(2))
        });
        chart.draw_series(refined.collect::<Vec<_>>()).map_err(|e| err(e.to_string()))?;
        let suffix = |a: &Axis| if a.is_log() { " (log scale)" } else { "" };
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(format!("{}{}", ax.key, suffix(ax)))
            .y_desc(format!("{}{}", ay.key, suffix(ay)))
            .x_label_formatter(&|v| label(ax, *v))
            .y_label_formatter(&|v| label(ay, *v))
            .label_style(("sans-serif", 13))
            .axis_desc_style(("sans-serif", 14))
            .draw()
            .map_err(|e| err(e.to_string()))?;

        let mut cb = ChartBuilder::on(&bar)
            .margin_top(40)
            .margin_bottom(60)
            .margin_left(8)
            .margin_right(4)
            .right_y_label_area_size(64)
            .build_cartesian_2d(0.0..1.0, vmin..vmax)
            .map_err(|e| err(e.to_string()))?;
        let steps = 64;
        cb.draw_series((0..steps).map(|k| {
            let a = vmin + (vmax - vmin) * k as f64 / steps as f64;
            let b = vmin + (vmax - vmin) * (k + 1) as f64 / steps as f64;
            Rectangle::new([(0.0, a), (1.0, b)], viridis((k as f64 + 0.5) / steps as f64).filled())
        }))
        .map_err(|e| err(e.to_string()))?;
        cb.configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .y_labels(7)
            .y_label_formatter(&|v| tick(*v))
            .label_style(("sans-serif", 12))
            .draw()
            .map_err(|e| err(e.to_string()))?;
        root.present().map_err(|e| err(e.to_string()))?;
    }
    Ok(svg)
}
