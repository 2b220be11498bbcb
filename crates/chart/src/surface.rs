//! A field v(z,t) drawn as a 3-D surface over the (t, z) floor, like the paper's Figures 3–6 and
//! 13–14: an axonometric view (t running towards the viewer, z away from them, v up),
//! quads filled back to front (painter's order) with the colour-map coordinate and the shade
//! interpolated per pixel from the quad's corners (Gouraud: the colour varies continuously
//! with the field, so it shows no stair-steps along the quads' edges, and the shade follows the
//! surface's vertex normals, so neighbouring quads show no streaks), mesh lines at about ten
//! span positions and every few time samples.
//!
//! The surface, the floor and the back walls are one indexed PNG raster (one pixel per
//! displayed pixel): [`LEVELS`] colours × [`SHADES`] shades, each pixel's continuous colour and
//! shade *ordered-dithered* between the two nearest entries (a 2 × 2 Bayer matrix: four
//! sub-levels, so 4·[`LEVELS`] colour steps and 4·[`SHADES`] shade steps as the eye averages
//! them, with no bands), deterministic by the pixel's position. Indexed and dithered rather
//! than truecolour for the folder's size: measured on the paper's and the b = 3000 fields, a
//! truecolour raster was 3 to 5 times the old 30-level one (70–130 kB a surface, over the 4-MB
//! folder bound), this 1.1 to 1.25 times. The colour bar is a small truecolour gradient; axes,
//! ticks and labels are vector. Heights are to scale
//! over the whole run; the colour is the companion heatmap's (±max |v| over t ≥
//! [`Heatmap::scale_from`], earlier values saturate), so the residual motion that is flat at
//! this height scale still shows.

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::field::{coolwarm_rgb, locate};
use crate::labels::{place, Label};
use crate::Heatmap;
use crate::{linear_ticks, px, scaled_svg_header, tick, tick_linear, ChartError, DrawError, CANVAS, SCALE};

/// At most this many time strips are drawn (samples are taken evenly; the CSV has them all).
const MAX_STRIPS: usize = 160;
/// A mesh line across the span every this many strips.
const MESH_EVERY: usize = 16;
/// At least this many span rows are drawn (interpolated between the grid's points).
const MIN_ROWS: usize = 64;
/// About this many mesh lines along t (at evenly spaced span positions).
const MESH_Z: usize = 10;
/// Colour levels × shade levels of the palette (252 of 256 entries, 3 reserved below).
const LEVELS: usize = 42;
const SHADES: usize = 6;
/// The background, the back walls' and floor's lines, the front edges (palette entries after
/// the colours, with these RGB values).
const PAPER_IX: u8 = (LEVELS * SHADES) as u8;
const WALL_IX: u8 = PAPER_IX + 1;
const EDGE_IX: u8 = PAPER_IX + 2;
const RESERVED: [[u8; 3]; 3] = [[255, 255, 255], [215, 215, 215], [120, 120, 120]];
/// Shading darkens by at most a quarter (factor 0.75 … 1), so a quad's colour stays readable
/// on the colour bar (which shows the unshaded colour); mesh lines are drawn at this factor.
const SHADE_MIN: f64 = 0.75;
const MESH_SHADE: f64 = 0.82;
/// The 2 × 2 Bayer matrix: thresholds (k + ½)/4 by the pixel's position.
const BAYER: [[f64; 2]; 2] = [[0.0, 2.0], [3.0, 1.0]];

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

/// The colour of colour-map coordinate `u` ∈ [0, 1] ([`coolwarm_rgb`]) darkened by the shade
/// factor `f` ∈ [[`SHADE_MIN`], 1], rounded once to 8 bits a channel.
fn shaded(u: f64, f: f64) -> [u8; 3] {
    coolwarm_rgb(u).map(|c| (c * f).round().clamp(0.0, 255.0) as u8)
}

