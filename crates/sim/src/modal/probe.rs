//! The sub-step probe of the exponential scheme: the exact tip rates and controls *inside* the
//! first integrator step after each jump of the held inputs (and the following steps while an
//! output is still rising at a step's end, [`ProbedStep`]), where the step ends alone miss a
//! transient shorter than the step.
//!
//! With strong tip damping (large b) a jump of the held estimate ĝ sets off a tip transient
//! that peaks microseconds after the jump and has died out long before the step's end: at
//! a = 1, b = 3500 with the explicit FTDO the θ̇(s) peak 2 µs after the jump at t = 3 ms is 11 %
//! above every step-end value at dt = 1 ms (measured against dt = 1e-6 s). The initial layer
//! ([`crate::layer`]) re-runs the first sample periods at finer steps; after it, the jumps come
//! every sample period, and re-running them all is out of reach. But between two step ends the
//! exponential scheme's loop is linear time-invariant, X(t_k + s) = E(s) X_k
//! ([`super::exact`]), so the outputs inside the step are y_o(s) = c_oᵀE(s) X_k, exactly, for
//! the rows c_o of q(s), θ(s), q̇(s), θ̇(s), τ1, τ2 in X (the displacement peaks move too: at
//! a = 0.01, b = 1000, q(s) peaks 35 µs after the jump at 5 ms, 2e-8 above every step end).
//!
//! The grid of sub-instants comes from the scaling-and-squaring chain that builds E(h): it
//! passes through E(δ_i) for δ_i = s₀2^i, so the rows c_oᵀE(kδ_i) follow by one product per
//! point (level i's points stepped by E(δ_i) from c_oᵀE(Fδ_i), which the chain reaches log₂F
//! levels later). The fine grid has [`FINE_PER_OCTAVE`] = F points per octave of s between s₀
//! and h (s = kδ_i, k = F … 2F − 1 at level i ≥ 1, k = 1 … 2F − 1 at level 0), plus s = 0 and s = h
//! (the recorded instants); its points at s₀4^m are the coarse grid, one point per two octaves.
//! Rows are stored for q, θ, q̇, θ̇; τ_c = −k_c(a x_c + b v_c) − ĝ_c is formed from them. A probe
//! evaluates the coarse grid (4 × ≈ ½ log₂(‖A‖h) dot products of length N); for each output
//! whose largest coarse |y_o| may lie below the signal's running peak by less than the coarse
//! grid can miss ([`PROBE_MARGIN`]), it climbs the fine grid from that point to a local maximum
//! (within the coarse neighbours), and the parabola through it and its fine neighbours gives
//! how far the true maximum may lie above it ([`SubStepPeak::miss`]). Cost: measured 1.4 × the
//! stepping of the explicit FTDO's default run without the probe, 1.3 × the whole run (one
//! step per sample period, so every step is probed).
//!
//! Every probed value is a value the exact solution of the scheme's loop takes (from the
//! scheme's state at the step's start), so a probe can only raise a peak toward its true
//! value. What it does not see: a sub-step maximum away from the coarse grid's largest value
//! (two maxima within one step, or an oscillation faster than one point per two octaves of s),
//! and sub-step transients inside a sample period after the step means of ḡ and φ̄ change
//! (the later steps once no output is rising at a step's end; their input changes are O(dt·ġ),
//! the jumps of ĝ are O(1) for the explicit FTDO). With 8 fine points per octave and the first
//! step alone, a = 1, b = 3500, explicit FTDO: the peaks of a dt = 1e-6 s run of FD 96–192 were
//! 0.15–0.8 % low (its transient peaks 1.6–2.4 µs after the jump, in its second or third step),
//! and FD 384's τ2 1.4e-4 below the fine run's; now within 1e-4 on FD 96–384 and FE 24–192
//! (`tests/sub_step.rs`).

use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, Par};

use super::gemv::RowMajor;
use super::woodbury::dot;

/// Fine grid points per octave of s (the fine grid's relative spacing is 1/32 to 1/64); a power
/// of two.
pub const FINE_PER_OCTAVE: usize = 32;

