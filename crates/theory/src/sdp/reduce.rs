//! The reduced form of the W-bounds pencil SDP ([`super::pencil_cross_check`]): the exact
//! elimination of the velocities (checked on the assembled matrices) and the hierarchical basis
//! in which the displacement block of κ is the identity and the LMI stays chordal.

use faer::{Mat, MatRef};

use crate::numerics::PencilError;

/// Nodal ← hierarchical change of basis of the clamped cubic Hermite (2N) and linear (N)
/// spaces on N = 2^L uniform elements of length `h`: column j holds the nodal coefficients
/// (value and slope at each node) of the hierarchical function at node j — the coarsest-level
/// shape function whose support is the pair of elements of its level around node j (the tip
/// node: the whole span). In 1D these functions are orthogonal across levels in ∫w''² and
/// ∫θ'², so TᵀKT is 2×2-block (Hermite) / diagonal (linear): a sparse κ-orthonormalisation.
pub fn hierarchical_basis(elements: usize, h: f64) -> Result<(Mat<f64>, Mat<f64>), PencilError> {
    let n = elements;
    if n == 0 || !n.is_power_of_two() {
        return Err(PencilError::NotPowerOfTwo(n));
    }
    let mut th = Mat::<f64>::zeros(2 * n, 2 * n);
    let mut tl = Mat::<f64>::zeros(n, n);
    for c in 1..=n {
        // half-width of node c's support, in elements: the largest power of two dividing c
        let half = if c == n { n } else { 1 << c.trailing_zeros() };
        let hh = half as f64 * h;
        let (cv, cs) = (2 * (c - 1), 2 * (c - 1) + 1);
        th[(cv, cv)] = 1.0;
        th[(cs, cs)] = 1.0;
        tl[(c - 1, c - 1)] = 1.0;
        for j in (c - half + 1)..=(c + half - 1).min(n) {
            if j == c {
                continue;
            }
            // Hermite shape functions of the coarse element, at ξ = relative position of node j
            let (value, value_d, slope, slope_d, hat) = if j < c {
                let t = (j + half - c) as f64 / half as f64;
                (
                    3.0 * t * t - 2.0 * t.powi(3),
                    (6.0 * t - 6.0 * t * t) / hh,
                    hh * (t.powi(3) - t * t),
                    3.0 * t * t - 2.0 * t,
                    t,
                )
            } else {
                let t = (j - c) as f64 / half as f64;
                let value = 1.0 - 3.0 * t * t + 2.0 * t.powi(3);
                (
                    value,
                    (6.0 * t * t - 6.0 * t) / hh,
                    hh * (t - 2.0 * t * t + t.powi(3)),
                    1.0 - 4.0 * t + 3.0 * t * t,
                    1.0 - t,
                )
            };
            let (jv, js) = (2 * (j - 1), 2 * (j - 1) + 1);
            th[(jv, cv)] = value;
            th[(js, cv)] = value_d;
            th[(jv, cs)] = slope;
            th[(js, cs)] = slope_d;
            tl[(j - 1, c - 1)] = hat;
        }
    }
    Ok((th, tl))
}

fn frobenius(a: MatRef<'_, f64>, b: MatRef<'_, f64>) -> f64 {
    (0..a.nrows()).flat_map(|i| (0..a.ncols()).map(move |j| a[(i, j)] * b[(i, j)])).sum()
}

/// The data of the reduced pencil SDP at one N, from the assembled forms.
///
/// With x = (q, θ) the displacements, v = (q̇, θ̇) the DG velocities, the assembly gives
/// W = [[W_dd, W_vdᵀ], [W_vd, A_b ⊗ M]], κ = [[κ_dd, 0], [0, I ⊗ M]] with M the diagonal DG
/// mass, A_b the 2×2 velocity weights and W_vd = [B_ki C_i] (C_1, C_2 the DG–Hermite and
/// DG–linear cross masses). Then W − λκ ⪰ 0 iff some symmetric 2×2 P satisfies
/// [[A_b − λI, B], [Bᵀ, P]] ⪰ 0 and W_dd − λκ_dd − [P_ij C_iᵀM⁻¹C_j] ⪰ 0 (u_i = M⁻¹C_i x_i
/// turns the velocity part into [[A, B], [Bᵀ, P]] ⊗ M; P = BᵀA⁻¹B attains it). The second
/// LMI is posed in the hierarchical basis scaled so that its κ-block is I.
pub(super) struct ReducedPencil {
    /// 2×2 velocity weights A_b (from W).
    pub(super) a_b: [[f64; 2]; 2],
    /// 2×2 cross weights B (from W).
    pub(super) b: [[f64; 2]; 2],
    /// W_dd, κ_dd, G_11, G_12, G_22 in the scaled hierarchical basis (3N × 3N).
    pub(super) w_dd: Mat<f64>,
    pub(super) kappa_dd: Mat<f64>,
    pub(super) g: [Mat<f64>; 3],
}

const STRUCTURE_TOLERANCE: f64 = 1e-12;

/// The velocity blocks of W and κ as multiples of the lumped velocity mass M and of the
/// couplings C1, C2 (the structure the exact elimination of the velocities needs), checked on
/// the assembled matrices: (a_b, b, diag M), or the residual when W, κ do not have it.
type VelocityStructure = ([[f64; 2]; 2], [[f64; 2]; 2], Vec<f64>);

