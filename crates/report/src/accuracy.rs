//! Accuracy section: tip error against grid size for FD and FE. Runs at [`GRIDS`] elements
//! on a uniform grid (grading 0); the reference is the Richardson extrapolation of the two
//! finest runs with the order observed on the three finest; the error is the max over
//! t ∈ [`T_SKIP`, t_end] (the first instants are the boundary layer where the control switches
//! on against an initial state that violates the clamp).

use serde::Serialize;
use wingcheck_claims::{Line, PlotData};
use wingcheck_sim::SimOutput;

use crate::chart::{LineChart, LineStyle};
use crate::figure::{Caption, Chart, Figure};
use crate::runs::{GRIDS, METHODS};
use crate::stats::fmt_num;
use wingcheck_sim::metrics::loglog_slope;

/// Start of the error window (s).
pub const T_SKIP: f64 = 0.1;

/// One row of the accuracy table (a method and a tip quantity).
#[derive(Debug, Clone, Serialize)]
pub struct AccuracyRow {
    /// `fd` or `fe`.
    pub method: String,
    /// `q(s,t)` or `θ(s,t)`.
    pub quantity: String,
    /// Order observed from the three finest grids (used for the extrapolation).
    pub richardson_order: String,
    /// max error per grid, formatted, in [`GRIDS`] order.
    pub errors: Vec<String>,
    /// Least-squares order fitted to the errors of the three coarsest grids.
    pub fitted_order: String,
}

fn max_diff(t: &[f64], a: &[f64], b: &[f64]) -> f64 {
    t.iter().zip(a.iter().zip(b)).filter(|(t, _)| **t >= T_SKIP).map(|(_, (x, y))| (x - y).abs()).fold(0.0, f64::max)
}

/// Errors of one quantity over the grids, the Richardson order and the fitted order.
fn study(t: &[f64], runs: &[Vec<f64>]) -> (Vec<f64>, f64, f64) {
    let n = runs.len();
    let d1 = max_diff(t, &runs[n - 2], &runs[n - 3]);
    let d2 = max_diff(t, &runs[n - 1], &runs[n - 2]);
    let p = (d1 / d2).log2();
    let p_used = if p.is_finite() && p > 0.5 { p.min(8.0) } else { 2.0 };
    let factor = 1.0 / (2f64.powf(p_used) - 1.0);
    let reference: Vec<f64> =
        runs[n - 1].iter().zip(&runs[n - 2]).map(|(fine, coarse)| fine + (fine - coarse) * factor).collect();
    let errors: Vec<f64> = runs.iter().map(|r| max_diff(t, r, &reference)).collect();
    let grids: Vec<f64> = GRIDS.iter().map(|&g| g as f64).collect();
    let order = -loglog_slope(&grids[..3], &errors[..3]);
    (errors, p, order)
}

/// The accuracy figure and table from `runs.accuracy`.
pub fn accuracy(accuracy: &[Vec<std::sync::Arc<SimOutput>>]) -> (Figure, Vec<AccuracyRow>) {
    let mut rows = Vec::new();
    let mut lines = Vec::new();
    let mut cap = Caption::default().t(format!(
        "Maximum tip error over t ∈ [{T_SKIP} s, t_end] against the number of elements (uniform grid), \
         reference: Richardson extrapolation of the two finest grids. Fitted orders (grids {}, {}, {}): ",
        GRIDS[0], GRIDS[1], GRIDS[2]
    ));
    for (m, outs) in METHODS.iter().zip(accuracy) {
        let t = &outs[0].series.t;
        for (qname, key) in [("q(s,t)", "q"), ("θ(s,t)", "theta")] {
            let series: Vec<Vec<f64>> = outs
                .iter()
                .map(|o| if key == "q" { o.series.q_tip.clone() } else { o.series.theta_tip.clone() })
                .collect();
            let (errors, p, order) = study(t, &series);
            let label = format!("{} {qname}", m.name().to_uppercase());
            cap = cap.t(format!("{label} ")).n(format!("acc.{}.{key}.order", m.name()), order).t("; ");
            let x: Vec<f64> = GRIDS.iter().map(|&g| g as f64).collect();
            lines.push(Line { label: label.clone(), x: x.clone(), y: errors.clone(), points: false });
            lines.push(Line { label: String::new(), x, y: errors.clone(), points: true });
            rows.push(AccuracyRow {
                method: m.name().to_string(),
                quantity: qname.into(),
                richardson_order: fmt_num(p),
                errors: errors.iter().map(|e| fmt_num(*e)).collect(),
                fitted_order: fmt_num(order),
            });
        }
    }
    let cap = cap.t(
        "the error of the finest grid is the extrapolation correction itself. Dashed: an O(N⁻²) reference slope (through twice the largest error at the coarsest grid).",
    );
    let x: Vec<f64> = GRIDS.iter().map(|&g| g as f64).collect();
    let top = lines.iter().filter_map(|l| l.y.first().copied()).filter(|v| v.is_finite()).fold(0.0_f64, f64::max);
    let n0 = x[0];
    let mut styles = vec![LineStyle::Solid; lines.len()];
    if top > 0.0 {
        lines.push(Line {
            label: "O(N⁻²) reference".into(),
            x: x.clone(),
            y: x.iter().map(|n| 2.0 * top * (n0 / n).powi(2)).collect(),
            points: false,
        });
        styles.push(LineStyle::Dashed);
    }
    let pd = PlotData {
        name: "accuracy".into(),
        title: "Tip error vs grid size".into(),
        x_label: "elements N".into(),
        y_label: "max tip error (q: m, θ: rad)".into(),
        log_x: true,
        log_y: true,
        lines,
    };
    let chart = LineChart { styles, ..LineChart::from(pd) };
    let fig = Figure {
        file: "accuracy-tip-error".into(),
        label: "Accuracy".into(),
        title: "Tip error vs grid size, FD and FE".into(),
        caption: cap.0,
        chart: Chart::Line(chart),
    };
    (fig, rows)
}
