//! The (a, b) region map: where the theorems' hypotheses hold, over the tip performance.
//!
//! A small 2-D search over the weights a, b of the control law (15), computed by the search
//! crate's own code ([`wingcheck_search::Search::evaluate`]: the closed loop of the configured
//! controller in the modal basis, the tight λ2 of W/κ and the best λ3 of (29)–(32) per point).
//! Drawn as the chart crate's grid heatmap ([`GridHeatmap`], the search's own heatmap): the RMS
//! tip deflection over the search's metric window (colour; log scale when the values span a
//! decade, linear below, [`LOG_SCALE_RATIO`]), the cells where the
//! search finds W ≻ 0 and (32) feasible (markers), the closed-form boundaries a/b = ω1 (W ≻ 0
//! below it; drawn at both bounds of the certified enclosure ω̲1 ≤ ω1 ≤ ω̄1 when there is one)
//! and a/b = r* ((32) feasible below it) as lines, the region where both hold hatched, and the
//! configured operating point.
//!
//! The grid is laid on half-decades through the configured (a, b), so that point is a node;
//! it spans a/b from a decade below min(r*, ω1, a/b) to a decade above max(…) and b over
//! ±[`B_DECADES`] decades. Work: one closed-loop run per point (≈ 10 ms each at the default
//! grid) and as many eigen/SOCP solves.

use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::prelude::*;
use wingcheck_claims::certify::omega1::EnclosureSummary;
use wingcheck_model::Config;
use wingcheck_search::heatmap::{MU_COLOUR, W_COLOUR};
use wingcheck_search::{modal::RunCache, Axis, PointResult, Search, SearchOptions, Status, TheoryCache};

use crate::chart::{tick, GridAxis, GridHeatmap, Mark, MarkShape, RGBColor};
use crate::figure::{Caption, Chart, Figure};
use crate::stats::fmt_num;
use crate::{Progress, ReportError};

/// Grid spacing in decades.
const STEP_DECADES: f64 = 0.5;
/// b spans b0 · 10^±B_DECADES.
pub const B_DECADES: f64 = 1.5;
/// At most this many values of a (the a range is clipped symmetrically around the boundaries).
const MAX_A: usize = 14;
/// The performance metric shown.
pub const METRIC: wingcheck_search::Metric = wingcheck_search::Metric::RmsQTip;

/// The region map's colour scale is logarithmic when its values span at least this factor
/// (a decade), linear below.
pub const LOG_SCALE_RATIO: f64 = 10.0;

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
    /// The certified enclosure of ω1 for the continuous model (exact), or why there is none.
    pub omega1_certified: EnclosureSummary,
    /// Closed-form (32) boundary a/b = r*.
    pub r_star: f64,
    /// The configured (a, b).
    pub operating: (f64, f64),
    /// Metric window (s).
    pub window: (f64, f64),
    /// The configured controller (upper case).
    pub controller: String,
}

/// Half-decade exponents from `lo` to `hi` (log10), through `center`; at most 64 on each side
/// (counts from non-finite or huge spans are clamped, never cast saturating to i32::MAX).
fn half_decades(center: f64, lo: f64, hi: f64) -> Vec<f64> {
    let steps = |x: f64| if x.is_finite() { (x / STEP_DECADES).ceil().clamp(0.0, 64.0) as i32 } else { 0 };
    let (down, up) = (steps(center - lo), steps(hi - center));
    (-down..=up).map(|k| center + k as f64 * STEP_DECADES).collect()
}

/// The search specs of the map for `cfg`, with the closed-form boundaries used to place it.
/// The grid runs through the configured (a, b) when both are > 0; a weight of 0 has no
/// logarithm, so then the grid is centred on b = 1 (b = 0) and on a/b at the smaller boundary
/// (a = 0), and the configured point is drawn only if it lies on the axes.
fn axes(cfg: &Config, omega1: f64, r_star: f64) -> (Vec<f64>, Vec<f64>) {
    let b0 = if cfg.control.b > 0.0 { cfg.control.b } else { 1.0 };
    let ratios = [r_star, omega1, cfg.control.a / b0];
    let rmin = ratios.iter().copied().filter(|r| *r > 0.0 && r.is_finite()).fold(f64::INFINITY, f64::min);
    let rmax = ratios.iter().copied().filter(|r| r.is_finite()).fold(0.0, f64::max);
    let a0 = if cfg.control.a > 0.0 {
        cfg.control.a
    } else if rmin.is_finite() {
        b0 * rmin
    } else {
        b0
    };
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
    // only weights the validator accepts (a map around b = 1e12 would ask for 3e12): the
    // configured point is always among them
    let accepted = |x: &f64| x.is_finite() && *x >= f64::MIN_POSITIVE && *x <= wingcheck_model::MAX_MAGNITUDE;
    let values = |logs: Vec<f64>| logs.into_iter().map(|e| 10f64.powf(e)).filter(accepted).collect::<Vec<f64>>();
    (values(la), values(lb))
}