/// The palette: colour level l (colour-map coordinate l/(LEVELS − 1)) at shade s (factor
/// SHADE_MIN … 1) is entry l·SHADES + s; then [`RESERVED`].
fn palette() -> Vec<[u8; 3]> {
    let mut p = Vec::with_capacity(256);
    for l in 0..LEVELS {
        for s in 0..SHADES {
            let f = SHADE_MIN + (1.0 - SHADE_MIN) * s as f64 / (SHADES - 1) as f64;
            p.push(shaded(l as f64 / (LEVELS - 1) as f64, f));
        }
    }
    p.extend(RESERVED);
    p
}

/// The palette entry of colour-map coordinate `u` ∈ [0, 1] at shade factor `f` at pixel
/// (x, y): each ordered-dithered to one of its two nearest levels (the Bayer threshold at the
/// pixel; the shade's matrix shifted by a row, so the two do not step together).
fn dithered(x: i32, y: i32, u: f64, f: f64) -> u8 {
    let t = |dy: i32| (BAYER[((y + dy) & 1) as usize][(x & 1) as usize] + 0.5) / 4.0;
    let level = ((u.clamp(0.0, 1.0) * (LEVELS - 1) as f64 + t(0)).floor() as usize).min(LEVELS - 1);
    let fs = ((f - SHADE_MIN) / (1.0 - SHADE_MIN)).clamp(0.0, 1.0);
    let shade = ((fs * (SHADES - 1) as f64 + t(1)).floor() as usize).min(SHADES - 1);
    (level * SHADES + shade) as u8
}

