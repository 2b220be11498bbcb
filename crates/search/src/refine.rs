//! Boundaries of the theory verdicts (W ≻ 0, (32) feasible) along each numeric axis: every
//! pair of grid neighbours whose verdicts differ brackets a boundary; with a tolerance the
//! bracket is bisected (geometric midpoint on log axes) using the theory alone, which is cheap
//! and needs no simulation. A W ≻ 0 boundary along `control.a` or `control.b` is a/b = ω₁, so
//! with a tolerance it is reported as the certified enclosure ω̲₁ ≤ ω₁ ≤ ω̄₁ of the continuous
//! model ([`wingcheck_claims::certify::omega1`], exact) instead of a bisected bracket.

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
    jobs.par_iter()
        .map(|&(p, d, kind, vp)| {
            tol.and_then(|_| certified(search, p, d, kind, vp))
                .unwrap_or_else(|| bisect(search, cache, p, d, kind, vp, tol))
        })
        .collect()
}

/// The W ≻ 0 boundary between point `p` and its upper neighbour along axis `d` from the
/// certified enclosure, when that axis is `control.a` or `control.b`: a ∈ [ω̲₁ b, ω̄₁ b] or
/// b ∈ [a/ω̄₁, a/ω̲₁] (rounded outwards). None — bisect instead — for other axes, without a
/// certificate, or if the interval does not lie inside the grid bracket.
fn certified(search: &Search, p: usize, d: usize, kind: usize, verdict_lo: bool) -> Option<BoundaryRow> {
    let axis = &search.grid.axes[d];
    if kind != 0 || !matches!(axis.key.as_str(), "control.a" | "control.b") {
        return None;
    }
    let cfg = apply_overrides(&search.base, &search.grid.overrides(p)).ok()?;
    let c = wingcheck_claims::certify::omega1::compute(&cfg).ok()?;
    let (w_lo, w_hi) = (c.1.lower_f64(), c.1.upper_f64());
    let (out_lo, out_hi) = (1.0 - 4.0 * f64::EPSILON, 1.0 + 4.0 * f64::EPSILON);
    let (lo, hi) = if axis.key == "control.a" {
        (w_lo * cfg.control.b * out_lo, w_hi * cfg.control.b * out_hi)
    } else {
        (cfg.control.a / w_hi * out_lo, cfg.control.a / w_lo * out_hi)
    };
    let i = search.grid.multi(p)[d];
    let (g0, g1) = (axis.numeric(i)?, axis.numeric(i + 1)?);
    if !(g0.min(g1) <= lo && hi <= g0.max(g1)) {
        return None;
    }
    let estimate = if axis.is_log() { (lo * hi).sqrt() } else { 0.5 * (lo + hi) };
    Some(BoundaryRow {
        kind: KINDS[kind],
        axis: d,
        point: p,
        lo,
        hi,
        estimate,
        verdict_at_lo: verdict_lo,
        bisections: 0,
        note: format!(
            "certified enclosure {} ≤ ω₁ ≤ {} rad/s of the continuous model (exact; omega1-enclosure.json)",
            wingcheck_claims::certify::omega1::exact_decimal(&c.1.lower),
            wingcheck_claims::certify::omega1::exact_decimal(&c.1.upper)
        ),
    })
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

/// `boundary.csv`: `kind,axis,<axis key columns…>,lo,hi,estimate,verdict_at_lo,bisections,note`
/// (docs/outputs.md); the axis-key columns hold the lower neighbour's values, with the
/// bisected axis' column set to the estimate; `lo`, `hi`, `estimate` are in the unit of the
/// key named in `axis`.
pub fn boundary_csv(grid: &Grid, rows: &[BoundaryRow]) -> String {
    let mut header = vec!["kind".to_string(), "axis".to_string()];
    header.extend(grid.axes.iter().map(|a| wingcheck_io::key_column(&a.key)));
    header.extend(["lo", "hi", "estimate", "verdict_at_lo", "bisections", "note"].map(String::from));
    let records = rows.iter().map(|r| {
        let mut vals = grid.texts(r.point);
        vals[r.axis] = wingcheck_io::number(r.estimate);
        let mut row = vec![r.kind.to_string(), grid.axes[r.axis].key.clone()];
        row.extend(vals);
        row.extend([
            wingcheck_io::number(r.lo),
            wingcheck_io::number(r.hi),
            wingcheck_io::number(r.estimate),
            r.verdict_at_lo.to_string(),
            r.bisections.to_string(),
            if r.note.is_empty() { "none".to_string() } else { r.note.clone() },
        ]);
        row
    });
    wingcheck_io::csv_text(header, records)
}
