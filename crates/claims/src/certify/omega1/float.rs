//! The floating-point side of the ω₁ enclosure: Galerkin eigenvalues by Sturm-count bisection
//! and the fundamental eigenvector by shifted inverse iteration, on the banded pencil of
//! [`wingcheck_cert::enclosure::pencil`].
//!
//! Written as plain scalar loops over the band (LDLᵀ without pivoting, as the exact check
//! does) rather than with a dense eigen-solver: the same f64 operations in the same order on
//! every machine, so the certificate's rounded decimals — and so `proofs/` — are reproduced
//! bit for bit whatever SIMD path a library would pick. Nothing here is trusted: every number
//! it produces is re-checked in exact arithmetic.

use crate::numerics::NumericsError;
use wingcheck_cert::banded::SymBand;
use wingcheck_cert::exact::to_f64;

/// A symmetric banded f64 matrix, `rows[i][d] = A[i][i + d]`.
#[derive(Debug, Clone)]
pub struct Band {
    bw: usize,
    rows: Vec<Vec<f64>>,
}

impl Band {
    /// Nearest-f64 copy of an exact banded matrix.
    pub fn from_exact(b: &SymBand) -> Band {
        Band { bw: b.bandwidth(), rows: (0..b.dim()).map(|i| b.row(i).iter().map(to_f64).collect()).collect() }
    }

    fn dim(&self) -> usize {
        self.rows.len()
    }

    /// `self − σ · other`.
    pub fn shifted(&self, sigma: f64, other: &Band) -> Band {
        let rows = self
            .rows
            .iter()
            .zip(&other.rows)
            .map(|(a, b)| a.iter().zip(b).map(|(x, y)| x - sigma * y).collect())
            .collect();
        Band { bw: self.bw, rows }
    }

    /// `self · x`.
    pub fn mul(&self, x: &[f64]) -> Vec<f64> {
        let mut y = vec![0.0; self.dim()];
        for (i, row) in self.rows.iter().enumerate() {
            for (d, a) in row.iter().enumerate() {
                y[i] += a * x[i + d];
                if d > 0 {
                    y[i + d] += a * x[i];
                }
            }
        }
        y
    }
}

/// A = L D Lᵀ without pivoting; `l[i][c]` = L[i][i − bw + c] for the band below the diagonal.
struct Ldlt {
    bw: usize,
    l: Vec<Vec<f64>>,
    d: Vec<f64>,
}

fn ldlt(a: &Band) -> Ldlt {
    let (n, bw) = (a.dim(), a.bw);
    let get = |i: usize, j: usize| -> f64 {
        let (i, j) = if i <= j { (i, j) } else { (j, i) };
        a.rows[i].get(j - i).copied().unwrap_or(0.0)
    };
    let mut l = vec![vec![0.0; bw]; n];
    let mut d = vec![0.0; n];
    for i in 0..n {
        let j0 = i.saturating_sub(bw);
        for j in j0..i {
            // L[i][j] = (A[i][j] − Σ_k L[i][k] D[k] L[j][k]) / D[j]
            let mut s = get(i, j);
            for k in j0.max(j.saturating_sub(bw))..j {
                s -= l[i][k + bw - i] * d[k] * l[j][k + bw - j];
            }
            l[i][j + bw - i] = s / d[j];
        }
        let mut s = get(i, i);
        for k in j0..i {
            let lik = l[i][k + bw - i];
            s -= lik * lik * d[k];
        }
        d[i] = s;
    }
    Ldlt { bw, l, d }
}

impl Ldlt {
    fn negative(&self) -> Option<usize> {
        self.d.iter().all(|x| x.is_finite() && *x != 0.0).then(|| self.d.iter().filter(|x| **x < 0.0).count())
    }

    fn solve(&self, b: &mut [f64]) {
        let (n, bw) = (b.len(), self.bw);
        for i in 0..n {
            for k in i.saturating_sub(bw)..i {
                b[i] -= self.l[i][k + bw - i] * b[k];
            }
        }
        for i in 0..n {
            b[i] /= self.d[i];
        }
        for i in (0..n).rev() {
            for j in i + 1..(i + bw + 1).min(n) {
                b[i] -= self.l[j][i + bw - j] * b[j];
            }
        }
    }
}

/// Negative pivots of K − σM in f64. An exactly zero pivot (σ on an eigenvalue of a leading
/// block, e.g. of the bending block of an uncoupled wing, or on a ratio K_ii/M_ii) is avoided
/// by moving σ up by 1e-13 relative, at most three times; None if that does not help.
pub fn count_below(k: &Band, m: &Band, sigma: f64) -> Option<usize> {
    let mut s = sigma;
    for _ in 0..4 {
        if let Some(n) = ldlt(&k.shifted(s, m)).negative() {
            return Some(n);
        }
        s *= 1.0 + 1e-13;
    }
    None
}