/// Compute the map: every point evaluated by the search code, in parallel.
pub fn region_map(
    cfg: &Config,
    omega1: f64,
    r_star: f64,
    progress: Option<&(dyn Fn(Progress) + Sync)>,
    cancel: &wingcheck_model::Cancel,
) -> Result<RegionMap, ReportError> {
    let (a, b) = axes(cfg, omega1, r_star);
    let region = ReportError::Region;
    let axes =
        vec![Axis::of_numbers("control.a", &a).map_err(region)?, Axis::of_numbers("control.b", &b).map_err(region)?];
    let search = Search::from_axes(cfg.clone(), axes, SearchOptions::default()).map_err(region)?;
    let (theory, runs) = (TheoryCache::new(SearchOptions::default().lyapunov_elements), RunCache::new());
    let total = search.points();
    if total > wingcheck_model::work::REGION_MAP_MAX_POINTS {
        // the work estimate counts at most this many points
        return Err(ReportError::RegionTooLarge { points: total, limit: wingcheck_model::work::REGION_MAP_MAX_POINTS });
    }
    let done = AtomicUsize::new(0);
    let points: Vec<PointResult> = (0..total)
        .into_par_iter()
        .map(|p| {
            cancel.check()?;
            let r = search.evaluate(p, &theory, &runs);
            let k = done.fetch_add(1, Ordering::SeqCst) + 1;
            if let Some(cb) = progress {
                cb(Progress { stage: "region map", done: k, total });
            }
            Ok(r)
        })
        .collect::<Result<_, wingcheck_model::Cancelled>>()?;
    let a: Vec<f64> = (0..a.len()).map(|i| search.grid.axes[0].numeric(i).unwrap_or(a[i])).collect();
    let b: Vec<f64> = (0..b.len()).map(|j| search.grid.axes[1].numeric(j).unwrap_or(b[j])).collect();
    let window = wingcheck_search::point::window(cfg, SearchOptions::default().window);
    let controller = serde_json::to_value(cfg.control.kind)
        .ok()
        .and_then(|v| v.as_str().map(str::to_uppercase))
        .unwrap_or_else(|| "configured".into());
    let omega1_certified = EnclosureSummary::deciding(cfg);
    Ok(RegionMap {
        a,
        b,
        points,
        omega1,
        omega1_certified,
        r_star,
        operating: (cfg.control.a, cfg.control.b),
        window,
        controller,
    })
}

const BLACK: RGBColor = RGBColor(0, 0, 0);

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

use wingcheck_sim::metrics::median;

impl RegionMap {
    fn cell(&self, i: usize, j: usize) -> &PointResult {
        &self.points[i * self.b.len() + j]
    }

