//! The (a, b) region map: where the theorems' hypotheses hold, over the tip performance.
//!
//! A small 2-D search over the weights a, b of the control law (15), computed by the search
//! crate's own code ([`wingcheck_search::Search::evaluate`]: the closed loop of the configured
//! controller in the modal basis, the tight λ2 of W/κ and the best λ3 of (29)–(32) per point).
//! Drawn: the RMS tip deflection over the search's metric window (colour, log scale), the
//! cells where the search finds W ≻ 0 and (32) feasible (markers), the closed-form boundaries
//! a/b = ω1 (W ≻ 0 below it) and a/b = r* ((32) feasible below it) as lines, and the
//! configured operating point.
//!
//! The grid is laid on half-decades through the configured (a, b), so that point is a node;
//! it spans a/b from a decade below min(r*, ω1, a/b) to a decade above max(…) and b over
//! ±[`B_DECADES`] decades. Work: one closed-loop run per point (≈ 10 ms each at the default
//! grid) and as many eigen/SOCP solves.

use std::sync::atomic::{AtomicUsize, Ordering};

use plotters::prelude::*;
use rayon::prelude::*;
use wingcheck_model::Config;
use wingcheck_search::{modal::RunCache, PointResult, Search, SearchOptions, Status, TheoryCache};

use crate::chart::{decade_label, px, scaled_svg_header, tick, viridis, Ticked, CANVAS, SCALE};
use crate::figure::{Caption, Chart, Figure};
use crate::{Progress, ReportError};

/// Grid spacing in decades.
const STEP_DECADES: f64 = 0.5;
/// b spans b0 · 10^±B_DECADES.
pub const B_DECADES: f64 = 1.5;
/// At most this many values of a (the a range is clipped symmetrically around the boundaries).
const MAX_A: usize = 14;
/// The performance metric shown.
pub const METRIC: &str = "rms_q_tip";

/// The map's data.
#[derive(Debug, Clone)]
pub struct RegionMap {
    /// Values of a (increasing).
    pub a: Vec<f64>,
    /// Values of b (increasing).
    pub b: Vec<f64>,
    /// Point results, row-major with a slowest (`points[i * b.len() + j]` is (a[i], b[j])).
    pub points: Vec<PointResult>,
    /// Closed-form W ≻ 0 boundary a/b = ω1 (rad/s).
    pub omega1: f64,
    /// Closed-form (32) boundary a/b = r*.
    pub r_star: f64,
    /// The configured (a, b).
    pub operating: (f64, f64),
    /// Metric window (s).
    pub window: (f64, f64),
    /// The configured controller (upper case).
    pub controller: String,
}

/// Half-decade exponents from `lo` to `hi` (log10), through `center`.
fn half_decades(center: f64, lo: f64, hi: f64) -> Vec<f64> {
    let down = ((center - lo) / STEP_DECADES).ceil().max(0.0) as i32;
    let up = ((hi - center) / STEP_DECADES).ceil().max(0.0) as i32;
    (-down..=up).map(|k| center + k as f64 * STEP_DECADES).collect()
}

/// The search specs of the map for `cfg`, with the closed-form boundaries used to place it.
fn axes(cfg: &Config, omega1: f64, r_star: f64) -> (Vec<f64>, Vec<f64>) {
    let (a0, b0) = (cfg.control.a, cfg.control.b);
    let ratios = [r_star, omega1, a0 / b0];
    let rmin = ratios.iter().copied().filter(|r| *r > 0.0 && r.is_finite()).fold(f64::INFINITY, f64::min);
    let rmax = ratios.iter().copied().filter(|r| r.is_finite()).fold(0.0, f64::max);
    let (la0, lb0) = (a0.log10(), b0.log10());
    let mut la = half_decades(la0, (b0 * rmin / 10.0).log10(), (b0 * rmax * 10.0).log10());
    while la.len() > MAX_A {
        // Drop from the longer side, never the configured point.
        if la0 - la[0] > la[la.len() - 1] - la0 {
            la.remove(0);
        } else {
            la.pop();
        }
    }
    let lb = half_decades(lb0, lb0 - B_DECADES, lb0 + B_DECADES);
    (la.into_iter().map(|e| 10f64.powf(e)).collect(), lb.into_iter().map(|e| 10f64.powf(e)).collect())
}