/// The palette entry of a mesh line over colour-map coordinate `u`: the nearest level at the
/// shade nearest [`MESH_SHADE`].
fn mesh_entry(u: f64) -> u8 {
    let level = (u.clamp(0.0, 1.0) * (LEVELS - 1) as f64).round() as usize;
    let shade = ((MESH_SHADE - SHADE_MIN) / (1.0 - SHADE_MIN) * (SHADES - 1) as f64).round() as usize;
    (level * SHADES + shade) as u8
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
    /// functions), so shared edges are never left open — each pixel's colour-map coordinate
    /// and shade factor interpolated linearly (barycentric weights of the pixel centre, clamped
    /// to the triangle) from the corners' `(u, shade)`, both continuous, then dithered to the
    /// palette ([`dithered`]).
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
                    self.set(x, y, dithered(x, y, at(|a| a.0), at(|a| a.1)));
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
        data: vec![PAPER_IX; ((bx1 - bx0) * (by1 - by0)) as usize],
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
        SHADE_MIN + (1.0 - SHADE_MIN) * (0.25 + 0.75 * lambert)
    };
    let u_of = |v: f64| (0.5 + 0.5 * v / cmax).clamp(0.0, 1.0);
    for &(_, i, j) in &quads {
        let c = [point(ks[i], j), point(ks[i + 1], j), point(ks[i + 1], j + 1), point(ks[i], j + 1)];
        let attr = [
            (u_of(c[0].3), shade_at(i, j)),
            (u_of(c[1].3), shade_at(i + 1, j)),
            (u_of(c[2].3), shade_at(i + 1, j + 1)),
            (u_of(c[3].3), shade_at(i, j + 1)),
        ];
        let mean = 0.25 * c.iter().map(|p| p.3).sum::<f64>();
        let p: Vec<(f64, f64)> = c.iter().map(|q| view.at(q.0, q.1, q.2)).collect();
        r.shaded_triangle([p[0], p[1], p[2]], [attr[0], attr[1], attr[2]]);
        r.shaded_triangle([p[0], p[2], p[3]], [attr[0], attr[2], attr[3]]);
        let line = mesh_entry(u_of(mean));
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
    let err = |cause: DrawError| ChartError { name: s.name.clone(), cause };
    let (nt, nz) = (s.t.len(), s.z.len());
    if nt < 2 || nz < 2 || s.values.len() != nt || s.values.iter().any(|r| r.len() != nz) {
        return Err(err(DrawError::FieldShape));
    }
    let (vmin, vmax) = height_range(s);
    let cmax = s.scale();
    let (t0, t1, z0, z1) = (s.t[0], s.t[nt - 1], s.z[0], s.z[nz - 1]);
    let view = VIEW;
    // the height axis labelled up to the peak (and down to the lowest value)
    let round = linear_ticks(vmin, vmax, 5);
    let vt = crate::with_ends(&round, vmin, vmax, 0.08);
    let (bx0, by0, bx1, by1) = view.bounds();
    let r = draw_surface(s, view, (vmin, vmax), &vt);
    let png = indexed_png(&r).map_err(err)?;
    // the colour bar's gradient, one pixel per displayed pixel of its height, top = +cmax
    let (cx, cy0, cy1) = (890.0, 40.0, 360.0);
    let bar_h = (cy1 - cy0) as usize;
    let bar: Vec<[u8; 3]> = (0..bar_h).map(|y| shaded(1.0 - (y as f64 + 0.5) / bar_h as f64, 1.0)).collect();
    let bar_png = rgb_png(1, bar_h, &bar).map_err(err)?;

    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, CANVAS).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(e.into()))?;
        let e = |e: DrawingAreaErrorKind<std::io::Error>| err(e.into());
        let c = |p: (f64, f64)| ((p.0 * SCALE as f64).round() as i32, (p.1 * SCALE as f64).round() as i32);
        let font = |h: HPos, v: VPos| {
            ("sans-serif", px(crate::labels::FONT_PX as u32)).into_font().color(&BLACK).pos(Pos::new(h, v))
        };
        let axis = BLACK.stroke_width(px(1));
        // Labels in priority order (axis titles, round ticks, then the added ends), each drawn
        // unless it meets one before it (labels::place); tick marks are all drawn.
        let (mut titles, mut ticks, mut ends) = (Vec::new(), Vec::new(), Vec::new());
        let label = |text: String, at: (f64, f64), h: HPos, v: VPos| Label { text, at, h, v };
        // t along the front-left edge, z along the front-right edge, v up the left corner; the
        // t labels sit 3 px lower than the tick's direction puts them, clear of the height
        // axis's lowest label at the shared corner.
        let tick_along = |from: (f64, f64), to: (f64, f64), out: (f64, f64), f: f64| {
            let p = (from.0 + f * (to.0 - from.0), from.1 + f * (to.1 - from.1));
            (p, (p.0 + out.0, p.1 + out.1))
        };
        let (o, tx, zx) = (view.at(0.0, 0.0, 0.0), view.at(1.0, 0.0, 0.0), view.at(1.0, 1.0, 0.0));
        for (from, to, out, drop, lo, hi, title, anchor) in [
            (o, tx, (-6.0, 7.0), 3.0, t0, t1, "t (s)", (HPos::Right, VPos::Top)),
            (tx, zx, (7.0, 6.0), 0.0, z0, z1, "z (m)", (HPos::Left, VPos::Top)),
        ] {
            root.draw(&PathElement::new(vec![c(from), c(to)], axis)).map_err(e)?;
            for v in linear_ticks(lo, hi, 5) {
                let (p, q) = tick_along(from, to, out, frac(v, lo, hi));
                root.draw(&PathElement::new(vec![c(p), c(q)], axis)).map_err(e)?;
                let at = (q.0 + 0.6 * out.0, q.1 + 0.6 * out.1 + drop);
                ticks.push(label(tick(v), at, anchor.0, anchor.1));
            }
            let mid = tick_along(from, to, out, 0.5).1;
            let at = (mid.0 + 5.5 * out.0, mid.1 + 5.5 * out.1);
            titles.push(label(title.to_string(), at, HPos::Center, VPos::Center));
        }
        let top = view.at(0.0, 0.0, 1.0);
        root.draw(&PathElement::new(vec![c(o), c(top)], axis)).map_err(e)?;
        for v in &vt {
            let p = view.at(0.0, 0.0, frac(*v, vmin, vmax));
            root.draw(&PathElement::new(vec![c(p), c((p.0 - 6.0, p.1))], axis)).map_err(e)?;
            let l = label(tick_linear(*v, vmax - vmin), (p.0 - 10.0, p.1), HPos::Right, VPos::Center);
            if round.contains(v) { &mut ticks } else { &mut ends }.push(l);
        }
        titles.push(label(s.value_label.clone(), (top.0, top.1 - 14.0), HPos::Center, VPos::Bottom));
        // Colour bar: the unshaded colour map as a gradient raster (embedded below), framed.
        root.draw(&Rectangle::new([c((cx, cy0)), c((cx + 18.0, cy1))], axis)).map_err(e)?;
        let bar_round = linear_ticks(-cmax, cmax, 4);
        for v in crate::with_ends(&bar_round, -cmax, cmax, 0.04) {
            let y = cy1 - frac(v, -cmax, cmax) * (cy1 - cy0);
            root.draw(&PathElement::new(vec![c((cx + 18.0, y)), c((cx + 23.0, y))], axis)).map_err(e)?;
            let l = label(tick_linear(v, 2.0 * cmax), (cx + 26.0, y), HPos::Left, VPos::Center);
            if bar_round.contains(&v) { &mut ticks } else { &mut ends }.push(l);
        }
        let at = (cx + 9.0, cy0 - 14.0);
        titles.push(label(format!("colour: {}", s.value_label), at, HPos::Center, VPos::Bottom));
        for l in place(titles.into_iter().chain(ticks).chain(ends).collect()) {
            root.draw(&Text::new(l.text, c(l.at), font(l.h, l.v))).map_err(e)?;
        }
        root.present().map_err(|e| err(e.into()))?;
    }
    let s4 = SCALE as i32;
    crate::embed_raster(&mut svg, &(bx0 * s4..bx1 * s4, by0 * s4..by1 * s4), &png).map_err(err)?;
    let (cx, cy0, cy1) = ((cx * SCALE as f64) as i32, (cy0 * SCALE as f64) as i32, (cy1 * SCALE as f64) as i32);
    crate::embed_raster(&mut svg, &(cx..cx + 18 * s4, cy0..cy1), &bar_png).map_err(err)?;
    Ok(scaled_svg_header(svg))
}

