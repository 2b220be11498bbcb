//! What a line chart shows ([`LineChart`]: its data, the style of each line, bands, markers,
//! levels, ranges) and the colours its lines and markers take; drawn by [`crate::line_svg`],
//! its legend panel by the legend's own module.

use plotters::style::RGBColor;

use crate::symlog::SymLog;
use crate::{px, PlotData, PALETTE};

/// How a line is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LineStyle {
    /// Polyline through the samples (or markers when the line asks for points).
    #[default]
    Solid,
    /// Zero-order hold: the value is held until the next sample (sampled signals).
    Step,
    /// Dashed polyline (reference lines, bounds).
    Dashed,
    /// A thin, light polyline: a secondary line under a band that is the main one (the output
    /// samples of a chattering signal, which alias it).
    Faint,
}

/// A band around a line: the signal's range between its samples (e.g. the full-rate min/max of
/// τ over each output interval, which the samples alone alias). Drawn as a translucent fill in
/// the line's colour, held over each interval (x_{k−1}, x_k] like the data it bounds; written to
/// the CSV as two columns beside the line's values.
#[derive(Debug, Clone, PartialEq)]
pub struct Band {
    /// Index of the line whose x the band uses (and whose colour).
    pub line: usize,
    /// Lower edge per sample of that line (over the interval ending there).
    pub lo: Vec<f64>,
    /// Upper edge per sample.
    pub hi: Vec<f64>,
    /// Legend text (e.g. `full-rate min … max per 10-ms output interval`).
    pub label: String,
    /// How it is drawn.
    pub style: BandStyle,
}

/// How a [`Band`] is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BandStyle {
    /// A translucent fill around its line.
    #[default]
    Shade,
    /// The fill with its edges as solid lines in the line's colour: the band is the main curve
    /// (a signal that chatters between its samples), not a shading around one.
    Edges,
    /// Not drawn and not in the legend (thinner than a line at the chart's scale), but written
    /// to the data file.
    Hidden,
}

/// A chart: the data and how to show it.
#[derive(Debug, Clone)]
pub struct LineChart {
    /// The data (labels with units, lines).
    pub data: PlotData,
    /// Style per line (missing entries: [`LineStyle::Solid`]).
    pub styles: Vec<LineStyle>,
    /// Show only this x range (the data outside is still in the CSV).
    pub x_range: Option<(f64, f64)>,
    /// Vertical markers at x with a label (e.g. `t_f = 0.054 s`).
    pub vlines: Vec<(f64, String)>,
    /// Horizontal levels at y with a label (e.g. the |g̃| threshold).
    pub hlines: Vec<(f64, String)>,
    /// A symmetric-log y axis with this transform (ignored when `data.log_y`); the legend panel
    /// states its linear threshold.
    pub symlog_y: Option<SymLog>,
    /// Show this y range instead of the data's padded range (a pair of figures on common axes).
    pub y_range: Option<(f64, f64)>,
    /// Bands around lines (full-rate ranges between samples).
    pub bands: Vec<Band>,
}

impl From<PlotData> for LineChart {
    fn from(data: PlotData) -> Self {
        LineChart {
            data,
            styles: Vec::new(),
            x_range: None,
            vlines: Vec::new(),
            hlines: Vec::new(),
            symlog_y: None,
            y_range: None,
            bands: Vec::new(),
        }
    }
}

impl LineChart {
    pub(crate) fn style(&self, i: usize) -> LineStyle {
        self.styles.get(i).copied().unwrap_or_default()
    }

    /// The symmetric-log transform of the y axis, if it has one.
    pub(crate) fn symlog(&self) -> Option<SymLog> {
        self.symlog_y.filter(|_| !self.data.log_y)
    }

    /// Every y value the chart shows (lines and bands inside the x range), for axis ranges.
    pub fn y_values(&self) -> Vec<f64> {
        let pd = &self.data;
        let in_x = |x: f64| (!pd.log_x || x > 0.0) && self.x_range.is_none_or(|(a, b)| x >= a && x <= b);
        let mut v: Vec<f64> =
            pd.lines.iter().flat_map(|l| l.x.iter().zip(&l.y).filter(|(x, _)| in_x(**x)).map(|(_, y)| *y)).collect();
        for b in &self.bands {
            if let Some(l) = pd.lines.get(b.line) {
                for (k, _) in l.x.iter().enumerate().filter(|(_, x)| in_x(**x)) {
                    v.extend(b.lo.get(k).copied().into_iter().chain(b.hi.get(k).copied()));
                }
            }
        }
        // the horizontal levels drawn (a threshold) are inside the axis too
        v.extend(self.hlines.iter().map(|(y, _)| *y).filter(|y| !pd.log_y || *y > 0.0));
        v.retain(|y| y.is_finite());
        v
    }

