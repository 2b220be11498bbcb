//! Heatmap of a metric over a 2-D search with the theory boundaries drawn over it, built as a
//! [`wingcheck_chart::GridHeatmap`] (the chart module shared with the report).

use wingcheck_chart::{grid_heatmap_svg, GridAxis, GridHeatmap, Mark, MarkShape, RGBColor};

use crate::heatmap_blocks::{
    block_centre, block_note, block_verdict, edge, thin_refined, AxisBlocks, BlockVerdict, MARK_BLOCKS, SEGMENT_BLOCKS,
};
use crate::metric::Metric;
use crate::point::PointVerdicts;
use crate::refine::{BoundaryRow, KINDS};
use crate::{Axis, Search, SearchError};

/// Colour of the W ≻ 0 marks (the closed-form line a/b = ω₁, the W ≻ 0 cells).
pub const W_COLOUR: RGBColor = RGBColor(255, 255, 255);
/// Colour of the (32) marks (the closed-form line a/b = r*, the feasible cells).
pub const MU_COLOUR: RGBColor = RGBColor(230, 30, 40);
const BOTH_COLOUR: RGBColor = RGBColor(0, 0, 0);

/// Axis title: the symbol, its meaning and unit (the report's region map's words), for the keys
/// a gain search usually sweeps; other keys by their name.
pub fn axis_title(key: &str, log: bool) -> String {
    let (what, unit) = match key {
        "control.a" => ("a, weight of the tip deflection in (15)", "dimensionless"),
        "control.b" => ("b, weight of the tip rate in (15)", "s"),
        "control.k1" => ("k1, bending gain of (15)", "N/m"),
        "control.k2" => ("k2, torsion gain of (15)", "N m"),
        "wing.xi" => ("ξ, Kelvin–Voigt damping coefficient", "s"),
        "wing.span" => ("s, span", "m"),
        "observer.sample_period" => ("T_s, the observer's sample period", "s"),
        _ => ("", ""),
    };
    let scale = if log { ", log scale" } else { "" };
    if what.is_empty() {
        format!("{key}{}", if log { " (log scale)" } else { "" })
    } else {
        format!("{what} ({unit}{scale})")
    }
}

fn axis_label(a: &Axis) -> String {
    axis_title(&a.key, a.is_log())
}

/// The closed-form marks of an (a, b) plane: the region where W ≻ 0 and (32) both hold
/// hatched, the lines a/b = ω₁ at both bounds `w` = (ω̲₁, ω̄₁) of its enclosure (or at ω₁ twice
/// when not certified), and the dashed line a/b = r*; the report's region map and the search's
/// heatmaps draw these alike. `a_lo` and `b` are the plot's lower a and its b range (cell
/// edges); the chart clips the lines to the plot. With `a_on_x` false the points are (b, a).
pub fn ratio_marks(w: (f64, f64), certified: bool, r_star: f64, a_lo: f64, b: (f64, f64), a_on_x: bool) -> Vec<Mark> {
    let (b_lo, b_hi) = b;
    let orient = |pts: Vec<(f64, f64)>| if a_on_x { pts } else { pts.into_iter().map(|(a, b)| (b, a)).collect() };
    let line = |r: f64| orient(vec![(r * b_lo, b_lo), (r * b_hi, b_hi)]);
    let r_both = w.0.min(r_star);
    // a decade left of both the plot and the line, so the polygon covers the plot's part where
    // a/b < min(ω̲₁, r*) whatever edge the line leaves by
    let far = a_lo.min(r_both * b_lo) / 10.0;
    let shade = orient(vec![(far, b_lo), (r_both * b_lo, b_lo), (r_both * b_hi, b_hi), (far, b_hi)]);
    vec![
        Mark {
            label: "W ≻ 0 and (32) both hold (closed forms): Theorem 2 applies".into(),
            colour: BOTH_COLOUR,
            shape: MarkShape::Hatch,
            points: shade,
        },
        Mark {
            label: if certified {
                "a/b = ω̲₁ and ω̄₁, the certified enclosure of ω₁ (W ≻ 0 left of it, exact)".into()
            } else {
                "a/b = ω₁ (W ≻ 0 left of it, closed form)".into()
            },
            colour: W_COLOUR,
            shape: MarkShape::Line,
            points: line(w.0),
        },
        // the upper bound (no second legend entry)
        Mark { label: String::new(), colour: W_COLOUR, shape: MarkShape::Line, points: line(w.1) },
        Mark {
            label: "a/b = r* ((32) feasible left of it, closed form)".into(),
            colour: MU_COLOUR,
            shape: MarkShape::DashedLine,
            points: line(r_star),
        },
    ]
}