    /// The W ≻ 0 boundary: (ω̲1, ω̄1) when certified, else (ω1, ω1).
    fn w_boundary(&self) -> (f64, f64) {
        self.omega1_certified.bounds().unwrap_or((self.omega1, self.omega1))
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
                    // Against the certified enclosure: W ≻ 0 below ω̲1, not above ω̄1 (either inside).
                    let (lo, hi) = self.w_boundary();
                    let r = a / b;
                    w_agree += usize::from(if r < lo {
                        w
                    } else if r > hi {
                        !w
                    } else {
                        true
                    });
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

    /// The map as CSV (docs/outputs.md, region-map.csv): the two axis keys, the status columns
    /// of the search's results.csv, and the metric with its unit; its cell is empty exactly when
    /// `rms_available` is false.
    pub fn to_csv(&self) -> String {
        let header = [
            "control__a".to_string(),
            "control__b".to_string(),
            "status".to_string(),
            "w_decided".to_string(),
            "w_positive_definite".to_string(),
            "feasible_32_decided".to_string(),
            "feasible_32".to_string(),
            "rms_available".to_string(),
            METRIC.column().to_string(),
        ];
        let flag = |b: bool| if b { "true" } else { "false" }.to_string();
        let mut rows = Vec::with_capacity(self.a.len() * self.b.len());
        for (i, a) in self.a.iter().enumerate() {
            for (j, b) in self.b.iter().enumerate() {
                let p = self.cell(i, j);
                let m = p.metric(METRIC);
                rows.push([
                    wingcheck_io::number(*a),
                    wingcheck_io::number(*b),
                    p.status.name().to_string(),
                    flag(p.w_positive_definite.is_some()),
                    flag(p.w_positive_definite == Some(true)),
                    flag(p.feasible_32.is_some()),
                    flag(p.feasible_32 == Some(true)),
                    flag(m.is_some()),
                    m.map(wingcheck_io::number).unwrap_or_default(),
                ]);
            }
        }
        wingcheck_io::csv_text(header, rows)
    }

    /// The map as a report figure.
    pub fn figure(&self) -> Figure {
        let s = self.stats();
        let (t0, t1) = self.window;
        let (_, log, ratio) = self.colour_scale();
        let scale = if log {
            format!("log colour scale: the values span a factor of {}", fmt_num(ratio))
        } else {
            format!(
                "linear colour scale: the values differ by only {} % (a log scale is used from a factor of {} up)",
                fmt_num(100.0 * (ratio - 1.0)),
                tick(LOG_SCALE_RATIO)
            )
        };
        let mut cap = Caption::default()
            .t(format!(
                "RMS tip deflection |q(s,t)| over [{}, {}] s of the {} closed loop (colour; {scale}) at each (a, b) of a {} × {} grid, computed by the search code; ",
                tick(t0),
                tick(t1),
                self.controller,
                self.a.len(),
                self.b.len()
            ))
            .t("open circles: W ≻ 0 (tight λ2 > 0, Theorem 1's hypothesis); red dots: (29)–(32) feasible (best λ3 > 0). Closed-form boundaries: W ≻ 0 iff a/b < ω₁ = ")
            .n("region.omega1", self.omega1)
            .t(match &self.omega1_certified {
                EnclosureSummary::Certified { lower_exact, upper_exact, relative_width, .. } => format!(
                    " 1/s, certified for the continuous model as {lower_exact} ≤ ω₁ ≤ {upper_exact} 1/s (exact certificate, relative width {}; white lines at both bounds, indistinguishable at this scale)",
                    wingcheck_model::format::format_error(*relative_width)
                ),
                EnclosureSummary::NotCertified { reason } => format!(" 1/s (white line; no certified enclosure: {reason})"),
            })
            .t(", (32) feasible iff a/b < r* = ")
            .n("region.r_star", self.r_star)
            .t(" 1/s (red dashed line); hatched: a/b < min(ω₁, r*), where both hold and Theorem 2 applies. Of the ")
            .count("region.cells", s.cells)
            .t(" cells, the search's W ≻ 0 verdict agrees with the closed form in ")
            .count("region.w_agree", s.w_agree)
            .t(" and its (32) verdict in ")
            .count("region.mu_agree", s.mu_agree)
            .t(". ");
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
            cap = cap.t("; at the configured point (open square): ").n("region.at_operating", v).t(" m");
        }
        cap = cap.t(".");
        if s.failed > 0 {
            cap = cap.t(format!(" Grey: {} cells whose run failed or diverged (see the CSV).", s.failed));
        }
        Figure {
            file: "region-map-ab".into(),
            label: "Region map".into(),
            title: "(a, b) region map: hypotheses vs tip performance".into(),
            caption: cap.0,
            chart: Chart::Grid { map: Box::new(self.heatmap()), csv: self.to_csv() },
        }
    }