    /// The data as CSV: the lines as [`PlotData::to_csv`] writes them; with bands, two more
    /// columns (the band's lower and upper edge) on the rows of each line a band belongs to.
    pub fn to_csv(&self) -> String {
        self.to_csv_with(wingcheck_io::number)
    }

    /// [`LineChart::to_csv`] with the y values and band edges written by `value` (e.g. to the
    /// digits of their error); x in the shortest round-trip form. Long form `series,x,y`
    /// ([`PlotData::to_csv`]); with bands, `y_min,y_max` (the band's edges, empty on rows of a
    /// line without one).
    pub fn to_csv_with(&self, value: impl Fn(f64) -> String) -> String {
        let pd = &self.data;
        let banded = !self.bands.is_empty();
        let header: &[&str] = if banded { &["series", "x", "y", "y_min", "y_max"] } else { &["series", "x", "y"] };
        let rows = pd.lines.iter().enumerate().flat_map(|(i, l)| {
            let band = self.bands.iter().find(|b| b.line == i);
            let value = &value;
            l.x.iter().zip(&l.y).enumerate().map(move |(k, (x, y))| {
                let mut row = vec![l.label.clone(), wingcheck_io::number(*x), value(*y)];
                if banded {
                    let edges = band.and_then(|b| Some((b.lo.get(k)?, b.hi.get(k)?)));
                    let (lo, hi) = edges.map_or((String::new(), String::new()), |(a, b)| (value(*a), value(*b)));
                    row.extend([lo, hi]);
                }
                row
            })
        });
        wingcheck_io::csv_text(header.iter().copied(), rows)
    }

    /// The chart with its longest polylines thinned to at most [`crate::MAX_DRAWN_SAMPLES`]
    /// points (every k-th sample, [`crate::stride`]) and their bands merged over the k intervals
    /// (no extreme lost, [`crate::thin_band`]); marker lines and shorter lines unchanged. The
    /// stride k is returned too (1: unchanged).
    pub fn thinned(&self) -> (LineChart, usize) {
        let n = self.data.lines.iter().filter(|l| !l.points).map(|l| l.x.len()).max().unwrap_or(0);
        let k = crate::stride(n);
        if k == 1 {
            return (self.clone(), 1);
        }
        let keep = crate::kept(n, k);
        let mut c = self.clone();
        let full: Vec<bool> = c.data.lines.iter().map(|l| !l.points && l.x.len() == n && l.y.len() == n).collect();
        for (l, _) in c.data.lines.iter_mut().zip(&full).filter(|(_, f)| **f) {
            l.x = crate::thin(&l.x, &keep);
            l.y = crate::thin(&l.y, &keep);
        }
        for b in c.bands.iter_mut().filter(|b| full.get(b.line) == Some(&true) && b.lo.len() == n && b.hi.len() == n) {
            (b.lo, b.hi) = crate::thin_band(&b.lo, &b.hi, &keep);
        }
        (c, k)
    }

    /// What the CSV holds, for the provenance record.
    pub fn csv_contents(&self) -> String {
        let bands = if self.bands.is_empty() {
            String::new()
        } else {
            format!("; y_min, y_max = the band ({}) per output interval", self.bands[0].label)
        };
        format!("{}{bands}", self.data.csv_contents())
    }
}

/// Colour index of each line: a labelled line takes the next colour; an unlabelled one
/// (e.g. the markers of the previous line) reuses the last.
pub(crate) fn colours(pd: &PlotData) -> Vec<RGBColor> {
    let mut next = 0usize;
    pd.lines
        .iter()
        .map(|l| {
            if !l.label.is_empty() || next == 0 {
                next += 1;
            }
            PALETTE[(next - 1) % PALETTE.len()]
        })
        .collect()
}

/// Colour of markers and levels.
pub(crate) const MARK: RGBColor = RGBColor(90, 90, 90);

/// Dash, gap (canvas px) and colour of the `k`-th vertical marker: each marker of a chart drawn
/// differently, so two close ones (a measured time and its bound) stay apart in the legend.
pub(crate) fn vline_style(k: usize) -> (u32, u32, RGBColor) {
    const STYLES: [(u32, u32, RGBColor); 3] = [(6, 4, MARK), (14, 4, RGBColor(0, 0, 0)), (2, 3, RGBColor(140, 60, 0))];
    let (d, g, c) = STYLES[k % STYLES.len()];
    (px(d), px(g), c)
}
