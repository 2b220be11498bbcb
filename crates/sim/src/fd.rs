//! The paper's finite differences, written in energy (summation-by-parts) form so the
//! matrices are symmetric: nodes z_i = i h, unknowns (q_i, θ_i) at 2(i−1)+{0,1} for
//! i = 1..N; clamp q_0 = θ_0 = 0 and ghost point q_{−1} = q_1 (q'(0) = 0); free end
//! q''(s) = 0 (ghost q_{N+1} = 2q_N − q_{N−1}, so the curvature at N vanishes). Bending
//! energy ½EI Σ_{i=0}^{N−1} c_i h (δ²q_i)² with c_0 = ½ (trapezoid), torsion energy
//! ½GJ Σ h ((θ_{i+1} − θ_i)/h)², lumped trapezoid mass (h, tip h/2). Interior rows
//! reproduce the 5-point stencil of q'''' and the 3-point stencil of θ''; the tip rows are
//! the half-cell balances in which the tip loads enter as point loads.

use wingcheck_model::Config;

use crate::assembly::{builders, finish, initial_q, initial_theta, output_grid, Interpolation, RawAssembly};
use crate::strain::StrainRow;

fn qd(i: usize) -> usize {
    2 * (i - 1)
}
fn td(i: usize) -> usize {
    2 * (i - 1) + 1
}

pub(crate) fn assemble(cfg: &Config, n_int: usize) -> RawAssembly {
    let s = cfg.wing.span;
    let h = s / n_int as f64;
    let n = 2 * n_int;
    let mut b = builders(n);
    let mut load_q = vec![0.0; n];
    let mut load_t = vec![0.0; n];
    for i in 1..=n_int {
        let w = if i == n_int { 0.5 * h } else { h };
        let z = i as f64 * h;
        b[0].add(qd(i), qd(i), w);
        b[1].add(td(i), td(i), w);
        // Cross mass: ∫(qφ + θv) lumped, added once to (q,θ) and mirrored to (θ,q).
        b[2].add(qd(i), td(i), w);
        load_q[qd(i)] = w * z;
        load_t[td(i)] = w * z;
    }
    // Bending: curvature rows δ²q_i, i = 0..N−1, as sparse coefficient lists.
    let h2 = h * h;
    let (mut strain_q, mut strain_t) = (Vec::with_capacity(n_int), Vec::with_capacity(n_int));
    for i in 0..n_int {
        let mut row: Vec<(usize, f64)> = Vec::with_capacity(3);
        if i == 0 {
            row.push((qd(1), 2.0 / h2)); // (q_{−1} − 2q_0 + q_1)/h² with q_{−1} = q_1, q_0 = 0
        } else {
            if i >= 2 {
                row.push((qd(i - 1), 1.0 / h2));
            }
            row.push((qd(i), -2.0 / h2));
            row.push((qd(i + 1), 1.0 / h2));
        }
        let c = if i == 0 { 0.5 } else { 1.0 };
        strain_q.push(StrainRow { pivot: qd(i + 1), entries: row.clone(), weight: c * h });
        for &(a, ca) in &row {
            for &(bb, cb) in &row {
                if a <= bb {
                    let v = c * h * ca * cb;
                    b[3].add(a, bb, v);
                }
            }
        }
    }
    // Torsion: slope rows (θ_{i+1} − θ_i)/h, i = 0..N−1.
    for i in 0..n_int {
        let mut row: Vec<(usize, f64)> = vec![(td(i + 1), 1.0 / h)];
        if i >= 1 {
            row.push((td(i), -1.0 / h));
        }
        strain_t.push(StrainRow { pivot: td(i + 1), entries: row.clone(), weight: h });
        for &(a, ca) in &row {
            for &(bb, cb) in &row {
                if a <= bb {
                    b[4].add(a, bb, h * ca * cb);
                }
            }
        }
    }
    let mut x0 = vec![0.0; n];
    for i in 1..=n_int {
        let z = i as f64 * h;
        x0[qd(i)] = initial_q(cfg, z).0;
        x0[td(i)] = initial_theta(cfg, z);
    }
    let z = output_grid(cfg);
    let mut q_rows = Vec::with_capacity(z.len());
    let mut theta_rows = Vec::with_capacity(z.len());
    for &zj in &z {
        let i = ((zj / h).floor() as usize).min(n_int - 1);
        let u = ((zj - i as f64 * h) / h).clamp(0.0, 1.0);
        let mut qr = Vec::new();
        let mut tr = Vec::new();
        for (node, w) in [(i, 1.0 - u), (i + 1, u)] {
            if node >= 1 && w != 0.0 {
                qr.push((qd(node), w));
                tr.push((td(node), w));
            }
        }
        q_rows.push(qr);
        theta_rows.push(tr);
    }
    RawAssembly {
        parts: finish(b),
        load_q,
        load_t,
        tip_q: qd(n_int),
        tip_theta: td(n_int),
        x0,
        interp: Interpolation { z, q_rows, theta_rows },
        strain_q,
        strain_t,
    }
}
