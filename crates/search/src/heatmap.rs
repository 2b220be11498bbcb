//! Heatmap of a metric over a 2-D search with the theory boundaries drawn over it, built as a
//! [`wingcheck_chart::GridHeatmap`] (the chart module shared with the report).

use wingcheck_chart::{grid_heatmap_svg, GridAxis, GridHeatmap, Mark, MarkShape, RGBColor};

use crate::metric::Metric;
use crate::point::PointVerdicts;
use crate::refine::{BoundaryRow, KINDS};
use crate::{Axis, Search, SearchError};

const W_COLOUR: RGBColor = RGBColor(255, 0, 255);
const MU_COLOUR: RGBColor = RGBColor(230, 30, 40);
const BOTH_COLOUR: RGBColor = RGBColor(0, 0, 0);

/// Axis title with its meaning and unit, for the keys a gain search usually sweeps.
fn axis_label(a: &Axis) -> String {
    let what = match a.key.as_str() {
        "control.a" => "weight a of q(s,t) in the control law (15), 1",
        "control.b" => "weight b of q̇(s,t) in (15), s",
        "control.k1" => "bending gain k1, N/m",
        "control.k2" => "torsion gain k2, N m/rad",
        "wing.xi" => "Kelvin–Voigt coefficient ξ, s",
        "observer.sample_period" => "observer sample period T, s",
        _ => "",
    };
    let scale = if a.is_log() { ", log scale" } else { "" };
    if what.is_empty() {
        format!("{}{}", a.key, if a.is_log() { " (log scale)" } else { "" })
    } else {
        format!("{} ({what}{scale})", a.key)
    }
}

fn grid_axis(a: &Axis) -> GridAxis {
    match a.numeric(0) {
        Some(_) => GridAxis {
            label: axis_label(a),
            centres: (0..a.len())
                .map(|i| a.text(i).parse().unwrap_or_else(|_| a.numeric(i).expect("numeric")))
                .collect(),
            log: a.is_log(),
            words: None,
        },
        None => GridAxis {
            label: axis_label(a),
            centres: (0..a.len()).map(|i| i as f64).collect(),
            log: false,
            words: Some((0..a.len()).map(|i| a.text(i)).collect()),
        },
    }
}

/// Quantity, unit and the reason a cell has no value, per heatmap metric.
fn metric_text(metric: Metric, window: (f64, f64)) -> (String, String, String) {
    let w = format!("[{}, {}] s", window.0, window.1);
    let failed = "no value: the point failed or diverged (failures.csv)".to_string();
    let unit = metric.unit().symbol();
    match metric {
        Metric::RmsQTip => (format!("Tip displacement RMS over {w}"), format!("RMS q(s,t) ({unit})"), failed),
        Metric::RmsThetaTip => (format!("Tip twist RMS over {w}"), format!("RMS θ(s,t) ({unit})"), failed),
        Metric::SettlingTime => (
            format!(
                "Settling time (|q|, |θ| within {} % of their initial values)",
                100.0 * wingcheck_sim::metrics::SETTLE_FRACTION
            ),
            format!("settling time ({unit})"),
            "no value: not settled by t_end, or the point failed".into(),
        ),
        other => (other.name().to_string(), format!("{other} ({unit})"), failed),
    }
}

