//! What the front ends show of a [`Comparison`]: the table (one row per metric, one column per
//! controller, each cell the value ± its error) and the tip responses and inputs of every
//! controller on common axes as one SVG (four panels q, θ, τ1, τ2 against t, drawn with the
//! project's chart crate and written atomically).

use std::path::Path;

use wingcheck_chart::{line_svg, Band, BandStyle, Line, LineChart, PlotData, SIZE};

use crate::compare::Comparison;
use crate::{AppError, Front};

/// The table of `c`: the header (`metric`, then each row's name) and one row of cells per
/// metric of [`crate::compare::COLUMNS`] (`value ± error unit` in the tool's number format,
/// `—` where a settling time is never reached), then the basis each controller stepped in.
pub fn table(c: &Comparison) -> (Vec<String>, Vec<Vec<String>>) {
    let mut header = vec!["metric".to_string()];
    header.extend(c.rows.iter().map(|r| r.name.clone()));
    let mut rows: Vec<Vec<String>> = c
        .columns
        .iter()
        .enumerate()
        .map(|(j, (label, _))| {
            let mut cells = vec![label.clone()];
            cells.extend(c.rows.iter().map(|r| r.values[j].as_ref().map_or("—".to_string(), |q| q.pm_text())));
            cells
        })
        .collect();
    let mut basis = vec!["basis (stepped in)".to_string()];
    basis.extend(c.rows.iter().map(|r| r.basis.clone()));
    rows.push(basis);
    (header, rows)
}

/// Refuse before any work an SVG path that cannot be written (not `.svg`, a missing or
/// read-only directory, a symlink or special file in the way).
pub fn check_svg_path(path: &Path, front: Front) -> Result<(), AppError> {
    let arg = front.arg("svg");
    let fail = |message: String| AppError::OutputPath { path: path.to_path_buf(), message };
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    if ext != "svg" {
        return Err(fail(format!("{arg} {}: use a .svg file name", path.display())));
    }
    wingcheck_io::check_output_file(path).map_err(|e| fail(format!("{arg}: {e}")))
}

/// The four panels' (file stem, y label, series index in [`crate::compare::CompareRow::series`],
/// index in its `tau_range`).
const PANELS: [(&str, &str, usize, Option<usize>); 4] = [
    ("compare-q", "q(s,t) (m)", 1, None),
    ("compare-theta", "θ(s,t) (rad)", 2, None),
    ("compare-tau1", "τ1 (N)", 3, Some(0)),
    ("compare-tau2", "τ2 (N m)", 4, Some(1)),
];

/// One panel: every row's series against t (s), τ with its full-rate range per output interval
/// as a band around the samples (which alias a chattering input).
fn panel(c: &Comparison, (name, y_label, k, range): (&str, &str, usize, Option<usize>)) -> LineChart {
    let lines = c
        .rows
        .iter()
        .map(|r| Line { label: r.name.clone(), x: r.series[0].clone(), y: r.series[k].clone(), points: false })
        .collect();
    let data = PlotData {
        name: name.to_string(),
        title: format!("{y_label} of every controller, same wing and disturbances"),
        x_label: "t (s)".to_string(),
        y_label: y_label.to_string(),
        log_x: false,
        log_y: false,
        lines,
    };
    let mut chart = LineChart::from(data);
    if let Some(i) = range {
        chart.bands = c
            .rows
            .iter()
            .enumerate()
            .filter(|(_, r)| r.tau_range[i].len() == r.series[0].len())
            .map(|(line, r)| Band {
                line,
                lo: r.tau_range[i].iter().map(|p| p.0).collect(),
                hi: r.tau_range[i].iter().map(|p| p.1).collect(),
                label: format!("{}: full-rate range", r.name),
                style: BandStyle::Shade,
            })
            .collect();
    }
    chart
}

/// The tip responses and inputs of every row of `c` on common axes: four panels (q, θ, τ1, τ2
/// against t, each at most [`wingcheck_chart::MAX_DRAWN_SAMPLES`] samples per line) stacked in
/// one SVG document.
pub fn svg(c: &Comparison) -> Result<String, AppError> {
    let (w, h) = SIZE;
    let mut out = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{}\" viewBox=\"0 0 {w} {}\">\n",
        4 * h,
        4 * h
    );
    for (i, p) in PANELS.into_iter().enumerate() {
        let (chart, _) = panel(c, p).thinned();
        let one = line_svg(&chart)?;
        // each panel is a nested <svg> (its own viewBox) placed below the previous one
        let body = one.trim_start_matches(|ch| ch != '<').replacen(
            "<svg ",
            &format!("<svg x=\"0\" y=\"{}\" ", i as u32 * h),
            1,
        );
        out.push_str(&body);
        out.push('\n');
    }
    out.push_str("</svg>\n");
    Ok(out)
}

/// Write [`svg`] of `c` to `path` atomically (`wingcheck_io::write_file_atomic`).
pub fn write_svg(c: &Comparison, path: &Path) -> Result<(), AppError> {
    Ok(wingcheck_io::write_file_atomic(path, svg(c)?.as_bytes())?)
}
