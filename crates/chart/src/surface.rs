//! A field v(z,t) drawn as a 3-D surface over the (t, z) floor, like the paper's Figures 3–6 and
//! 13–14: an axonometric view (t running towards the viewer, z away from them, v up),
//! quads filled back to front (painter's order) with the colour level and the shade
//! interpolated per pixel from the quad's corners (Gouraud: the colour bands follow the field's
//! contours instead of the quads' edges, so they show no stair-steps, and the shade follows the
//! surface's vertex normals, so neighbouring quads show no streaks), mesh lines at about ten
//! span positions and every few time samples.
//!
//! The surface, the floor and the back walls are one indexed PNG raster (one pixel per
//! displayed pixel); axes, ticks, labels and the colour bar are vector. Heights are to scale
//! over the whole run; the colour is the companion heatmap's (±max |v| over t ≥
//! [`Heatmap::scale_from`], earlier values saturate), so the residual motion that is flat at
//! this height scale still shows.

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::field::{coolwarm, locate};
use crate::Heatmap;
use crate::{linear_ticks, px, scaled_svg_header, tick, tick_linear, ChartError, CANVAS, SCALE};

/// At most this many time strips are drawn (samples are taken evenly; the CSV has them all).
const MAX_STRIPS: usize = 160;
/// A mesh line across the span every this many strips.
const MESH_EVERY: usize = 16;
/// At least this many span rows are drawn (interpolated between the grid's points).
const MIN_ROWS: usize = 64;
/// About this many mesh lines along t (at evenly spaced span positions).
const MESH_Z: usize = 10;
/// Colour levels × shade levels of the palette (≤ 256 with the reserved entries).
const LEVELS: usize = 30;
const SHADES: usize = 8;
const WHITE_IX: u8 = (LEVELS * SHADES) as u8;
const WALL_IX: u8 = WHITE_IX + 1;
const EDGE_IX: u8 = WHITE_IX + 2;

/// Displayed-pixel geometry of the projection: P(u, w, h) for u = t fraction, w = z fraction,
/// h = height fraction, all in [0, 1].
#[derive(Clone, Copy)]
struct View {
    origin: (f64, f64),
    t_axis: (f64, f64),
    z_axis: (f64, f64),
    height: f64,
}

const VIEW: View = View { origin: (118.0, 300.0), t_axis: (470.0, 84.0), z_axis: (250.0, -62.0), height: 205.0 };

impl View {
    fn at(&self, u: f64, w: f64, h: f64) -> (f64, f64) {
        (
            self.origin.0 + u * self.t_axis.0 + w * self.z_axis.0,
            self.origin.1 + u * self.t_axis.1 + w * self.z_axis.1 - h * self.height,
        )
    }
    /// The raster's rectangle (displayed px): the box's bounding rectangle plus a margin.
    fn bounds(&self) -> (i32, i32, i32, i32) {
        let corners = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)];
        let pts: Vec<(f64, f64)> =
            corners.iter().flat_map(|&(u, w)| [self.at(u, w, 0.0), self.at(u, w, 1.0)]).collect();
        let (x0, x1) = pts.iter().fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p.0), b.max(p.0)));
        let (y0, y1) = pts.iter().fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p.1), b.max(p.1)));
        (x0.floor() as i32 - 2, y0.floor() as i32 - 2, x1.ceil() as i32 + 2, y1.ceil() as i32 + 2)
    }
}

/// An indexed raster with painter's-order drawing.
struct Raster {
    w: usize,
    h: usize,
    off: (i32, i32),
    data: Vec<u8>,
}

impl Raster {
    fn set(&mut self, x: i32, y: i32, c: u8) {
        let (x, y) = (x - self.off.0, y - self.off.1);
        if x >= 0 && y >= 0 && (x as usize) < self.w && (y as usize) < self.h {
            self.data[y as usize * self.w + x as usize] = c;
        }
    }