/// Render `metric` over a 2-D search (x = first axis, y = second), log colour scale if `log`;
/// `values`: the metric at every point, `verdicts`: every point's verdicts (index order).
/// Marks: the W ≻ 0 and (32) boundaries between grid cells, the theorem-feasible cells
/// (both hold), and refined boundary points.
pub fn heatmap_svg(
    search: &Search,
    values: Vec<Option<f64>>,
    verdicts: &[PointVerdicts],
    metric: Metric,
    log: bool,
    boundary: &[BoundaryRow],
) -> Result<String, SearchError> {
    let name = format!("heatmap-{metric}");
    let err = |e: String| SearchError::Io { path: format!("{name}.svg"), detail: e };
    let grid = &search.grid;
    let (ax, ay) = (grid_axis(&grid.axes[0]), grid_axis(&grid.axes[1]));
    let (nx, ny) = (grid.dims()[0], grid.dims()[1]);
    if values.len() != nx * ny || verdicts.len() != nx * ny {
        return Err(err(format!("{} values and {} verdicts for {nx} × {ny} cells", values.len(), verdicts.len())));
    }
    // row-major with the first axis slowest: point grid.index([i, j]) = i·ny + j, the chart's order
    // cell edges in axis values, for the boundary segments between cells
    let edge = |a: &GridAxis, i: usize| -> f64 {
        let c = |k: usize| if a.log { a.centres[k].log10() } else { a.centres[k] };
        let n = a.centres.len();
        let e = if i == 0 {
            c(0) - 0.5 * (c(1) - c(0))
        } else if i == n {
            c(n - 1) + 0.5 * (c(n - 1) - c(n - 2))
        } else {
            0.5 * (c(i - 1) + c(i))
        };
        if a.log {
            10f64.powf(e)
        } else {
            e
        }
    };
    let mut marks = Vec::new();
    for (kind, colour, label) in [
        (0, W_COLOUR, "boundary of W ≻ 0 (Theorem 1) between grid cells"),
        (1, MU_COLOUR, "boundary of (29)–(32) feasibility between grid cells"),
    ] {
        let v = |p: usize| if kind == 0 { verdicts[p].w_positive_definite } else { verdicts[p].feasible_32 };
        let mut seg = Vec::new();
        for i in 0..nx {
            for j in 0..ny {
                let p = grid.index(&[i, j]);
                if i + 1 < nx && matches!((v(p), v(grid.index(&[i + 1, j]))), (Some(a), Some(b)) if a != b) {
                    seg.extend([(edge(&ax, i + 1), edge(&ay, j)), (edge(&ax, i + 1), edge(&ay, j + 1))]);
                }
                if j + 1 < ny && matches!((v(p), v(grid.index(&[i, j + 1]))), (Some(a), Some(b)) if a != b) {
                    seg.extend([(edge(&ax, i), edge(&ay, j + 1)), (edge(&ax, i + 1), edge(&ay, j + 1))]);
                }
            }
        }
        marks.push(Mark { label: label.into(), colour, shape: MarkShape::Segments, points: seg });
    }
    let both = (0..nx * ny)
        .filter(|&p| verdicts[p].theorem_feasible() == Some(true))
        .map(|p| {
            let m = grid.multi(p);
            (ax.centres[m[0]], ay.centres[m[1]])
        })
        .collect();
    marks.push(Mark {
        label: "W ≻ 0 and (32) both hold (Theorem 2 applies)".into(),
        colour: BOTH_COLOUR,
        shape: MarkShape::Dots,
        points: both,
    });
    for (kind, colour) in [(KINDS[0], W_COLOUR), (KINDS[1], MU_COLOUR)] {
        let refined: Vec<(f64, f64)> = boundary
            .iter()
            .filter(|r| r.bisections > 0 && r.kind == kind)
            .map(|r| {
                let m = grid.multi(r.point);
                let mut c = [ax.centres[m[0]], ay.centres[m[1]]];
                c[r.axis] = r.estimate;
                (c[0], c[1])
            })
            .collect();
        if !refined.is_empty() {
            let label = format!("refined {} boundary point", if kind == KINDS[0] { "W ≻ 0" } else { "(32)" });
            marks.push(Mark { label, colour, shape: MarkShape::Circles, points: refined });
        }
    }
    let window = crate::point::window(&search.base, search.options.window);
    let (title, value_label, missing_label) = metric_text(metric, window);
    let h = GridHeatmap {
        name: name.clone(),
        title,
        x: ax,
        y: ay,
        values,
        log_values: log,
        value_label,
        missing_label,
        marks,
    };
    grid_heatmap_svg(&h).map_err(|e| err(e.detail))
}