/// The fine search runs where the coarse grid's largest |y_o| plus this × its range over the
/// step's coarse points (largest − smallest |y_o|) reaches the signal's running peak: one point
/// per two octaves misses the maximum of a peak of the shape s e^{−λs} (unit curvature in ln s)
/// by ≤ 21 % of its height (half gap ln 2 in ln s), and the range is at least the rest of that
/// height, so the whole range leaves a margin for narrower peaks; tests/sub_step.rs checks the
/// screen and the climb against the whole fine grid. A slowly varying output (q, θ over one
/// step) has a small range, so its fine search runs only where it is within that range of its
/// peak.
pub const PROBE_MARGIN: f64 = 1.0;

/// Outputs probed, in the order of the rows: q(s), θ(s), q̇(s), θ̇(s), τ1, τ2 (the first six
/// of [`crate::Peaks::signals`]; g̃ is the observer's, constant over a step).
pub const PROBED: usize = 6;

/// Rows stored per grid point: q(s), θ(s), q̇(s), θ̇(s); τ_c = −k_c(a x_c + b v_c) − ĝ_c is
/// formed from them ([`TauRows`]), exactly as the control law (15) forms it.
const ROWS: usize = 4;

/// τ_c(s) = gain_x[c]·x_c(s) + gain_v[c]·v_c(s) − X[g_hat_at[c]]: the control law (15) on the
/// probed tip values, with ĝ_c held in the state X.
#[derive(Debug, Clone, Copy)]
pub(crate) struct TauRows {
    /// −k_c a (N/m, N m/rad).
    pub(crate) gain_x: [f64; 2],
    /// −k_c b (N s/m, N m s/rad).
    pub(crate) gain_v: [f64; 2],
    /// Index of ĝ_c in X.
    pub(crate) g_hat_at: [usize; 2],
}

/// What a probe of one step found: the largest value of each output inside the step (where it
/// is not at the step's ends), and whether an output that may reach its running peak was still
/// rising in |y| at the step's end — its maximum may then lie in the next step, which is probed
/// too ([`crate::modal`]'s runs: a transient longer than the step, as at dt = 1e-6 s after a
/// jump whose tip transient peaks 1.6 µs later).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProbedStep {
    /// Per output (q, θ, q̇, θ̇, τ1, τ2), the largest value found strictly inside the step.
    pub peaks: [Option<SubStepPeak>; PROBED],
    /// An output that passed the screen had its largest value at the step's end.
    pub rising_at_end: bool,
}

/// The largest value of one output found inside a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SubStepPeak {
    /// Time after the step's start (s).
    pub s: f64,
    /// The output's value there (units of the signal).
    pub value: f64,
    /// How far the true maximum of |y| near s may lie above |value| (units of the signal):
    /// twice the rise of the parabola through the largest fine-grid value and its neighbours
    /// (one-sided: |value| itself is attained).
    pub miss: f64,
}

/// Builds the probe's rows level by level during the scaling-and-squaring chain.
#[derive(Debug)]
pub(crate) struct ProbeBuilder {
    /// The output rows c_o as the columns of an N × 4 matrix.
    outputs: Mat<f64>,
    /// s₀ (s) and the number of doublings m (h = s₀2^m).
    s0: f64,
    doublings: u32,
    /// (s, rows c_oᵀE(s)) in ascending s.
    points: Vec<(f64, [Vec<f64>; ROWS])>,
    tau: TauRows,
    /// The chain's last log₂F + 1 level matrices E(s₀2^ℓ), oldest first.
    recent: std::collections::VecDeque<Mat<f64>>,
}

impl ProbeBuilder {
    /// A builder for the output rows `outputs` (each of length N) of a chain starting at `s0`
    /// with `doublings` doublings.
    /// The rows are those of q, θ, q̇, θ̇; `tau` forms τ1, τ2 from them.
    pub(crate) fn new(outputs: [Vec<f64>; ROWS], tau: TauRows, s0: f64, doublings: u32) -> ProbeBuilder {
        let len = outputs[0].len();
        let m = Mat::from_fn(len, ROWS, |i, o| outputs[o][i]);
        let zero = outputs.clone();
        ProbeBuilder { outputs: m, s0, doublings, points: vec![(0.0, zero)], tau, recent: Default::default() }
    }

