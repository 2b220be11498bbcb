//! Heatmaps of a field v(z,t) (t on x, z on y) with a colour bar; diverging colour map
//! symmetric about 0 (blue < 0 < red).
//!
//! The field is a PNG raster (one pixel per displayed pixel, bilinear in t and z between the
//! samples, so span rows do not show as bands) embedded in the SVG as a data URI; axes, ticks,
//! labels and the colour bar stay vector. The colour scale is ±max |v| over t ≥
//! [`Heatmap::scale_from`]: the large initial condition would otherwise wash out the residual
//! motion; earlier values saturate, and a dashed line marks where the scale starts.

use plotters::prelude::*;

use plotters::coord::types::RangedCoordf64;

use crate::{linear_ticks, px, scaled_svg_header, tick, tick_linear, Ticked, CANVAS, SCALE};
use crate::{ChartError, DrawError};

/// A field sampled on a (t, z) grid, drawn as a map ([`heatmap_svg`]) or a 3-D surface
/// ([`crate::surface_svg`]).
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
    /// The colour scale is set by the samples with t ≥ this (s).
    pub scale_from: f64,
    /// A fixed half-width of the colour scale instead (a pair of maps on one scale).
    pub vmax: Option<f64>,
}

impl Heatmap {
    /// The data as CSV in long form, `t_s,z_m,value` (one row per sample time and grid point,
    /// t outer); `value` is in the unit of [`Self::value_label`], which the report's
    /// `provenance.json` lists for every figure file. Values in the shortest round-trip form.
    pub fn to_csv(&self) -> String {
        self.to_csv_with(wingcheck_io::number)
    }

    /// [`Heatmap::to_csv`] with the field's values written by `value` (e.g. to the digits of
    /// their error); times and grid points as grid coordinates ([`wingcheck_io::grid_number`]:
    /// to 1/1000 of their spacing).
    pub fn to_csv_with(&self, value: impl Fn(f64) -> String) -> String {
        let spacing = |v: &[f64]| v.windows(2).map(|w| w[1] - w[0]).fold(f64::INFINITY, f64::min);
        let (dt, dz) = (spacing(&self.t), spacing(&self.z));
        let z: Vec<String> = self.z.iter().map(|z| wingcheck_io::grid_number(*z, dz)).collect();
        let rows = self.t.iter().zip(&self.values).flat_map(|(t, row)| {
            let (value, t) = (&value, wingcheck_io::grid_number(*t, dt));
            z.iter().zip(row).map(move |(z, v)| [t.clone(), z.clone(), value(*v)])
        });
        wingcheck_io::csv_text(["t_s", "z_m", "value"], rows)
    }

    /// What the CSV holds, for the provenance record.
    pub fn csv_contents(&self) -> String {
        format!(
            "field v(z,t) in long form: t_s = time (s), z_m = position along the span (m), value = {}",
            self.value_label
        )
    }

    /// Half-width of the colour scale: `vmax` when set, else [`Heatmap::own_scale`].
    pub fn scale(&self) -> f64 {
        self.vmax.filter(|v| v.is_finite() && *v > 0.0).unwrap_or_else(|| self.own_scale())
    }

    /// The map with its sample times thinned to at most [`crate::MAX_DRAWN_SAMPLES`] (every k-th
    /// row, [`crate::stride`]; the colour scale fixed first, so it is the full data's); the
    /// stride k too (1: unchanged).
    pub fn thinned(&self) -> (Heatmap, usize) {
        let n = self.t.len();
        let k = crate::stride(n);
        if k == 1 || self.values.len() != n {
            return (self.clone(), 1);
        }
        let keep = crate::kept(n, k);
        let h = Heatmap {
            t: crate::thin(&self.t, &keep),
            values: keep.iter().map(|&i| self.values[i].clone()).collect(),
            vmax: Some(self.scale()),
            ..self.clone()
        };
        (h, k)
    }

    /// max |v| over t ≥ `scale_from` (1 if that is 0).
    pub fn own_scale(&self) -> f64 {
        let m = self
            .t
            .iter()
            .zip(&self.values)
            .filter(|(t, _)| **t >= self.scale_from)
            .flat_map(|(_, row)| row.iter())
            .filter(|v| v.is_finite())
            .fold(0.0_f64, |m, v| m.max(v.abs()));
        if m > 0.0 {
            m
        } else {
            1.0
        }
    }
}