/// Compute the map: every point evaluated by the search code, in parallel.
pub fn region_map(
    cfg: &Config,
    omega1: f64,
    r_star: f64,
    progress: Option<&(dyn Fn(Progress) + Sync)>,
) -> Result<RegionMap, ReportError> {
    let (a, b) = axes(cfg, omega1, r_star);
    let list = |v: &[f64]| v.iter().map(|x| format!("{x:e}")).collect::<Vec<_>>().join(",");
    let specs = [format!("control.a={}", list(&a)), format!("control.b={}", list(&b))];
    let search = Search::new(cfg.clone(), &specs, SearchOptions::default())
        .map_err(|e| ReportError::Region { detail: e.to_string() })?;
    let (theory, runs) = (TheoryCache::new(SearchOptions::default().lyapunov_elements), RunCache::new());
    let total = search.points();
    let done = AtomicUsize::new(0);
    let points: Vec<PointResult> = (0..total)
        .into_par_iter()
        .map(|p| {
            let r = search.evaluate(p, &theory, &runs);
            let k = done.fetch_add(1, Ordering::SeqCst) + 1;
            if let Some(cb) = progress {
                cb(Progress { stage: "region map", done: k, total });
            }
            r
        })
        .collect();
    let a: Vec<f64> = (0..a.len()).map(|i| search.grid.axes[0].numeric(i).unwrap_or(a[i])).collect();
    let b: Vec<f64> = (0..b.len()).map(|j| search.grid.axes[1].numeric(j).unwrap_or(b[j])).collect();
    let window = wingcheck_search::point::window(cfg, SearchOptions::default().window);
    let controller = serde_json::to_value(cfg.control.kind)
        .ok()
        .and_then(|v| v.as_str().map(str::to_uppercase))
        .unwrap_or_else(|| "configured".into());
    Ok(RegionMap { a, b, points, omega1, r_star, operating: (cfg.control.a, cfg.control.b), window, controller })
}

/// Grey for cells without a metric (failed or diverged runs).
const NO_DATA: RGBColor = RGBColor(170, 170, 170);
const W_LINE: RGBColor = RGBColor(255, 255, 255);
const MU_LINE: RGBColor = RGBColor(230, 30, 40);

/// Summary numbers of the map (for the caption).
#[derive(Debug, Clone, Copy)]
pub struct RegionStats {
    /// Cells where the search's W ≻ 0 verdict agrees with a/b < ω1.
    pub w_agree: usize,
    /// Cells where the search's (32) verdict agrees with a/b < r*.
    pub mu_agree: usize,
    /// Cells with both verdicts.
    pub cells: usize,
    /// Median metric over the cells where both hypotheses hold (None if none).
    pub median_feasible: Option<f64>,
    /// Median metric over the other cells.
    pub median_infeasible: Option<f64>,
    /// Smallest metric and where (a, b).
    pub best: Option<(f64, f64, f64)>,
    /// Metric at the configured point.
    pub at_operating: Option<f64>,
    /// Cells without a metric.
    pub failed: usize,
}

fn median(mut v: Vec<f64>) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    Some(if n % 2 == 1 { v[n / 2] } else { 0.5 * (v[n / 2 - 1] + v[n / 2]) })
}

impl RegionMap {
    fn cell(&self, i: usize, j: usize) -> &PointResult {
        &self.points[i * self.b.len() + j]
    }