    /// Record the points the chain's level `level` completes, from e = E(s₀2^level): at level
    /// 0 the points k s₀, k = 1 … 2F − 1 (F = [`FINE_PER_OCTAVE`]); at level ℓ ≥ log₂F the
    /// points kδ_i of level i = ℓ − log₂F, k = F … 2F − 1, starting from c_oᵀE(Fδ_i) = c_oᵀe and
    /// stepping by E(δ_i), kept from log₂F levels earlier (one product per point).
    pub(crate) fn level(&mut self, level: u32, e: &Mat<f64>) {
        let f = FINE_PER_OCTAVE as u64;
        let lag = FINE_PER_OCTAVE.trailing_zeros();
        self.recent.push_back(e.clone());
        if self.recent.len() > lag as usize + 1 {
            self.recent.pop_front();
        }
        let len = self.outputs.nrows();
        let mut next = Mat::<f64>::zeros(len, ROWS);
        let doublings = self.doublings;
        let k_hi = move |i: u32| (2 * f - 1).min((1u64 << (doublings - i).min(62)) - 1);
        if level == 0 {
            let mut w = self.outputs.clone();
            for k in 1..=k_hi(0) {
                // wᵀ ← wᵀE(s₀)
                matmul(next.as_mut(), Accum::Replace, e.transpose(), w.as_ref(), 1.0, Par::Seq);
                std::mem::swap(&mut w, &mut next);
                self.points.push((k as f64 * self.s0, columns(&w)));
            }
            return;
        }
        if level < lag + 1 {
            return;
        }
        let i = level - lag;
        if f > k_hi(i) {
            return;
        }
        let delta = self.s0 * 2f64.powi(i as i32);
        let mut w = Mat::<f64>::zeros(len, ROWS);
        matmul(w.as_mut(), Accum::Replace, e.transpose(), self.outputs.as_ref(), 1.0, Par::Seq);
        self.points.push((f as f64 * delta, columns(&w)));
        let step = &self.recent[0];
        for k in f + 1..=k_hi(i) {
            matmul(next.as_mut(), Accum::Replace, step.transpose(), w.as_ref(), 1.0, Par::Seq);
            std::mem::swap(&mut w, &mut next);
            self.points.push((k as f64 * delta, columns(&w)));
        }
    }

    /// The probe, with the last point s = h from e = E(h).
    pub(crate) fn finish(mut self, h: f64, e: &Mat<f64>) -> SubStepProbe {
        let len = self.outputs.nrows();
        self.points.push((h, columns(&(e.transpose() * &self.outputs))));
        let times: Vec<f64> = self.points.iter().map(|p| p.0).collect();
        let rows = |idx: &[usize]| {
            RowMajor::new(&Mat::from_fn(idx.len() * ROWS, len, |r, j| self.points[idx[r / ROWS]].1[r % ROWS][j]))
        };
        let all: Vec<usize> = (0..times.len()).collect();
        // coarse: the interior points with s/s₀ a power of four (exact in floating point), and
        // the two ends
        let coarse: Vec<usize> = all
            .iter()
            .copied()
            .filter(|&j| {
                let ratio = times[j] / self.s0;
                j == 0 || j + 1 == times.len() || is_coarse(ratio)
            })
            .collect();
        let fine = rows(&all);
        let coarse_rows = rows(&coarse);
        SubStepProbe { times, fine, coarse: coarse_rows, coarse_at: coarse, tau: self.tau }
    }
}

/// The columns of the N × 4 matrix w as rows.
fn columns(w: &Mat<f64>) -> [Vec<f64>; ROWS] {
    std::array::from_fn(|o| (0..w.nrows()).map(|r| w[(r, o)]).collect())
}

/// The index and value of the largest of `values` (the first of equals; (0, −1) if empty).
fn argmax(values: impl Iterator<Item = (usize, f64)>) -> (usize, f64) {
    values.fold((0, -1.0), |acc, (j, v)| if v > acc.1 { (j, v) } else { acc })
}