    /// Fill the triangle — pixel centres inside it or within half a pixel of it (edge
    /// functions), so shared edges are never left open — each pixel's colour level and shade
    /// interpolated linearly (barycentric weights of the pixel centre, clamped to the triangle)
    /// from the corners' `(level, shade)`, both continuous: the level's integer part and the
    /// nearest shade.
    fn shaded_triangle(&mut self, p: [(f64, f64); 3], attr: [(f64, f64); 3]) {
        let x0 = p.iter().map(|q| q.0).fold(f64::MAX, f64::min).floor() as i32;
        let x1 = p.iter().map(|q| q.0).fold(f64::MIN, f64::max).ceil() as i32;
        let y0 = p.iter().map(|q| q.1).fold(f64::MAX, f64::min).floor() as i32;
        let y1 = p.iter().map(|q| q.1).fold(f64::MIN, f64::max).ceil() as i32;
        let edge = |a: (f64, f64), b: (f64, f64), x: f64, y: f64| (b.0 - a.0) * (y - a.1) - (b.1 - a.1) * (x - a.0);
        let area = edge(p[0], p[1], p[2].0, p[2].1);
        if area.abs() < 1e-12 {
            return;
        }
        let len = |a: (f64, f64), b: (f64, f64)| (b.0 - a.0).hypot(b.1 - a.1).max(1e-12);
        let lens = [len(p[1], p[2]), len(p[2], p[0]), len(p[0], p[1])];
        for y in y0..=y1 {
            for x in x0..=x1 {
                let (fx, fy) = (x as f64 + 0.5, y as f64 + 0.5);
                let e = [edge(p[1], p[2], fx, fy), edge(p[2], p[0], fx, fy), edge(p[0], p[1], fx, fy)];
                if e.iter().zip(&lens).all(|(v, l)| v * area.signum() / l >= -0.5) {
                    let w = e.map(|v| (v / area).max(0.0));
                    let sum = (w[0] + w[1] + w[2]).max(1e-300);
                    let at = |f: fn(&(f64, f64)) -> f64| (0..3).map(|k| w[k] * f(&attr[k])).sum::<f64>() / sum;
                    let level = ((at(|a| a.0) + 1e-9).floor().max(0.0) as usize).min(LEVELS - 1);
                    let shade = (at(|a| a.1).round().max(0.0) as usize).min(SHADES - 1);
                    self.set(x, y, (level * SHADES + shade) as u8);
                }
            }
        }
    }

    /// A one-pixel line.
    fn line(&mut self, a: (f64, f64), b: (f64, f64), c: u8) {
        let n = (b.0 - a.0).abs().max((b.1 - a.1).abs()).ceil().max(1.0) as usize;
        for i in 0..=n {
            let s = i as f64 / n as f64;
            self.set((a.0 + s * (b.0 - a.0)).floor() as i32, (a.1 + s * (b.1 - a.1)).floor() as i32, c);
        }
    }
}

/// Palette: LEVELS colour levels × SHADES shade levels, then white, wall grey, edge grey.
fn palette() -> Vec<u8> {
    let mut p = Vec::with_capacity(3 * 256);
    for l in 0..LEVELS {
        let c = coolwarm((l as f64 + 0.5) / LEVELS as f64);
        for s in 0..SHADES {
            // shading darkens by at most a quarter, so a quad's colour stays readable on the
            // colour bar (which shows the unshaded level)
            let f = 0.75 + 0.25 * s as f64 / (SHADES - 1) as f64;
            p.extend([c.0, c.1, c.2].map(|v| (v as f64 * f).round() as u8));
        }
    }
    p.extend([255, 255, 255, 215, 215, 215, 120, 120, 120]);
    p
}

/// The height range (0 included) of the field.
fn height_range(s: &Heatmap) -> (f64, f64) {
    let finite = s.values.iter().flatten().filter(|v| v.is_finite());
    let (vmin, vmax) = finite.fold((0.0_f64, 0.0_f64), |(a, b), v| (a.min(*v), b.max(*v)));
    if vmax - vmin > 0.0 {
        (vmin, vmax)
    } else {
        (vmin - 1.0, vmax + 1.0)
    }
}

/// The fraction of [a, b] at v.
fn frac(v: f64, a: f64, b: f64) -> f64 {
    if b > a {
        (v - a) / (b - a)
    } else {
        0.0
    }
}