fn velocity_structure(
    w: &Mat<f64>,
    kappa: &Mat<f64>,
    cs: [MatRef<'_, f64>; 2],
    n: usize,
) -> Result<VelocityStructure, PencilError> {
    let (nd, nv) = (3 * n, 4 * n);
    let off = [nd, nd + nv];
    let dcol = [0, 2 * n];
    let m: Vec<f64> = (0..nv).map(|i| kappa[(nd + i, nd + i)]).collect();
    let mm = Mat::from_fn(nv, nv, |i, j| if i == j { m[i] } else { 0.0 });
    let block = |r0: usize, c0: usize, r: usize, c: usize| w.submatrix(r0, c0, r, c);
    let mut a_b = [[0.0; 2]; 2];
    let mut b = [[0.0; 2]; 2];
    let mut residual = 0.0f64;
    let scale = w.norm_max().max(f64::MIN_POSITIVE);
    for k in 0..2 {
        for l in 0..2 {
            let wb = block(off[k], off[l], nv, nv);
            a_b[k][l] = frobenius(wb, mm.as_ref()) / frobenius(mm.as_ref(), mm.as_ref());
            residual = residual.max((wb - a_b[k][l] * &mm).norm_max());
            let wc = block(off[k], dcol[l], nv, cs[l].ncols());
            b[k][l] = frobenius(wc, cs[l]) / frobenius(cs[l], cs[l]);
            residual = residual.max((wc - b[k][l] * cs[l]).norm_max());
        }
    }
    let kappa_cross = kappa.submatrix(nd, 0, 2 * nv, nd).norm_max();
    let kappa_vv = (kappa.submatrix(nd, nd, 2 * nv, 2 * nv)
        - Mat::from_fn(2 * nv, 2 * nv, |i, j| if i == j { m[i % nv] } else { 0.0 }))
    .norm_max();
    if residual > STRUCTURE_TOLERANCE * scale || kappa_cross + kappa_vv > STRUCTURE_TOLERANCE * kappa.norm_max() {
        return Err(PencilError::VelocityStructure { residual: residual / scale });
    }
    Ok((a_b, b, m))
}

/// The change of basis T·S of the 3N displacements: the hierarchical basis T, then the
/// block-Cholesky S that makes κ's displacement block the identity (checked to 1e-10).
fn hierarchical_congruence(kappa_d: &Mat<f64>, n: usize, h: f64) -> Result<Mat<f64>, PencilError> {
    let nd = 3 * n;
    let (th, tl) = hierarchical_basis(n, h)?;
    let mut t = Mat::<f64>::zeros(nd, nd);
    t.submatrix_mut(0, 0, 2 * n, 2 * n).copy_from(&th);
    t.submatrix_mut(2 * n, 2 * n, n, n).copy_from(&tl);
    let kh = t.transpose() * kappa_d * &t;
    let mut s = Mat::<f64>::zeros(nd, nd);
    for c in 0..n {
        let (i0, i1) = (2 * c, 2 * c + 1);
        let l11 = kh[(i0, i0)].sqrt();
        let l21 = kh[(i0, i1)] / l11;
        let l22 = (kh[(i1, i1)] - l21 * l21).sqrt();
        s[(i0, i0)] = 1.0 / l11;
        s[(i0, i1)] = -l21 / (l11 * l22);
        s[(i1, i1)] = 1.0 / l22;
    }
    for i in 2 * n..nd {
        s[(i, i)] = 1.0 / kh[(i, i)].sqrt();
    }
    let ts = &t * &s;
    let identity_error = (ts.transpose() * kappa_d * &ts - Mat::<f64>::identity(nd, nd)).norm_max();
    if !identity_error.is_finite() || identity_error > 1e-10 {
        return Err(PencilError::NotOrthonormal(identity_error));
    }
    Ok(ts)
}

pub(super) fn reduce(
    w: &Mat<f64>,
    kappa: &Mat<f64>,
    c1: &Mat<f64>,
    c2: &Mat<f64>,
    n: usize,
    h: f64,
) -> Result<ReducedPencil, PencilError> {
    let nd = 3 * n;
    let cs = [c1.as_ref(), c2.as_ref()];
    let dcol = [0, 2 * n];
    let (a_b, b, m) = velocity_structure(w, kappa, cs, n)?;
    // G_ij = C_iᵀ M⁻¹ C_j embedded in the 3N displacement space
    let minv_c = |c: MatRef<'_, f64>| Mat::from_fn(c.nrows(), c.ncols(), |i, j| c[(i, j)] / m[i]);
    let embed = |k: usize, l: usize| {
        let g = cs[k].transpose() * minv_c(cs[l]);
        let mut e = Mat::<f64>::zeros(nd, nd);
        for i in 0..g.nrows() {
            for j in 0..g.ncols() {
                e[(dcol[k] + i, dcol[l] + j)] += g[(i, j)];
                if k != l {
                    e[(dcol[l] + j, dcol[k] + i)] += g[(i, j)];
                }
            }
        }
        e
    };
    let kappa_d = kappa.submatrix(0, 0, nd, nd).to_owned();
    let ts = hierarchical_congruence(&kappa_d, n, h)?;
    let congruent = |x: &Mat<f64>| ts.transpose() * x * &ts;
    Ok(ReducedPencil {
        a_b,
        b,
        w_dd: congruent(&w.submatrix(0, 0, nd, nd).to_owned()),
        kappa_dd: congruent(&kappa_d),
        g: [congruent(&embed(0, 0)), congruent(&embed(0, 1)), congruent(&embed(1, 1))],
    })
}