/// s/s₀ = 4^m (exact for the grid's integer multiples of powers of two).
fn is_coarse(ratio: f64) -> bool {
    let r = ratio.round() as u64;
    if r == 0 || (r as f64) != ratio {
        return false;
    }
    let odd = r >> r.trailing_zeros();
    odd == 1 && r.trailing_zeros() % 2 == 0
}

/// The rows c_oᵀE(s) on the fine and coarse grids of one step h.
#[derive(Debug)]
pub(crate) struct SubStepProbe {
    /// The fine grid's s (s), ascending, from 0 to h.
    times: Vec<f64>,
    /// Row 4j + o: c_oᵀE(times[j]) for q, θ, q̇, θ̇.
    fine: RowMajor,
    /// The same for the coarse points.
    coarse: RowMajor,
    /// Fine index of each coarse point.
    coarse_at: Vec<usize>,
    tau: TauRows,
}

impl SubStepProbe {
    /// The work buffer of [`SubStepProbe::probe`] (the coarse grid's values).
    pub(crate) fn buffer(&self) -> Vec<f64> {
        vec![0.0; self.coarse.rows()]
    }

    /// Points of the fine grid (with s = 0 and s = h).
    pub(crate) fn fine_points(&self) -> usize {
        self.times.len()
    }

    /// Probe the step starting from the state `x` (X_k of [`super::exact`], padded): for each
    /// output o whose coarse maximum may reach `running[o]` ([`PROBE_MARGIN`]), the largest
    /// fine-grid value strictly inside the step, if it is not at the step's ends, and whether
    /// such an output had its largest value at the step's end ([`ProbedStep`]).
    /// With `exhaustive`, every output's whole fine grid instead (no screen; for testing it).
    pub(crate) fn probe(&self, x: &[f64], running: [f64; PROBED], buf: &mut [f64], exhaustive: bool) -> ProbedStep {
        self.coarse.mul_into(x, buf);
        let points = self.coarse_at.len();
        let last = self.times.len() - 1;
        let mut rising_at_end = false;
        let peaks = std::array::from_fn(|o| {
            if exhaustive {
                let (found, at_end) = self.fine_maximum(x, o, 0, last);
                rising_at_end |= at_end;
                return found;
            }
            let mut bottom = f64::INFINITY;
            let (best, top) = argmax((0..points).map(|j| {
                let v = self.value(|r| buf[ROWS * j + r], x, o).abs();
                bottom = bottom.min(v);
                (j, v)
            }));
            let reaches = top + PROBE_MARGIN * (top - bottom) >= running[o];
            if !reaches || top == 0.0 {
                return None;
            }
            let lo = self.coarse_at[best.saturating_sub(1)];
            let hi = self.coarse_at[(best + 1).min(points - 1)];
            let (found, at_end) = self.fine_climb(x, o, lo, hi, self.coarse_at[best]);
            rising_at_end |= at_end;
            found
        });
        ProbedStep { peaks, rising_at_end }
    }

    /// Output o from the stored rows' values `row(r)` (r = 0 … 3) and the state x.
    #[inline]
    fn value(&self, row: impl Fn(usize) -> f64, x: &[f64], o: usize) -> f64 {
        if o < ROWS {
            row(o)
        } else {
            let (c, t) = (o - ROWS, &self.tau);
            t.gain_x[c] * row(c) + t.gain_v[c] * row(2 + c) - x[t.g_hat_at[c]]
        }
    }

    /// Output o at fine point j from the state x.
    fn fine_value(&self, x: &[f64], o: usize, j: usize) -> f64 {
        self.value(|r| dot(self.fine.row(ROWS * j + r), x), x, o)
    }