/// The raster: floor, back walls with the height ticks `vt`, and the surface in painter's
/// order (`s` checked by the caller: ≥ 2 × 2 samples, one value per (t, z)).
fn draw_surface(s: &Heatmap, view: View, (vmin, vmax): (f64, f64), vt: &[f64]) -> Raster {
    let (nt, nz) = (s.t.len(), s.z.len());
    let cmax = s.scale();
    let (t0, t1, z0, z1) = (s.t[0], s.t[nt - 1], s.z[0], s.z[nz - 1]);
    let (bx0, by0, bx1, by1) = view.bounds();
    let mut r = Raster {
        w: (bx1 - bx0) as usize,
        h: (by1 - by0) as usize,
        off: (bx0, by0),
        data: vec![WHITE_IX; ((bx1 - bx0) * (by1 - by0)) as usize],
    };
    // Floor and back walls (t = t0 on the left, z = z1 at the back), with the height ticks.
    for &(a, b) in
        &[((0.0, 0.0), (1.0, 0.0)), ((1.0, 0.0), (1.0, 1.0)), ((1.0, 1.0), (0.0, 1.0)), ((0.0, 1.0), (0.0, 0.0))]
    {
        r.line(view.at(a.0, a.1, 0.0), view.at(b.0, b.1, 0.0), WALL_IX);
    }
    for h in vt.iter().map(|v| frac(*v, vmin, vmax)).chain([1.0]) {
        r.line(view.at(0.0, 0.0, h), view.at(0.0, 1.0, h), WALL_IX);
        r.line(view.at(0.0, 1.0, h), view.at(1.0, 1.0, h), WALL_IX);
    }
    for (u, w) in [(0.0, 0.0), (0.0, 1.0), (1.0, 1.0)] {
        r.line(view.at(u, w, 0.0), view.at(u, w, 1.0), WALL_IX);
    }
    // Time samples drawn: evenly spaced indices, first and last kept.
    let strips = (nt - 1).min(MAX_STRIPS);
    let ks: Vec<usize> = (0..=strips).map(|i| (i * (nt - 1) + strips / 2) / strips).collect();
    // Span rows drawn: evenly spaced (the grid may be graded, with long elements whose flat
    // quads would show as steps), values linear in z between grid points.
    let rows: Vec<(f64, usize, f64)> = (0..nz.max(MIN_ROWS))
        .map(|i| {
            let z = z0 + (z1 - z0) * i as f64 / (nz.max(MIN_ROWS) - 1) as f64;
            let (j, w) = locate(&s.z, z);
            (z, j, w)
        })
        .collect();
    let nz = rows.len();
    let point = |k: usize, i: usize| {
        let (z, j, w) = rows[i];
        let v = (1.0 - w) * s.values[k][j] + w * s.values[k][j + 1];
        let v = if v.is_finite() { v } else { 0.0 };
        (frac(s.t[k], t0, t1), frac(z, z0, z1), frac(v, vmin, vmax), v)
    };
    // Mesh lines along t at about MESH_Z evenly spaced span positions.
    let band = |j: usize| (frac(rows[j].0, z0, z1) * MESH_Z as f64).floor() as i64;
    let mesh_z: Vec<bool> = (0..nz).map(|j| j == 0 || band(j) != band(j - 1)).collect();
    // Quads, back to front: the floor's screen y grows towards the viewer.
    let mut quads: Vec<(f64, usize, usize)> = Vec::with_capacity(strips * (nz - 1));
    for i in 0..strips {
        for j in 0..nz - 1 {
            let (u, w) =
                (0.5 * (point(ks[i], j).0 + point(ks[i + 1], j).0), 0.5 * (point(ks[i], j).1 + point(ks[i], j + 1).1));
            quads.push((view.at(u, w, 0.0).1, i, j));
        }
    }
    quads.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
    // Light from the upper left, towards the viewer; normals in (u, w, h) scaled to the box.
    let light = {
        let l = [-0.5_f64, -0.6, 0.75];
        let n = (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]).sqrt();
        [l[0] / n, l[1] / n, l[2] / n]
    };
    let aspect = [1.6, 0.9, 0.8];
    // the shade at each drawn vertex from its normal (central differences on the drawn grid)
    let shade_at = |i: usize, j: usize| {
        let (ia, ib) = (i.saturating_sub(1), (i + 1).min(strips));
        let (ja, jb) = (j.saturating_sub(1), (j + 1).min(nz - 1));
        let (a, b) = (point(ks[ia], j), point(ks[ib], j));
        let (c, d) = (point(ks[i], ja), point(ks[i], jb));
        let du = [(b.0 - a.0) * aspect[0], 0.0, (b.2 - a.2) * aspect[2]];
        let dw = [0.0, (d.1 - c.1) * aspect[1], (d.2 - c.2) * aspect[2]];
        let n = [du[1] * dw[2] - du[2] * dw[1], du[2] * dw[0] - du[0] * dw[2], du[0] * dw[1] - du[1] * dw[0]];
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt().max(1e-300);
        let lambert = ((n[0] * light[0] + n[1] * light[1] + n[2] * light[2]) / len).abs();
        (0.25 + 0.75 * lambert) * (SHADES - 1) as f64
    };
    let level_of = |v: f64| (0.5 + 0.5 * v / cmax).clamp(0.0, 1.0) * LEVELS as f64;
    for &(_, i, j) in &quads {
        let c = [point(ks[i], j), point(ks[i + 1], j), point(ks[i + 1], j + 1), point(ks[i], j + 1)];
        let attr = [
            (level_of(c[0].3), shade_at(i, j)),
            (level_of(c[1].3), shade_at(i + 1, j)),
            (level_of(c[2].3), shade_at(i + 1, j + 1)),
            (level_of(c[3].3), shade_at(i, j + 1)),
        ];
        let mean = 0.25 * c.iter().map(|p| p.3).sum::<f64>();
        let level = (level_of(mean) as usize).min(LEVELS - 1);
        let p: Vec<(f64, f64)> = c.iter().map(|q| view.at(q.0, q.1, q.2)).collect();
        r.shaded_triangle([p[0], p[1], p[2]], [attr[0], attr[1], attr[2]]);
        r.shaded_triangle([p[0], p[2], p[3]], [attr[0], attr[2], attr[3]]);
        let line = (level * SHADES + 2) as u8;
        if mesh_z[j] {
            r.line(p[0], p[1], line);
        }
        if j + 2 == nz {
            r.line(p[3], p[2], line);
        }
        if i % MESH_EVERY == 0 {
            r.line(p[0], p[3], line);
        }
        if i + 1 == strips {
            r.line(p[1], p[2], line);
        }
    }
    for (a, b) in [((0.0, 0.0), (1.0, 0.0)), ((1.0, 0.0), (1.0, 1.0))] {
        r.line(view.at(a.0, a.1, 0.0), view.at(b.0, b.1, 0.0), EDGE_IX);
    }
    r
}

