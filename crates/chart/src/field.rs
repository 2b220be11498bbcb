//! Heatmaps of a field v(z,t) (t on x, z on y) with a colour bar; diverging colour map
//! symmetric about 0 (blue < 0 < red).

use plotters::prelude::*;

use crate::ChartError;
use crate::{tick, tick_linear, SIZE};

/// A field sampled on a (t, z) grid.
#[derive(Debug, Clone)]
pub struct Heatmap {
    /// File stem.
    pub name: String,
    /// Sample times t_k (s), increasing.
    pub t: Vec<f64>,
    /// Grid points z_j (m), increasing.
    pub z: Vec<f64>,
    /// values[k][j] = v(z_j, t_k).
    pub values: Vec<Vec<f64>>,
    /// Label of the colour bar (quantity and unit).
    pub value_label: String,
}

/// Time columns drawn at most (the CSV has every sample).
const MAX_COLUMNS: usize = 250;

impl Heatmap {
    /// The data as CSV: one row per sample time, one column per grid point.
    pub fn to_csv(&self) -> String {
        let mut out = String::from("t_s");
        for z in &self.z {
            out.push_str(&format!(",z={z}"));
        }
        out.push('\n');
        for (t, row) in self.t.iter().zip(&self.values) {
            out.push_str(&t.to_string());
            for v in row {
                out.push_str(&format!(",{v}"));
            }
            out.push('\n');
        }
        out
    }
}

/// Diverging colour map ("coolwarm"): u ∈ [0,1], 0.5 ↦ near white.
fn coolwarm(u: f64) -> RGBColor {
    const STOPS: [(f64, [f64; 3]); 5] = [
        (0.0, [59.0, 76.0, 192.0]),
        (0.25, [141.0, 176.0, 254.0]),
        (0.5, [242.0, 242.0, 242.0]),
        (0.75, [244.0, 154.0, 123.0]),
        (1.0, [180.0, 4.0, 38.0]),
    ];
    let u = if u.is_finite() { u.clamp(0.0, 1.0) } else { 0.5 };
    let i = STOPS.iter().rposition(|(s, _)| *s <= u).unwrap_or(0).min(STOPS.len() - 2);
    let (s0, c0) = STOPS[i];
    let (s1, c1) = STOPS[i + 1];
    let w = (u - s0) / (s1 - s0);
    let c = |k: usize| (c0[k] + w * (c1[k] - c0[k])).round() as u8;
    RGBColor(c(0), c(1), c(2))
}

/// Cell edges around increasing centres: midpoints, ends at the first/last centre.
fn edges(c: &[f64]) -> Vec<f64> {
    let n = c.len();
    let mut e = Vec::with_capacity(n + 1);
    e.push(c[0]);
    for i in 1..n {
        e.push(0.5 * (c[i - 1] + c[i]));
    }
    e.push(c[n - 1]);
    e
}

/// Render the heatmap as an SVG document.
pub fn heatmap_svg(h: &Heatmap) -> Result<String, ChartError> {
    let err = |e: String| ChartError { name: h.name.clone(), detail: e };
    if h.t.len() < 2 || h.z.len() < 2 || h.values.len() != h.t.len() {
        return Err(err("need at least 2 times and 2 grid points".into()));
    }
    let vmax = h.values.iter().flatten().filter(|v| v.is_finite()).fold(0.0_f64, |m, v| m.max(v.abs()));
    let vmax = if vmax > 0.0 { vmax } else { 1.0 };
    let stride = h.t.len().div_ceil(MAX_COLUMNS);
    let cols: Vec<usize> = (0..h.t.len()).step_by(stride).collect();
    let tc: Vec<f64> = cols.iter().map(|&k| h.t[k]).collect();
    let te = edges(&tc);
    let ze = edges(&h.z);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(e.to_string()))?;
        let (main, bar) = root.split_horizontally(SIZE.0 - 120);
        let mut chart = ChartBuilder::on(&main)
            .margin(12)
            .x_label_area_size(44)
            .y_label_area_size(60)
            .build_cartesian_2d(te[0]..te[te.len() - 1], ze[0]..ze[ze.len() - 1])
            .map_err(|e| err(e.to_string()))?;
        let mut cells = Vec::with_capacity(cols.len() * h.z.len());
        for (c, &k) in cols.iter().enumerate() {
            for j in 0..h.z.len() {
                let color = coolwarm(0.5 + 0.5 * h.values[k][j] / vmax);
                cells.push(Rectangle::new([(te[c], ze[j]), (te[c + 1], ze[j + 1])], color.filled()));
            }
        }
        chart.draw_series(cells).map_err(|e| err(e.to_string()))?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("t (s)")
            .y_desc("z (m)")
            .x_label_formatter(&|v| tick(*v))
            .y_label_formatter(&|v| tick(*v))
            .label_style(("sans-serif", 14))
            .axis_desc_style(("sans-serif", 15))
            .draw()
            .map_err(|e| err(e.to_string()))?;

        let mut cb = ChartBuilder::on(&bar)
            .margin_top(12)
            .margin_bottom(56)
            .margin_left(10)
            .margin_right(4)
            .right_y_label_area_size(64)
            .caption(h.value_label.as_str(), ("sans-serif", 14))
            .build_cartesian_2d(0.0..1.0, -vmax..vmax)
            .map_err(|e| err(e.to_string()))?;
        let steps = 64;
        cb.draw_series((0..steps).map(|i| {
            let a = -vmax + 2.0 * vmax * i as f64 / steps as f64;
            let b = -vmax + 2.0 * vmax * (i + 1) as f64 / steps as f64;
            Rectangle::new([(0.0, a), (1.0, b)], coolwarm((i as f64 + 0.5) / steps as f64).filled())
        }))
        .map_err(|e| err(e.to_string()))?;
        cb.configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .y_labels(7)
            .y_label_formatter(&|v| tick_linear(*v, 2.0 * vmax))
            .label_style(("sans-serif", 13))
            .draw()
            .map_err(|e| err(e.to_string()))?;
        root.present().map_err(|e| err(e.to_string()))?;
    }
    Ok(svg)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colour_map_ends_and_middle() {
        // The stops of the table above.
        assert_eq!(coolwarm(0.0), RGBColor(59, 76, 192));
        assert_eq!(coolwarm(0.5), RGBColor(242, 242, 242));
        assert_eq!(coolwarm(1.0), RGBColor(180, 4, 38));
    }
}
