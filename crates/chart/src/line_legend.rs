//! The legend panel of a line chart ([`crate::line_svg`]): one entry per labelled line with its
//! swatch as drawn, each band, the markers and levels, text wrapped to the panel's width.

use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;

use crate::line_chart::{colours, vline_style, BandStyle, LineChart, LineStyle, MARK};
use crate::{px, DrawError};

/// Characters per line of the legend panel's text (17-px sans-serif in [`crate::line::LEGEND_W`] px less
/// the swatch).
const LEGEND_CHARS: usize = 23;

/// `text` wrapped at word boundaries into lines of at most [`LEGEND_CHARS`] characters (a
/// longer word is a line of its own).
fn wrap(text: &str) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for w in text.split(' ') {
        match lines.last_mut() {
            Some(l) if l.chars().count() + 1 + w.chars().count() <= LEGEND_CHARS => {
                l.push(' ');
                l.push_str(w);
            }
            _ => lines.push(w.to_string()),
        }
    }
    lines
}

/// Whether a line has a point that can be drawn on the chart's axes (finite, positive on a
/// log axis, inside a zoomed x range).
fn drawable(c: &LineChart, l: &crate::Line) -> bool {
    let (xa, xb) = c.x_range.unwrap_or((f64::NEG_INFINITY, f64::INFINITY));
    l.x.iter().zip(&l.y).any(|(x, y)| {
        x.is_finite()
            && y.is_finite()
            && (!c.data.log_x || *x > 0.0)
            && (!c.data.log_y || *y > 0.0)
            && *x >= xa
            && *x <= xb
    })
}

/// Draw a legend entry's text wrapped ([`wrap`]) with its first line beside the swatch at
/// height `y`; the height of its last line.
fn legend_text(
    area: &DrawingArea<SVGBackend, Shift>,
    text: &str,
    (x, y): (i32, i32),
    font: &TextStyle,
) -> Result<i32, DrawError> {
    let mut y = y;
    for (i, line) in wrap(text).into_iter().enumerate() {
        if i > 0 {
            y += px(21) as i32;
        }
        area.draw(&Text::new(line, (x, y - px(9) as i32), font.clone()))?;
    }
    Ok(y)
}

/// The legend panel: one entry per labelled line (swatch as drawn: the same line width and
/// dash pattern, or the marker), each band (a filled swatch), then the markers and levels. A
/// line with nothing drawable on these axes (e.g. 0 throughout on a log axis) says so.
pub(crate) fn draw_legend(area: &DrawingArea<SVGBackend, Shift>, c: &LineChart) -> Result<(), DrawError> {
    let pd = &c.data;
    let colours = colours(pd);
    let font = ("sans-serif", px(17)).into_font().color(&BLACK);
    let mut y = px(24) as i32;
    let x0 = px(10) as i32;
    let step = px(26) as i32;
    let swatch = |y: i32| vec![(x0, y), (x0 + px(28) as i32, y)];
    for (i, line) in pd.lines.iter().enumerate() {
        if line.label.is_empty() {
            continue;
        }
        let color = colours[i];
        // A line followed by an unlabelled marker series of the same colour gets both.
        let marked = line.points || pd.lines.get(i + 1).is_some_and(|n| n.label.is_empty() && n.points);
        if !line.points {
            let w = px(if i == 0 { 3 } else { 2 });
            if c.style(i) == LineStyle::Dashed {
                area.draw(&DashedPathElement::new(swatch(y), px(8), px(5), color.stroke_width(w)))?;
            } else if c.style(i) == LineStyle::Faint {
                let faint = color.mix(0.7).stroke_width(px(1));
                area.draw(&DashedPathElement::new(swatch(y), px(3), px(3), faint))?;
            } else {
                area.draw(&PathElement::new(swatch(y), color.stroke_width(w)))?;
            }
        }
        if marked {
            area.draw(&Circle::new((x0 + px(14) as i32, y), px(4), color.filled()))?;
        }
        let text = if drawable(c, line) {
            line.label.clone()
        } else if pd.log_y {
            format!("{} (≤ 0 throughout: not on the log axis)", line.label)
        } else {
            format!("{} (outside the plotted range)", line.label)
        };
        y = legend_text(area, &text, (x0 + px(36) as i32, y), &font)? + step;
    }
    for b in c.bands.iter().filter(|b| b.style != BandStyle::Hidden) {
        let color = colours.get(b.line).copied().unwrap_or(MARK);
        let (top, bottom) = (y - px(7) as i32, y + px(7) as i32);
        let r = Rectangle::new([(x0, top), (x0 + px(28) as i32, bottom)], color.mix(0.3).filled());
        area.draw(&r)?;
        if b.style == BandStyle::Edges {
            for edge in [top, bottom] {
                let l = vec![(x0, edge), (x0 + px(28) as i32, edge)];
                area.draw(&PathElement::new(l, color.stroke_width(px(2))))?;
            }
        }
        y = legend_text(area, &b.label, (x0 + px(36) as i32, y), &font)? + step;
    }
    let levels = c
        .vlines
        .iter()
        .enumerate()
        .map(|(k, v)| (v, vline_style(k)))
        .chain(c.hlines.iter().map(|h| (h, (px(3), px(4), MARK))));
    for ((_, label), (dash, gap, colour)) in levels {
        area.draw(&DashedPathElement::new(swatch(y), dash, gap, colour.stroke_width(px(2))))?;
        y = legend_text(area, label, (x0 + px(36) as i32, y), &font)? + step;
    }
    if let Some(s) = c.symlog() {
        y += step / 2;
        for line in s.note() {
            area.draw(&Text::new(line, (x0, y - px(9) as i32), font.clone()))?;
            y += step;
        }
    }
    Ok(())
}