/// Render the surface as an SVG document (raster surface, vector axes).
pub fn surface_svg(s: &Heatmap) -> Result<String, ChartError> {
    let err = |e: String| ChartError { name: s.name.clone(), detail: e };
    let (nt, nz) = (s.t.len(), s.z.len());
    if nt < 2 || nz < 2 || s.values.len() != nt || s.values.iter().any(|r| r.len() != nz) {
        return Err(err("need at least 2 times and 2 grid points, and one value per (t, z)".into()));
    }
    let (vmin, vmax) = height_range(s);
    let cmax = s.scale();
    let (t0, t1, z0, z1) = (s.t[0], s.t[nt - 1], s.z[0], s.z[nz - 1]);
    let view = VIEW;
    // the height axis labelled up to the peak (and down to the lowest value)
    let vt = crate::with_ends(&linear_ticks(vmin, vmax, 5), vmin, vmax, 0.08);
    let (bx0, by0, bx1, by1) = view.bounds();
    let r = draw_surface(s, view, (vmin, vmax), &vt);
    let png = indexed_png(&r).map_err(err)?;

    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, CANVAS).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(e.to_string()))?;
        let e = |e: DrawingAreaErrorKind<std::io::Error>| err(e.to_string());
        let c = |p: (f64, f64)| ((p.0 * SCALE as f64).round() as i32, (p.1 * SCALE as f64).round() as i32);
        let font = |h: HPos, v: VPos| ("sans-serif", px(16)).into_font().color(&BLACK).pos(Pos::new(h, v));
        let axis = BLACK.stroke_width(px(1));
        // t along the front-left edge, z along the front-right edge, v up the left corner.
        let tick_along = |from: (f64, f64), to: (f64, f64), out: (f64, f64), f: f64| {
            let p = (from.0 + f * (to.0 - from.0), from.1 + f * (to.1 - from.1));
            (p, (p.0 + out.0, p.1 + out.1))
        };
        let (o, tx, zx) = (view.at(0.0, 0.0, 0.0), view.at(1.0, 0.0, 0.0), view.at(1.0, 1.0, 0.0));
        for (from, to, out, lo, hi, label, anchor) in [
            (o, tx, (-6.0, 7.0), t0, t1, "t (s)", (HPos::Right, VPos::Top)),
            (tx, zx, (7.0, 6.0), z0, z1, "z (m)", (HPos::Left, VPos::Top)),
        ] {
            root.draw(&PathElement::new(vec![c(from), c(to)], axis)).map_err(e)?;
            for v in linear_ticks(lo, hi, 5) {
                let (p, q) = tick_along(from, to, out, frac(v, lo, hi));
                root.draw(&PathElement::new(vec![c(p), c(q)], axis)).map_err(e)?;
                let at = (q.0 + 0.6 * out.0, q.1 + 0.6 * out.1);
                root.draw(&Text::new(tick(v), c(at), font(anchor.0, anchor.1))).map_err(e)?;
            }
            let mid = tick_along(from, to, out, 0.5).1;
            let at = (mid.0 + 5.5 * out.0, mid.1 + 4.0 * out.1);
            root.draw(&Text::new(label.to_string(), c(at), font(HPos::Center, VPos::Center))).map_err(e)?;
        }
        let top = view.at(0.0, 0.0, 1.0);
        root.draw(&PathElement::new(vec![c(o), c(top)], axis)).map_err(e)?;
        for v in &vt {
            let p = view.at(0.0, 0.0, frac(*v, vmin, vmax));
            root.draw(&PathElement::new(vec![c(p), c((p.0 - 6.0, p.1))], axis)).map_err(e)?;
            let label = tick_linear(*v, vmax - vmin);
            root.draw(&Text::new(label, c((p.0 - 10.0, p.1)), font(HPos::Right, VPos::Center))).map_err(e)?;
        }
        root.draw(&Text::new(s.value_label.clone(), c((top.0, top.1 - 14.0)), font(HPos::Center, VPos::Bottom)))
            .map_err(e)?;
        // Colour bar: the palette's brightest shade per level.
        let (cx, cy0, cy1) = (890.0, 40.0, 360.0);
        for l in 0..LEVELS {
            let ya = cy1 - (l + 1) as f64 * (cy1 - cy0) / LEVELS as f64;
            let yb = cy1 - l as f64 * (cy1 - cy0) / LEVELS as f64;
            let col = coolwarm((l as f64 + 0.5) / LEVELS as f64);
            root.draw(&Rectangle::new([c((cx, ya)), c((cx + 18.0, yb + 0.5))], col.filled())).map_err(e)?;
        }
        root.draw(&Rectangle::new([c((cx, cy0)), c((cx + 18.0, cy1))], axis)).map_err(e)?;
        for v in crate::with_ends(&linear_ticks(-cmax, cmax, 4), -cmax, cmax, 0.04) {
            let y = cy1 - frac(v, -cmax, cmax) * (cy1 - cy0);
            root.draw(&PathElement::new(vec![c((cx + 18.0, y)), c((cx + 23.0, y))], axis)).map_err(e)?;
            let label = tick_linear(v, 2.0 * cmax);
            root.draw(&Text::new(label, c((cx + 26.0, y)), font(HPos::Left, VPos::Center))).map_err(e)?;
        }
        root.draw(&Text::new(
            format!("colour: {}", s.value_label),
            c((cx + 9.0, cy0 - 10.0)),
            font(HPos::Center, VPos::Bottom),
        ))
        .map_err(e)?;
        root.present().map_err(|e| err(e.to_string()))?;
    }
    let s4 = SCALE as i32;
    crate::embed_raster(&mut svg, &(bx0 * s4..bx1 * s4, by0 * s4..by1 * s4), &png).map_err(err)?;
    Ok(scaled_svg_header(svg))
}