    /// Agreement with the closed forms, medians inside/outside the hypotheses, best cell.
    pub fn stats(&self) -> RegionStats {
        let (mut w_agree, mut mu_agree, mut cells, mut failed) = (0, 0, 0, 0);
        let (mut inside, mut outside) = (Vec::new(), Vec::new());
        let mut best: Option<(f64, f64, f64)> = None;
        let mut at_operating = None;
        for (i, &a) in self.a.iter().enumerate() {
            for (j, &b) in self.b.iter().enumerate() {
                let p = self.cell(i, j);
                if let (Some(w), Some(m)) = (p.w_positive_definite, p.feasible_32) {
                    cells += 1;
                    w_agree += usize::from(w == (a / b < self.omega1));
                    mu_agree += usize::from(m == (a / b < self.r_star));
                }
                let v = p.metric(METRIC).filter(|v| v.is_finite() && p.status == Status::Ok);
                match v {
                    Some(v) => {
                        if p.theorem_feasible() == Some(true) {
                            inside.push(v);
                        } else {
                            outside.push(v);
                        }
                        if best.is_none_or(|(bv, _, _)| v < bv) {
                            best = Some((v, a, b));
                        }
                        let (a0, b0) = self.operating;
                        if (a / a0 - 1.0).abs() < 1e-9 && (b / b0 - 1.0).abs() < 1e-9 {
                            at_operating = Some(v);
                        }
                    }
                    None => failed += 1,
                }
            }
        }
        RegionStats {
            w_agree,
            mu_agree,
            cells,
            median_feasible: median(inside),
            median_infeasible: median(outside),
            best,
            at_operating,
            failed,
        }
    }

    /// The map as CSV: a, b, status, verdicts, the metric.
    pub fn to_csv(&self) -> String {
        let mut out = format!("a,b,status,w_positive_definite,feasible_32,{METRIC}_m\n");
        let o = |v: Option<bool>| v.map_or(String::new(), |b| b.to_string());
        for (i, a) in self.a.iter().enumerate() {
            for (j, b) in self.b.iter().enumerate() {
                let p = self.cell(i, j);
                let m = p.metric(METRIC).map_or(String::new(), |v| v.to_string());
                out.push_str(&format!(
                    "{a},{b},{},{},{},{m}\n",
                    p.status.name(),
                    o(p.w_positive_definite),
                    o(p.feasible_32)
                ));
            }
        }
        out
    }

    /// The map as a report figure.
    pub fn figure(&self) -> Figure {
        let s = self.stats();
        let (t0, t1) = self.window;
        let mut cap = Caption::default()
            .t(format!(
                "RMS tip deflection |q(s,t)| over [{}, {}] s of the {} closed loop (colour, log scale) at each (a, b) of a {} × {} grid, computed by the search code; ",
                tick(t0),
                tick(t1),
                self.controller,
                self.a.len(),
                self.b.len()
            ))
            .t("open circles: W ≻ 0 (tight λ2 > 0, Theorem 1's hypothesis); red dots: (29)–(32) feasible (best λ3 > 0). Closed-form boundaries: W ≻ 0 iff a/b < ω1 = ")
            .n("region.omega1", self.omega1)
            .t(" rad/s (white line), (32) feasible iff a/b < r* = ")
            .n("region.r_star", self.r_star)
            .t(" (red dashed line); the search's verdicts agree with them in ")
            .count("region.w_agree", s.w_agree)
            .t(" and ")
            .count("region.mu_agree", s.mu_agree)
            .t(format!(" of {} cells. ", s.cells));
        if let (Some(fi), Some(inf)) = (s.median_feasible, s.median_infeasible) {
            cap = cap
                .t("Median RMS where both hypotheses hold: ")
                .n("region.median_feasible", fi)
                .t(" m; elsewhere: ")
                .n("region.median_infeasible", inf)
                .t(if fi > 1.05 * inf {
                    " m — the theorems' conditions hold where the tip performance is worse. "
                } else if inf > 1.05 * fi {
                    " m — the tip performance is better where the theorems' conditions hold. "
                } else {
                    " m — within 5 %: the hypotheses do not separate good from poor tip performance here. "
                });
        } else if s.median_feasible.is_none() {
            cap = cap.t("No cell satisfies both hypotheses. ");
        }
        if let Some((v, a, b)) = s.best {
            cap = cap.t("Smallest RMS on the grid: ").n("region.best", v).t(format!(
                " m at a = {}, b = {}",
                tick(a),
                tick(b)
            ));
        }
        if let Some(v) = s.at_operating {
            cap = cap.t("; at the configured point (cross): ").n("region.at_operating", v).t(" m");
        }
        cap = cap.t(".");
        if s.failed > 0 {
            cap = cap.t(format!(" Grey: {} cells whose run failed or diverged (see the CSV).", s.failed));
        }
        Figure {
            file: "region-map-ab".into(),
            label: "Region map R1".into(),
            title: "(a, b) region map: hypotheses vs tip performance".into(),
            caption: cap.0,
            chart: Chart::Region(Box::new(self.clone())),
        }
    }

