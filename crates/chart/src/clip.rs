//! Plane geometry for the grid heatmap's marks, in pixel or plot coordinates: segments clipped
//! to a rectangle (plotters would pin coordinates outside the plot to its frame) and hatch
//! lines clipped to a convex polygon.

/// The part of segment p–q inside the rectangle `bounds` ((x0, x1), (y0, y1)), by
/// Liang–Barsky; None if it misses the rectangle.
pub(crate) fn clip_segment(
    p: (f64, f64),
    q: (f64, f64),
    bounds: ((f64, f64), (f64, f64)),
) -> Option<((f64, f64), (f64, f64))> {
    let (d0, d1) = (q.0 - p.0, q.1 - p.1);
    let ((x0, x1), (y0, y1)) = bounds;
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for (pk, qk) in [(-d0, p.0 - x0), (d0, x1 - p.0), (-d1, p.1 - y0), (d1, y1 - p.1)] {
        if pk == 0.0 {
            if qk < 0.0 {
                return None;
            }
        } else if pk < 0.0 {
            t0 = t0.max(qk / pk);
        } else {
            t1 = t1.min(qk / pk);
        }
    }
    (t0 <= t1).then_some(((p.0 + t0 * d0, p.1 + t0 * d1), (p.0 + t1 * d0, p.1 + t1 * d1)))
}

/// Spacing (displayed px) of hatch lines.
pub(crate) const HATCH_STEP: u32 = 9;

/// Hatch lines (pixel coordinates, slope −1: lower left to upper right on screen) spaced
/// `step` px apart, clipped to the convex polygon `corners` (either orientation) and to the
/// columns `x_clip`: each line x + y = k·step, clipped by Cyrus–Beck against every edge.
pub(crate) fn hatch(corners: &[(f64, f64)], step: f64, x_clip: (i32, i32)) -> Vec<[(i32, i32); 2]> {
    let n = corners.len();
    if n < 3 || step <= 0.0 {
        return Vec::new();
    }
    // Orientation (signed area) so that "inside" is on the same side of every edge.
    let area2: f64 = (0..n)
        .map(|i| {
            let (a, b) = (corners[i], corners[(i + 1) % n]);
            a.0 * b.1 - b.0 * a.1
        })
        .sum();
    let sign = if area2 >= 0.0 { 1.0 } else { -1.0 };
    let (x0, x1) = (f64::from(x_clip.0), f64::from(x_clip.1));
    let sums = corners.iter().map(|p| p.0 + p.1);
    let (kmin, kmax) = sums.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(v), h.max(v)));
    let mut out = Vec::new();
    let mut k = (kmin / step).ceil();
    while k * step <= kmax {
        // The line p(t) = (t, k·step − t), t = x.
        let c = k * step;
        let (mut t0, mut t1) = (x0, x1);
        for i in 0..n {
            let (a, b) = (corners[i], corners[(i + 1) % n]);
            // inside: sign · cross(b − a, p − a) ≥ 0, linear in t: α t + β ≥ 0
            let (ex, ey) = (b.0 - a.0, b.1 - a.1);
            let alpha = sign * (-ex - ey);
            let beta = sign * (ex * (c - a.1) - ey * (-a.0));
            if alpha.abs() < 1e-12 {
                if beta < 0.0 {
                    t1 = t0 - 1.0;
                }
            } else if alpha > 0.0 {
                t0 = t0.max(-beta / alpha);
            } else {
                t1 = t1.min(-beta / alpha);
            }
        }
        if t1 > t0 {
            out.push([(t0.round() as i32, (c - t0).round() as i32), (t1.round() as i32, (c - t1).round() as i32)]);
        }
        k += 1.0;
    }
    out
}

