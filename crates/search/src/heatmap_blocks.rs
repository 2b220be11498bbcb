//! Blocks of grid cells for the heatmaps' marks, so that an SVG's size does not grow with the
//! number of points. The cells themselves are one raster image (its size is set by the display,
//! not the grid); the marks drawn over them — a circle or dot per cell, boundary segments
//! between cells, refined boundary points — are vector shapes, one per cell. Above
//! [`MARK_BLOCKS`] cells per axis the per-cell marks are drawn per block of k × l cells, where
//! every cell of the block holds; above [`SEGMENT_BLOCKS`] the boundaries are drawn between
//! blocks (a block that contains the boundary is outlined); at most [`MAX_REFINED`] refined
//! boundary points of each kind are drawn. The legend says so whenever it happens.

use wingcheck_chart::GridAxis;

/// Largest number of per-cell marks (circles, dots) along one axis.
pub const MARK_BLOCKS: usize = 32;
/// Largest number of blocks along one axis between which boundary segments are drawn.
pub const SEGMENT_BLOCKS: usize = 128;
/// Largest number of refined boundary points of one kind drawn (evenly thinned above).
pub const MAX_REFINED: usize = 256;

/// The cells of one axis grouped into consecutive blocks of `size` (the last may be shorter).
#[derive(Debug, Clone, Copy)]
pub struct AxisBlocks {
    /// Cells of the axis.
    pub cells: usize,
    /// Cells per block.
    pub size: usize,
}

impl AxisBlocks {
    /// Blocks of `cells` cells, at most `cap` of them.
    pub fn new(cells: usize, cap: usize) -> Self {
        AxisBlocks { cells, size: cells.div_ceil(cap.max(1)).max(1) }
    }

    /// Number of blocks.
    pub fn count(&self) -> usize {
        self.cells.div_ceil(self.size)
    }

    /// The cells of block `b`.
    pub fn range(&self, b: usize) -> std::ops::Range<usize> {
        b * self.size..((b + 1) * self.size).min(self.cells)
    }
}

/// Cell edge `i` of axis `a` in axis values (the midpoints between centres; the ends half a
/// spacing out, geometric on a log axis).
pub fn edge(a: &GridAxis, i: usize) -> f64 {
    let c = |k: usize| if a.log { a.centres[k].log10() } else { a.centres[k] };
    let n = a.centres.len();
    let e = if n == 1 {
        c(0) + if i == 0 { -0.5 } else { 0.5 }
    } else if i == 0 {
        c(0) - 0.5 * (c(1) - c(0))
    } else if i == n {
        c(n - 1) + 0.5 * (c(n - 1) - c(n - 2))
    } else {
        0.5 * (c(i - 1) + c(i))
    };
    if a.log {
        10f64.powf(e)
    } else {
        e
    }
}

/// Where a block's mark is drawn: its cell's centre for a block of one cell, else the middle of
/// its edges (geometric on a log axis).
pub fn block_centre(a: &GridAxis, blocks: &AxisBlocks, b: usize) -> f64 {
    let r = blocks.range(b);
    if r.len() == 1 {
        return a.centres[r.start];
    }
    let (lo, hi) = (edge(a, r.start), edge(a, r.end));
    if a.log {
        (lo * hi).sqrt()
    } else {
        0.5 * (lo + hi)
    }
}

/// A block's verdict: every known cell true, every known cell false, or both kinds present;
/// None when no cell of the block is known.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BlockVerdict {
    /// Every known cell holds.
    True,
    /// No known cell holds.
    False,
    /// The boundary passes through the block.
    Mixed,
}

/// The verdict of the block of cells `cells` (each `Some(holds)` or unknown).
pub fn block_verdict(cells: impl Iterator<Item = Option<bool>>) -> Option<BlockVerdict> {
    let (mut t, mut f) = (false, false);
    for v in cells.flatten() {
        if v {
            t = true;
        } else {
            f = true;
        }
    }
    match (t, f) {
        (true, true) => Some(BlockVerdict::Mixed),
        (true, false) => Some(BlockVerdict::True),
        (false, true) => Some(BlockVerdict::False),
        (false, false) => None,
    }
}

/// The legend's note for marks drawn per block ("" for single cells).
pub fn block_note(x: &AxisBlocks, y: &AxisBlocks, what: &str) -> String {
    if x.size == 1 && y.size == 1 {
        String::new()
    } else {
        format!(" ({what} per block of {} × {} cells)", x.size, y.size)
    }
}

/// At most [`MAX_REFINED`] of `points`, evenly spaced in their order, and the legend's note.
pub fn thin_refined(points: Vec<(f64, f64)>) -> (Vec<(f64, f64)>, String) {
    let n = points.len();
    if n <= MAX_REFINED {
        return (points, String::new());
    }
    let step = n.div_ceil(MAX_REFINED);
    let kept: Vec<_> = points.into_iter().step_by(step).collect();
    let note = format!(" (one in {step} of {n} shown)");
    (kept, note)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocks_cover_every_cell_once_and_respect_the_cap() {
        for cells in [1usize, 7, 32, 33, 64, 1000, 4097] {
            for cap in [1usize, 32, 128] {
                let b = AxisBlocks::new(cells, cap);
                assert!(b.count() <= cap.max(1) && b.count() >= 1, "{cells} {cap}");
                let covered: Vec<usize> = (0..b.count()).flat_map(|k| b.range(k)).collect();
                assert_eq!(covered, (0..cells).collect::<Vec<_>>(), "{cells} {cap}");
            }
        }
        // up to the cap, one block per cell: the marks are the per-cell marks
        assert_eq!(AxisBlocks::new(32, 32).size, 1);
        assert_eq!(AxisBlocks::new(33, 32).size, 2);
    }

    #[test]
    fn a_block_is_mixed_only_with_both_verdicts_and_unknown_cells_are_ignored() {
        use BlockVerdict::*;
        assert_eq!(block_verdict([Some(true), None, Some(true)].into_iter()), Some(True));
        assert_eq!(block_verdict([Some(false), None].into_iter()), Some(False));
        assert_eq!(block_verdict([Some(true), Some(false)].into_iter()), Some(Mixed));
        assert_eq!(block_verdict([None, None].into_iter()), None);
    }

    #[test]
    fn refined_points_are_thinned_to_the_cap_evenly() {
        let pts: Vec<(f64, f64)> = (0..1000).map(|i| (i as f64, 0.0)).collect();
        let (kept, note) = thin_refined(pts);
        assert!(kept.len() <= MAX_REFINED && kept.len() >= MAX_REFINED / 2);
        assert_eq!(kept[1].0 - kept[0].0, 4.0);
        assert_eq!(note, " (one in 4 of 1000 shown)");
    }
}