/// Diverging colour map ("coolwarm"): u ∈ [0,1], 0.5 ↦ near white.
pub(crate) fn coolwarm(u: f64) -> RGBColor {
    let c = coolwarm_rgb(u).map(|v| v.round() as u8);
    RGBColor(c[0], c[1], c[2])
}

/// [`coolwarm`] before rounding: RGB in [0, 255], continuous in u (so a shaded surface can
/// round once, after shading).
pub(crate) fn coolwarm_rgb(u: f64) -> [f64; 3] {
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
    [0, 1, 2].map(|k| c0[k] + w * (c1[k] - c0[k]))
}

/// Index k and weight w with x = (1−w)·c[k] + w·c[k+1] (clamped to the ends).
pub(crate) fn locate(c: &[f64], x: f64) -> (usize, f64) {
    let n = c.len();
    let k = c.partition_point(|v| *v <= x).saturating_sub(1).min(n - 2);
    let w = ((x - c[k]) / (c[k + 1] - c[k])).clamp(0.0, 1.0);
    (k, if w.is_finite() { w } else { 0.0 })
}

/// Colour levels of the raster (an indexed PNG: one byte per pixel, small files).
const LEVELS: usize = 128;

/// PNG (indexed colour, [`LEVELS`] levels of [`coolwarm`]) of the field on a `w × h` pixel
/// raster covering [t0, t1] × [z0, z1], top row = z1.
fn raster_png(h: &Heatmap, w: usize, hgt: usize, vmax: f64) -> Result<Vec<u8>, DrawError> {
    let (t0, t1) = (h.t[0], h.t[h.t.len() - 1]);
    let (z0, z1) = (h.z[0], h.z[h.z.len() - 1]);
    let cols: Vec<(usize, f64)> = (0..w).map(|i| locate(&h.t, t0 + (t1 - t0) * (i as f64 + 0.5) / w as f64)).collect();
    let rows: Vec<(usize, f64)> =
        (0..hgt).map(|j| locate(&h.z, z1 - (z1 - z0) * (j as f64 + 0.5) / hgt as f64)).collect();
    let mut data = Vec::with_capacity(w * hgt);
    for &(j, wz) in &rows {
        for &(k, wt) in &cols {
            let v = |kk: usize, jj: usize| h.values[kk][jj];
            let a = (1.0 - wz) * v(k, j) + wz * v(k, j + 1);
            let b = (1.0 - wz) * v(k + 1, j) + wz * v(k + 1, j + 1);
            let u = (0.5 + 0.5 * ((1.0 - wt) * a + wt * b) / vmax).clamp(0.0, 1.0);
            let u = if u.is_finite() { u } else { 0.5 };
            data.push(((u * LEVELS as f64) as usize).min(LEVELS - 1) as u8);
        }
    }
    let palette: Vec<u8> = (0..LEVELS)
        .flat_map(|i| {
            let c = coolwarm((i as f64 + 0.5) / LEVELS as f64);
            [c.0, c.1, c.2]
        })
        .collect();
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, w as u32, hgt as u32);
        enc.set_color(png::ColorType::Indexed);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_palette(palette);
        enc.set_compression(png::Compression::Best);
        let mut wr = enc.write_header()?;
        wr.write_image_data(&data)?;
    }
    Ok(out)
}

