//! Boundaries of the theory verdicts (W ≻ 0, (32) feasible) along each numeric axis: every
//! pair of grid neighbours whose verdicts differ brackets a boundary; with a tolerance the
//! bracket is bisected (geometric midpoint on log axes) using the theory alone, which is cheap
//! and needs no simulation.

use rayon::prelude::*;
use wingcheck_model::apply_overrides;

use crate::axis::Grid;
use crate::point::PointVerdicts;
use crate::theory::TheoryCache;
use crate::Search;

/// Which verdict a boundary separates.
pub const KINDS: [&str; 2] = ["w_positive_definite", "feasible_32"];

/// One located boundary crossing.
#[derive(Debug, Clone, PartialEq)]
pub struct BoundaryRow {
    /// `w_positive_definite` or `feasible_32`.
    pub kind: &'static str,
    /// Axis bisected.
    pub axis: usize,
    /// Point index of the lower grid neighbour (its other coordinates are the row's).
    pub point: usize,
    /// Lower end of the final bracket (axis units).
    pub lo: f64,
    /// Upper end of the final bracket.
    pub hi: f64,
    /// Estimate: √(lo·hi) on log axes, (lo + hi)/2 otherwise.
    pub estimate: f64,
    /// Verdict at `lo` (the verdict at `hi` is its negation).
    pub verdict_at_lo: bool,
    /// Theory evaluations spent bisecting.
    pub bisections: usize,
    /// Set when a theory evaluation failed during bisection (the bracket is then wider).
    pub note: String,
}

fn verdict(p: &PointVerdicts, kind: usize) -> Option<bool> {
    if kind == 0 {
        p.w_positive_definite
    } else {
        p.feasible_32
    }
}

/// Brackets (and, with `tol`, refined brackets) of every verdict change between grid
/// neighbours (`points`: the verdicts of every point, in index order), ordered by (lower point index, axis, kind). Deterministic: each bracket is
/// bisected independently, results collected in order.
pub fn boundaries(
    search: &Search,
    points: &[PointVerdicts],
    cache: &TheoryCache,
    tol: Option<f64>,
) -> Vec<BoundaryRow> {
    let grid = &search.grid;
    let mut jobs = Vec::new();
    for p in 0..points.len() {
        let m = grid.multi(p);
        for (d, axis) in grid.axes.iter().enumerate() {
            if axis.numeric(0).is_none() || m[d] + 1 >= grid.dims()[d] {
                continue;
            }
            let mut mq = m.clone();
            mq[d] += 1;
            let q = grid.index(&mq);
            for kind in 0..KINDS.len() {
                if let (Some(vp), Some(vq)) = (verdict(&points[p], kind), verdict(&points[q], kind)) {
                    if vp != vq {
                        jobs.push((p, d, kind, vp));
                    }
                }
            }
        }
    }
    jobs.par_iter().map(|&(p, d, kind, vp)| bisect(search, cache, p, d, kind, vp, tol)).collect()
}

fn bisect(
    search: &Search,
    cache: &TheoryCache,
    p: usize,
    d: usize,
    kind: usize,
    verdict_lo: bool,
    tol: Option<f64>,
) -> BoundaryRow {
    let axis = &search.grid.axes[d];
    let i = search.grid.multi(p)[d];
    let value = |i: usize| axis.text(i).parse::<f64>().unwrap_or_else(|_| axis.numeric(i).expect("numeric"));
    let (mut lo, mut hi) = (value(i), value(i + 1));
    let span = (axis.numeric(axis.len() - 1).expect("numeric") - axis.numeric(0).expect("numeric")).abs();
    let log = axis.is_log();
    let mid = |lo: f64, hi: f64| if log { (lo * hi).sqrt() } else { 0.5 * (lo + hi) };
    let converged = |lo: f64, hi: f64, t: f64| if log { hi / lo - 1.0 <= t } else { hi - lo <= t * span };
    let mut overrides = search.grid.overrides(p);
    let mut bisections = 0;
    let mut note = String::new();
    // integer axes keep the grid bracket (no values in between to try)
    if let Some(t) = tol.filter(|_| !axis.integer) {
        while !converged(lo, hi, t) && bisections < 200 {
            let m = mid(lo, hi);
            if m <= lo || m >= hi {
                break;
            }
            overrides[d] = axis.override_value(m);
            let v = apply_overrides(&search.base, &overrides)
                .map_err(|e| e.to_string())
                .and_then(|cfg| cache.verdicts(&cfg).map_err(|e| e.to_string()));
            bisections += 1;
            let v = match v {
                Ok(v) if kind == 0 => Some(v.w_positive_definite()),
                Ok(v) => v.feasible_32(),
                Err(e) => {
                    note = e;
                    None
                }
            };
            match v {
                Some(v) if v == verdict_lo => lo = m,
                Some(_) => hi = m,
                None => {
                    if note.is_empty() {
                        note = "theory undetermined (solver status)".into();
                    }
                    break;
                }
            }
        }
    }
    BoundaryRow {
        kind: KINDS[kind],
        axis: d,
        point: p,
        lo,
        hi,
        estimate: mid(lo, hi),
        verdict_at_lo: verdict_lo,
        bisections,
        note,
    }
}

/// `boundary.csv`: `kind,axis,<axis keys…>,lo,hi,estimate,verdict_at_lo,bisections,note`;
/// the axis-key columns hold the lower neighbour's values, with the bisected axis' column
/// set to the estimate.
pub fn boundary_csv(grid: &Grid, rows: &[BoundaryRow]) -> String {
    let keys: Vec<&str> = grid.axes.iter().map(|a| a.key.as_str()).collect();
    let mut out = format!("kind,axis,{},lo,hi,estimate,verdict_at_lo,bisections,note\n", keys.join(","));
    for r in rows {
        let mut vals = grid.texts(r.point);
        vals[r.axis] = format!("{}", r.estimate);
        let vals: Vec<String> =
            vals.iter().map(|v| if v.contains(',') { format!("\"{v}\"") } else { v.clone() }).collect();
        out.push_str(&format!(
            "{},{},{},{},{},{},{},{},{}\n",
            r.kind,
            keys[r.axis],
            vals.join(","),
            r.lo,
            r.hi,
            r.estimate,
            r.verdict_at_lo,
            r.bisections,
            r.note.replace(',', ";")
        ));
    }
    out
}