    /// A local maximum of |y_o| on the fine points lo..=hi, climbing from `start` (the coarse
    /// grid's largest) toward larger values, if not at the step's ends, with its miss; and
    /// whether the climb ended at the step's end.
    fn fine_climb(&self, x: &[f64], o: usize, lo: usize, hi: usize, start: usize) -> (Option<SubStepPeak>, bool) {
        let value = |j: usize| self.fine_value(x, o, j).abs();
        let (mut m, mut top) = (start, value(start));
        for dir in [1isize, -1] {
            let mut moved = false;
            loop {
                let next = m as isize + dir;
                if next < lo as isize || next > hi as isize {
                    break;
                }
                let v = value(next as usize);
                if v <= top {
                    break;
                }
                (m, top, moved) = (next as usize, v, true);
            }
            if moved {
                break;
            }
        }
        (self.peak_at(x, o, m), m + 1 == self.times.len())
    }

    /// The largest |y_o| over the fine points lo..=hi from the state x, if not at the step's
    /// ends, with its miss; and whether it is at the step's end.
    fn fine_maximum(&self, x: &[f64], o: usize, lo: usize, hi: usize) -> (Option<SubStepPeak>, bool) {
        let (m, _) = argmax((lo..=hi).map(|j| (j, self.fine_value(x, o, j).abs())));
        (self.peak_at(x, o, m), m + 1 == self.times.len())
    }

    /// The value of output o at fine point m with its miss, if m is inside the step.
    fn peak_at(&self, x: &[f64], o: usize, m: usize) -> Option<SubStepPeak> {
        if m == 0 || m + 1 == self.times.len() {
            return None; // the maximum is at a recorded instant
        }
        let [y0, y1, y2] = [m - 1, m, m + 1].map(|j| self.fine_value(x, o, j));
        let miss = 2.0 * parabola_rise(self.times[m - 1], self.times[m], self.times[m + 1], y0, y1, y2);
        Some(SubStepPeak { s: self.times[m], value: y1, miss })
    }
}

/// How far the maximum of |p| for the parabola p through (s0, y0), (s1, y1), (s2, y2) lies
/// above |y1| (|y1| ≥ |y0|, |y2|, s0 < s1 < s2); the larger neighbour difference where the
/// parabola has no interior maximum (then the points do not resolve the peak's shape).
fn parabola_rise(s0: f64, s1: f64, s2: f64, y0: f64, y1: f64, y2: f64) -> f64 {
    let sign = if y1 < 0.0 { -1.0 } else { 1.0 };
    let (z0, z1, z2) = (sign * y0, sign * y1, sign * y2);
    let d1 = (z1 - z0) / (s1 - s0);
    let d2 = (z2 - z1) / (s2 - s1);
    let c = (d2 - d1) / (s2 - s0);
    let fallback = (z1 - z0).abs().max((z1 - z2).abs());
    let concave = c < 0.0;
    if !concave {
        return fallback;
    }
    let slope = d1 + c * (s1 - s0);
    let at = s1 - slope / (2.0 * c);
    if !(s0..=s2).contains(&at) {
        return fallback;
    }
    (-slope * slope / (4.0 * c)).max(0.0)
}

#[cfg(test)]
mod tests {
    use super::{is_coarse, parabola_rise};

    #[test]
    fn a_parabola_s_rise_is_its_vertex() {
        // Reference: p(s) = 1 − (s − 0.3)² has its maximum 1 at s = 0.3 (analytic); through
        // s = 0.2, 0.35, 0.5 the largest point is p(0.35) = 0.9975, so the rise is 0.0025.
        let p = |s: f64| 1.0 - (s - 0.3) * (s - 0.3);
        let rise = parabola_rise(0.2, 0.35, 0.5, p(0.2), p(0.35), p(0.5));
        assert!((rise - 0.0025).abs() < 1e-15, "{rise}");
        // negative values: the same for −p
        let rise = parabola_rise(0.2, 0.35, 0.5, -p(0.2), -p(0.35), -p(0.5));
        assert!((rise - 0.0025).abs() < 1e-15, "{rise}");
    }

    #[test]
    fn the_coarse_grid_is_one_point_per_two_octaves() {
        // Reference: s/s₀ = k·2^i is coarse for the powers of four only (by definition)
        let coarse: Vec<u64> = (1..=64).filter(|&k| is_coarse(k as f64)).collect();
        assert_eq!(coarse, vec![1, 4, 16, 64]);
        assert!(!is_coarse(0.5) && !is_coarse(2.0) && !is_coarse(12.0));
    }
}