/// The closed-form marks of a search over (control.a, control.b) in either order (None for
/// other axes, or when ω₁ or r* is not a positive finite number).
fn closed_form_marks(search: &Search, ax: &GridAxis, ay: &GridAxis) -> Option<Vec<Mark>> {
    let keys = (search.grid.axes[0].key.as_str(), search.grid.axes[1].key.as_str());
    let a_on_x = match keys {
        ("control.a", "control.b") => true,
        ("control.b", "control.a") => false,
        _ => return None,
    };
    if !(ax.log && ay.log) {
        return None;
    }
    let cfg = &search.base;
    let omega1 = wingcheck_theory::w_threshold(cfg).ok()?.value;
    let r_star = wingcheck_theory::MuData::closed_form_ratio(cfg);
    if !(omega1.is_finite() && omega1 > 0.0 && r_star.is_finite() && r_star > 0.0) {
        return None;
    }
    let enclosure = wingcheck_claims::certify::omega1::EnclosureSummary::deciding(cfg);
    let w = enclosure.bounds().unwrap_or((omega1, omega1));
    let (a_axis, b_axis) = if a_on_x { (ax, ay) } else { (ay, ax) };
    let edges = |g: &GridAxis| {
        let c = &g.centres;
        let n = c.len();
        let half = if n > 1 { (c[1] / c[0]).sqrt() } else { 10f64.sqrt() };
        let half_end = if n > 1 { (c[n - 1] / c[n - 2]).sqrt() } else { 10f64.sqrt() };
        (c[0] / half, c[n - 1] * half_end)
    };
    Some(ratio_marks(w, enclosure.bounds().is_some(), r_star, edges(a_axis).0, edges(b_axis), a_on_x))
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
                100.0 * crate::point::settle_fraction()
            ),
            format!("settling time ({unit})"),
            "no value: not settled by t_end, or the point failed".into(),
        ),
        other => (other.short_name().to_string(), format!("{} ({unit})", other.short_name()), failed),
    }
}

/// The marks of the closed-form boundaries and the search's verdicts per cell (per block of
/// cells above [`MARK_BLOCKS`] / [`SEGMENT_BLOCKS`] cells per axis): on an (a, b) plane the
/// closed-form lines with the verdicts as circles and dots (the report's region map); on other
/// axes the verdict boundaries between grid cells and the cells where both hold.
fn verdict_marks(search: &Search, ax: &GridAxis, ay: &GridAxis, verdicts: &[PointVerdicts]) -> Vec<Mark> {
    let grid = &search.grid;
    let (nx, ny) = (grid.dims()[0], grid.dims()[1]);
    let mut marks = Vec::new();
    let (mx, my) = (AxisBlocks::new(nx, MARK_BLOCKS), AxisBlocks::new(ny, MARK_BLOCKS));
    let every = block_note(&mx, &my, "a mark where every cell holds");
    // the centres of the mark blocks whose every cell satisfies `f`
    let cells = |f: &dyn Fn(&PointVerdicts) -> bool| -> Vec<(f64, f64)> {
        let mut pts = Vec::new();
        for bi in 0..mx.count() {
            for bj in 0..my.count() {
                let all = mx.range(bi).all(|i| my.range(bj).all(|j| f(&verdicts[grid.index(&[i, j])])));
                if all {
                    pts.push((block_centre(ax, &mx, bi), block_centre(ay, &my, bj)));
                }
            }
        }
        pts
    };
    let closed = closed_form_marks(search, ax, ay);
    if let Some(lines) = &closed {
        // the (a, b) plane: the closed-form boundaries as lines and the search's verdicts per
        // cell, as in the report's region map
        marks.extend(lines.iter().cloned());
        marks.push(Mark {
            label: format!("W ≻ 0 (search verdict){every}"),
            colour: W_COLOUR,
            shape: MarkShape::Circles,
            points: cells(&|v| v.w_positive_definite == Some(true)),
        });
        marks.push(Mark {
            label: format!("(32) feasible (search verdict){every}"),
            colour: MU_COLOUR,
            shape: MarkShape::Dots,
            points: cells(&|v| v.feasible_32 == Some(true)),
        });
        return marks;
    }
    for (kind, colour, label) in [
        (0, W_COLOUR, "boundary of W ≻ 0 (Theorem 1) between grid cells"),
        (1, MU_COLOUR, "boundary of (29)–(32) feasibility between grid cells"),
    ] {
        let v = |p: usize| if kind == 0 { verdicts[p].w_positive_definite } else { verdicts[p].feasible_32 };
        let (sx, sy) = (AxisBlocks::new(nx, SEGMENT_BLOCKS), AxisBlocks::new(ny, SEGMENT_BLOCKS));
        let note = block_note(&sx, &sy, "drawn; a block the boundary crosses is outlined,");
        marks.push(Mark {
            label: format!("{label}{note}"),
            colour,
            shape: MarkShape::Segments,
            points: boundary_segments(grid, ax, ay, (&sx, &sy), &v),
        });
    }
    marks.push(Mark {
        label: format!("W ≻ 0 and (32) both hold (Theorem 2 applies){every}"),
        colour: BOTH_COLOUR,
        shape: MarkShape::Dots,
        points: cells(&|v| v.theorem_feasible() == Some(true)),
    });
    marks
}

