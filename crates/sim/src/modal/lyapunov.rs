//! The eigenbasis step's Lyapunov forms ([`super::diagonal`]): the solution P_c of
//! ΛᴴP + PΛ = −ḡgᵀ in the eigenbasis as a real symmetric matrix over the compact layout's N
//! slots, and its low-rank factor, so that e_cᵀP_c e_c = Σ_j (f_j · ê)².

use faer::{c64, Mat};

use super::layout::Layout;

/// Eigenvalues of P below this fraction of its largest are dropped from its factor (as the
/// dense scheme's Gramians, [`super::exact`]).
const FACTOR_CUTOFF: f64 = 1e-15;

/// One of all N eigenvalues for [`real_form_reference`]: λ, g_i, and ê_i as Σ t_α ξ_α.
#[cfg(test)]
type Eigenvalue = (c64, c64, Vec<(usize, c64)>);

/// The real symmetric matrices P_r of ξ ↦ êᴴP_cê over all N eigenvalues for both channels'
/// rows `g[c]`, ξ the N real coordinates of x̂ in `layout` (the representatives' real parts
/// and the pairs' imaginary parts), (P_c)_ij = −ḡ_ci g_cj/(λ̄_i + λ_j) (the Lyapunov solution of
/// ΛᴴP + PΛ = −ḡgᵀ): a real eigenvalue has ê = ξ_re, a pair ê = ξ_re ± iξ_im.
///
/// Conjugation maps a pair of eigenvalues (i, j) to (ī, j̄) with the same real contribution to
/// the same entries of P_r, so only one pair per such orbit is formed (twice its share where
/// the orbit has two); the contribution of (j, i) to entry (b, a) equals that of (i, j) to
/// (a, b) exactly (the entries of t are 1 and ±i), so only the representatives' upper triangle
/// is formed; and the denominators are shared by both channels. The same sums as
/// [`real_form_reference`] (unit test below); a profile of both channels measured 4.5 × less
/// time in the sums (the N × N matrices they fill are the same).
pub(crate) fn real_forms(g: [&[c64]; 2], lam: &[c64], reps: &[(usize, f64)], layout: &Layout) -> [Mat<f64>; 2] {
    let k = lam.len();
    let one = c64::new(1.0, 0.0);
    let slot = |i: usize| layout.slot(i).expect("every representative's parts have a slot");
    let is_pair = |r: usize| reps[r].1 == 2.0;
    // the + member of each representative: its ê = Σ t ξ_α over (slot, t) with t = 1 on the
    // real part's slot and t = i on a pair's imaginary part's slot
    let slots: Vec<(usize, Option<usize>)> = (0..k).map(|r| (slot(r), is_pair(r).then(|| slot(k + r)))).collect();
    let n = layout.len();
    let mut p = [Mat::<f64>::zeros(n, n), Mat::<f64>::zeros(n, n)];
    for r in 0..k {
        let (ra, ri) = slots[r];
        for s in r..k {
            let (sa, si) = slots[s];
            // the orbits' representatives (r's + member, s's + or − member) and their sizes
            let (conjugates, weight): (&[bool], f64) = match (is_pair(r), is_pair(s)) {
                (true, true) => (&[false, true], 2.0),
                (true, false) | (false, true) => (&[false], 2.0),
                (false, false) => (&[false], 1.0),
            };
            for &conj_j in conjugates {
                let lj = if conj_j { lam[s].conj() } else { lam[s] };
                let d = one / (lam[r].conj() + lj);
                for (c, pc) in p.iter_mut().enumerate() {
                    let gj = if conj_j { g[c][s].conj() } else { g[c][s] };
                    let pij = -(g[c][r].conj() * gj) * d * weight;
                    // Re(conj(t_a) P t_b) with t_a ∈ {1, i}, t_b ∈ {1, ±i}
                    let sign = if conj_j { -1.0 } else { 1.0 };
                    let mut add = |a: usize, b: usize, v: f64| {
                        pc[(a, b)] += v;
                        if s > r {
                            pc[(b, a)] += v;
                        }
                    };
                    add(ra, sa, pij.re);
                    if let Some(sb) = si {
                        // t_b = ±i: Re(P·(±i)) = ∓Im P
                        add(ra, sb, -sign * pij.im);
                    }
                    if let Some(rb) = ri {
                        // conj(t_a) = −i: Re(−i P) = Im P
                        add(rb, sa, pij.im);
                        if let Some(sb) = si {
                            // Re(−i P (±i)) = ±Re P
                            add(rb, sb, sign * pij.re);
                        }
                    }
                }
            }
        }
    }
    // symmetrise in place (the representatives' diagonal blocks are formed one-sided)
    for pc in &mut p {
        for a in 0..n {
            for b in a + 1..n {
                let v = 0.5 * (pc[(a, b)] + pc[(b, a)]);
                pc[(a, b)] = v;
                pc[(b, a)] = v;
            }
        }
    }
    p
}

