//! Text labels placed without overlaps: each label's box is estimated from its text (plotters
//! only estimates text width too; the viewer's sans-serif font draws it), and labels are
//! taken in priority order, a label whose box (with a margin) meets one already taken being
//! left out. Its tick mark is drawn still: only the text goes.

use plotters::style::text_anchor::{HPos, VPos};

/// Font size of chart labels, displayed px.
pub(crate) const FONT_PX: f64 = 16.0;
/// Clear space kept around every label, displayed px (so two labels are at least twice this
/// apart).
pub(crate) const MARGIN_PX: f64 = 2.0;

/// A label: its text, the anchor point (displayed px) and how the text sits on it.
#[derive(Clone)]
pub(crate) struct Label {
    pub text: String,
    pub at: (f64, f64),
    pub h: HPos,
    pub v: VPos,
}

/// The width of `text` at [`FONT_PX`], from per-character widths of a Helvetica-like
/// sans-serif (in em: digits 0.556, `.` `,` and space 0.278, minus and `×` 0.584, brackets
/// 0.333, superscripts about 0.4), other characters at 0.65 em (wider than most letters, so the
/// estimate errs towards more room).
pub(crate) fn text_width(text: &str) -> f64 {
    let em: f64 = text
        .chars()
        .map(|c| match c {
            '0'..='9' => 0.556,
            '.' | ',' | ' ' => 0.278,
            '−' | '-' | '×' | '+' => 0.584,
            '(' | ')' => 0.333,
            '⁰' | '¹' | '²' | '³' | '⁴' | '⁵' | '⁶' | '⁷' | '⁸' | '⁹' | '⁻' => 0.4,
            _ => 0.65,
        })
        .sum();
    em * FONT_PX
}

impl Label {
    /// The label's box (x0, y0, x1, y1), displayed px: the estimated width by the font size.
    pub(crate) fn bounds(&self) -> (f64, f64, f64, f64) {
        let w = text_width(&self.text);
        let x0 = match self.h {
            HPos::Left => self.at.0,
            HPos::Center => self.at.0 - w / 2.0,
            HPos::Right => self.at.0 - w,
        };
        let y0 = match self.v {
            VPos::Top => self.at.1,
            VPos::Center => self.at.1 - FONT_PX / 2.0,
            VPos::Bottom => self.at.1 - FONT_PX,
        };
        (x0, y0, x0 + w, y0 + FONT_PX)
    }

    /// Whether the boxes of `self` and `other`, each grown by [`MARGIN_PX`], meet.
    pub(crate) fn meets(&self, other: &Label) -> bool {
        let (a, b) = (self.bounds(), other.bounds());
        let m = 2.0 * MARGIN_PX;
        a.0 < b.2 + m && b.0 < a.2 + m && a.1 < b.3 + m && b.1 < a.3 + m
    }
}

/// The labels to draw: `labels` in priority order, each kept unless it meets one kept before.
pub(crate) fn place(labels: Vec<Label>) -> Vec<Label> {
    let mut kept: Vec<Label> = Vec::with_capacity(labels.len());
    for l in labels {
        if !kept.iter().any(|k| k.meets(&l)) {
            kept.push(l);
        }
    }
    kept
}

#[cfg(test)]
mod tests {
    use super::*;

    fn label(text: &str, at: (f64, f64)) -> Label {
        Label { text: text.into(), at, h: HPos::Right, v: VPos::Center }
    }

    #[test]
    fn a_label_meeting_an_earlier_one_is_left_out() {
        // "0" and "−0.1136" right-aligned at the same x, 12 px apart vertically: boxes of 16 px
        // height overlap (12 < 16 + 2·2); 21 px apart they do not (21 > 20).
        let kept = place(vec![label("0", (100.0, 100.0)), label("−0.1136", (100.0, 112.0))]);
        assert_eq!(kept.len(), 1);
        assert_eq!(kept[0].text, "0");
        let kept = place(vec![label("0", (100.0, 100.0)), label("−0.1136", (100.0, 121.0))]);
        assert_eq!(kept.len(), 2);
        // side by side: "1.5" ends at 100, "2" starts 3 px later: too close (margins 2 + 2)
        let a = Label { text: "1.5".into(), at: (100.0, 50.0), h: HPos::Right, v: VPos::Top };
        let b = Label { text: "2".into(), at: (103.0, 50.0), h: HPos::Left, v: VPos::Top };
        assert!(a.meets(&b) && b.meets(&a));
        let c = Label { at: (105.0, 50.0), ..b };
        assert!(!a.meets(&c));
    }

    #[test]
    fn widths_follow_the_characters() {
        // "−0.1136": minus 0.584 + five digits 0.556 + point 0.278 = 3.642 em = 58.3 px at 16 px
        assert!((text_width("−0.1136") - 3.642 * 16.0).abs() < 1e-9);
        assert!(text_width("10⁻³") < text_width("1000"));
    }
}