fn indexed_png(r: &Raster) -> Result<Vec<u8>, String> {
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, r.w as u32, r.h as u32);
        enc.set_color(png::ColorType::Indexed);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_palette(palette());
        enc.set_compression(png::Compression::Best);
        let mut wr = enc.write_header().map_err(|e| e.to_string())?;
        wr.write_image_data(&r.data).map_err(|e| e.to_string())?;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn projection_puts_the_box_corners_where_the_view_says() {
        // Reference: the View constants — P(0,0,0) is the origin, P(1,0,0) the origin plus the
        // t axis, P(0,0,1) the origin raised by the height.
        let v = VIEW;
        assert_eq!(v.at(0.0, 0.0, 0.0), v.origin);
        assert_eq!(v.at(1.0, 0.0, 0.0), (v.origin.0 + v.t_axis.0, v.origin.1 + v.t_axis.1));
        assert_eq!(v.at(0.0, 0.0, 1.0), (v.origin.0, v.origin.1 - v.height));
        // Everything drawn fits the canvas, the colour bar to its right.
        let (x0, y0, x1, y1) = v.bounds();
        assert!(x0 >= 0 && y0 >= 0 && x1 < 870 && y1 <= crate::SIZE.1 as i32 - 40, "{x0} {y0} {x1} {y1}");
    }

    #[test]
    fn a_ridge_in_front_hides_the_floor_behind_it() {
        // v = 1 on the last time sample (the edge nearest the viewer), 0 elsewhere: a slope
        // rising over the last strip, u ∈ [0.9, 1]. Reference: the projection (View constants).
        // The floor point F = (u, w) = (0.7, 0.764) lies behind the slope and projects onto the
        // same pixel as the slope point u ≈ 0.92, w ≈ 0.35, h ≈ 0.22 (solving P(u, w, 10(u − 0.9))
        // = P(0.7, 0.764, 0)); drawn back to front, that pixel shows the slope's colour (v ≈ 0.22
        // interpolated there: level ⌊(½ + ½·0.22)·LEVELS⌋ = 18 of 30), not the floor's (v = 0: the
        // middle level).
        let (nt, nz) = (11, 5);
        let values: Vec<Vec<f64>> = (0..nt).map(|k| vec![if k == nt - 1 { 1.0 } else { 0.0 }; nz]).collect();
        let s = Heatmap {
            name: "ridge".into(),
            t: (0..nt).map(|k| k as f64).collect(),
            z: (0..nz).map(|j| j as f64 * 0.5).collect(),
            values,
            value_label: "v (m)".into(),
            // colour scale ±1 (the whole run)
            scale_from: 0.0,
            vmax: None,
        };
        let r = draw_surface(&s, VIEW, height_range(&s), &[0.0, 1.0]);
        let level = |p: (f64, f64)| {
            let ix = r.data[(p.1.floor() as i32 - r.off.1) as usize * r.w + (p.0.floor() as i32 - r.off.0) as usize];
            ix as usize / SHADES
        };
        let slope = level(VIEW.at(0.7, 0.764, 0.0));
        assert!((17..=19).contains(&slope), "the floor behind the slope is hidden: level {slope}");
        // A floor point not behind it shows the floor: v = 0, the middle level.
        assert_eq!(level(VIEW.at(0.2, 0.5, 0.0)), LEVELS / 2);
    }

    #[test]
    fn painter_order_draws_the_nearer_quad_last() {
        // A 1-pixel raster point covered by two triangles: the later one wins.
        let mut r = Raster { w: 10, h: 10, off: (0, 0), data: vec![0; 100] };
        let flat = |level: f64| [(level, 0.0); 3];
        r.shaded_triangle([(0.0, 0.0), (10.0, 0.0), (0.0, 10.0)], flat(1.0));
        r.shaded_triangle([(0.0, 0.0), (10.0, 0.0), (0.0, 10.0)], flat(2.0));
        assert_eq!(r.data[2 * 10 + 2] as usize, 2 * SHADES);
        // A pixel well outside the triangle stays untouched.
        assert_eq!(r.data[9 * 10 + 9], 0);
    }
}