/// Render the heatmap as an SVG document (raster field, vector axes).
pub fn heatmap_svg(h: &Heatmap) -> Result<String, ChartError> {
    let err = |cause: DrawError| ChartError { name: h.name.clone(), cause };
    if h.t.len() < 2 || h.z.len() < 2 || h.values.len() != h.t.len() || h.values.iter().any(|r| r.len() != h.z.len()) {
        return Err(err(DrawError::FieldShape));
    }
    let vmax = h.scale();
    let (t0, t1) = (h.t[0], h.t[h.t.len() - 1]);
    let (z0, z1) = (h.z[0], h.z[h.z.len() - 1]);
    let mut svg = String::new();
    let plot_px;
    {
        let root = SVGBackend::with_string(&mut svg, CANVAS).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(e.into()))?;
        let (main, bar) = root.split_horizontally(CANVAS.0 - px(130));
        let mut chart = ChartBuilder::on(&main)
            .margin(px(12))
            .x_label_area_size(px(46))
            .y_label_area_size(px(64))
            .build_cartesian_2d(
                Ticked::<RangedCoordf64>::new(t0..t1, linear_ticks(t0, t1, 10)),
                Ticked::<RangedCoordf64>::new(z0..z1, linear_ticks(z0, z1, 5)),
            )
            .map_err(|e| err(e.into()))?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("t (s)")
            .y_desc("z (m)")
            .x_label_formatter(&|v| tick(*v))
            .y_label_formatter(&|v| tick(*v))
            .label_style(("sans-serif", px(18)))
            .axis_desc_style(("sans-serif", px(19)))
            .axis_style(BLACK.stroke_width(px(1)))
            .set_all_tick_mark_size(px(5))
            .draw()
            .map_err(|e| err(e.into()))?;
        plot_px = chart.plotting_area().get_pixel_range();
        if h.scale_from > t0 && h.scale_from < t1 {
            chart
                .draw_series(DashedLineSeries::new(
                    vec![(h.scale_from, z0), (h.scale_from, z1)],
                    px(6),
                    px(4),
                    BLACK.mix(0.7).stroke_width(px(2)),
                ))
                .map_err(|e| err(e.into()))?;
        }

        let mut cb = ChartBuilder::on(&bar)
            .margin_top(px(28))
            .margin_bottom(px(58))
            .margin_left(px(10))
            .margin_right(px(4))
            .right_y_label_area_size(px(70))
            .build_cartesian_2d(
                0.0..1.0,
                // the scale's ends labelled too (unless a tick is within 6 % of them)
                Ticked::<RangedCoordf64>::new(
                    -vmax..vmax,
                    crate::with_ends(&linear_ticks(-vmax, vmax, 6), -vmax, vmax, 0.06),
                ),
            )
            .map_err(|e| err(e.into()))?;
        let steps = 64;
        cb.draw_series((0..steps).map(|i| {
            let a = -vmax + 2.0 * vmax * i as f64 / steps as f64;
            let b = -vmax + 2.0 * vmax * (i + 1) as f64 / steps as f64;
            Rectangle::new([(0.0, a), (1.0, b)], coolwarm((i as f64 + 0.5) / steps as f64).filled())
        }))
        .map_err(|e| err(e.into()))?;
        cb.configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .y_label_formatter(&|v| tick_linear(*v, 2.0 * vmax))
            .label_style(("sans-serif", px(17)))
            .axis_style(BLACK.stroke_width(px(1)))
            .set_all_tick_mark_size(px(4))
            .draw()
            .map_err(|e| err(e.into()))?;
        bar.draw(&Text::new(
            h.value_label.clone(),
            (px(8) as i32, px(6) as i32),
            ("sans-serif", px(18)).into_font().color(&BLACK),
        ))
        .map_err(|e| err(e.into()))?;
        root.present().map_err(|e| err(e.into()))?;
    }
    // The raster, one pixel per displayed pixel, placed under the axes (right after the
    // background rectangle, so the axis lines are drawn over its border).
    let (xr, yr) = &plot_px;
    let (w, hgt) =
        (((xr.end - xr.start) as u32 / SCALE).max(2) as usize, ((yr.end - yr.start) as u32 / SCALE).max(2) as usize);
    let png = raster_png(h, w, hgt, vmax).map_err(err)?;
    crate::embed_raster(&mut svg, &plot_px, &png).map_err(err)?;
    Ok(scaled_svg_header(svg))
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

    #[test]
    fn locate_interpolates_and_clamps() {
        let c = [0.0, 1.0, 3.0];
        assert_eq!(locate(&c, 2.0), (1, 0.5));
        assert_eq!(locate(&c, -1.0), (0, 0.0));
        assert_eq!(locate(&c, 5.0), (1, 1.0));
    }
}