    /// Render as an SVG (cells as an embedded PNG raster, everything else vector).
    pub fn svg(&self) -> Result<String, ReportError> {
        let err = |e: String| ReportError::Chart { name: "region-map".into(), detail: e };
        let (na, nb) = (self.a.len(), self.b.len());
        if na < 2 || nb < 2 {
            return Err(err("the map needs at least 2 values of a and of b".into()));
        }
        let la: Vec<f64> = self.a.iter().map(|v| v.log10()).collect();
        let lb: Vec<f64> = self.b.iter().map(|v| v.log10()).collect();
        let half = STEP_DECADES / 2.0;
        let (x0, x1) = (la[0] - half, la[na - 1] + half);
        let (y0, y1) = (lb[0] - half, lb[nb - 1] + half);
        let vals: Vec<f64> =
            self.points.iter().filter_map(|p| p.metric(METRIC)).filter(|v| v.is_finite() && *v > 0.0).collect();
        let (vlo, vhi) = (
            vals.iter().copied().fold(f64::INFINITY, f64::min).log10(),
            vals.iter().copied().fold(0.0, f64::max).log10(),
        );
        let (vlo, vhi) = if vals.is_empty() {
            (-3.0, 0.0)
        } else if vhi - vlo < 1e-6 {
            (vlo - 0.5, vhi + 0.5)
        } else {
            (vlo, vhi)
        };
        let colour = |v: Option<f64>| match v.filter(|v| v.is_finite() && *v > 0.0) {
            Some(v) => viridis((v.log10() - vlo) / (vhi - vlo)),
            None => NO_DATA,
        };
        let int_ticks =
            |lo: f64, hi: f64| ((lo.ceil() as i32)..=(hi.floor() as i32)).map(f64::from).collect::<Vec<_>>();
        let mut svg = String::new();
        let plot_px;
        {
            let root = SVGBackend::with_string(&mut svg, (CANVAS.0, CANVAS.1 + px(160))).into_drawing_area();
            root.fill(&WHITE).map_err(|e| err(e.to_string()))?;
            let (main, side) = root.split_horizontally(CANVAS.0 - px(250));
            let mut chart = ChartBuilder::on(&main)
                .margin(px(14))
                .x_label_area_size(px(48))
                .y_label_area_size(px(70))
                .build_cartesian_2d(
                    Ticked::<plotters::coord::types::RangedCoordf64>::new(x0..x1, int_ticks(x0, x1)),
                    Ticked::<plotters::coord::types::RangedCoordf64>::new(y0..y1, int_ticks(y0, y1)),
                )
                .map_err(|e| err(e.to_string()))?;
            chart
                .configure_mesh()
                .disable_mesh()
                .x_desc("a, weight of the tip deflection in (15) (dimensionless, log scale)")
                .y_desc("b, weight of the tip rate (s, log scale)")
                .x_label_formatter(&|v| decade_label(10f64.powf(*v)))
                .y_label_formatter(&|v| decade_label(10f64.powf(*v)))
                .label_style(("sans-serif", px(18)))
                .axis_desc_style(("sans-serif", px(18)))
                .axis_style(BLACK.stroke_width(px(1)))
                .set_all_tick_mark_size(px(5))
                .draw()
                .map_err(|e| err(e.to_string()))?;
            plot_px = chart.plotting_area().get_pixel_range();
            let e = |e: DrawingAreaErrorKind<std::io::Error>| err(e.to_string());
            // Verdict markers per cell.
            for (i, &x) in la.iter().enumerate() {
                for (j, &y) in lb.iter().enumerate() {
                    let p = self.cell(i, j);
                    if p.w_positive_definite == Some(true) {
                        chart
                            .draw_series(std::iter::once(Circle::new((x, y), px(7), W_LINE.stroke_width(px(2)))))
                            .map_err(e)?;
                    }
                    if p.feasible_32 == Some(true) {
                        chart.draw_series(std::iter::once(Circle::new((x, y), px(3), MU_LINE.filled()))).map_err(e)?;
                    }
                }
            }
            // Closed-form boundaries: log a = log b + log r.
            let line = |r: f64| vec![(y0 + r.log10(), y0), (y1 + r.log10(), y1)];
            chart
                .draw_series(std::iter::once(PathElement::new(line(self.omega1), W_LINE.stroke_width(px(3)))))
                .map_err(e)?;
            chart
                .draw_series(DashedLineSeries::new(line(self.r_star), px(10), px(6), MU_LINE.stroke_width(px(3))))
                .map_err(e)?;
            // The configured point.
            let (xa, yb) = (self.operating.0.log10(), self.operating.1.log10());
            let d = 0.12;
            for seg in [[(xa - d, yb - d), (xa + d, yb + d)], [(xa - d, yb + d), (xa + d, yb - d)]] {
                chart
                    .draw_series(std::iter::once(PathElement::new(seg.to_vec(), BLACK.stroke_width(px(5)))))
                    .map_err(e)?;
                chart
                    .draw_series(std::iter::once(PathElement::new(seg.to_vec(), WHITE.stroke_width(px(2)))))
                    .map_err(e)?;
            }

            // Side panel: colour bar and legend.
            let font = ("sans-serif", px(16)).into_font().color(&BLACK);
            side.draw(&Text::new("RMS |q(s,t)| (m)", (px(8) as i32, px(14) as i32), font.clone())).map_err(e)?;
            let (bx, by, bw, bh) = (px(12) as i32, px(44) as i32, px(28) as i32, px(250) as i32);
            let steps = 64;
            for k in 0..steps {
                let u0 = k as f64 / steps as f64;
                let ya = by + bh - ((k + 1) as f64 / steps as f64 * bh as f64) as i32;
                let yb2 = by + bh - (u0 * bh as f64) as i32;
                side.draw(&Rectangle::new([(bx, ya), (bx + bw, yb2)], viridis(u0 + 0.5 / steps as f64).filled()))
                    .map_err(e)?;
            }
            side.draw(&Rectangle::new([(bx, by), (bx + bw, by + bh)], BLACK.stroke_width(px(1)))).map_err(e)?;
            let mut bar_ticks = crate::chart::log_ticks(10f64.powf(vlo), 10f64.powf(vhi), &[]);
            if bar_ticks.len() < 2 {
                // A narrow range (less than a 1-2-5 step): label its ends.
                bar_ticks = vec![10f64.powf(vlo), 10f64.powf(vhi)];
            }
            for t in bar_ticks {
                let u = (t.log10() - vlo) / (vhi - vlo);
                let yy = by + bh - (u * bh as f64) as i32;
                side.draw(&PathElement::new(
                    vec![(bx + bw, yy), (bx + bw + px(5) as i32, yy)],
                    BLACK.stroke_width(px(1)),
                ))
                .map_err(e)?;
                side.draw(&Text::new(tick(t), (bx + bw + px(8) as i32, yy - px(8) as i32), font.clone())).map_err(e)?;
            }
            let mut y = by + bh + px(40) as i32;
            let x = px(12) as i32;
            let step = px(30) as i32;
            side.draw(&Circle::new((x + px(10) as i32, y), px(7), RGBColor(80, 80, 80).stroke_width(px(2))))
                .map_err(e)?;
            side.draw(&Text::new("W ≻ 0 (search)", (x + px(28) as i32, y - px(8) as i32), font.clone())).map_err(e)?;
            y += step;
            side.draw(&Circle::new((x + px(10) as i32, y), px(3), MU_LINE.filled())).map_err(e)?;
            side.draw(&Text::new("(32) feasible (search)", (x + px(28) as i32, y - px(8) as i32), font.clone()))
                .map_err(e)?;
            y += step;
            side.draw(&PathElement::new(
                vec![(x, y), (x + px(22) as i32, y)],
                RGBColor(80, 80, 80).stroke_width(px(3)),
            ))
            .map_err(e)?;
            side.draw(&Text::new("a/b = ω1 (closed form)", (x + px(28) as i32, y - px(8) as i32), font.clone()))
                .map_err(e)?;
            y += step;
            side.draw(&PathElement::new(vec![(x, y), (x + px(8) as i32, y)], MU_LINE.stroke_width(px(3))))
                .map_err(e)?;
            side.draw(&PathElement::new(
                vec![(x + px(13) as i32, y), (x + px(22) as i32, y)],
                MU_LINE.stroke_width(px(3)),
            ))
            .map_err(e)?;
            side.draw(&Text::new("a/b = r* (closed form)", (x + px(28) as i32, y - px(8) as i32), font.clone()))
                .map_err(e)?;
            y += step;
            side.draw(&Text::new("× configured (a, b)", (x, y - px(8) as i32), font.clone())).map_err(e)?;
            y += step;
            side.draw(&Rectangle::new(
                [(x, y - px(8) as i32), (x + px(20) as i32, y + px(8) as i32)],
                NO_DATA.filled(),
            ))
            .map_err(e)?;
            side.draw(&Text::new("run failed / diverged", (x + px(28) as i32, y - px(8) as i32), font)).map_err(e)?;
            root.present().map_err(|e| err(e.to_string()))?;
        }
        // Cells: one raster pixel per displayed pixel, nearest cell.
        let (xr, yr) = &plot_px;
        let (w, h) = (
            ((xr.end - xr.start) as u32 / SCALE).max(2) as usize,
            ((yr.end - yr.start) as u32 / SCALE).max(2) as usize,
        );
        let mut data = Vec::with_capacity(w * h * 3);
        for r in 0..h {
            let y = y1 - (y1 - y0) * (r as f64 + 0.5) / h as f64;
            let j = (((y - y0) / STEP_DECADES).floor() as usize).min(nb - 1);
            for c in 0..w {
                let x = x0 + (x1 - x0) * (c as f64 + 0.5) / w as f64;
                let i = (((x - x0) / STEP_DECADES).floor() as usize).min(na - 1);
                let p = self.cell(i, j);
                let col = colour(p.metric(METRIC).filter(|_| p.status == Status::Ok));
                data.extend_from_slice(&[col.0, col.1, col.2]);
            }
        }
        let mut png = Vec::new();
        {
            let mut enc = png::Encoder::new(&mut png, w as u32, h as u32);
            enc.set_color(png::ColorType::Rgb);
            enc.set_depth(png::BitDepth::Eight);
            let mut wr = enc.write_header().map_err(|e| err(e.to_string()))?;
            wr.write_image_data(&data).map_err(|e| err(e.to_string()))?;
        }
        crate::chart::embed_raster(&mut svg, &plot_px, &png).map_err(err)?;
        // The canvas is taller than the line charts'.
        let svg = svg.replacen(
            &format!("<svg width=\"{}\" height=\"{}\"", CANVAS.0, CANVAS.1 + px(160)),
            &format!("<svg width=\"{}\" height=\"{}\"", CANVAS.0 / SCALE, (CANVAS.1 + px(160)) / SCALE),
            1,
        );
        Ok(scaled_svg_header(svg))
    }
}