/// Indices of the points of the polyline `p` (canvas coordinates) kept by Douglas–Peucker with
/// tolerance `tol`: every dropped point lies within `tol` of the segment between the kept points
/// around it. The ends are always kept. Iterative (no recursion depth limit).
pub(crate) fn simplified(p: &[(f64, f64)], tol: f64) -> Vec<usize> {
    let n = p.len();
    if n <= 2 {
        return (0..n).collect();
    }
    let mut keep = vec![false; n];
    keep[0] = true;
    keep[n - 1] = true;
    let mut stack = vec![(0usize, n - 1)];
    while let Some((a, b)) = stack.pop() {
        let (ax, ay) = p[a];
        let (dx, dy) = (p[b].0 - ax, p[b].1 - ay);
        let len = (dx * dx + dy * dy).sqrt();
        let mut worst = (0.0, 0usize);
        for (k, &(x, y)) in p.iter().enumerate().take(b).skip(a + 1) {
            let d = if len > 0.0 {
                ((x - ax) * dy - (y - ay) * dx).abs() / len
            } else {
                ((x - ax).powi(2) + (y - ay).powi(2)).sqrt()
            };
            if d > worst.0 {
                worst = (d, k);
            }
        }
        if worst.0 > tol {
            keep[worst.1] = true;
            stack.push((a, worst.1));
            stack.push((worst.1, b));
        }
    }
    (0..n).filter(|&k| keep[k]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_are_clipped_to_the_plot_not_pinned_to_its_frame() {
        let unit = ((0.0, 1.0), (0.0, 1.0));
        // y = 2x − 0.5 from x = −1 to 1 crosses the unit square from (0.25, 0) to (0.75, 1).
        let (a, b) = clip_segment((-1.0, -2.5), (1.0, 1.5), unit).unwrap();
        assert!(
            (a.0 - 0.25).abs() < 1e-12 && a.1.abs() < 1e-12 && (b.0 - 0.75).abs() < 1e-12 && (b.1 - 1.0).abs() < 1e-12
        );
        // Wholly outside: none; wholly inside: unchanged.
        assert_eq!(clip_segment((2.0, 0.0), (3.0, 1.0), unit), None);
        assert_eq!(clip_segment((0.1, 0.2), (0.3, 0.4), unit), Some(((0.1, 0.2), (0.3, 0.4))));
    }

    #[test]
    fn hatch_lines_stay_inside_the_polygon() {
        // The triangle (0,0), (100,0), (0,100): lines x + y = k·10 for k = 1..10 run from
        // (0, 10k) to (10k, 0) — wholly inside, end points on the legs (reference: geometry);
        // k = 0 touches the corner only and is not drawn.
        let tri = [(0.0, 0.0), (100.0, 0.0), (0.0, 100.0)];
        let lines = hatch(&tri, 10.0, (-1000, 1000));
        assert_eq!(lines.len(), 10, "{lines:?}");
        for (i, l) in lines.iter().enumerate() {
            let c = 10 * (i as i32 + 1);
            assert_eq!(*l, [(0, c), (c, 0)], "line {}", i + 1);
        }
        // Clipped to columns x ∈ [0, 30]: no point beyond x = 30; same with the other orientation.
        let rev = [(0.0, 100.0), (100.0, 0.0), (0.0, 0.0)];
        for l in hatch(&rev, 10.0, (0, 30)) {
            assert!(l.iter().all(|p| (0..=30).contains(&p.0) && p.0 + p.1 <= 100), "{l:?}");
        }
    }
}

#[cfg(test)]
mod simplify_tests {
    use super::simplified;

    #[test]
    fn a_straight_run_keeps_its_ends_and_a_corner_stays() {
        // Reference: collinear points are within any tolerance of their chord; the corner of an
        // L is 50/√2 ≈ 35 px off the chord of the whole path.
        let line: Vec<(f64, f64)> = (0..100).map(|k| (k as f64, 2.0 * k as f64)).collect();
        assert_eq!(simplified(&line, 1.0), vec![0, 99]);
        let l: Vec<(f64, f64)> = (0..=50).map(|k| (k as f64, 0.0)).chain((1..=50).map(|k| (50.0, k as f64))).collect();
        assert_eq!(simplified(&l, 1.0), vec![0, 50, 100]);
    }
}