/// The straightforward sum of [`real_forms`] for one channel (test reference): P_r of ξ ↦ êᴴPê over all N eigenvalues, ξ the N real
/// coordinates of x̂ in `layout` (the representatives' real parts and the pairs' imaginary
/// parts), P_ij = −ḡ_i g_j/(λ̄_i + λ_j) (the Lyapunov solution of Λᴴ P + PΛ = −ḡgᵀ): a real
/// eigenvalue has ê = ξ_re, a pair ê = ξ_re ± iξ_im.
#[cfg(test)]
fn real_form_reference(g: &[c64], lam: &[c64], reps: &[(usize, f64)], layout: &Layout) -> Mat<f64> {
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
        // (p[piv, :] − Σ_f f[piv] f) / root, one contiguous pass per earlier row
        let mut row: Vec<f64> = (0..n).map(|i| p[(piv, i)]).collect();
        for f in &rows {
            let fp = f[piv];
            for (x, fi) in row.iter_mut().zip(f) {
                *x -= fp * fi;
            }
        }
        for x in &mut row {
            *x /= root;
        }
        for (i, di) in diag.iter_mut().enumerate() {
            *di -= row[i] * row[i];
        }
        diag[piv] = 0.0;
        rows.push(row);
    }
    Mat::from_fn(rows.len(), n, |r, c| rows[r][c])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Both channels' forms against the straightforward sum over all N × N eigenvalue pairs,
    /// on a spectrum with real eigenvalues and conjugate pairs interleaved.
    #[test]
    fn real_forms_equal_the_sum_over_every_eigenvalue_pair() {
        // representatives: (index, weight 1 real / 2 pair), in solver order
        let reps = [(0, 2.0), (2, 1.0), (3, 2.0), (5, 1.0), (6, 1.0), (7, 2.0)];
        let lam: Vec<c64> = [(-0.3, 4.0), (-2.0, 0.0), (-0.01, 40.0), (-7.5, 0.0), (-1e3, 0.0), (-5.0, 0.5)]
            .iter()
            .map(|&(a, b)| c64::new(a, b))
            .collect();
        let layout = Layout::new(&reps);
        let g0: Vec<c64> = (0..6)
            .map(|r| {
                if reps[r].1 == 2.0 {
                    c64::new(0.3 + r as f64, -1.1 * r as f64 + 0.2)
                } else {
                    c64::new(1.5 - r as f64, 0.0)
                }
            })
            .collect();
        let g1: Vec<c64> = g0.iter().map(|x| x * c64::new(0.7, 0.0) + c64::new(-0.25, 0.0)).collect();
        let g1: Vec<c64> =
            g1.iter().enumerate().map(|(r, x)| if reps[r].1 == 2.0 { *x + c64::new(0.0, 0.4) } else { *x }).collect();
        let fast = real_forms([&g0, &g1], &lam, &reps, &layout);
        for (c, g) in [&g0, &g1].iter().enumerate() {
            let slow = real_form_reference(g, &lam, &reps, &layout);
            let scale = slow.norm_max();
            let diff = (&fast[c] - &slow).norm_max();
            // round-off of sums of at most four terms of this size
            assert!(diff <= 1e-14 * scale, "channel {c}: {diff:e} against {scale:e}");
            assert!(scale > 0.1);
        }
    }
}