/// Segments between adjacent blocks whose verdicts differ (true, false, or mixed: the boundary
/// crosses the block); with blocks of one cell, the boundary between cells.
fn boundary_segments(
    grid: &crate::Grid,
    ax: &GridAxis,
    ay: &GridAxis,
    (sx, sy): (&AxisBlocks, &AxisBlocks),
    v: &dyn Fn(usize) -> Option<bool>,
) -> Vec<(f64, f64)> {
    let (bx, by) = (sx.count(), sy.count());
    let mut block = Vec::with_capacity(bx * by);
    for i in 0..bx {
        for j in 0..by {
            block.push(block_verdict(
                sx.range(i).flat_map(|x| sy.range(j).map(move |y| (x, y))).map(|(x, y)| v(grid.index(&[x, y]))),
            ));
        }
    }
    let at = |i: usize, j: usize| block[i * by + j];
    let differ = |a: Option<BlockVerdict>, b: Option<BlockVerdict>| matches!((a, b), (Some(a), Some(b)) if a != b);
    let (ex, ey) = (|i: usize| edge(ax, sx.range(i).start), |j: usize| edge(ay, sy.range(j).start));
    let (ex_end, ey_end) = (|i: usize| edge(ax, sx.range(i).end), |j: usize| edge(ay, sy.range(j).end));
    let mut seg = Vec::new();
    for i in 0..bx {
        for j in 0..by {
            if i + 1 < bx && differ(at(i, j), at(i + 1, j)) {
                seg.extend([(ex(i + 1), ey(j)), (ex(i + 1), ey_end(j))]);
            }
            if j + 1 < by && differ(at(i, j), at(i, j + 1)) {
                seg.extend([(ex(i), ey(j + 1)), (ex_end(i), ey(j + 1))]);
            }
        }
    }
    seg
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
    let grid = &search.grid;
    let (ax, ay) = (grid_axis(&grid.axes[0]), grid_axis(&grid.axes[1]));
    let (nx, ny) = (grid.dims()[0], grid.dims()[1]);
    if values.len() != nx * ny || verdicts.len() != nx * ny {
        return Err(SearchError::HeatmapCells { name, values: values.len(), verdicts: verdicts.len(), nx, ny });
    }
    let mut marks = verdict_marks(search, &ax, &ay, verdicts);
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
            let (refined, note) = thin_refined(refined);
            let label = format!("refined {} boundary point{note}", if kind == KINDS[0] { "W ≻ 0" } else { "(32)" });
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
    grid_heatmap_svg(&h).map_err(|source| SearchError::Heatmap { source })
}
