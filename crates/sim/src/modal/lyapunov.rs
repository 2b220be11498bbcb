//! The eigenbasis step's Lyapunov forms ([`super::diagonal`]): the solution P_c of
//! ΛᴴP + PΛ = −ḡgᵀ in the eigenbasis as a real symmetric matrix over the compact layout's N
//! slots, and its low-rank factor, so that e_cᵀP_c e_c = Σ_j (f_j · ê)².

use faer::{c64, Mat};

use super::layout::Layout;

/// Eigenvalues of P below this fraction of its largest are dropped from its factor (as the
/// dense scheme's Gramians, [`super::exact`]).
const FACTOR_CUTOFF: f64 = 1e-15;

/// One of all N eigenvalues for [`real_form`]: λ, g_i, and ê_i as Σ t_α ξ_α.
type Eigenvalue = (c64, c64, Vec<(usize, c64)>);

/// The real symmetric matrix P_r of ξ ↦ êᴴPê over all N eigenvalues, ξ the N real
/// coordinates of x̂ in `layout` (the representatives' real parts and the pairs' imaginary
/// parts), P_ij = −ḡ_i g_j/(λ̄_i + λ_j) (the Lyapunov solution of Λᴴ P + PΛ = −ḡgᵀ): a real
/// eigenvalue has ê = ξ_re, a pair ê = ξ_re ± iξ_im.
pub(crate) fn real_form(g: &[c64], lam: &[c64], reps: &[(usize, f64)], layout: &Layout) -> Mat<f64> {
    let k = g.len();
    let i1 = c64::new(0.0, 1.0);
    let one = c64::new(1.0, 0.0);
    let slot = |i: usize| layout.slot(i).expect("every representative's parts have a slot");
    // every eigenvalue: (λ, g, its ê as Σ t ξ_α)
    let mut full: Vec<Eigenvalue> = Vec::with_capacity(2 * k);
    for r in 0..k {
        let l = lam[r];
        if reps[r].1 == 2.0 {
            let (re, im) = (slot(r), slot(k + r));
            full.push((l, g[r], vec![(re, one), (im, i1)]));
            full.push((l.conj(), g[r].conj(), vec![(re, one), (im, -i1)]));
        } else {
            full.push((l, g[r], vec![(slot(r), one)]));
        }
    }
    let n = layout.len();
    let mut p = Mat::<f64>::zeros(n, n);
    for (li, gi, ti) in &full {
        for (lj, gj, tj) in &full {
            let pij = -(gi.conj() * gj) / (li.conj() + lj);
            for (a, ta) in ti {
                for (b, tb) in tj {
                    p[(*a, *b)] += (ta.conj() * pij * tb).re;
                }
            }
        }
    }
    Mat::from_fn(n, n, |a, b| 0.5 * (p[(a, b)] + p[(b, a)]))
}

/// Rows f_j with ξᵀPξ = Σ_j (f_j·ξ)² up to the dropped remainder, for a positive semidefinite
/// P: Cholesky with complete (diagonal) pivoting, stopped where the largest remaining diagonal
/// is below [`FACTOR_CUTOFF`] × the largest initial one (the remainder is positive semidefinite
/// with that diagonal, so it changes ξᵀPξ by at most its trace × |ξ|²). O(N r²) for rank r;
/// written by hand because faer has no pivoted (low-rank) Cholesky.
pub(crate) fn pivoted_cholesky(p: &Mat<f64>) -> Mat<f64> {
    let n = p.nrows();
    let mut diag: Vec<f64> = (0..n).map(|i| p[(i, i)]).collect();
    let top = diag.iter().copied().fold(0.0, f64::max);
    let mut rows: Vec<Vec<f64>> = Vec::new();
    loop {
        let (piv, d) =
            diag.iter().copied().enumerate().fold((0, f64::NEG_INFINITY), |b, (i, d)| if d > b.1 { (i, d) } else { b });
        if d.is_nan() || d <= FACTOR_CUTOFF * top || rows.len() == n {
            break;
        }
        let root = d.sqrt();
        let row: Vec<f64> =
            (0..n).map(|i| (p[(piv, i)] - rows.iter().map(|f| f[piv] * f[i]).sum::<f64>()) / root).collect();
        for (i, di) in diag.iter_mut().enumerate() {
            *di -= row[i] * row[i];
        }
        diag[piv] = 0.0;
        rows.push(row);
    }
    Mat::from_fn(rows.len(), n, |r, c| rows[r][c])
}