    /// The map as a chart-crate grid heatmap: the metric per cell (log colour scale), the
    /// search's verdicts per cell, the closed-form boundaries as lines across the plot, the
    /// region where both closed forms hold shaded, and the configured point.
    /// The RMS values the map colours (runs that succeeded), and whether their colour scale is
    /// logarithmic: when they span at least a factor of [`LOG_SCALE_RATIO`] (else linear, so a
    /// small relative range is not spread over the whole scale as if it were decades).
    fn colour_scale(&self) -> (Vec<Option<f64>>, bool, f64) {
        let values: Vec<Option<f64>> =
            self.points.iter().map(|p| p.metric(METRIC).filter(|v| v.is_finite() && p.status == Status::Ok)).collect();
        let positive = values.iter().flatten().copied().filter(|v| *v > 0.0);
        let (lo, hi) = positive.fold((f64::INFINITY, 0.0f64), |(l, h), v| (l.min(v), h.max(v)));
        let ratio = if lo.is_finite() && lo > 0.0 { hi / lo } else { 1.0 };
        (values, ratio >= LOG_SCALE_RATIO, ratio)
    }

    /// The map's cells, axes and marks as a chart.
    pub fn heatmap(&self) -> GridHeatmap {
        let axis = |label: &str, centres: &[f64]| GridAxis {
            label: label.into(),
            centres: centres.to_vec(),
            log: true,
            words: None,
        };
        let (values, log_values, _) = self.colour_scale();
        GridHeatmap {
            name: "region-map-ab".into(),
            title: String::new(),
            x: axis(&wingcheck_search::heatmap::axis_title("control.a", true), &self.a),
            y: axis(&wingcheck_search::heatmap::axis_title("control.b", true), &self.b),
            values,
            log_values,
            value_label: "RMS |q(s,t)| (m)".into(),
            missing_label: "run failed or diverged".into(),
            marks: self.marks(),
        }
    }

    /// The map's marks: the region where both hypotheses hold (hatched), the search's verdicts
    /// per cell, the closed-form boundaries and the configured point.
    fn marks(&self) -> Vec<Mark> {
        let cells = |f: &dyn Fn(&PointResult) -> bool| -> Vec<(f64, f64)> {
            let mut v = Vec::new();
            for (i, &a) in self.a.iter().enumerate() {
                for (j, &b) in self.b.iter().enumerate() {
                    if f(self.cell(i, j)) {
                        v.push((a, b));
                    }
                }
            }
            v
        };
        // The b range of the plot (cell edges: half a step beyond the end centres); the
        // closed-form boundaries and the hatched region as the search's heatmaps draw them.
        let half = 10f64.powf(STEP_DECADES / 2.0);
        let (b_lo, b_hi) = (self.b[0] / half, self.b[self.b.len() - 1] * half);
        let a_lo = self.a[0] / half;
        let closed = wingcheck_search::heatmap::ratio_marks(
            self.w_boundary(),
            self.omega1_certified.bounds().is_some(),
            self.r_star,
            a_lo,
            (b_lo, b_hi),
            true,
        );
        let mut marks = closed;
        marks.extend([
            Mark {
                label: "W ≻ 0 (search verdict)".into(),
                colour: W_COLOUR,
                shape: MarkShape::Circles,
                points: cells(&|p| p.w_positive_definite == Some(true)),
            },
            Mark {
                label: "(32) feasible (search verdict)".into(),
                colour: MU_COLOUR,
                shape: MarkShape::Dots,
                points: cells(&|p| p.feasible_32 == Some(true)),
            },
            Mark {
                label: "configured (a, b)".into(),
                colour: BLACK,
                shape: MarkShape::Cross,
                points: vec![self.operating],
            },
        ]);
        marks
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 46, item 3: a map around b = 1e12 (the validator's largest weight) asked the search
    /// for b up to 10^13.5, which the search's validation refused. Every weight on the axes is
    /// one the validator accepts, and the configured point stays on them.
    #[test]
    fn the_maps_weights_stay_within_the_validators_range() {
        let top = wingcheck_model::MAX_MAGNITUDE;
        for (a, b) in [(1.0, top), (top, 1.0), (top, top)] {
            let mut cfg = Config::paper();
            (cfg.control.a, cfg.control.b) = (a, b);
            let (la, lb) = axes(&cfg, 1.0, 0.5);
            for x in la.iter().chain(&lb) {
                assert!(x.is_finite() && *x > 0.0 && *x <= top, "{x} on the axes of a = {a}, b = {b}");
            }
            let near = |v: &[f64], x: f64| v.iter().any(|y| (y / x - 1.0).abs() < 1e-12);
            assert!(near(&la, a) && near(&lb, b), "({a}, {b}) not on {la:?} × {lb:?}");
            assert!(lb.len() >= 4, "b keeps the decades below: {lb:?}");
        }
    }
}