/// The raster as an indexed PNG with [`palette`].
fn indexed_png(r: &Raster) -> Result<Vec<u8>, DrawError> {
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, r.w as u32, r.h as u32);
        enc.set_color(png::ColorType::Indexed);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_palette(palette().as_flattened().to_vec());
        enc.set_compression(png::Compression::Best);
        let mut wr = enc.write_header()?;
        wr.write_image_data(&r.data)?;
    }
    Ok(out)
}

/// A truecolour PNG of `w × h` pixels (rows top to bottom), filtered per row adaptively (a
/// smooth gradient leaves small repeating differences, which deflate compresses well).
fn rgb_png(w: usize, h: usize, data: &[[u8; 3]]) -> Result<Vec<u8>, DrawError> {
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, w as u32, h as u32);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_compression(png::Compression::Best);
        enc.set_adaptive_filter(png::AdaptiveFilterType::Adaptive);
        let mut wr = enc.write_header()?;
        wr.write_image_data(data.as_flattened())?;
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

    fn ridge(nt: usize, nz: usize, v: impl Fn(usize, usize) -> f64) -> Heatmap {
        Heatmap {
            name: "ridge".into(),
            t: (0..nt).map(|k| k as f64).collect(),
            z: (0..nz).map(|j| j as f64 * 0.5).collect(),
            values: (0..nt).map(|k| (0..nz).map(|j| v(k, j)).collect()).collect(),
            value_label: "v (m)".into(),
            // colour scale ±max |v| (the whole run)
            scale_from: 0.0,
            vmax: None,
        }
    }

    /// The colour at a displayed point.
    fn pixel(r: &Raster, p: (f64, f64)) -> [u8; 3] {
        at(r, p.0.floor() as i32, p.1.floor() as i32)
    }

    /// The colour of pixel (x, y).
    fn at(r: &Raster, x: i32, y: i32) -> [u8; 3] {
        palette()[r.data[(y - r.off.1) as usize * r.w + (x - r.off.0) as usize] as usize]
    }

    /// The mean colour of the 2 × 2 dither cell holding pixel (x, y) (what the eye sees).
    fn cell_mean(r: &Raster, x: i32, y: i32) -> [f64; 3] {
        let (x0, y0) = (x & !1, y & !1);
        let mut m = [0.0; 3];
        for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            let c = at(r, x0 + dx, y0 + dy);
            (0..3).for_each(|k| m[k] += 0.25 * c[k] as f64);
        }
        m
    }

    #[test]
    fn a_ridge_in_front_hides_the_floor_behind_it() {
        // v = 1 on the last time sample (the edge nearest the viewer), 0 elsewhere: a slope
        // rising over the last strip, u ∈ [0.9, 1]. Reference: the projection (View constants).
        // The floor point F = (u, w) = (0.7, 0.764) lies behind the slope and projects onto the
        // same pixel as the slope point u ≈ 0.92, w ≈ 0.35, h ≈ 0.22 (solving P(u, w, 10(u − 0.9))
        // = P(0.7, 0.764, 0)); drawn back to front, that pixel shows the slope's colour (v ≈ 0.22
        // interpolated there: colour-map coordinate ½ + ½·0.22 = 0.61, coolwarm ≈ (243, 203,
        // 189), red above blue by ≈ 54, ≥ 40 after shading by ≥ 0.75, ≥ 35 with a dither step),
        // not the floor's (v = 0: coolwarm(½) = (242, 242, 242), grey; dithered to the levels
        // 20/41 or 21/41 on either side, red and blue within 8 of each other).
        let s = ridge(11, 5, |k, _| if k == 10 { 1.0 } else { 0.0 });
        let r = draw_surface(&s, VIEW, height_range(&s), &[0.0, 1.0]);
        let [red, _, blue] = pixel(&r, VIEW.at(0.7, 0.764, 0.0));
        assert!(red as i32 - blue as i32 >= 35, "the floor behind the slope is hidden: {red} {blue}");
        // A floor point not behind it shows the floor: grey.
        let [red, green, blue] = pixel(&r, VIEW.at(0.2, 0.5, 0.0));
        assert!((red as i32 - blue as i32).abs() <= 8 && green >= 170, "{red} {green} {blue}");
    }

    #[test]
    fn a_linear_field_is_drawn_without_bands() {
        // v = ½ − t/40 over t ∈ [0, 40] (a ramp falling towards the viewer, so nothing hides
        // it; flat in z), coloured on ±½: the colour-map coordinate runs linearly from 1 to 0
        // along t. Along the line w = 0.55 (between mesh lines) for u ∈ [0.42, 0.78] (between the
        // cross-span mesh lines at strips 16 and 32 of 40), the colour as the eye sees it (the
        // mean of each 2 × 2 dither cell) changes from cell to cell by at most the map's
        // steepest slope over a cell plus a quarter level: coolwarm's stops are 0.25 apart with
        // at most 150 of a channel between them (green 154 → 4), so 600 a unit of u; the t axis
        // is ≈ 478 px, a cell ≈ 3 px along the line: 600·3/478 ≈ 3.8, plus 600/(4·41) ≈ 3.7 and
        // a shade step's quarter (≈ 3): ≤ 11. The former 30 levels stepped by 600/30 = 20 at
        // once. Reference: coolwarm's stops in field.rs, the View constants, LEVELS.
        let s = ridge(41, 5, |k, _| 0.5 - k as f64 / 40.0);
        let r = draw_surface(&s, VIEW, height_range(&s), &[0.0]);
        let mut cells: Vec<((i32, i32), [f64; 3])> = Vec::new();
        for i in 0..=720 {
            let u = 0.42 + 0.36 * i as f64 / 720.0;
            let p = VIEW.at(u, 0.55, 1.0 - u);
            let (x, y) = (p.0.floor() as i32, p.1.floor() as i32);
            if cells.last().is_none_or(|c| c.0 != (x & !1, y & !1)) {
                cells.push(((x & !1, y & !1), cell_mean(&r, x, y)));
            }
        }
        let step = |a: &[f64; 3], b: &[f64; 3]| (0..3).map(|k| (a[k] - b[k]).abs()).fold(0.0, f64::max);
        let largest = cells.windows(2).map(|w| step(&w[0].1, &w[1].1)).fold(0.0, f64::max);
        assert!(largest <= 11.0, "a step of {largest} between neighbouring cells");
        let mut distinct: Vec<[u64; 3]> = cells.iter().map(|c| c.1.map(|v| (v * 4.0) as u64)).collect();
        distinct.sort();
        distinct.dedup();
        // The ramp spans 0.36 of the map: 0.36·4·41 ≈ 59 dithered steps; 30 levels would give
        // 0.36·30 ≈ 11 bands and at most two mixed cells at each edge, ≤ 33 distinct colours.
        assert!(distinct.len() >= 45, "{} distinct colours in {} cells", distinct.len(), cells.len());
        // and the ramp's ends are the map's colours there, shaded: colour-map coordinate 0.58
        // (coolwarm ≈ (243, 214, 204): red above blue by ≈ 39, ≥ 29 shaded) and 0.22 (≈ (131,
        // 164, 247): blue above red by ≈ 116, ≥ 87 shaded)
        let (first, last) = (cells[0].1, cells[cells.len() - 1].1);
        assert!(first[0] - first[2] > 25.0 && last[2] - last[0] > 80.0, "{first:?} {last:?}");
    }

    #[test]
    fn painter_order_draws_the_nearer_quad_last() {
        // A 1-pixel raster point covered by two triangles: the later one wins.
        let mut r = Raster { w: 10, h: 10, off: (0, 0), data: vec![PAPER_IX; 100] };
        let flat = |u: f64| [(u, 1.0); 3];
        r.shaded_triangle([(0.0, 0.0), (10.0, 0.0), (0.0, 10.0)], flat(0.0));
        r.shaded_triangle([(0.0, 0.0), (10.0, 0.0), (0.0, 10.0)], flat(1.0));
        // coolwarm(1) = (180, 4, 38) (field.rs's last stop), the last level, unshaded
        assert_eq!(palette()[r.data[2 * 10 + 2] as usize], [180, 4, 38]);
        // A pixel well outside the triangle stays untouched.
        assert_eq!(r.data[9 * 10 + 9], PAPER_IX);
    }

    #[test]
    fn height_labels_never_overlap_and_round_ticks_win() {
        // A field from `low` to 1 (Figure 5's range at the paper's point is −0.1136 … 1). The
        // height axis is 205 px: its lowest value `low` sits 205·|low|/(1 − low) px below the 0
        // tick. Labels 16 px high with 2 px clear around need 20 px: at −0.1136 that is 20.9 px,
        // so both show; at −0.09, 16.9 px: the end gives way to the round tick 0 (it used to
        // be drawn over it). Reference: the View constants and labels::place.
        let texts = |low: f64| {
            let svg = surface_svg(&ridge(21, 4, |k, j| {
                if k == 0 && j == 3 {
                    1.0
                } else if k == 2 {
                    low
                } else {
                    0.0
                }
            }))
            .unwrap();
            svg.split("<text")
                .skip(1)
                .filter_map(|t| Some(t.split_once('>')?.1.split_once('<')?.0.trim().to_string()))
                .collect::<Vec<_>>()
        };
        let at = texts(-0.1136);
        assert!(at.iter().any(|t| t == "−0.1136") && at.iter().filter(|t| *t == "0").count() >= 2, "{at:?}");
        // every label of the colour bar (±1 at its ends) and of the t axis (0 … 20 s, as
        // Figure 5's) shows, clear of the titles
        for v in ["−1", "−0.5", "0.5", "1", "5", "10", "15", "20"] {
            assert!(at.iter().any(|t| t == v), "{v}: {at:?}");
        }
        let at = texts(-0.09);
        assert!(!at.iter().any(|t| t == "−0.09") && at.iter().any(|t| t == "0.2"), "{at:?}");
    }

    #[test]
    fn the_same_field_gives_the_same_bytes() {
        let s = ridge(31, 7, |k, j| ((k as f64) * 0.3).sin() * (j as f64 * 0.4).cos());
        assert_eq!(surface_svg(&s).unwrap(), surface_svg(&s).unwrap());
    }
}