/// Upper ends σᵢ of bisection brackets of the `count` lowest Galerkin eigenvalues: the
/// smallest float with f64 count(σᵢ) ≥ i found by halving a bracket to relative width 1e-14.
pub fn eigenvalue_upper_ends(k: &Band, m: &Band, count: usize) -> Result<Vec<f64>, NumericsError> {
    let cnt = |s: f64| count_below(k, m, s).ok_or(NumericsError::LdltBreakdown(s));
    // A scale: K's largest diagonal over M's smallest bounds every eigenvalue from above.
    let dk = k.rows.iter().map(|r| r[0]).fold(0.0, f64::max);
    let dm = m.rows.iter().map(|r| r[0]).fold(f64::INFINITY, f64::min);
    let mut top = dk / dm;
    for _ in 0..64 {
        if cnt(top)? >= count {
            break;
        }
        top *= 2.0;
    }
    let mut out = Vec::with_capacity(count);
    for i in 1..=count {
        let (mut lo, mut hi) = (out.last().copied().unwrap_or(0.0) * 0.5, top);
        while hi - lo > 1e-14 * hi {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if cnt(mid)? >= i {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        out.push(hi);
    }
    Ok(out)
}

/// The fundamental eigenvector by inverse iteration with K − σM, σ just below μ₁ (positive
/// definite there), from the all-ones start, M-normalised.
pub fn fundamental_vector(k: &Band, m: &Band, mu1: f64) -> Result<Vec<f64>, NumericsError> {
    let mut sigma = mu1 * (1.0 - 1e-6);
    let mut f = ldlt(&k.shifted(sigma, m));
    for _ in 0..3 {
        if f.negative().is_some() {
            break;
        }
        sigma *= 1.0 - 1e-13;
        f = ldlt(&k.shifted(sigma, m));
    }
    if f.negative() != Some(0) {
        return Err(NumericsError::ShiftNotDefinite);
    }
    let mut x = vec![1.0; m.dim()];
    for _ in 0..12 {
        let mut y = m.mul(&x);
        f.solve(&mut y);
        let norm = y.iter().zip(m.mul(&y)).map(|(a, b)| a * b).sum::<f64>().sqrt();
        if !(norm.is_finite() && norm > 0.0) {
            return Err(NumericsError::DegenerateVector("inverse iteration produced a zero or non-finite vector"));
        }
        x = y.iter().map(|v| v / norm).collect();
    }
    Ok(x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use wingcheck_cert::enclosure::{pencil, WingConstants};
    use wingcheck_cert::exact::{frac, int};

    /// The uncoupled paper wing (ρx_c = 0): bending and torsion decouple, so the bisection
    /// lands on σ where a block's last pivot is exactly 0.0 in f64 (seen at σ = 18.2726977…).
    /// The counts still come out, and agree with the analytic uncoupled spectrum: bending
    /// (1.8751, 4.6941, 7.8548)⁴·EI/(ρs⁴), torsion ((2j−1)π/(2s))²·GJ/I_p (within the Galerkin
    /// error, < 1e-4 relative for these low modes on 24 elements: O(h⁴) for bending), and above.
    #[test]
    fn uncoupled_counts_survive_exact_zero_pivots() {
        let w = WingConstants {
            span: int(2),
            rho: int(10),
            rho_xc: int(0),
            ei: frac(1, 5),
            gj: frac(1, 2),
            ip: frac(3, 2),
        };
        let p = pencil(&w, 24);
        let (k, m) = (Band::from_exact(&p.stiffness), Band::from_exact(&p.mass));
        assert!(count_below(&k, &m, 1.8272697755458935e1).is_some());
        let mu = eigenvalue_upper_ends(&k, &m, 6).unwrap();
        let scale_b = 0.2 / (10.0 * 16.0);
        let scale_t = 0.5 / 1.5;
        let mut analytic: Vec<f64> = [1.875104068711961f64, 4.694091132974175, 7.854757438237613]
            .iter()
            .map(|b| b.powi(4) * scale_b)
            .chain((1..=4).map(|j| ((2 * j - 1) as f64 * std::f64::consts::PI / 4.0).powi(2) * scale_t))
            .collect();
        analytic.sort_by(f64::total_cmp);
        for (g, a) in mu.iter().zip(&analytic) {
            assert!(*g >= *a * (1.0 - 1e-12) && *g <= *a * (1.0 + 1e-4), "Galerkin {g} vs analytic {a}");
        }
    }
}
